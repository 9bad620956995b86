#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): where the
# device's bulk attempts spend their time. The 10,000-plant default stand resolved with
# CANOPY_BULK_STATS (the kernels' busy timeline against the scan's wall time) with 4 lanes and
# with 1, then Nsight Compute on a few launches of the attempt kernels at 1,000 plants.
# Writes into $OUT.
set -u
source scripts/device_common.sh
device_info
for lanes in 4 1 4; do
  echo "## lanes $lanes" | tee -a $OUT/profile.log
  CANOPY_BULK_STATS=1 CANOPY_PLAN_STATS=1 .devbin/bin/bench_resolve --backends cuda --sizes 10000 --dense-sizes "" --levels exact \
    --lanes $lanes --csv $OUT/p.csv 2>&1 | grep -v "^batched scan" | tee -a $OUT/profile.log | grep -E "kernels|^cuda"
done
NCU=$(command -v ncu || ls /opt/nvidia/nsight-compute/*/ncu /usr/local/cuda/bin/ncu 2>/dev/null | head -1)
echo "ncu: $NCU" | tee -a $OUT/profile.log
for k in attempt_exact_kernel attempt_boxes_kernel; do
  timeout 200 $NCU --clock-control none --kernel-name $k --launch-skip 40 --launch-count 2 --section SpeedOfLight --section Occupancy \
    --section LaunchStats --section WarpStateStats --section SchedulerStats --section MemoryWorkloadAnalysis \
    .devbin/bin/bench_resolve --backends cuda --sizes 1000 --dense-sizes "" --levels exact --csv /tmp/n.csv > $OUT/ncu_$k.txt 2>&1
  echo "ncu $k rc $?" | tee -a $OUT/profile.log
done
