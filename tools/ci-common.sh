# Sourced by the CI job scripts (tools/ci-*.sh, tools/coverage.sh).
#
# ci_build B FAIL [MESON SETUP ARGS ...] [-- NINJA TARGETS ...]
#   Configures the build folder B with meson once (CC and the like from the environment), then
#   builds the targets (everything when none are given) with two jobs, the log in B/build.log.
#   On a failure it prints the tail of the log as TAP comments ("# ...") and calls the command
#   FAIL with the reason ("meson setup failed", "build failed"); FAIL is expected to print the
#   job's "not ok" line(s) and exit.
ci_build() {
  local B=$1 fail=$2 log
  shift 2
  local setup=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do setup+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  if [ ! -f "$B/build.ninja" ]; then
    log=$(mktemp) # not in $B: meson writes its .gitignore only into a folder it creates
    if ! meson setup "$B" "${setup[@]}" >"$log" 2>&1; then
      sed 's/^/# /' "$log" | tail -n 20
      rm -f "$log"
      "$fail" "meson setup failed"; return 1
    fi
    rm -f "$log"
  fi
  if ! ninja -C "$B" -j2 "$@" >"$B/build.log" 2>&1; then
    grep -E -A5 'error|warning' "$B/build.log" | head -n 40 | sed 's/^/# /'
    "$fail" "build failed"; return 1
  fi
}
