# Sourced (not run) by the scripts/device_*.sh that run on the GPU machine, from the repository
# root, after scripts/device_bundle.sh here: the carried environment (.devbin/env.sh) and the
# steps several of them share. $OUT is the folder whose files come back from the machine.
source .devbin/env.sh

# The GPU and the host CPU (lscpu's lines matching $1, by default the model and the CPU count),
# printed and, where $OUT is set, written to $OUT/device.txt.
device_info() {
  { nvidia-smi -L; lscpu | grep -E "${1:-Model name|^CPU\(s\)}"; } | tee ${OUT:+$OUT/device.txt}
}

# The CUDA tests: their log in $OUT/test_cuda.log; the exit status and the summary printed.
run_test_cuda() {
  .devbin/bin/test_cuda > "$OUT/test_cuda.log" 2>&1
  echo "test_cuda rc $?" | tee -a "$OUT/test_cuda.log"
  tail -4 "$OUT/test_cuda.log"
}

# 1,000 default plants in 20 rows of 50 resolved and written as glb, obj and ply by the CPU
# backend and by each way named (cuda: the CUDA backend, attempts on the device; host: the CUDA
# backend with the host's turn search), each file compared byte for byte with the CPU's
# (report.json differs in its timings and device only). Prints each run's resolution line and a
# line per file and way: "identical (way) NAME BYTES" or "DIFFERENT (way) NAME".
compare_resolved_files() {
  local stand="grammars/tomato.yaml --rows 20 --per-row 50 --formats glb,obj,ply" way args f name
  echo "# .devbin/bin/canopy stand $stand, --backend cpu against: $*; cmp of every file"
  for way in cpu "$@"; do
    case $way in
      cpu) args="--backend cpu" ;;
      cuda) args="--backend cuda" ;;
      host) args="--backend cuda --resolve-host-search" ;;
      *) echo "compare_resolved_files: unknown way $way" >&2; return 2 ;;
    esac
    rm -rf "/tmp/f_$way"
    .devbin/bin/canopy stand $stand -o "/tmp/f_$way" $args 2>&1 | grep "^resolution" | sed "s/^/$way: /"
  done
  for f in /tmp/f_cpu/*; do
    name=$(basename "$f")
    for way in "$@"; do
      if cmp -s "$f" "/tmp/f_$way/$name"; then echo "identical ($way) $name $(stat -c %s "$f")"; else echo "DIFFERENT ($way) $name"; fi
    done
  done
}
