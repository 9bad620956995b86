#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): Nsight
# Compute's source counters (stall samples per CUDA line and SASS instruction) for the first
# launch of the exact attempt kernel at 10,000 plants with one lane. Writes the report, the
# per-line CSV (cuda,sass: each source line with its instructions) and the details into $OUT.
set -u
source scripts/device_common.sh
NCU=/usr/local/cuda/bin/ncu
timeout 200 $NCU --clock-control none --kernel-name attempt_exact_kernel --launch-skip 0 --launch-count 1 --section SourceCounters --section WarpStateStats --import-source yes -o $OUT/exact -f \
  .devbin/bin/bench_resolve --backends cuda --sizes 10000 --dense-sizes "" --levels exact --lanes 1 --csv /tmp/n.csv > $OUT/ncu_run.txt 2>&1
echo "rc $?"; tail -3 $OUT/ncu_run.txt
$NCU -i $OUT/exact.ncu-rep --page source --csv --print-source cuda,sass > $OUT/source_cuda.csv 2> $OUT/source_err.txt; echo "src rc $?"; head -c 600 $OUT/source_err.txt
$NCU -i $OUT/exact.ncu-rep --page details --print-details all > $OUT/details.txt 2>&1; echo "det rc $?"
ls -la $OUT
