#!/usr/bin/env bash
# Builds the fuzz targets with clang and runs them one after another for SECONDS in all (default
# 60): the grammar parser half of it, seeded with the repository's grammars, and each reader of a
# user's table (positions files, a stand folder's plants.csv + organs.csv, a sweep's runs.csv +
# sweep.json) a sixth, seeded from tests/fuzz/corpus. Usage: fuzz.sh SOURCE_DIR BUILD_DIR [SECONDS]; with
# CANOPY_CHECK_BUILD_ONLY=1 it builds and stops.
set -euo pipefail
src=$1 build=$2 seconds=${3:-60}
cxx=$(command -v clang++-14 || command -v clang++ || true)
if [ -z "$cxx" ]; then echo "fuzz: clang++ not found (install clang-14 and libclang-rt-14-dev)"; exit 1; fi
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" \
  -DCANOPY_FUZZ=ON -DCANOPY_CUDA=OFF -DCANOPY_TOOLS=OFF -DCANOPY_TESTS=OFF >"$build.configure.log" 2>&1 \
  || { cat "$build.configure.log"; exit 1; }
targets=(fuzz_grammar fuzz_positions fuzz_stand_tables fuzz_sweep_files)
cmake --build "$build" --target "${targets[@]}"
# scripts/test.sh builds the tree before ctest, so the test's time is the fuzzing's.
[ "${CANOPY_CHECK_BUILD_ONLY:-0}" = 1 ] && exit 0

# Seeds: files as they are, and two-file inputs (a folder holding both files) joined at a NUL byte
# as the targets cut them.
seed() {  # seed TARGET: fills and prints the target's corpus folder
  local corpus="$build/corpus/$1"
  mkdir -p "$corpus"
  case $1 in
    fuzz_grammar) find "$src/grammars" -name '*.yaml' -exec cp {} "$corpus/" \; ;;
    fuzz_positions) cp "$src"/tests/fuzz/corpus/positions/*.csv "$corpus/" ;;
    fuzz_stand_tables)
      for d in "$src"/tests/fuzz/corpus/stand/*/; do
        { cat "$d/plants.csv"; printf '\0'; cat "$d/organs.csv"; } >"$corpus/$(basename "$d")"
      done ;;
    fuzz_sweep_files)
      for d in "$src"/tests/fuzz/corpus/sweep/*/; do
        { cat "$d/runs.csv"; printf '\0'; cat "$d/sweep.json"; } >"$corpus/$(basename "$d")"
      done ;;
  esac
  echo "$corpus"
}
share=$((seconds / 6 > 5 ? seconds / 6 : 5))
for target in "${targets[@]}"; do
  t=$share
  [ "$target" = fuzz_grammar ] && t=$((seconds - 3 * share > 5 ? seconds - 3 * share : 5))
  corpus=$(seed "$target")
  echo "fuzz: $target for $t s"
  "$build/tests/fuzz/$target" -max_total_time="$t" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$build/$target-" "$corpus" 2>&1 | tail -n 25
done
