#!/usr/bin/env bash
# Builds the grammar fuzz target with clang and runs it for SECONDS (default 60) from a corpus of
# the repository's grammars. Usage: fuzz.sh SOURCE_DIR BUILD_DIR [SECONDS]; with
# CANOPY_CHECK_BUILD_ONLY=1 it builds and stops.
set -euo pipefail
src=$1 build=$2 seconds=${3:-60}
cxx=$(command -v clang++-14 || command -v clang++ || true)
if [ -z "$cxx" ]; then echo "fuzz: clang++ not found (install clang-14 and libclang-rt-14-dev)"; exit 1; fi
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" \
  -DCANOPY_FUZZ=ON -DCANOPY_CUDA=OFF -DCANOPY_TOOLS=OFF -DCANOPY_TESTS=OFF >"$build.configure.log" 2>&1 \
  || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" --target fuzz_grammar
# scripts/test.sh builds the tree before ctest, so the test's time is the fuzzing's.
[ "${CANOPY_CHECK_BUILD_ONLY:-0}" = 1 ] && exit 0
corpus="$build/corpus"
mkdir -p "$corpus"
find "$src/grammars" "$src/tests/fuzz/corpus" -name '*.yaml' -exec cp {} "$corpus/" \; 2>/dev/null || true
"$build/tests/fuzz/fuzz_grammar" -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$build/" "$corpus" 2>&1 | tail -n 25
