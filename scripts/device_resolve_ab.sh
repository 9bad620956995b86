#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here, with the
# bench_resolve of an earlier commit copied to .devbin/bin/bench_resolve_REV): the 10,000-plant
# resolution with the earlier and the current binary alternated on the same machine (the GPU
# machines' host CPUs differ from loan to loan by up to a third), then the 1,000-plant and dense
# rows with the current one. Writes into $OUT.
set -u
source scripts/device_common.sh
device_info
old=$(ls .devbin/bin/bench_resolve_* | head -1)
for r in 1 2 3; do
  for b in $old .devbin/bin/bench_resolve; do
    $b --backends cuda --sizes 10000 --dense-sizes "" --levels exact --csv $OUT/ab_$(basename $b)_$r.csv 2>&1 | grep "^cuda" | sed "s|^|$(basename $b) run $r: |"
  done
done | tee $OUT/ab.log
.devbin/bin/bench_resolve --backends cuda,cpu --sizes 1000,10000 --dense-sizes 1000 --levels exact --csv $OUT/resolve_h200.csv 2>&1 | tee $OUT/resolve_h200.log | tail -7
