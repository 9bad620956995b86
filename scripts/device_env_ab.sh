#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the
# 10,000-plant default stand resolved under each environment setting of ENVS (";"-separated,
# "-" for none), alternated REPS times; resolve s and round 1's scan s (CANOPY_PLAN_STATS).
set -u
source .devbin/env.sh
B="--backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
IFS=';' read -ra envs <<< "${ENVS:--;OMP_WAIT_POLICY=passive;GOMP_SPINCOUNT=10000}"
{
nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"
for r in $(seq ${REPS:-3}); do
  for e in "${envs[@]}"; do
    [ "$e" = "-" ] && set_env="" || set_env="$e"
    out=$(eval env $set_env CANOPY_PLAN_STATS=1 .devbin/bin/bench_resolve $B 2>&1)
    echo "${e}: resolve $(echo "$out" | grep '^cuda' | awk '{print $12}') round 1 $(echo "$out" | grep -m1 'resolution phases' | grep -o 'scan [0-9.]*,' | head -1 | tr -d ,) $(echo "$out" | grep -m1 'resolution phases' | grep -o 'scan [0-9.]*, the rest' | head -1)"
  done
done
} 2>&1 | tee $OUT/env_ab.log
