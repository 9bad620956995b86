#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the
# 10,000-plant default stand resolved with LANES lanes (default "4 6 8") and THREADS threads per
# lane (default 16), alternated REPS times; resolve s and round 1's scan s (CANOPY_PLAN_STATS).
set -u
source .devbin/env.sh
B="--backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
BIN=${BIN:-.devbin/bin/bench_resolve}
{
nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"
for r in $(seq ${REPS:-3}); do
  for lanes in ${LANES:-4 6 8}; do
    for threads in ${THREADS:-16}; do
      out=$(CANOPY_PLAN_STATS=1 OMP_NUM_THREADS=$threads eval $BIN $B --lanes $lanes 2>&1)
      echo "lanes $lanes threads $threads resolve $(echo "$out" | grep '^cuda' | awk '{print $12}') round 1 $(echo "$out" | grep -m1 'resolution phases' | grep -o 'scan [0-9.]*,' | head -1 | tr -d ,)"
    done
  done
done
} 2>&1 | tee $OUT/lanes.log
