#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here, with
# variants of bench_resolve copied to .devbin/bin/bench_resolve_<name>): the 10,000-plant default
# stand resolved by this build and by each variant, alternated, then each with one lane and
# CANOPY_BULK_STATS (the kernels' busy time). Writes the log into $OUT.
set -u
source scripts/device_common.sh
reps=${REPS:-2}
{
device_info
B="--backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
bins=".devbin/bin/bench_resolve $(ls .devbin/bin/bench_resolve_* 2>/dev/null)"
for r in $(seq $reps); do
  for bin in $bins; do
    echo "$(basename $bin) $(eval $bin $B | grep '^cuda')"
  done
done
for bin in $bins; do
  echo "## $(basename $bin), one lane"; CANOPY_BULK_STATS=1 eval $bin $B --lanes 1 2>&1 | grep -E "bulk attempts|kernels|^cuda"
  echo "## $(basename $bin), 4 lanes"; CANOPY_BULK_STATS=1 eval $bin $B 2>&1 | grep -E "bulk attempts|kernels|^cuda"
done
} 2>&1 | tee $OUT/variants.log
