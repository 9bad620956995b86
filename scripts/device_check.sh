#!/usr/bin/env bash
# The GPU check of a change. Run on the GPU machine from the repository root, with the bundle that
# scripts/device_bundle.sh assembled on the build machine carried along (.devbin/):
#   1. the CUDA tests (test_cuda: every contact level equal to the CPU's, resolution's turns equal);
#   2. a resolved 1,000-plant stand written by the CPU backend, the CUDA default (attempts on the
#      device) and CUDA with the host's turn search, every file compared byte for byte
#      (report.json aside: it holds timings and the device's name);
#   3. a short device benchmark: bench/run.sh --quick (CUDA detection of 10,000 plants; resolution
#      of 1,000, 10,000 and dense 1,000 plants on the CPU and CUDA backends).
# Results in $OUT (default device-check/): device.txt, test_cuda.log, files.txt, bench/ (the CSV
# files with commit, date and machine columns, merged into copies of bench/results'), summary.txt.
# Exit status 0 when the tests pass and every file is identical.
# Usage: [OUT=DIR] bash scripts/device_check.sh [--no-bench]
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-device-check}
[ -f .devbin/env.sh ] || { echo "device_check: no .devbin/ (run scripts/device_bundle.sh on the build machine, carry .devbin)" >&2; exit 1; }
source .devbin/env.sh
mkdir -p "$OUT"
status=0
{
  nvidia-smi -L
  lscpu | grep -E 'Model name|^CPU\(s\)'
  echo "commit: $(cat .devbin/commit 2>/dev/null || echo unknown)"
} | tee "$OUT/device.txt"

# 1. The CUDA tests (exit 77 means no GPU was found: a failure here).
.devbin/bin/test_cuda > "$OUT/test_cuda.log" 2>&1
rc=$?
echo "test_cuda: exit $rc, $(grep -E '^\[doctest\] (test cases|assertions)' "$OUT/test_cuda.log" | tr -s ' ' | paste -sd';')" |
  tee "$OUT/summary.txt"
[ $rc = 0 ] || status=1

# 2. The files of one resolved stand from each way of running it, against the CPU backend's.
stand="grammars/tomato.yaml --rows 20 --per-row 50 --formats glb,obj,ply"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
{
  echo "# .devbin/bin/canopy stand $stand -o DIR, then cmp of every file against --backend cpu's"
  for way in cpu cuda host; do
    case $way in
      cpu) args="--backend cpu" ;;
      cuda) args="--backend cuda" ;;
      host) args="--backend cuda --resolve-host-search" ;;
    esac
    .devbin/bin/canopy stand $stand -o "$work/$way" $args 2>&1 | grep '^resolution' | sed "s/^/$way: /"
  done
  for f in "$work"/cpu/*; do
    name=$(basename "$f")
    [ "$name" = report.json ] && continue
    for way in cuda host; do
      if cmp -s "$f" "$work/$way/$name"; then echo "identical ($way) $name $(stat -c %s "$f")"
      else echo "DIFFERENT ($way) $name"; fi
    done
  done
} > "$OUT/files.txt" 2>&1
cat "$OUT/files.txt"
different=$(grep -c '^DIFFERENT' "$OUT/files.txt")
identical=$(grep -c '^identical' "$OUT/files.txt")
echo "files: $identical identical, $different different" | tee -a "$OUT/summary.txt"
[ "$different" = 0 ] && [ "$identical" -gt 0 ] || status=1

# 3. A short device benchmark.
if [ "${1:-}" != --no-bench ]; then
  mkdir -p "$OUT/bench"
  cp bench/results/*.csv bench/results/machine.txt "$OUT/bench/"
  BIN=.devbin/bin bash bench/run.sh --quick --out "$OUT/bench" detect_cuda resolve > "$OUT/bench.log" 2>&1 ||
    { echo "bench: failed (bench.log)" | tee -a "$OUT/summary.txt"; status=1; }
  # The tables' rows: detection (plants, level, times) and resolution (backend, stand, times).
  grep -E '^(device:| +[0-9]+ (exact|organ|leaf|plant) |back |cuda |cpu )' "$OUT/bench.log" | tee -a "$OUT/summary.txt"
fi
echo "device_check: $([ $status = 0 ] && echo passed || echo FAILED)" | tee -a "$OUT/summary.txt"
exit $status
