#!/bin/bash
# On the GPU machine, from the repository root (after scripts/device_bundle.sh here, with an
# older build's bench_detect_cuda copied to .devbin/bin/bench_detect_cuda_old): the CUDA tests,
# then the detection benchmark of both builds alternated (ROUNDS times; SIZES, default
# 10000,100000), then a CPU/CUDA byte comparison of a resolved stand's files. Writes into $OUT.
set -u
source scripts/device_common.sh
device_info
run_test_cuda
for r in $(seq 1 ${ROUNDS:-2}); do
  for b in old new; do
    bin=.devbin/bin/bench_detect_cuda; [ $b = old ] && bin=.devbin/bin/bench_detect_cuda_old
    echo "## round $r, $b: $bin --sizes ${SIZES:-10000,100000} --repeats 9" | tee -a $OUT/detect_ab.log
    $bin --sizes ${SIZES:-10000,100000} --repeats 9 --csv $OUT/detect_cuda_${b}_$r.csv >> $OUT/detect_ab.log 2>&1
  done
done
grep -v "^wrote" $OUT/detect_ab.log | tail -60
compare_resolved_files cuda > $OUT/files.txt 2>&1
cat $OUT/files.txt
