#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the CUDA
# tests, the resolution benchmark on the CUDA backend, and a CPU/CUDA byte comparison of the files
# of a resolved stand. Writes into $OUT.
set -u
source .devbin/env.sh
nvidia-smi -L | tee $OUT/device.txt
.devbin/bin/test_cuda > $OUT/test_cuda.log 2>&1; echo "test_cuda rc $?" | tee -a $OUT/test_cuda.log; tail -4 $OUT/test_cuda.log
.devbin/bin/bench_resolve --backends cuda --sizes 1000,10000 --dense-sizes 1000 --levels exact --csv $OUT/resolve_cuda.csv 2>&1 | tee $OUT/resolve_cuda.log | tail -5
{
  echo "# .devbin/bin/canopy stand grammars/tomato.yaml --rows 20 --per-row 50 --formats glb,obj,ply --backend {cpu,cuda}; cmp of every file (report.json differs in timings and device only)"
  for b in cpu cuda; do .devbin/bin/canopy stand grammars/tomato.yaml -o /tmp/f_$b --rows 20 --per-row 50 --formats glb,obj,ply --backend $b 2>&1 | grep "^resolution"; done
  for f in /tmp/f_cpu/*; do n=$(basename $f); if cmp -s $f /tmp/f_cuda/$n; then echo "identical $n $(stat -c %s $f)"; else echo "DIFFERENT $n"; fi; done
} > $OUT/files.txt 2>&1
cat $OUT/files.txt
