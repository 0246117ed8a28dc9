#!/usr/bin/env bash
# A short crane run under valgrind memcheck: the paper scene (model build, static equilibrium by
# the settling run, then the integration) to T_END seconds, built without sanitizers in
# build-valgrind/. Passes when memcheck reports no error and no definitely, indirectly or
# possibly lost block ("still reachable" blocks of the system libraries are allowed), and the
# run completed. Prints one TAP point; exit status 0 when it passed. The full report is in
# build-valgrind/valgrind.log.
#   bash tools/ci-valgrind.sh
# Environment: BUILD_VALGRIND (default build-valgrind), T_END (default 0.05 s: 45 s of CPU under
# valgrind, most of it the settling run), TRACK_ORIGINS=yes (where uninitialised values come
# from, in a report; doubles the time).
set -uo pipefail
cd "$(dirname "$0")/.."
B=${BUILD_VALGRIND:-build-valgrind}
T_END=${T_END:-0.05}
name="valgrind memcheck: crane paper --t-end $T_END"
bash tools/install-deps.sh >&2 || { echo "not ok - $name: installing packages failed"; exit 1; }
command -v valgrind >/dev/null || { echo "not ok - $name: valgrind is not installed"; exit 1; }
fail() { echo "not ok - $name: $1"; exit 1; }
. tools/ci-common.sh
ci_build "$B" fail -Dwerror=true -Dtests=false -- crane/program/crane

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
log="$B/valgrind.log"
start=$(date +%s)
# One OpenMP thread for CHOLMOD (as the tests run it): a live thread pool at exit would show as
# "possibly lost" thread stacks that belong to libgomp, not to us.
OMP_NUM_THREADS=1 valgrind --tool=memcheck --leak-check=full \
  --show-leak-kinds=definite,indirect,possible --errors-for-leak-kinds=definite,indirect,possible \
  --track-origins="${TRACK_ORIGINS:-no}" --num-callers=30 --error-exitcode=99 --log-file="$log" \
  "$B/crane/program/crane" paper --t-end "$T_END" --no-plots --quiet --out "$out" \
  >"$B/crane.log" 2>&1
rc=$?
secs=$(($(date +%s) - start))

summary=$(grep -E 'ERROR SUMMARY' "$log" | tail -n 1)
errors=$(sed -nE 's/.*ERROR SUMMARY: ([0-9,]+) errors.*/\1/p' <<<"$summary" | tr -d ,)
lost() { # bytes lost of a kind (0 when valgrind reports that all blocks were freed)
  local v
  v=$(grep -E "$1 lost:" "$log" | tail -n 1 | sed -nE 's/.*lost: ([0-9,]+) bytes.*/\1/p' | tr -d ,)
  echo "${v:-0}"
}
def=$(lost definitely); ind=$(lost indirectly); pos=$(lost possibly)
reach=$(grep -E 'still reachable:' "$log" | tail -n 1 | sed -nE 's/.*reachable: (.*)/\1/p')
allocs=$(grep -E 'total heap usage' "$log" | tail -n 1 | sed -nE 's/.*usage: ([0-9,]+) allocs.*/\1/p')
completed=0
grep -q '^status: completed' "$out/status.txt" 2>/dev/null && completed=1
rows=$(($(wc -l <"$out/results.csv" 2>/dev/null || echo 1) - 1))

echo "# valgrind exit $rc in $secs s; $summary; lost: definitely $def, indirectly $ind, possibly $pos bytes; still reachable: ${reach:-0 bytes}; ${allocs:-?} allocations; $rows result rows"
if [ "$rc" -eq 0 ] && [ "${errors:-1}" -eq 0 ] && [ "$def" -eq 0 ] && [ "$ind" -eq 0 ] \
   && [ "$pos" -eq 0 ] && [ "$completed" -eq 1 ] && [ "$rows" -gt 0 ]; then
  echo "ok - $name: 0 errors, no leak (definitely/indirectly/possibly lost 0 bytes), run completed ($secs s)"
  exit 0
fi
grep -E '^==[0-9]+== (Invalid|Conditional|Use of|Syscall|Mismatched|Source and|.*lost in loss record)' \
  "$log" | head -n 20 | sed 's/^/# /'
sed 's/^/# crane: /' "$B/crane.log" | tail -n 5
echo "not ok - $name: exit $rc, ${errors:-?} errors, lost $def/$ind/$pos bytes (definitely/indirectly/possibly), completed=$completed; see $log (TRACK_ORIGINS=yes for more)"
exit 1
