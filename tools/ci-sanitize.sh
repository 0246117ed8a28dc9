#!/usr/bin/env bash
# The whole unit-test suite under AddressSanitizer (leak detection on) and
# UndefinedBehaviorSanitizer (every report fatal: -fno-sanitize-recover=all), built in build-asan/
# with warnings as errors. Prints one TAP point, "ok - ..." or "not ok - ..." (with the failing
# tests and their sanitizer reports); exit status 0 when it passed.
#   bash tools/ci-sanitize.sh [meson test options, e.g. --suite solver]
# Environment: BUILD_ASAN (build folder, default build-asan), TIMEOUT_MULTIPLIER (default 8: the
# crane model test takes about 7 times longer than without sanitizers).
set -uo pipefail
cd "$(dirname "$0")/.."
B=${BUILD_ASAN:-build-asan}
name="sanitizers: test suite under ASan+UBSan ($B)"
bash tools/install-deps.sh >&2 || { echo "not ok - $name: installing packages failed"; exit 1; }
fail() { echo "not ok - $name: $1"; exit 1; }
. tools/ci-common.sh
start=$(date +%s)
ci_build "$B" fail -Dwerror=true -Db_sanitize=address,undefined -Db_lundef=false \
  -Dc_args=-fno-sanitize-recover=all -Dc_link_args=-fno-sanitize-recover=all
build_s=$(($(date +%s) - start))
# the sanitizers must really be in: the library calls the ASan and the (aborting) UBSan runtimes
syms=$(nm -D "$B/libbgdae.so" 2>/dev/null)
if ! grep -q '__asan_report' <<<"$syms" || ! grep -q '__ubsan_handle_.*_abort' <<<"$syms"; then
  echo "not ok - $name: the library is not instrumented (no __asan_report / __ubsan_handle_*_abort)"
  exit 1
fi

# detect_leaks: LeakSanitizer at exit of every test program (and of the crane program the
# program test runs); halt_on_error with UBSan's -fno-sanitize-recover: the first report ends
# the program with a failure. CHOLMOD's OpenMP runs on one thread (as in tests/meson.build).
export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=report_objects=1
export OMP_NUM_THREADS=1
start=$(date +%s)
meson test -C "$B" --print-errorlogs --num-processes 2 \
  --timeout-multiplier "${TIMEOUT_MULTIPLIER:-8}" "$@" >"$B/test.log" 2>&1
mrc=$?
test_s=$(($(date +%s) - start))

python3 - "$B/meson-logs/testlog.json" "$mrc" "$build_s" "$test_s" "$name" "$B/test.log" <<'PY'
import json, re, sys
path, mrc, build_s, test_s, name, log = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5], sys.argv[6]
progs = points = bad_points = 0
failed = []
try:
    lines = open(path).read().splitlines()
except OSError:
    lines = []
for line in lines:
    t = json.loads(line)
    out = (t.get("stdout") or "") + (t.get("stderr") or "")
    progs += 1
    ok = len(re.findall(r"^ok\b", t.get("stdout") or "", re.M))
    bad = len(re.findall(r"^not ok\b(?!.*#\s*TODO)", t.get("stdout") or "", re.M | re.I))
    points += ok
    bad_points += bad
    san = re.search(r"(ERROR: (AddressSanitizer|LeakSanitizer)[^\n]*|runtime error:[^\n]*)", out)
    if t.get("result") not in ("OK", "EXPECTEDFAIL", "SKIP") or bad or san:
        why = san.group(0) if san else f"{t.get('result')}, {bad} failing points"
        failed.append((t["name"], why, round(t.get("duration", 0), 1)))
slow = sorted(((round(json.loads(l).get("duration", 0)), json.loads(l)["name"]) for l in lines), reverse=True)[:2]
slow_txt = ", ".join(f"{n} {d} s" for d, n in slow)
print(f"# build {build_s} s, tests {test_s} s (slowest: {slow_txt})")
if failed or mrc or not progs:
    for n, why, d in failed:
        print(f"# FAILED {n} ({d} s): {why}")
    try:
        tail = open(log).read().splitlines()[-60:]
        print("\n".join("# " + l for l in tail))
    except OSError:
        pass
    print(f"not ok - {name}: {len(failed)} of {progs} test programs failed "
          f"({points} points passed, {bad_points} failed)")
    sys.exit(1)
print(f"ok - {name}: {progs} test programs, {points} test points, no sanitizer report, "
      f"no leak ({test_s} s)")
PY
