#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here): the
# 10,000-plant default stand resolved on the CUDA backend three ways, alternated three times:
# the default (heap in huge pages: tools/huge_page_heap.hpp), CANOPY_HUGE_PAGES=0 (4 KiB pages),
# and the host's turn search; then the kernels' busy timeline and the phases once, and the
# 1,000-plant and dense stands. Prints to stdout.
set -u
source .devbin/env.sh
nvidia-smi -L
B=".devbin/bin/bench_resolve --backends cuda --sizes 10000 --dense-sizes '' --levels exact --csv /tmp/x.csv"
for r in 1 2 3; do
  echo "default"; eval $B | grep "^cuda"
  echo "CANOPY_HUGE_PAGES=0"; CANOPY_HUGE_PAGES=0 eval $B | grep "^cuda"
  echo "--host-search"; eval $B --host-search | grep "^cuda"
done
CANOPY_BULK_STATS=1 CANOPY_PLAN_STATS=1 eval $B 2>&1 | grep -E "kernels|phases|^cuda"
.devbin/bin/bench_resolve --backends cuda --sizes 1000 --dense-sizes 1000 --levels exact --csv /tmp/y.csv | grep "^cuda"
CANOPY_HUGE_PAGES=0 .devbin/bin/bench_resolve --backends cuda --sizes 1000 --dense-sizes 1000 --levels exact --csv /tmp/y.csv | grep "^cuda"
