#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here, with
# variants of bench_resolve copied to .devbin/bin/bench_resolve_<name>): the 10,000-plant default
# stand resolved by this build and each variant, alternated REPS times, printing the resolve
# seconds with the scan's and the planning lanes' seconds (CANOPY_PLAN_STATS, CANOPY_BULK_STATS).
set -u
source scripts/device_common.sh
reps=${REPS:-4}
B="--backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
bins=".devbin/bin/bench_resolve $(ls .devbin/bin/bench_resolve_* 2>/dev/null)"
{
device_info
for r in $(seq $reps); do
  for bin in $bins; do
    out=$(CANOPY_PLAN_STATS=1 CANOPY_BULK_STATS=1 eval $bin $B 2>&1)
    resolve=$(echo "$out" | grep '^cuda' | awk '{print $12}')
    scan=$(echo "$out" | grep -m1 'resolution phases' | grep -o 'scan [0-9.]*,' | head -1 | tr -d ,)
    lanes=$(echo "$out" | grep -m4 'planning lane' | awk '{printf "%s ", $4}')
    calls=$(echo "$out" | grep 'bulk attempts on' | grep -o '[0-9.]* s in calls ([^)]*)')
    echo "$(basename $bin) resolve $resolve | round 1 $scan | lanes in batches $lanes| $calls"
  done
done
} 2>&1 | tee $OUT/scan_phases.log
