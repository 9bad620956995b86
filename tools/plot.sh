#!/usr/bin/env bash
# Plots with gnuplot (Debian gnuplot-nox), each as PNG and SVG.
#   tools/plot.sh sweep DIR            from DIR/summary.csv (canopy sweep): contacts per plant and
#                                      mean turn against density, one curve per age (and row
#                                      spacing, where the sweep has several); leaf area
#                                      index against density; intercepted fraction of the direct
#                                      beam and of the diffuse sky against density, per age, after
#                                      resolution (solid) and before it (dashed)
#   tools/plot.sh bench [RESULTS] [OUT]  from bench/results: detection time against false
#                                      positives per level (speed against error), and detection
#                                      time against plant count per backend
set -euo pipefail
command -v gnuplot >/dev/null || { echo "plot.sh: gnuplot is missing (apt-get install gnuplot-nox)" >&2; exit 1; }

# column FILE NAME: the 1-based index of a CSV column.
column() { head -1 "$1" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }

# quoted TEXT: TEXT inside a gnuplot string in single quotes, where a quote is written twice (a
# folder named d'x ended the string).
quoted() { printf '%s' "${1//\'/\'\'}"; }

# render NAME SCRIPT: runs the gnuplot SCRIPT body twice, into NAME.png and NAME.svg.
render() {
  local name=$1 body=$2 out; out=$(quoted "$1")
  gnuplot <<<"set terminal pngcairo size 900,600 font 'sans,11'; set output '$out.png'; $body"
  gnuplot <<<"set terminal svg size 900,600 font 'sans,11'; set output '$out.svg'; $body"
  echo "wrote $name.png $name.svg"
}

# curves DIR PREFIX: the data files DIR/PREFIX_<steps>_<row spacing>.dat, one per line, by age
# then row spacing as numbers (a listing splits folder names with spaces and sorts 20 before 6).
curves() {
  find "$1" -maxdepth 1 -name "$2_*.dat" -printf '%f\n' | sort -t_ -k2,2n -k3,3g
}

# title STEPS ROW_SPACING ROW_SPACINGS: a curve's title; the row spacing named where the sweep
# has several (a curve per age and row spacing: one per age joined cells of different rows).
title() {
  if [ "$3" -gt 1 ]; then echo "age $1 steps, rows $2 m"; else echo "age $1 steps"; fi
}

# plot_if DATA PREFIX COLUMN NAME SCRIPT: renders NAME from SCRIPT where some curve of DATA's
# PREFIX files has a value in COLUMN (gnuplot fails on a plot with none: a sweep without
# resolution has no turns); else says what was skipped.
plot_if() {
  if cat "$1"/"$2"_*.dat | awk -v c="$3" '$c != "NaN" { found = 1 } END { exit !found }'; then
    render "$4" "$5"
  else
    echo "skipped $4: no cell has a value"
  fi
}

sweep() {
  local dir=$1 sum=$1/summary.csv
  [ -f "$sum" ] || { echo "plot.sh: no $sum (run canopy sweep first)" >&2; exit 1; }
  local cd cs cr cb cw ct cts cl cls
  cd=$(column "$sum" density); cs=$(column "$sum" steps); cr=$(column "$sum" row_spacing)
  cb=$(column "$sum" exact_between_per_plant_mean)
  cw=$(column "$sum" exact_within_per_plant_mean)
  ct=$(column "$sum" mean_turn_deg_mean); cts=$(column "$sum" mean_turn_deg_sd)
  cl=$(column "$sum" lai_mean); cls=$(column "$sum" lai_sd)
  local data=$dir/plot_data
  mkdir -p "$data"
  rm -f "$data"/age_*.dat
  local spacings; spacings=$(tail -n +2 "$sum" | cut -d, -f"$cr" | sort -u | wc -l)
  # One file per age and row spacing: density, contacts per plant (between + within) and its
  # spread, turn, LAI. An empty cell (every run of the cell failed) is NaN, a gap, never 0; an
  # empty standard deviation (a cell of one run) is drawn without a bar. The spread of between +
  # within is that of the runs' sums, from runs.csv (the two counts are not independent: summing
  # their variances drew bars up to 5 times too long).
  local runs=$dir/runs.csv rd rs rr rst rb rw
  rd=$(column "$runs" density); rs=$(column "$runs" steps); rr=$(column "$runs" row_spacing)
  rst=$(column "$runs" status); rb=$(column "$runs" exact_between_per_plant); rw=$(column "$runs" exact_within_per_plant)
  awk -F, -v d="$rd" -v s="$rs" -v r="$rr" -v st="$rst" -v b="$rb" -v w="$rw" '
    NR > 1 && $st == "ok" && $b != "" && $w != "" { k = $d "," $s "," $r; x = $b + $w; n[k]++; m[k] += x; q[k] += x * x }
    END { for (k in n) { mean = m[k] / n[k]; var = n[k] > 1 ? (q[k] - n[k] * mean * mean) / (n[k] - 1) : -1;
          print k "," (var < 0 ? (n[k] > 1 ? 0 : "") : sqrt(var)) } }' "$runs" > "$data/sum_sd.csv"
  tail -n +2 "$sum" | sort -t, -k"$cd","$cd"g | awk -F, -v d="$cd" -v s="$cs" -v r="$cr" -v b="$cb" -v w="$cw" \
    -v t="$ct" -v ts="$cts" -v l="$cl" -v ls="$cls" -v out="$data" -v sds="$data/sum_sd.csv" '
    BEGIN { while ((getline line < sds) > 0) { split(line, p, ","); sd[p[1] "," p[2] "," p[3]] = p[4] } }
    function v(x) { return x == "" ? "NaN" : x }
    function e(m, x) { return m == "" ? "NaN" : (x == "" ? 0 : x) }
    { f = out "/age_" $s "_" $r ".dat";
      total = ($b == "" || $w == "") ? "" : $b + $w;
      print $d, v(total), e(total, sd[$d "," $s "," $r]), v($t), e($t, $ts), v($l), e($l, $ls) > f }'
  local plots_c="" plots_t="" plots_l="" name
  while IFS= read -r name; do
    local f key steps spacing
    f=$(quoted "$data/$name"); key=${name#age_}; key=${key%.dat}; steps=${key%%_*}; spacing=${key#*_}
    local label; label=$(title "$steps" "$spacing" "$spacings")
    plots_c+="'$f' using 1:2:3 with yerrorlines title '$label', "
    plots_t+="'$f' using 1:4:5 with yerrorlines title '$label', "
    plots_l+="'$f' using 1:6:7 with yerrorlines title '$label', "
  done < <(curves "$data" age)
  local common="set key left top; set grid; set offsets graph 0.03, graph 0.03, graph 0.08, 0; set xlabel 'density (plants per m^2)';"
  plot_if "$data" age 2 "$dir/contacts_vs_density" "$common set ylabel 'organ contacts per plant before resolution (exact)'; plot ${plots_c%, }"
  plot_if "$data" age 4 "$dir/turn_vs_density" "$common set ylabel 'mean turn after resolution (degrees)'; plot ${plots_t%, }"
  plot_if "$data" age 6 "$dir/lai_vs_density" "$common set ylabel 'leaf area index (inner plants)'; plot ${plots_l%, }"
  light_plots "$dir" "$sum" "$cd" "$cs" "$cr" "$spacings"
}

# light_plots DIR SUMMARY DENSITY_COL STEPS_COL ROW_SPACING_COL ROW_SPACINGS: interception against
# density per age and row spacing (sweeps made with their light columns; skipped when the columns
# are empty).
light_plots() {
  local dir=$1 sum=$2 cd=$3 cs=$4 cr=$5 spacings=$6 data=$1/plot_data
  local cols="" name
  for name in direct_before direct_after diffuse_before diffuse_after; do
    local c m; m=$(column "$sum" "${name}_mean"); [ -n "$m" ] || return 0
    c=$(column "$sum" "${name}_sd"); cols+="$m $c "
  done
  [ -n "$(tail -n +2 "$sum" | awk -F, -v c="${cols%% *}" '$c != ""')" ] || return 0
  rm -f "$data"/light_*.dat
  # One file per age and row spacing: density, then mean and sd of direct before, after, diffuse
  # before, after (NaN where a run had no resolution or the cell failed).
  tail -n +2 "$sum" | sort -t, -k"$cd","$cd"g | awk -F, -v d="$cd" -v s="$cs" -v r="$cr" -v cols="$cols" -v out="$data" \
    'BEGIN { n = split(cols, c, " ") } { f = out "/light_" $s "_" $r ".dat"; line = $d;
      for (i = 1; i <= n; i++) line = line " " ($c[i] == "" ? (i % 2 == 0 && $c[i - 1] != "" ? 0 : "NaN") : $c[i]);
      print line > f }'
  local pd="" pf="" k=0
  while IFS= read -r name; do
    local f key steps spacing
    f=$(quoted "$data/$name"); key=${name#light_}; key=${key%.dat}; steps=${key%%_*}; spacing=${key#*_}; k=$((k + 1))
    local label; label=$(title "$steps" "$spacing" "$spacings")
    pd+="'$f' using 1:4:5 with yerrorlines lc $k pt 7 title '$label, resolved', '' using 1:2 with lines lc $k dt 2 title 'as grown', "
    pf+="'$f' using 1:8:9 with yerrorlines lc $k pt 7 title '$label, resolved', '' using 1:6 with lines lc $k dt 2 title 'as grown', "
  done < <(curves "$data" light)
  local common="set key right bottom; set grid; set offsets graph 0.03, graph 0.03, graph 0.08, graph 0.08; set xlabel 'density (plants per m^2)';"
  # Drawn where the stands as grown have values: a sweep without resolution has no resolved curve.
  plot_if "$data" light 2 "$dir/interception_direct_vs_density" "$common set ylabel 'intercepted fraction of the direct beam (periodic)'; plot ${pd%, }"
  plot_if "$data" light 6 "$dir/interception_diffuse_vs_density" "$common set ylabel 'intercepted fraction of the diffuse sky (periodic)'; plot ${pf%, }"
}

# first_machine CSV: the CSV's header and the rows of the machine of its first row, where it has a
# machine column (bench/run.sh keeps the latest run of each machine in one file); else all of it.
first_machine() {
  awk -F, 'NR == 1 {by = ($NF == "machine"); print; next} NR == 2 {m = $NF} !by || $NF == m' "$1"
}

bench() {
  local res=${1:-bench/results} out=${2:-bench/results}
  [ -f "$res/detect_cpu.csv" ] || { echo "plot.sh: no $res/detect_cpu.csv" >&2; exit 1; }
  mkdir -p "$out/plot_data"
  local cpu=$out/plot_data/detect_cpu.csv gpu=$res/detect_cuda.csv
  first_machine "$res/detect_cpu.csv" > "$cpu"
  # Speed against error: per level, seconds against false positives, two threads, largest stand.
  local n; n=$(awk -F, 'NR>1 && $4==2 && $5=="mbvt" {print $1}' "$cpu" | sort -n | tail -1)
  awk -F, -v n="$n" 'NR>1 && $1==n && $4==2 && $5=="mbvt" && $6 ~ /^to / {sub(/^to /, "", $6); print $7, ($9 < 1 ? 1 : $9), $6}' "$cpu" \
    > "$out/plot_data/speed_error.dat"
  render "$out/speed_vs_error" "set grid; set logscale y; set xlabel 'detection time to the level, s ($n plants, 2 CPU threads)';
    set ylabel 'false positives against the exact level (organ pairs, log; 0 drawn at 1)'; set offsets 0.05, 0.05, 0, 0;
    plot '$out/plot_data/speed_error.dat' using 1:2 with linespoints pt 7 notitle, '' using 1:2:3 with labels offset 2,1 notitle"
  # Time against plant count per backend: CPU (2 threads) and each GPU of the GPU file with its host's CPU.
  awk -F, 'NR>1 && $4==2 && $5=="mbvt" && $6=="to exact" {print $1, $7}' "$cpu" | sort -n > "$out/plot_data/cpu_exact.dat"
  local plots="'$out/plot_data/cpu_exact.dat' using 1:2 with linespoints pt 7 title 'CPU, 2 threads'"
  if [ -f "$gpu" ]; then
    local cp cl ct cc cdv dev i=0
    cp=$(column "$gpu" plants); cl=$(column "$gpu" level); ct=$(column "$gpu" gpu_detect_s); cc=$(column "$gpu" cpu_total_s)
    cdv=$(column "$gpu" device)
    while IFS= read -r dev; do
      i=$((i + 1))
      awk -F, -v p="$cp" -v l="$cl" -v t="$ct" -v c="$cc" -v d="$cdv" -v dev="$dev" 'NR>1 && $l=="exact" && $d==dev {print $p, $t, $c}' "$gpu" |
        sort -n > "$out/plot_data/gpu_exact_$i.dat"
      plots+=", '$out/plot_data/gpu_exact_$i.dat' using 1:2 with linespoints pt $((3 + 2 * i)) title 'CUDA, $dev (stand on the device: box fit + stages)'"
      plots+=", '' using 1:3 with linespoints pt $((4 + 2 * i)) title 'CPU, every core of the $dev host'"
    done < <(awk -F, -v d="$cdv" 'NR>1 && !seen[$d]++ {print $d}' "$gpu")
  fi
  render "$out/time_vs_plants" "set grid; set logscale xy; set key left top; set xlabel 'plants (default stand)';
    set ylabel 'detection time to the exact level, s'; plot $plots"
}

case "${1:-}" in
  sweep) sweep "${2:?usage: plot.sh sweep DIR}" ;;
  bench) bench "${2:-}" "${3:-}" ;;
  *) echo "usage: tools/plot.sh sweep DIR | bench [RESULTS] [OUT]" >&2; exit 2 ;;
esac
