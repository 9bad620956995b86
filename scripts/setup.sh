#!/usr/bin/env bash
# Installs what canopy needs from Debian's packages (as root), only what is missing; safe to rerun.
set -euo pipefail
# Every package the build and the test suites use, a fresh Debian root included: clang-14 with its
# sanitizer and fuzzer runtimes and its OpenMP (the fuzz tree, tests/ci/fuzz.sh), clang-format-14
# (the sources' .clang-format), CA certificates for npm's download of the glTF validator.
packages=(cmake ninja-build g++ pkg-config libeigen3-dev libyaml-cpp-dev libfmt-dev doctest-dev libcli11-dev
          nlohmann-json3-dev libtinygltf-dev clang-14 libclang-rt-14-dev libomp-14-dev assimp-utils python3 libcgal-dev
          libfcl-dev libembree-dev libpng-dev gnuplot-nox pybind11-dev python3-dev python3-numpy python3-pytest
          python3-matplotlib python3-venv python3-setuptools python3-wheel libopenmpi-dev openmpi-bin clang-format-14
          ca-certificates)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# Node.js runs the Khronos glTF validator in the tests (and the lindenmayer benchmark). An
# installed node (Debian's or another vendor's package) is kept as it is.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "setup: installing nodejs npm"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
fi
cd "$(dirname "$0")/.."
if [ ! -d tests/tools/node/node_modules/gltf-validator ] || [ ! -d tests/tools/node/node_modules/three ]; then
  (cd tests/tools/node && npm install --no-audit --no-fund --silent)
fi
