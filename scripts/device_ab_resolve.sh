#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here, with an
# older build's bench_resolve copied to .devbin/bin/bench_resolve_<commit>): test_cuda, then the
# 10,000-plant default stand resolved by this build, the older one and this build's host search,
# alternated three times; the device kernels' times with one lane (CANOPY_BULK_STATS) for both
# builds; the 1,000-plant and dense stands. Writes the log into $OUT.
set -u
source scripts/device_common.sh
{
device_info
run_test_cuda
OLD=$(ls .devbin/bin/bench_resolve_* | head -1)
B="--backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
for r in $(seq ${REPS:-3}); do
  echo "this build $(eval .devbin/bin/bench_resolve $B | grep '^cuda' | awk '{print $12}')  $(basename $OLD) $(eval $OLD $B | grep '^cuda' | awk '{print $12}')  host search $(eval .devbin/bin/bench_resolve $B --host-search | grep '^cuda' | awk '{print $12}')"
done
for bin in .devbin/bin/bench_resolve $OLD; do
  echo "## $bin, one lane"; CANOPY_BULK_STATS=1 eval $bin $B --lanes 1 2>&1 | grep -E "bulk attempts on|kernels|^cuda"
done
CANOPY_BULK_STATS=1 CANOPY_PLAN_STATS=1 eval .devbin/bin/bench_resolve $B 2>&1 | grep -E "bulk attempts on|kernels|phases|^cuda"
for bin in .devbin/bin/bench_resolve $OLD; do
  echo "## $bin"; $bin --backends cuda --sizes 1000 --dense-sizes 1000 --levels exact --csv /tmp/y.csv | grep "^cuda"
done
} 2>&1 | tee $OUT/ab.log
