#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here, with an
# older build's bench_detect_cuda copied to .devbin/bin/bench_detect_cuda_old): the CUDA tests,
# then the detection benchmark of both builds alternated (ROUNDS times; SIZES, default
# 10000,100000), then a CPU/CUDA byte comparison of a resolved stand's files. Writes into $OUT.
set -u
source .devbin/env.sh
nvidia-smi -L | tee $OUT/device.txt
lscpu | grep -E "Model name|^CPU\(s\)" | tee -a $OUT/device.txt
.devbin/bin/test_cuda > $OUT/test_cuda.log 2>&1; echo "test_cuda rc $?" | tee -a $OUT/test_cuda.log; tail -4 $OUT/test_cuda.log
for r in $(seq 1 ${ROUNDS:-2}); do
  for b in old new; do
    bin=.devbin/bin/bench_detect_cuda; [ $b = old ] && bin=.devbin/bin/bench_detect_cuda_old
    echo "## round $r, $b: $bin --sizes ${SIZES:-10000,100000} --repeats 9" | tee -a $OUT/detect_ab.log
    $bin --sizes ${SIZES:-10000,100000} --repeats 9 --csv $OUT/detect_cuda_${b}_$r.csv >> $OUT/detect_ab.log 2>&1
  done
done
grep -v "^wrote" $OUT/detect_ab.log | tail -60
{
  echo "# .devbin/bin/canopy stand grammars/tomato.yaml --rows 20 --per-row 50 --formats glb,obj,ply --backend cpu and --backend cuda; cmp of every file (report.json differs in timings and device only)"
  for b in cpu cuda; do .devbin/bin/canopy stand grammars/tomato.yaml -o /tmp/f_$b --rows 20 --per-row 50 --formats glb,obj,ply --backend $b 2>&1 | grep "^resolution"; done
  for f in /tmp/f_cpu/*; do n=$(basename $f); if cmp -s $f /tmp/f_cuda/$n; then echo "identical $n $(stat -c %s $f)"; else echo "DIFFERENT $n"; fi; done
} > $OUT/files.txt 2>&1
cat $OUT/files.txt
