#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the CUDA
# tests, the resolution benchmark on the CUDA backend (the host's turn search, then the default:
# each level's attempts on the device, in lanes), and a CPU/CUDA byte comparison of the files of
# a resolved stand, both ways of searching. Writes into $OUT.
set -u
source .devbin/env.sh
nvidia-smi -L | tee $OUT/device.txt
lscpu | grep -E "Model name|^CPU\(s\)" | tee -a $OUT/device.txt
.devbin/bin/test_cuda > $OUT/test_cuda.log 2>&1; echo "test_cuda rc $?" | tee -a $OUT/test_cuda.log; tail -4 $OUT/test_cuda.log
.devbin/bin/bench_resolve --backends cuda --sizes 1000,10000 --dense-sizes 1000 --levels exact --host-search --csv $OUT/resolve_cuda_host_search.csv 2>&1 | tee $OUT/resolve_cuda_host_search.log | tail -5
CANOPY_BULK_STATS=1 .devbin/bin/bench_resolve --backends cuda --sizes 1000,10000 --dense-sizes 1000 --levels exact --csv $OUT/resolve_cuda_device_search.csv 2>&1 | tee $OUT/resolve_cuda_device_search.log | grep -v "^batched scan" | tail -8
{
  echo "# .devbin/bin/canopy stand grammars/tomato.yaml --rows 20 --per-row 50 --formats glb,obj,ply --backend cpu, --backend cuda (attempts on the device), --backend cuda --resolve-host-search; cmp of every file (report.json differs in timings and device only)"
  for b in cpu cuda; do .devbin/bin/canopy stand grammars/tomato.yaml -o /tmp/f_$b --rows 20 --per-row 50 --formats glb,obj,ply --backend $b 2>&1 | grep "^resolution"; done
  .devbin/bin/canopy stand grammars/tomato.yaml -o /tmp/f_host --rows 20 --per-row 50 --formats glb,obj,ply --backend cuda --resolve-host-search 2>&1 | grep "^resolution"
  for f in /tmp/f_cpu/*; do n=$(basename $f); for o in cuda host; do if cmp -s $f /tmp/f_$o/$n; then echo "identical ($o) $n $(stat -c %s $f)"; else echo "DIFFERENT ($o) $n"; fi; done; done
} > $OUT/files.txt 2>&1
cat $OUT/files.txt
