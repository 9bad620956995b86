#!/usr/bin/env bash
# One GPU session: the CUDA tests and file identity, then canopy stand end to end by stage.
set -u
source .devbin/env.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
t0=$(date +%s)
OUT=$OUT/check timeout 240 bash scripts/device_check.sh --no-bench > $OUT/check.log 2>&1; echo "device_check rc=$? $(( $(date +%s) - t0 )) s" | tee -a $OUT/progress.txt
for b in cuda auto cpu; do
  sizes=1000,10000,100000; [ $b = cuda ] || sizes=1000,10000
  timeout 150 .devbin/bin/bench_stand --backend $b --sizes $sizes --csv $OUT/stand.csv $([ -f $OUT/stand.csv ] && echo --append) > $OUT/stand_$b.log 2>&1
  echo "bench_stand $b rc=$? $(( $(date +%s) - t0 )) s" | tee -a $OUT/progress.txt
done
left=$(( 580 - ($(date +%s) - t0) ))
if [ $left -gt 30 ]; then
  timeout $left .devbin/bin/bench_light --plants 10000 --errors 0.002 --plant-errors 0.05 --csv $OUT/light.csv > $OUT/light.log 2>&1
  echo "bench_light rc=$? $(( $(date +%s) - t0 )) s" | tee -a $OUT/progress.txt
fi
rm -rf $OUT/check/bench
