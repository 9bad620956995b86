#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here, with
# variants of bench_resolve copied to .devbin/bin/): Nsight Compute's launch, occupancy and warp
# state figures for one launch of the exact attempt kernel (10,000 plants, one lane) of each
# binary in NCU_BINS (names under .devbin/bin) at each launch index of NCU_SKIPS.
set -u
source scripts/device_common.sh
NCU=$(command -v ncu || ls /opt/nvidia/nsight-compute/*/ncu /usr/local/cuda/bin/ncu 2>/dev/null | head -1)
for v in ${NCU_BINS:-bench_resolve}; do
  for skip in ${NCU_SKIPS:-0 60}; do
  echo "#### $v launch-skip $skip"
  timeout 150 $NCU --clock-control none --kernel-name attempt_exact_kernel --launch-skip $skip --launch-count 1 --section SpeedOfLight --section Occupancy \
    --section LaunchStats --section WarpStateStats .devbin/bin/$v --backends cuda --sizes 10000 --dense-sizes "" --levels exact --lanes 1 --csv /tmp/n.csv 2>&1 | grep -E "Duration|Occupancy|Registers|Block Limit|Grid Size|Waves|Stall|Warp Cycles|Active Warps|Shared Memory Config|Driver Shared|Dynamic Shared|Static Shared|Threads|Compute \(SM\)|Memory Throughput|^cuda"
  done
done
