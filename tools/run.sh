#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job: the crane from its model file
# (crane crane/models/paper.yaml: the model run as bgsim runs it, results and statistics with
# the paper's Fig. 5 in results/paper/), then the benchmark harness
# (every problem, our solver and IDA, rtol 1e-4 .. 1e-10, stability suite, the undamped and
# the damped crane over 20 s against IDA, the error estimate of crane --error-estimate against the true error;
# report in results/bench/report.md) and the KLU timings on block-banded matrices.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
[ -d build ] || meson setup build --buildtype=release >/dev/null
ninja -C build >/dev/null
./build/crane/program/crane crane/models/paper.yaml --out results/paper
./build/bench/bench --stability --crane-full --error-estimate --out results/bench "$@"
echo "report: results/bench/report.md"
./build/bench/klu_bench
