#!/usr/bin/env bash
# Regenerates the canonical benchmark results in bench/results/ (docs/performance.md explains each
# file and its method). Run from anywhere after `bash scripts/build.sh`.
#
# Usage: bash bench/run.sh [--quick --out DIR] [--out DIR] [STEP...]
# Steps, in this order (default: every step this machine can run):
#   derive       derivation speed, canopy beside the lindenmayer npm package    derive.csv
#   generate     growing the default stand and writing its files                generate.csv
#   stand        canopy stand end to end by stage, 1,000-100,000 plants; CPU     stand.csv
#                backend, and on a GPU also the CUDA backend
#   detect       CPU detection per level, the AABB-tree baseline and FCL        detect_cpu.csv
#   detect_cuda  CUDA detection up to 100,000 plants (needs a GPU)              detect_cuda.csv
#   resolve      resolution, CPU; on a GPU also CUDA (device and host search)   resolve.csv
#   scale        tiled runs on 1 and 2 MPI ranks, weak and strong scaling       scale.csv
#   light        light interception: rays/s, time against standard error      light.csv
#   render       canopy render of 1,000 and 10,000 plants at 1920x1080          render.csv
#   experiment   the density sweep of docs/experiments.md and its plots        experiment/
#   plots        tools/plot.sh bench: speed_vs_error.png, time_vs_plants.png
#
# Every CSV gets commit, date and machine columns after the program's own. A file holds the
# latest run of each machine: rows of other machines already in it are kept (when its columns are
# the same), this machine's are replaced. machine.txt describes every machine the files name.
# --out DIR writes there instead (bench/results' files are copied in first, so the same merge
# applies); --quick runs small sizes for a check, and so needs --out (quick rows are not the
# canonical figures). Environment: BIN (the programs' folder, default build/tools),
# CANOPY_COMMIT and CANOPY_MACHINE (override what is recorded).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

quick=0 out=bench/results steps=()
while [ $# -gt 0 ]; do
  case $1 in
    --quick) quick=1 ;;
    --out) out=${2:?--out needs a folder}; shift ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "bench/run.sh: unknown option $1" >&2; exit 2 ;;
    *) steps+=("$1") ;;
  esac
  shift
done
if [ "$quick" = 1 ] && [ "$out" = bench/results ]; then
  echo "bench/run.sh: --quick needs --out DIR (quick runs are not the canonical results)" >&2
  exit 2
fi
BIN=${BIN:-build/tools}
[ -x "$BIN/canopy" ] || { echo "bench/run.sh: no $BIN/canopy (run scripts/build.sh, or set BIN)" >&2; exit 1; }

has_gpu() { command -v nvidia-smi >/dev/null && nvidia-smi -L >/dev/null 2>&1 && [ -x "$BIN/bench_detect_cuda" ]; }
gpu_count() { nvidia-smi -L 2>/dev/null | grep -c '^GPU' || true; }

# The code measured: the checked-out commit, "-dirty" where files other than results differ.
commit_id() {
  if [ -n "${CANOPY_COMMIT:-}" ]; then echo "$CANOPY_COMMIT"; return; fi
  # A bundle's binaries know the commit they were built from (scripts/device_bundle.sh); a copied
  # tree's git may not be at it.
  if [ -f "$BIN/../commit" ]; then cat "$BIN/../commit"; return; fi
  if git rev-parse --short=7 HEAD >/dev/null 2>&1; then
    local c; c=$(git rev-parse --short=7 HEAD)
    [ -z "$(git status --porcelain --untracked-files=no -- . ':(exclude)bench/results')" ] || c+=-dirty
    echo "$c"
  else echo unknown; fi
}

# A short name for this machine: CPU model, CPU count and GPUs, e.g. amd-epyc-2c or
# intel-xeon-16c+h200 (2xh200 for two).
machine_id() {
  if [ -n "${CANOPY_MACHINE:-}" ]; then echo "$CANOPY_MACHINE"; return; fi
  local id
  id=$(lscpu | sed -n 's/^Model name: *//p' | head -1 | sed -E 's/\((R|TM|r|tm)\)//g; s/ (CPU|Processor)\b//g; s/ @.*//' |
         tr 'A-Z' 'a-z' | sed -E 's/[^a-z0-9]+/-/g; s/^-+|-+$//g')
  id+=-$(nproc)c
  if has_gpu; then
    local n name
    n=$(gpu_count)
    name=$(nvidia-smi --query-gpu=name --format=csv,noheader | head -1 | sed -E 's/^NVIDIA //; s/ .*//' | tr 'A-Z' 'a-z')
    id+=+$([ "$n" -gt 1 ] && echo "${n}x")$name
  fi
  echo "$id"
}

# What machine.txt says of this machine.
describe_machine() {
  echo "## $MACHINE"
  echo "cpu: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) CPUs$(grep -q avx512f /proc/cpuinfo && echo ', AVX-512')"
  echo "memory: $(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo)"
  if has_gpu; then
    echo "gpu: $(nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader | sort | uniq -c |
                 sed -E 's/^ *([0-9]+) /\1 x /' | paste -sd';')"
  fi
  echo "os: $(. /etc/os-release && echo "$PRETTY_NAME"), Linux $(uname -r)"
  echo "compiler: $(c++ --version 2>/dev/null | head -1)$(command -v nvcc >/dev/null && echo "; nvcc $(nvcc --version | sed -n 's/.*release \([0-9.]*\).*/\1/p')")"
}

# machine.txt with this machine's section written afresh at the end (the notes of its earlier
# section kept), and the sections of machines that no CSV names any more left out.
update_machine_txt() {
  local f=$out/machine.txt named
  named=" $({ cat "$out"/*.csv "$out"/experiment/*.csv 2>/dev/null || true; } | awk -F, '$NF != "machine" {print $NF}' |
             sort -u | paste -sd' ') "
  {
    if [ -f "$f" ]; then
      awk -v m="## $MACHINE" -v named="$named" '
        /^## / { started = 1; on = ($0 != m) && index(named, " " substr($0, 4) " ") > 0 }
        (!started || on) && NF' "$f" | awk '/^## / && NR > 1 {print ""} {print}'
      echo
    else
      printf '# The machines named in the machine column of the CSV files here (bench/run.sh).\n\n'
    fi
    describe_machine
    # The notes of this machine's earlier section: "note:" and its indented lines.
    if [ -f "$f" ]; then
      awk -v m="## $MACHINE" '/^## / {on = ($0 == m); note = 0; next}
        on && /^note:/ {note = 1} on && note && (/^note:/ || /^  /) {print} on && !/^note:/ && !/^  / {note = 0}' "$f"
    fi
  } > "$work/machine.txt"
  mv "$work/machine.txt" "$f"
}

# stamp NEW NAME: out/NAME becomes NEW's header and rows with commit,date,machine added, after the
# rows of other machines that out/NAME held (kept only where its columns are NEW's).
stamp() {
  local new=$1 dest=$out/$2 header
  header="$(head -1 "$new" | tr -d '\r'),commit,date,machine"
  {
    echo "$header"
    if [ -f "$dest" ]; then
      if [ "$(head -1 "$dest")" = "$header" ]; then
        tail -n +2 "$dest" | awk -F, -v m="$MACHINE" '$NF != m'
      else
        echo "bench/run.sh: $2's columns changed; the rows of other machines are dropped" >&2
      fi
    fi
    tail -n +2 "$new" | grep -v '^#' | sed "s/\$/,$COMMIT,$DATE,$MACHINE/"
  } > "$work/stamped.csv"
  mv "$work/stamped.csv" "$dest"
  echo "bench/run.sh: wrote $dest ($(($(wc -l < "$dest") - 1)) rows)"
}

# stamp_rows FILE: commit,date,machine added to every row of FILE (a folder made afresh).
stamp_rows() {
  awk -v add="$COMMIT,$DATE,$MACHINE" 'NR == 1 {print $0 ",commit,date,machine"; next} {print $0 "," add}' "$1" > "$work/rows.csv"
  mv "$work/rows.csv" "$1"
}

step_derive() {
  "$BIN/bench_derive" grammars/tomato.yaml grammars/classic/abop_1_24a.yaml:9 grammars/classic/abop_1_24d.yaml:7 \
    grammars/classic/algae.yaml:30 grammars/classic/abop_1_31a.yaml:30 grammars/classic/abop_2_6.yaml:16 \
    $([ "$quick" = 1 ] && echo --repeats 1) --csv "$work/derive.csv"
  if command -v node >/dev/null && command -v npm >/dev/null; then
    (cd bench && npm install --no-audit --no-fund --silent)
    node bench/lindenmayer_bench.js "$work/lindenmayer.csv"
    tail -n +2 "$work/lindenmayer.csv" >> "$work/derive.csv"
  else
    echo "bench/run.sh: no node: derive.csv without the lindenmayer rows" >&2
  fi
  stamp "$work/derive.csv" derive.csv
}

step_generate() {
  "$BIN/bench_generate" $([ "$quick" = 1 ] && echo --sizes 100,1000) --dir "$work/generate" --csv "$work/generate.csv"
  rm -rf "$work/generate"
  stamp "$work/generate.csv" generate.csv
}

step_stand() {
  local sizes=1000,10000,100000 csv=$work/stand.csv
  [ "$quick" = 1 ] && sizes=100,1000
  # A size the machine cannot hold is refused by canopy stand itself (bench_stand says which, and
  # exits 1): the other sizes' rows are kept.
  "$BIN/bench_stand" --backend cpu --sizes "$sizes" --csv "$csv" ||
    echo "bench/run.sh: stand: a size failed on the CPU backend (no row for it)" >&2
  if has_gpu; then
    "$BIN/bench_stand" --backend cuda --sizes "$sizes" --csv "$csv" --append ||
      echo "bench/run.sh: stand: a size failed on the CUDA backend (no row for it)" >&2
  fi
  stamp "$csv" stand.csv
}

step_detect() {
  if [ "$quick" = 1 ]; then "$BIN/bench_detect" --sizes 200,1000 --repeats 3 --csv "$work/detect_cpu.csv"
  else "$BIN/bench_detect" --repeats 9 --csv "$work/detect_cpu.csv"; fi
  stamp "$work/detect_cpu.csv" detect_cpu.csv
}

step_detect_cuda() {
  if [ "$quick" = 1 ]; then "$BIN/bench_detect_cuda" --sizes 10000 --repeats 5 --csv "$work/detect_cuda.csv"
  else "$BIN/bench_detect_cuda" --repeats 9 --csv "$work/detect_cuda.csv"; fi
  stamp "$work/detect_cuda.csv" detect_cuda.csv
}

step_resolve() {
  local sizes=() csv=$work/resolve.csv
  [ "$quick" = 1 ] && sizes=(--sizes 1000,10000 --dense-sizes 1000 --levels exact)
  "$BIN/bench_resolve" --backends cpu "${sizes[@]}" --csv "$csv"
  if has_gpu; then
    "$BIN/bench_resolve" --backends cuda "${sizes[@]}" --csv "$csv" --append
    "$BIN/bench_resolve" --backends cuda --host-search --sizes 1000,10000 --dense-sizes 1000 --levels exact --csv "$csv" --append
  fi
  stamp "$csv" resolve.csv
}

step_scale() {
  local backend=cpu threads=1 bind=(--bind-to core) s1=10000 s2=20000,10000
  if has_gpu; then
    backend=cuda threads=$(($(nproc) / 2)) bind=(--bind-to none)
    [ "$quick" = 1 ] || { s1=10000,100000; s2=20000,200000,100000; }
  elif [ "$(nproc)" -gt 2 ]; then
    threads=$(($(nproc) / 2))
  fi
  [ "$quick" = 1 ] && [ "$backend" = cpu ] && { s1=1000; s2=2000,1000; }
  [ "$(id -u)" = 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  OMP_NUM_THREADS=$threads mpirun "${bind[@]}" -x OMP_NUM_THREADS -np 1 "$BIN/bench_scale" --sizes "$s1" \
    --backend $backend --threads "$threads" --csv "$work/scale.csv"
  OMP_NUM_THREADS=$threads mpirun "${bind[@]}" -x OMP_NUM_THREADS -np 2 "$BIN/bench_scale" --sizes "$s2" \
    --backend $backend --threads "$threads" --csv "$work/scale.csv"
  stamp "$work/scale.csv" scale.csv
}

step_light() {
  if [ "$quick" = 1 ]; then "$BIN/bench_light" --plants 1000 --errors 0.01 --plant-errors 0.05 --csv "$work/light.csv"
  else
    # The command's default (auto): a GPU, where there is one, draws every pass; the host traces.
    if [ -e /dev/nvidiactl ]; then
      "$BIN/bench_light" --plants 1000 --errors 0.01,0.005,0.002,0.001 --plant-errors 0.05,0.02,0.01,0.002 --csv "$work/light.csv"
      "$BIN/bench_light" --plants 10000 --errors 0.01,0.002 --plant-errors 0.05,0.01,0.002 --csv "$work/light.csv" --append
      light_append=--append
    fi
    "$BIN/bench_light" --caster trace --plants 1000 --errors 0.01,0.005,0.002,0.001 --plant-errors 0.05,0.02,0.01 \
      --csv "$work/light.csv" ${light_append:-}
    "$BIN/bench_light" --caster trace --plants 10000 --errors 0.01,0.002 --plant-errors 0.05 --csv "$work/light.csv" --append
  fi
  stamp "$work/light.csv" light.csv
}

step_render() {
  local n rows per line csv=$work/render.csv
  echo "plants,organs,width,height,render_s,peak_rss_gb,cpu_threads" > "$csv"
  for n in $([ "$quick" = 1 ] && echo 1000 || echo 1000 10000); do
    rows=$((n >= 100 ? n / 100 : 1)) per=$((n >= 100 ? 100 : n))
    "$BIN/canopy" stand grammars/tomato.yaml --rows "$rows" --per-row "$per" --random-rotation --jitter 0.02 \
      --no-resolve --formats ply -o "$work/stand" > /dev/null
    # canopy render prints "wrote FILE (WxH, N organs) in S s, peak memory G GB".
    line=$("$BIN/canopy" render "$work/stand" -o "$work/picture.png" --size 1920x1080 | grep '^wrote')
    sed -E "s/.*, ([0-9]+) organs\) in ([0-9.]+) s, peak memory ([0-9.]+) GB.*/$n,\1,1920,1080,\2,\3,$(nproc)/" <<< "$line" >> "$csv"
    rm -rf "$work/stand" "$work/picture.png"
  done
  stamp "$csv" render.csv
}

step_experiment() {
  local dir=$out/experiment
  rm -rf "$dir"
  "$BIN/canopy" sweep grammars/tomato.yaml --density 1.5,2,2.5,3,4 --row-spacing 1.0 --steps 16,19,22 --seeds 3 \
    --rows 3 --per-row 5 -o "$dir"
  bash tools/plot.sh sweep "$dir"
  rm -rf "$dir/plot_data" "$dir"/*.svg   # the docs show the PNGs
  stamp_rows "$dir/runs.csv"
  stamp_rows "$dir/summary.csv"
}

step_plots() {
  bash tools/plot.sh bench "$out" "$out"
  rm -rf "$out/plot_data" "$out"/*.svg
}

all=(derive generate stand detect detect_cuda resolve scale light render experiment plots)
if [ ${#steps[@]} -eq 0 ]; then
  for s in "${all[@]}"; do
    case $s in
      detect_cuda) has_gpu || { echo "bench/run.sh: no GPU here: detect_cuda.csv kept as it is" >&2; continue; } ;;
      scale) command -v mpirun >/dev/null && [ -x "$BIN/bench_scale" ] ||
               { echo "bench/run.sh: no mpirun or bench_scale: scale.csv kept as it is" >&2; continue; } ;;
      light) [ -x "$BIN/bench_light" ] || { echo "bench/run.sh: no bench_light (no Embree): light.csv kept as it is" >&2; continue; } ;;
      render) "$BIN/canopy" info | grep -q '^render: Embree' ||
                { echo "bench/run.sh: canopy render not built: render.csv kept as it is" >&2; continue; } ;;
    esac
    steps+=("$s")
  done
fi
for s in "${steps[@]}"; do
  [[ " ${all[*]} " == *" $s "* ]] || { echo "bench/run.sh: unknown step $s (steps: ${all[*]})" >&2; exit 2; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
COMMIT=$(commit_id) DATE=$(date -u +%Y-%m-%d) MACHINE=$(machine_id)
if [ "$out" != bench/results ] && [ ! -d "$out" ]; then
  mkdir -p "$out"
  cp bench/results/*.csv bench/results/machine.txt "$out"/ 2>/dev/null || true
fi
echo "bench/run.sh: commit $COMMIT, machine $MACHINE, steps: ${steps[*]}, into $out"
for s in "${steps[@]}"; do
  echo "== $s"
  "step_$s"
done
update_machine_txt
