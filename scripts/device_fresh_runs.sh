#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here), first thing
# on a fresh loan: the 10,000-plant CUDA resolution three times in a row (does a fresh machine's
# first run cost more?), then 60 GB written to and removed from /dev/shm, then twice more; each
# run's phases and page faults (CANOPY_PLAN_STATS) and the free memory.
set -u
source scripts/device_common.sh
B="--backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
{
nvidia-smi -L; free -g | head -2; cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag; uptime
for r in 1 2 3; do
  CANOPY_PLAN_STATS=1 eval .devbin/bin/bench_resolve $B 2>&1 | grep -E '^cuda|phases|faults' | head -8
  grep -E 'MemFree|^Cached' /proc/meminfo
done
dd if=/dev/zero of=/dev/shm/x bs=1M count=60000 status=none; rm /dev/shm/x; echo "wrote and removed 60 GB in /dev/shm"
for r in 4 5; do
  CANOPY_PLAN_STATS=1 eval .devbin/bin/bench_resolve $B 2>&1 | grep -E '^cuda|phases|faults' | head -3
done
} 2>&1 | tee $OUT/fresh.log
