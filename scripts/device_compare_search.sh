#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the CUDA
# backend's two ways of planning resolution alternated twice (the host's candidate-by-candidate
# search, then the default: attempts on the device in 4 lanes) at 1,000, 10,000 and dense 1,000
# plants, then a byte comparison of a resolved stand's files from the CPU backend and both ways.
source .devbin/env.sh
nvidia-smi -L; lscpu | grep -E "Model name|^CPU\(s\)"
B() { .devbin/bin/bench_resolve --backends cuda --sizes 1000,10000 --dense-sizes 1000 --levels exact --csv /tmp/x.csv "$@" 2>&1 | grep "^cuda"; }
for i in 1 2; do echo "== host search"; B --host-search; echo "== device search, 4 lanes"; B; done
{
  for b in cpu cuda; do .devbin/bin/canopy stand grammars/tomato.yaml -o /tmp/f_$b --rows 20 --per-row 50 --formats glb,obj,ply --backend $b 2>&1 | grep "^resolution"; done
  .devbin/bin/canopy stand grammars/tomato.yaml -o /tmp/f_host --rows 20 --per-row 50 --formats glb,obj,ply --backend cuda --resolve-host-search 2>&1 | grep "^resolution"
  for f in /tmp/f_cpu/*; do n=$(basename $f); for o in cuda host; do if cmp -s $f /tmp/f_$o/$n; then echo "identical ($o) $n $(stat -c %s $f)"; else echo "DIFFERENT ($o) $n"; fi; done; done
} 2>&1 | tee $OUT/files.txt
