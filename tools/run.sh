#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job: the KLU benchmark on block-banded
# matrices (the crane scene takes its place once the crane lands).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
[ -d build ] || meson setup build --buildtype=release >/dev/null
ninja -C build >/dev/null
exec ./build/bench/klu_bench "$@"
