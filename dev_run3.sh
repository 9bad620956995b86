#!/usr/bin/env bash
set -u
source .devbin/env.sh
t0=$(date +%s)
.devbin/bin/test_cuda > $OUT/test_cuda.log 2>&1; echo "test_cuda rc=$? $(( $(date +%s) - t0 )) s" | tee -a $OUT/progress.txt
grep -E '^\[doctest\] (test cases|assertions)' $OUT/test_cuda.log; grep -B3 -A8 'ERROR' $OUT/test_cuda.log | head -30
export OMP_NUM_THREADS=16
for n in 20000 200000; do
  timeout 150 mpirun --bind-to none -x OMP_NUM_THREADS -np 2 .devbin/bin/bench_scale --sizes $n --backend cuda --threads 16 --grammar grammars/tomato.yaml --csv $OUT/scale.csv > $OUT/scale2_$n.log 2>&1
  echo "scale np2 $n rc=$? $(( $(date +%s) - t0 )) s" | tee -a $OUT/progress.txt
  grep -v -E 'pmix|dlopen|Perhaps' $OUT/scale2_$n.log | tail -4
done
