#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the
# 10,000-plant default stand resolved with each batch size of BATCHES (contacts per batch of
# planning; default "8192 16384"), alternated REPS times; resolve s and round 1's scan s.
set -u
source .devbin/env.sh
B="--backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
{
nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"
for r in $(seq ${REPS:-3}); do
  for batch in ${BATCHES:-8192 16384}; do
    out=$(CANOPY_PLAN_STATS=1 eval .devbin/bin/bench_resolve $B --batch $batch 2>&1)
    echo "batch $batch resolve $(echo "$out" | grep '^cuda' | awk '{print $12}') round 1 $(echo "$out" | grep -m1 'resolution phases' | grep -o 'scan [0-9.]*,' | head -1 | tr -d ,)"
  done
done
} 2>&1 | tee $OUT/batch.log
