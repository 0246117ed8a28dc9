#!/usr/bin/env bash
# Builds the libFuzzer targets with clang in build-fuzz/ (-Dfuzz=true: libFuzzer, ASan, UBSan)
# and runs each for FUZZ_TIME seconds from a temporary copy of its seed corpus (fuzz/corpus/*),
# so that the repository is not changed: fuzz_scene (the scene-file parser, with the dictionary
# fuzz/scene.dict), fuzz_dae_input (the DAE solver's input validation), fuzz_model_yaml
# (the model files' YAML loader and expressions), fuzz_model (the whole model-file reader) and
# fuzz_sweep (crane-sweep's sweep files, with the dictionary fuzz/sweep.dict).
# Every seed is run
# first. Prints one TAP point per target; exit status 0 when all passed. A crashing input is
# kept in build-fuzz/artifacts/ (add it to the corpus once the bug is fixed); the logs are in
# build-fuzz/fuzz-<target>.log.
#   bash tools/ci-fuzz.sh [target ...]
# Environment: BUILD_FUZZ (default build-fuzz), FUZZ_TIME (seconds per target, default 30).
set -uo pipefail
cd "$(dirname "$0")/.."
B=${BUILD_FUZZ:-build-fuzz}
T=${FUZZ_TIME:-30}
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(fuzz_scene fuzz_dae_input fuzz_model_yaml fuzz_model fuzz_sweep)
fail_all() { for t in "${targets[@]}"; do echo "not ok - fuzz $t: $1"; done; exit 1; }
bash tools/install-deps.sh >&2 || fail_all "installing packages failed"
command -v clang >/dev/null || fail_all "clang is not installed (libFuzzer)"
build_targets=()
for t in "${targets[@]}"; do build_targets+=("fuzz/$t"); done
. tools/ci-common.sh
CC=clang ci_build "$B" fail_all -Dfuzz=true -Dtests=false -Dwerror=true -- "${build_targets[@]}"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$B/artifacts"
failed=0
for t in "${targets[@]}"; do
  case $t in
    fuzz_scene) corpus=fuzz/corpus/scene; extra=(-dict=fuzz/scene.dict) ;;
    fuzz_dae_input) corpus=fuzz/corpus/dae; extra=() ;;
    fuzz_model_yaml) corpus=fuzz/corpus/model; extra=() ;;
    fuzz_model) corpus=fuzz/corpus/modelfile; extra=() ;;
    fuzz_sweep) corpus=fuzz/corpus/sweep; extra=(-dict=fuzz/sweep.dict) ;;
    *) echo "not ok - fuzz $t: unknown target"; failed=1; continue ;;
  esac
  mkdir -p "$work/$t"
  cp -r "$corpus/." "$work/$t/"
  seeds=$(find "$work/$t" -type f | wc -l)
  log="$B/fuzz-$t.log"
  # -timeout: one input may take at most 10 s; -rss_limit_mb: memory; leaks are detected
  # (LeakSanitizer) after each input that allocates more than it frees
  "$B/fuzz/$t" -max_total_time="$T" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$B/artifacts/$t-" "${extra[@]}" "$work/$t" >"$log" 2>&1
  rc=$?
  runs=$(sed -nE 's/^stat::number_of_executed_units: *([0-9]+).*/\1/p' "$log" | tail -n 1)
  eps=$(sed -nE 's/^stat::average_exec_per_sec: *([0-9]+).*/\1/p' "$log" | tail -n 1)
  new=$(sed -nE 's/^stat::new_units_added: *([0-9]+).*/\1/p' "$log" | tail -n 1)
  cov=$(grep -E '^#[0-9]+' "$log" | tail -n 1 | sed -nE 's/.*cov: ([0-9]+) ft: ([0-9]+).*/\1 edges, \2 features/p')
  if [ "$rc" -eq 0 ] && ! grep -qE '^==[0-9]+==ERROR|runtime error:|^fuzz_[a-z_]+: ' "$log"; then
    echo "ok - fuzz $t: $T s, ${runs:-?} runs (${eps:-?}/s), $seeds seeds, ${new:-?} new inputs, ${cov:-? coverage}, no crash, leak or failed check"
  else
    grep -E -A12 '^==[0-9]+==ERROR|runtime error:|^fuzz_[a-z_]+: |deadly signal|Test unit written' \
      "$log" | head -n 40 | sed 's/^/# /'
    echo "not ok - fuzz $t: exit $rc after ${runs:-?} runs; input kept in $B/artifacts/, log $log"
    failed=1
  fi
done
exit $failed
