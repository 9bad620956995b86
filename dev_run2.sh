#!/usr/bin/env bash
set -u
source .devbin/env.sh
t0=$(date +%s)
.devbin/bin/test_cuda > $OUT/test_cuda.log 2>&1; echo "test_cuda rc=$? $(( $(date +%s) - t0 )) s" | tee -a $OUT/progress.txt
grep -B3 -A12 'ERROR' $OUT/test_cuda.log | head -60
export OMP_NUM_THREADS=16
timeout 220 mpirun --bind-to none -x OMP_NUM_THREADS -np 1 .devbin/bin/bench_scale --sizes 500000 --backend cuda --threads 16 --grammar grammars/tomato.yaml --csv $OUT/scale.csv > $OUT/scale1.log 2>&1
echo "scale np1 rc=$? $(( $(date +%s) - t0 )) s" | tee -a $OUT/progress.txt
left=$(( 500 - ($(date +%s) - t0) ))
timeout $left mpirun --bind-to none -x OMP_NUM_THREADS -np 2 .devbin/bin/bench_scale --sizes 1000000 --backend cuda --threads 16 --grammar grammars/tomato.yaml --csv $OUT/scale.csv > $OUT/scale2.log 2>&1
echo "scale np2 rc=$? $(( $(date +%s) - t0 )) s" | tee -a $OUT/progress.txt
left=$(( 585 - ($(date +%s) - t0) ))
[ $left -gt 20 ] && timeout $left .devbin/bin/bench_light --plants 10000 --errors 0.002 --plant-errors 0.05 --threads 16 --grammar grammars/tomato.yaml --csv $OUT/light.csv > $OUT/light.log 2>&1
echo "light rc=$? $(( $(date +%s) - t0 )) s" | tee -a $OUT/progress.txt
tail -4 $OUT/scale1.log $OUT/scale2.log; tail -5 $OUT/light.log
