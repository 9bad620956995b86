#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): how the
# host's resolution planning scales over the machine's cores, and whether pinning OpenMP's
# threads changes it. Writes into $OUT.
set -u
source scripts/device_common.sh
device_info "Model name|^CPU\(s\)|Thread\(s\) per core|Core\(s\) per socket|Socket\(s\)|MHz|L3|NUMA node\(s\)"
nproc | tee -a $OUT/device.txt
for t in 1 2 4 8 16; do
  .devbin/bin/bench_resolve --backends cpu --sizes 1000 --dense-sizes "" --levels exact --threads $t --csv $OUT/threads.csv --append 2>&1 | grep "^cpu" | sed "s/^/threads $t: /"
done | tee $OUT/threads.log
for bind in unset close spread; do
  if [ $bind = unset ]; then unset OMP_PROC_BIND OMP_PLACES; else export OMP_PROC_BIND=$bind OMP_PLACES=cores; fi
  .devbin/bin/bench_resolve --backends cuda --sizes 10000 --dense-sizes "" --levels exact --csv $OUT/bind_$bind.csv 2>&1 | grep "^cuda" | sed "s/^/bind $bind: /"
done | tee $OUT/bind.log
