#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the
# 10,000-plant default stand resolved on the CUDA backend three ways, alternated three times:
# the default, the whole heap in huge pages (GLIBC_TUNABLES=glibc.malloc.hugetlb=1: tried in the
# 22nd session and not kept, bench/results/resolve_session22.txt), and the host's turn search;
# then the kernels' busy timeline and the phases once, and the 1,000-plant and dense stands both
# ways. Prints to stdout.
set -u
source scripts/device_common.sh
device_info
B=".devbin/bin/bench_resolve --backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
for r in 1 2 3; do
  echo "default"; eval $B | grep "^cuda"
  echo "glibc.malloc.hugetlb=1"; GLIBC_TUNABLES=glibc.malloc.hugetlb=1 eval $B | grep "^cuda"
  echo "--host-search"; eval $B --host-search | grep "^cuda"
done
CANOPY_BULK_STATS=1 CANOPY_PLAN_STATS=1 eval $B 2>&1 | grep -E "kernels|phases|^cuda"
.devbin/bin/bench_resolve --backends cuda --sizes 1000 --dense-sizes 1000 --levels exact --csv /tmp/y.csv | grep "^cuda"
GLIBC_TUNABLES=glibc.malloc.hugetlb=1 .devbin/bin/bench_resolve --backends cuda --sizes 1000 --dense-sizes 1000 --levels exact --csv /tmp/y.csv | grep "^cuda"
