#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs, only those that are missing.
set -euo pipefail
pkgs=(build-essential meson ninja-build pkg-config python3 libsuitesparse-dev liblapack-dev
      libblas-dev libsundials-dev libinih-dev gnuplot-nox
      libarpack2-dev  # the sparse modal analysis (solver/bg_modes.c)
      libyaml-dev  # model files (model/mdl_yaml.c)
      python3-dev python3-numpy python3-pytest  # the Python package (python/) and its tests
      python3-scipy python3-matplotlib  # its sparse Jacobians, examples/python/compare_scipy.py
      cmake  # the CMake package's version file (meson) and the CMake install check (tools/test.sh)
      libopenmpi-dev openmpi-bin  # crane-sweep's MPI engine and its mpirun test (crane/sweep/)
      valgrind gcovr clang libclang-rt-14-dev)  # CI jobs (tools/ci-*.sh, tools/coverage.sh)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "Installing: ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
