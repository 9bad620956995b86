source .devbin/env.sh
B="--backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
{
nvidia-smi -L; free -g | head -2; cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag; uptime
for r in 1 2 3; do
  s=$(date +%s.%N)
  CANOPY_PLAN_STATS=1 eval .devbin/bin/bench_resolve $B 2>&1 | grep -E '^cuda|phases|round' | head -8
  echo "wall $(echo "$(date +%s.%N) - $s" | bc)"; grep -E 'MemFree|^Cached' /proc/meminfo
done
s=$(date +%s.%N); dd if=/dev/zero of=/dev/shm/x bs=1M count=60000 status=none; rm /dev/shm/x; echo "touch 60G $(echo "$(date +%s.%N) - $s" | bc) s"
for r in 4 5; do
  CANOPY_PLAN_STATS=1 eval .devbin/bin/bench_resolve $B 2>&1 | grep -E '^cuda|phases' | head -3
done
} 2>&1 | tee $OUT/fresh.log
