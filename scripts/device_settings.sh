#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the
# 10,000-plant default stand resolved under each setting of SETTINGS (";"-separated; a setting is
# environment assignments and/or bench_resolve options, e.g. "--lanes 4;--lanes 6",
# "--batch 8192;--batch 16384", "-;OMP_WAIT_POLICY=passive", "-" for none), alternated REPS times
# (default 3); prints each run's resolve s, round 1's scan s, the scan's CPU seconds (all threads,
# every round) and its minor page faults (CANOPY_PLAN_STATS).
set -u
source scripts/device_common.sh
IFS=';' read -ra settings <<< "${SETTINGS:---lanes 4;--lanes 6;--lanes 8}"
{
device_info
for r in $(seq ${REPS:-3}); do
  for s in "${settings[@]}"; do
    envs=() args=()
    for w in $s; do
      case $w in -) ;; [A-Z_]*=*) envs+=("$w") ;; *) args+=("$w") ;; esac
    done
    out=$(env "${envs[@]}" CANOPY_PLAN_STATS=1 .devbin/bin/bench_resolve --backends cuda --sizes 10000 --dense-sizes '' \
      --levels exact --csv /tmp/x.csv "${args[@]}" 2>&1)
    echo "$s: resolve $(echo "$out" | grep '^cuda' | awk '{print $12}') round 1 $(echo "$out" | grep -m1 'resolution phases' | grep -o 'scan [0-9.]*,' | head -1 | tr -d ,)" \
      "| scan CPU s $(echo "$out" | grep -o 'CPU s (all threads) setup to candidates [0-9.]*, scan [0-9.]*' | awk '{print $NF}')" \
      "| scan's minor faults (k) $(echo "$out" | grep -o 'faults (thousands): .*' | grep -o 'scan [0-9.]*' | awk '{print $2}')"
  done
done
} 2>&1 | tee $OUT/settings.log
