#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the CUDA
# backend's two ways of planning resolution alternated twice (the host's candidate-by-candidate
# search, then the default: attempts on the device in 4 lanes) at 1,000, 10,000 and dense 1,000
# plants, then a byte comparison of a resolved stand's files from the CPU backend and both ways.
source scripts/device_common.sh
device_info
B() { .devbin/bin/bench_resolve --backends cuda --sizes 1000,10000 --dense-sizes 1000 --levels exact --csv /tmp/x.csv "$@" 2>&1 | grep "^cuda"; }
for i in 1 2; do echo "== host search"; B --host-search; echo "== device search, 4 lanes"; B; done
compare_resolved_files cuda host 2>&1 | tee $OUT/files.txt
