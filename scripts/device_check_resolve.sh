#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the CUDA
# tests, the resolution benchmark on the CUDA backend (the host's turn search, then the default:
# each level's attempts on the device, in lanes), and a CPU/CUDA byte comparison of the files of
# a resolved stand, both ways of searching. Writes into $OUT.
set -u
source scripts/device_common.sh
device_info
run_test_cuda
.devbin/bin/bench_resolve --backends cuda --sizes 1000,10000 --dense-sizes 1000 --levels exact --host-search --csv $OUT/resolve_cuda_host_search.csv 2>&1 | tee $OUT/resolve_cuda_host_search.log | tail -5
CANOPY_BULK_STATS=1 .devbin/bin/bench_resolve --backends cuda --sizes 1000,10000 --dense-sizes 1000 --levels exact --csv $OUT/resolve_cuda_device_search.csv 2>&1 | tee $OUT/resolve_cuda_device_search.log | grep -v "^batched scan" | tail -8
compare_resolved_files cuda host > $OUT/files.txt 2>&1
cat $OUT/files.txt
