#!/usr/bin/env bash
# canopy sweep end to end: the rows of a tiny grid, the summary, resuming (nothing redone, a torn
# line dropped), a failed run recorded as failed, bad specifications refused with clear errors.
# Usage: CANOPY=path/to/canopy test_cli_sweep.sh SOURCE_DIR
set -u
src=$1
canopy=${CANOPY:?set CANOPY to the canopy binary}
source "$(dirname "$0")/check.sh"
g="$src/grammars/tomato.yaml"
sweep() { "$canopy" sweep "$g" --plant-spacing 0.3,0.45 --steps 10:12:2 --seeds 2 --rows 3 --per-row 3 --backend cpu "$@"; }

sweep -o "$tmp/s" >"$tmp/log" 2>&1
check "exit" "0" "$?"
check "runs rows" "9" "$(wc -l < "$tmp/s/runs.csv" | tr -d ' ')"
check "summary rows" "5" "$(wc -l < "$tmp/s/summary.csv" | tr -d ' ')"
col() { python3 -c "
import csv,sys; r=list(csv.DictReader(open('$1'))); print(' '.join(x['$2'] for x in r))"; }
check "cells and seeds" "0.3|10|1 0.3|10|2 0.3|12|1 0.3|12|2 0.45|10|1 0.45|10|2 0.45|12|1 0.45|12|2" \
  "$(python3 -c "
import csv; print(' '.join(f\"{x['plant_spacing']}|{x['steps']}|{x['seed']}\" for x in csv.DictReader(open('$tmp/s/runs.csv'))))")"
check "all ok" "ok ok ok ok ok ok ok ok" "$(col "$tmp/s/runs.csv" status)"
check "plants" "9 9 9 9 9 9 9 9" "$(col "$tmp/s/runs.csv" plants)"
check "lai on the one inner plant" "1 1 1 1 1 1 1 1" "$(col "$tmp/s/runs.csv" lai_plants)"
check "density" "True" "$(python3 -c "
import csv; print(all(abs(float(x['density']) - 1/(float(x['plant_spacing'])*float(x['row_spacing']))) < 1e-3 for x in csv.DictReader(open('$tmp/s/runs.csv'))))")"
check "denser means more LAI" "True" "$(python3 -c "
import csv; r={(x['plant_spacing'],x['steps']):float(x['lai_mean']) for x in csv.DictReader(open('$tmp/s/summary.csv'))}
print(r[('0.3','12')] > r[('0.45','12')] and r[('0.3','10')] > r[('0.45','10')])")"
check "resolved: nothing left" "0 0 0 0 0 0 0 0" "$(col "$tmp/s/runs.csv" residual_contacts)"
check "summary runs" "2 2 2 2" "$(col "$tmp/s/summary.csv" runs)"
# Light before and after resolution: fractions in (0, 1), the fractions' errors at most the
# default 0.002 (STAR's may be larger), denser stands intercepting more.
check "light columns" "True" "$(python3 -c "
import csv; r=list(csv.DictReader(open('$tmp/s/runs.csv')))
ok=all(0 < float(x[c+w]) < 1 for x in r for c in ('ground_cover_','direct_','diffuse_','star_') for w in ('before','after'))
print(ok and all(0 < float(x['mean_inclination_after']) < 90 and float(x['light_s']) > 0 for x in r))")"
check "denser intercepts more" "True" "$(python3 -c "
import csv; r={(x['plant_spacing'],x['steps']):x for x in csv.DictReader(open('$tmp/s/summary.csv'))}
print(all(float(r[('0.3',a)][c]) > float(r[('0.45',a)][c]) for a in ('10','12') for c in ('direct_after_mean','diffuse_after_mean','ground_cover_after_mean')))")"

# Plots of the sweep (gnuplot): PNG and SVG of each curve.
if command -v gnuplot >/dev/null; then
  bash "$src/tools/plot.sh" sweep "$tmp/s" >/dev/null 2>&1
  check "plot exit" "0" "$?"
  # The contacts' bars are the spread of each cell's runs' between + within (summing the two
  # counts' variances drew them up to 5 times too long).
  check "plot: the spread of between + within" "True" "$(python3 -c "
import csv, glob, statistics
runs = [r for r in csv.DictReader(open('$tmp/s/runs.csv')) if r['status'] == 'ok']
ok = True
for f in glob.glob('$tmp/s/plot_data/age_*.dat'):
    steps, rows = f.rsplit('/', 1)[1][4:-4].split('_')
    for line in open(f):
        d, total, spread = line.split()[:3]
        xs = [float(r['exact_between_per_plant']) + float(r['exact_within_per_plant']) for r in runs
              if float(r['density']) == float(d) and r['steps'] == steps and r['row_spacing'] == rows]
        ok = ok and len(xs) == 2 and abs(float(spread) - statistics.stdev(xs)) <= 1e-6 * (1 + statistics.stdev(xs))
print(ok)")"
  for f in contacts_vs_density turn_vs_density lai_vs_density interception_direct_vs_density interception_diffuse_vs_density; do
    check "plot $f.png" "PNG" "$(head -c 4 "$tmp/s/$f.png" 2>/dev/null | tail -c 3)"
    check "plot $f.svg" "1" "$(grep -c '<svg' "$tmp/s/$f.svg" 2>/dev/null | sed 's/[2-9]/1/')"
  done
  rm -rf "$tmp/s"/*.png "$tmp/s"/*.svg "$tmp/s/plot_data"
  # Without resolution the stands as grown are drawn (the plots were skipped: 'no cell has a
  # value'); a cell of one run has a mean and no standard deviation (it was written 0).
  "$canopy" sweep "$g" --plant-spacing 0.45 --steps 10 --seeds 1 --rows 3 --per-row 3 --backend cpu --no-resolve \
    -o "$tmp/nores" >/dev/null 2>&1
  check "one run: mean, no sd" "0 True True" "$? $(python3 -c "
import csv; r = next(csv.DictReader(open('$tmp/nores/summary.csv'))); print(r['lai_mean'] != '', r['lai_sd'] == '')")"
  bash "$src/tools/plot.sh" sweep "$tmp/nores" >/dev/null 2>&1
  check "plot without resolution: interception drawn" "0 PNG" "$? $(head -c 4 "$tmp/nores/interception_direct_vs_density.png" 2>/dev/null | tail -c 3)"
else
  check "gnuplot installed (run scripts/setup.sh)" "yes" "no"
fi

# Resume: nothing redone, the file unchanged.
cp "$tmp/s/runs.csv" "$tmp/runs.before"
sweep -o "$tmp/s" >"$tmp/log2" 2>&1
check "resume exit" "0" "$?"
check "resume runs nothing" "1" "$(grep -c '^sweep: 0 runs made now' "$tmp/log2")"
cmp -s "$tmp/runs.before" "$tmp/s/runs.csv"
check "resume leaves runs.csv" "0" "$?"

# Resuming with other settings is refused, naming them, runs.csv untouched; settings that change
# no answer (threads) resume as before.
"$canopy" sweep "$g" --plant-spacing 0.3,0.45 --steps 10:12:2 --seeds 2 --rows 3 --per-row 2 --jitter 0 --backend cpu \
  -o "$tmp/s" >"$tmp/o" 2>"$tmp/e"
check "other settings refused" "2" "$?"
check "other settings named" "1" "$(grep -c 'holds 8 run(s) made with other settings (per_row 3 -> 2; jitter 0.02 -> 0.0)' "$tmp/e")"
cmp -s "$tmp/runs.before" "$tmp/s/runs.csv"
check "other settings: runs.csv untouched" "0" "$?"
sweep -o "$tmp/s" --threads 1 >"$tmp/o" 2>&1
check "threads resume" "1" "$(grep -c '^sweep: 0 runs made now' "$tmp/o")"
check "sweep.json" "3" "$(python3 -c "import json; print(json.load(open('$tmp/s/sweep.json'))['rows'])")"
one() { "$canopy" sweep "$g" --plant-spacing 0.45 --steps 10 --seeds 1 --rows 1 --per-row 2 --backend cpu -o "$tmp/c" "$@"; }
one --set nodes=12 --set phyllotaxis=137 >/dev/null 2>&1
one --set phyllotaxis=137.0 --set nodes=12 >"$tmp/o" 2>&1
check "--set in another order resumes" "1" "$(grep -c '^sweep: 0 runs made now' "$tmp/o")"
one --set nodes=13 --set phyllotaxis=137 >"$tmp/o" 2>"$tmp/e"
check "--set other value refused" "1" "$(grep -c 'set {"nodes":12.0,"phyllotaxis":137.0} -> {"nodes":13.0,"phyllotaxis":137.0}' "$tmp/e")"
one --sun 40,90 >"$tmp/o" 2>"$tmp/e"
check "--sun other value refused" "1" "$(grep -c 'light {"sun":"60,180","sky":"soc","sky_directions":46,"error":0.002} -> {"sun":"40,90"' "$tmp/e")"
"$canopy" sweep "$g" --plant-spacing 0.45 --steps 10 --seeds 1 --rows 1 --per-row 2 --backend cpu --no-light -o "$tmp/nl" >/dev/null 2>&1
check "--no-light leaves the light columns empty" "|" "$(python3 -c "
import csv; r=list(csv.DictReader(open('$tmp/nl/runs.csv'))); print(r[0]['direct_before'] + '|' + r[0]['light_s'])")"

# The grammar is compared as a document: a comment or blank line added resumes, a value changed is
# refused, and a sweep.json of an earlier canopy (the digest of the file's bytes) still resumes.
cp "$g" "$tmp/gd.yaml"
oneg() { "$canopy" sweep "$tmp/gd.yaml" --plant-spacing 0.45 --steps 10 --seeds 1 --rows 1 --per-row 2 --backend cpu -o "$tmp/d" "$@"; }
oneg >/dev/null 2>&1
printf '\n# a note added between runs\n' >> "$tmp/gd.yaml"
oneg >"$tmp/o" 2>&1
check "grammar comment resumes" "1" "$(grep -c '^sweep: 0 runs made now' "$tmp/o")"
python3 -c "
import json; p='$tmp/d/sweep.json'; j=json.load(open(p)); h=0xcbf29ce484222325
for c in open('$tmp/gd.yaml','rb').read(): h=((h^c)*0x100000001b3)&(2**64-1)
j['grammar_digest']=format(h,'016x'); json.dump(j,open(p,'w'),indent=2)"
oneg >"$tmp/o" 2>&1
check "earlier sweep.json resumes" "1" "$(grep -c '^sweep: 0 runs made now' "$tmp/o")"
# Runs without their sweep.json cannot be compared with any settings: refused, the table as it was.
cp -r "$tmp/d" "$tmp/nojson"; rm "$tmp/nojson/sweep.json"; cp "$tmp/nojson/runs.csv" "$tmp/runs.nojson"
"$canopy" sweep "$tmp/gd.yaml" --plant-spacing 0.45 --steps 10 --seeds 1 --rows 1 --per-row 2 --backend cpu -o "$tmp/nojson" >"$tmp/o" 2>"$tmp/e"
check "runs without sweep.json: refused, table kept" "2 1 0" \
  "$? $(grep -c 'holds 1 run(s) but no sweep.json' "$tmp/e") $(cmp -s "$tmp/nojson/runs.csv" "$tmp/runs.nojson"; echo $?)"
sed -i 's/^  nodes: 18 /  nodes: 17 /' "$tmp/gd.yaml"
oneg >"$tmp/o" 2>"$tmp/e"
check "grammar value refused" "2" "$?"
check "grammar value named" "1" "$(grep -c 'other settings (grammar_digest ' "$tmp/e")"

# An interrupted sweep: three runs done and a torn fourth line; resuming makes exactly five.
head -4 "$tmp/runs.before" > "$tmp/s/runs.csv"
printf '3,0.3,1,3.3333,12,2,ok,9,11' >> "$tmp/s/runs.csv"
sweep -o "$tmp/s" >"$tmp/log3" 2>&1
check "interrupted: resumed runs" "1" "$(grep -c '^sweep: 5 runs made now' "$tmp/log3")"
check "interrupted: rows" "9" "$(wc -l < "$tmp/s/runs.csv" | tr -d ' ')"
check "interrupted: same results" "$(cut -d, -f1-25 "$tmp/runs.before" | sort)" "$(cut -d, -f1-25 "$tmp/s/runs.csv" | sort)"
# A machine that lost power may leave the appended line as NUL bytes: torn, dropped, run again.
cp "$tmp/s/runs.csv" "$tmp/runs.whole"; head -8 "$tmp/runs.whole" > "$tmp/s/runs.csv"; head -c 40 /dev/zero >> "$tmp/s/runs.csv"
sweep -o "$tmp/s" >"$tmp/log3" 2>&1
check "NUL tail: one run made again" "1 9" "$(grep -c '^sweep: 1 runs made now' "$tmp/log3") $(wc -l < "$tmp/s/runs.csv" | tr -d ' ')"

# A failed run is recorded as failed, kept on resuming, run again with --retry-failed.
printf 'axiom: A(1)\nsteps: 3\nproductions:\n  - A(x) -> I(0.1, 0.01) [ A(x) ] [ A(x) ]\norgans:\n  I: {prototype: cylinder, kind: internode}\n' > "$tmp/exp.yaml"
"$canopy" sweep "$tmp/exp.yaml" --steps 3,40 --seeds 1 --rows 1 --per-row 2 --max-modules 100000 --backend cpu -o "$tmp/f" >"$tmp/log4" 2>&1
check "failed: exit 3" "3" "$?"
check "failed: statuses" "ok failed" "$(col "$tmp/f/runs.csv" status)"
check "failed: message" "1" "$(python3 -c "
import csv; r=list(csv.DictReader(open('$tmp/f/runs.csv'))); print(int('module' in r[1]['message']))")"
"$canopy" sweep "$tmp/exp.yaml" --steps 3,40 --seeds 1 --rows 1 --per-row 2 --max-modules 100000 --backend cpu -o "$tmp/f" >"$tmp/log5" 2>&1
rc5=$?
check "failed: kept on resume, exit 3" "1 3" "$(grep -c '^sweep: 0 runs made now' "$tmp/log5") $rc5"
check "failed: resume names the kept failure" "1" \
  "$(grep -c '^sweep: 1 runs of .* are recorded as failed by an earlier call; --retry-failed runs them again' "$tmp/log5")"
# A grid without the failed run's cell: its failure is not this call's (exit 0, nothing said).
"$canopy" sweep "$tmp/exp.yaml" --steps 3 --seeds 1 --rows 1 --per-row 2 --max-modules 100000 --backend cpu -o "$tmp/f" >"$tmp/log5b" 2>&1
check "failed run outside the grid: exit 0" "0 0" "$? $(grep -c 'recorded as failed' "$tmp/log5b")"
# --retry-failed over that grid leaves the other cell's failure in runs.csv (it was erased).
"$canopy" sweep "$tmp/exp.yaml" --steps 3 --seeds 1 --rows 1 --per-row 2 --max-modules 100000 --backend cpu --retry-failed \
  -o "$tmp/f" >"$tmp/log5c" 2>&1
check "retry outside the failed cell keeps it" "0 ok failed" "$? $(col "$tmp/f/runs.csv" status)"
"$canopy" sweep "$tmp/exp.yaml" --steps 3,40 --seeds 1 --rows 1 --per-row 2 --max-modules 100000 --backend cpu --retry-failed \
  -o "$tmp/f" >"$tmp/log6" 2>&1
check "failed: retried" "1" "$(grep -c '^sweep: 1 runs made now (1 failed)' "$tmp/log6")"
check "failed: retried run keeps its number" "0:3 1:40" "$(python3 -c "
import csv; print(' '.join(r['run'] + ':' + r['steps'] for r in csv.DictReader(open('$tmp/f/runs.csv'))))")"

# A run keeps its number when the grid grows: the new runs take the numbers after the largest
# (numbered by their place in the grown grid, two runs shared a number).
grow() { "$canopy" sweep "$g" --plant-spacing 0.45 --steps 3,4 --rows 1 --per-row 2 --no-light --backend cpu -o "$tmp/n" "$@"; }
grow --seeds 1 >/dev/null 2>&1 && grow --seeds 2 >/dev/null 2>&1
check "grown grid: numbers" "0:3:1 1:4:1 2:3:2 3:4:2" "$(python3 -c "
import csv; print(' '.join(r['run'] + ':' + r['steps'] + ':' + r['seed'] for r in csv.DictReader(open('$tmp/n/runs.csv'))))")"

# The same sun written otherwise is the same sweep (compared as text, "60.0,180" was refused).
sunny() { "$canopy" sweep "$g" --plant-spacing 0.45 --steps 3 --seeds 1 --rows 1 --per-row 2 --backend cpu --light-error 0.05 -o "$tmp/sun" "$@"; }
sunny --sun 60,180 >/dev/null 2>&1
sunny --sun " 60.0,180" >"$tmp/o" 2>&1
check "sun written otherwise resumes" "0 1" "$? $(grep -c '^sweep: 0 runs made now' "$tmp/o")"
sunny --sun 61,180 >/dev/null 2>"$tmp/e"
check "another sun refused" "2 1" "$? $(grep -c 'made with other settings (light' "$tmp/e")"

# A range's values are the decimals it names (0.1:0.3:0.1 made 0.30000000000000004); a sweep begun
# with such a value resumes with it done and keeps one cell for it.
tiny() { "$canopy" sweep "$g" --plant-spacing 0.1:0.3:0.1 --rows 1 --per-row 2 --seeds 1 --steps 3 --no-light --backend cpu -o "$tmp/r" "$@"; }
tiny >"$tmp/o" 2>&1
check "range values" "0.1 0.2 0.3" "$(col "$tmp/r/runs.csv" plant_spacing)"
sed -i 's/^2,0.3,/2,0.30000000000000004,/' "$tmp/r/runs.csv"
tiny >"$tmp/o" 2>&1
check "earlier range value resumes" "0 1" "$? $(grep -c '^sweep: 0 runs made now' "$tmp/o")"
check "earlier range value adopted" "0.1 0.2 0.3|3" "$(col "$tmp/r/runs.csv" plant_spacing)|$(($(wc -l < "$tmp/r/summary.csv") - 1))"
# A failed run written with such a value keeps its number when it is run again.
python3 - "$tmp/r/runs.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for r in rows:
    if r["run"] == "2": r["plant_spacing"], r["status"] = "0.30000000000000004", "failed"
with open(sys.argv[1], "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n"); w.writeheader(); w.writerows(rows)
PY
tiny --retry-failed >"$tmp/o" 2>&1
check "earlier range value retried keeps its number" "0 0:0.1:ok 1:0.2:ok 2:0.3:ok" "$? $(python3 -c "
import csv; print(' '.join(r['run'] + ':' + r['plant_spacing'] + ':' + r['status'] for r in csv.DictReader(open('$tmp/r/runs.csv'))))")"
# Densities give plant spacings one rounding apart in different row-spacing cells (1/(2 x 0.6),
# 1/(1.5 x 0.8)): a finished sweep run again makes nothing and keeps its four cells.
dens() { "$canopy" sweep "$g" --row-spacing 0.6,0.8 --density 1.5,2 --steps 3 --seeds 1 --rows 1 --per-row 2 --no-light \
  --no-resolve --backend cpu -o "$tmp/dn"; }
dens >/dev/null 2>&1
dens >"$tmp/o" 2>&1
check "density sweep resumes" "1 5" "$(grep -c '^sweep: 0 runs made now (0 failed), 4 in' "$tmp/o") $(wc -l < "$tmp/dn/summary.csv")"
# Plots: a curve per age and row spacing (one per age joined the two row spacings' cells), in a
# folder whose name has a space; a cell whose runs all failed is a gap (NaN), not 0 contacts.
if command -v gnuplot >/dev/null; then
  cp -r "$tmp/dn" "$tmp/d n"
  bash "$src/tools/plot.sh" sweep "$tmp/d n" >/dev/null 2>&1
  check "plot: folder with a space, a curve per row spacing" "0 age_3_0.6.dat age_3_0.8.dat" \
    "$? $(cd "$tmp/d n/plot_data" && ls age_*.dat | tr '\n' ' ' | sed 's/ $//')"
  check "plot: rows named in titles" "1" "$(grep -c "age 3 steps, rows 0.6 m" "$tmp/d n/contacts_vs_density.svg" | sed 's/[2-9]/1/')"
  bash "$src/tools/plot.sh" sweep "$tmp/f" >/dev/null 2>&1
  check "plot: failed cell is a gap" "0 NaN" "$? $(cut -d' ' -f2 "$tmp/f/plot_data/age_40_1.dat")"
fi
# runs.csv as only a sweep writes it: a run's second row (pooled in the summary as another seed)
# and a torn line that is not the last (only a kill tears, and only the last) are refused by line.
cp "$tmp/r/runs.csv" "$tmp/r.good"
sed -n 3p "$tmp/r.good" >> "$tmp/r/runs.csv"
tiny >"$tmp/o" 2>"$tmp/e"
check "a run twice in runs.csv" "2 1" "$? $(grep -c 'runs.csv:5: the run of line 3 again (plant spacing 0.2' "$tmp/e")"
cp "$tmp/r.good" "$tmp/r/runs.csv"
sed -i '3s/,ok,.*$/,ok,9/' "$tmp/r/runs.csv"
tiny >"$tmp/o" 2>"$tmp/e"
check "a torn middle line" "2 1" "$? $(grep -c 'runs.csv:3: not a whole row of 43 columns, and not the last line' "$tmp/e")"
check "refusals leave runs.csv" "$(sed 3d "$tmp/r.good")" "$(sed 3d "$tmp/r/runs.csv")"

# A cell whose plants would stand past 1e8 m is refused before any run (each run failed alike),
# a density naming itself and its spacing; no folder is made.
"$canopy" sweep "$g" --density 1e-300 --rows 1 --per-row 2 --seeds 1 --steps 8 --backend cpu -o "$tmp/far" >"$tmp/o" 2>"$tmp/e"
check "far density refused up front" "2 1 0" \
  "$? $(grep -c 'density 1e-300 plants/m2 (a plant spacing of 1e+300 m at a row spacing of 1 m): --plant-spacing 1e+300 m: plants may stand at most' "$tmp/e") $(ls -d "$tmp/far" 2>/dev/null | wc -l)"
"$canopy" sweep "$g" --plant-spacing 0.4,1e9 --rows 1 --per-row 2 --seeds 1 --steps 8 --backend cpu -o "$tmp/far" >"$tmp/o" 2>"$tmp/e"
check "far spacing refused up front" "2 1 0" \
  "$? $(grep -c 'plant-spacing 1e+09 m: plants may stand at most 1e+08 m' "$tmp/e") $(ls -d "$tmp/far" 2>/dev/null | wc -l)"

# A sweep's light tile is its lattice (it has no --tile): a spacing too small for light fails the
# run naming the spacings.
"$canopy" sweep "$g" --plant-spacing 0.0001 --row-spacing 0.001 --rows 2 --per-row 3 --seeds 1 --steps 8 --backend cpu \
  -o "$tmp/small" >"$tmp/o" 2>&1
check "tiny lattice: the run fails" "3 1" "$? $(grep -c "failed: the light's tile is the stand's lattice (0.0003 x 0.002 m" "$tmp/o")"

# Bad specifications: a clear error, exit 2, no folder.
bad() {  # bad NAME PATTERN ARGS...
  local name=$1 pattern=$2; shift 2
  rm -rf "$tmp/bad"
  "$canopy" sweep "$g" "$@" -o "$tmp/bad" >"$tmp/o" 2>"$tmp/e"
  check "$name exit" "2" "$?"
  check "$name message" "1" "$(grep -c -- "$pattern" "$tmp/e")"
  check "$name no folder" "0" "$([ -e "$tmp/bad" ] && echo 1 || echo 0)"
}
bad "empty range" "range '0.5:0.3:0.1' is empty" --plant-spacing 0.5:0.3:0.1
bad "negative spacing" "\-\-plant-spacing: -0.3 must be greater than 0" --plant-spacing 0.3,-0.3
bad "zero step" "step of '0.3:0.5:0' must be positive" --row-spacing 0.3:0.5:0
bad "not a number" "'abc' is not a decimal number" --density 2,abc
bad "hexadecimal" "'0x10' is not a decimal number" --steps 3,0x10
bad "empty item" "empty item in '0.3,,0.4'" --plant-spacing 0.3,,0.4
bad "a value twice" "\-\-plant-spacing: 0.3 is given twice in '0.3,0.2,0.3'" --plant-spacing 0.3,0.2,0.3
bad "a density twice" "\-\-density: 2 is given twice" --density 2,3,2.0
bad "fractional steps" "10.5 is not a whole number" --steps 10.5
bad "sun below the horizon" "elevation -5 is not above the horizon" --sun -5,10
bad "sun not a pair" "'60' is not ELEVATION,AZIMUTH" --sun 60
bad "light error" "\-\-light-error: 0 is not in" --light-error 0
bad "range of 100,001 values" "has more than 100,000 values" --plant-spacing 1:100001:1
bad "range past a long" "has more than 100,000 values" --plant-spacing 0:1e30:1
bad "too many runs" "= 10010000000000 runs, more than the 1000000 a sweep takes" --plant-spacing 0.001:100:0.001 --steps 0:1000:1 --seeds 100000
# -o naming a file: refused by name.
touch "$tmp/afile"
"$canopy" sweep "$g" --seeds 1 -o "$tmp/afile" >"$tmp/o" 2>"$tmp/e"
check "sweep -o a file" "1 1" "$? $(grep -c "cannot create the sweep folder $tmp/afile: " "$tmp/e")"
# --density and --plant-spacing are two ways to say one thing: refused together (the parser's).
rm -rf "$tmp/bad"
"$canopy" sweep "$g" --density 5 --plant-spacing 0.3 -o "$tmp/bad" >"$tmp/o" 2>"$tmp/e"
check "density with plant spacing" "108 1 0" "$? $(grep -c 'excludes' "$tmp/e") $([ -e "$tmp/bad" ] && echo 1 || echo 0)"
# A light setting with --no-light was taken unread, mistakes and all (--sun junk ran).
"$canopy" sweep "$g" --no-light --sun junk -o "$tmp/bad" >"$tmp/o" 2>"$tmp/e"
check "light option with --no-light" "108 1 0" "$? $(grep -c 'excludes' "$tmp/e") $([ -e "$tmp/bad" ] && echo 1 || echo 0)"
# One sweep writes a folder at a time (two at once each ran every cell, and the summary pooled
# their duplicate rows): the folder's lock, held here as a running sweep holds it.
if command -v flock >/dev/null; then
  mkdir -p "$tmp/locked"
  flock "$tmp/locked/.sweep.lock" sleep 5 &
  holder=$!
  sleep 0.3
  "$canopy" sweep "$g" --rows 1 --per-row 2 --plant-spacing 0.4 --steps 4 --seeds 1 --no-light -o "$tmp/locked" >"$tmp/o" 2>"$tmp/e"
  check "a folder another sweep writes" "2 1 .sweep.lock" "$? $(grep -c 'another canopy sweep is writing' "$tmp/e") $(ls -A "$tmp/locked")"
  # A stand run that replaces the folder meanwhile keeps the lock (a lock on the folder itself
  # stayed with the folder swapped away, and a second sweep ran beside the first).
  "$canopy" stand "$g" --rows 1 --per-row 2 --steps 4 -o "$tmp/locked" >/dev/null 2>&1
  "$canopy" sweep "$g" --rows 1 --per-row 2 --plant-spacing 0.4 --steps 4 --seeds 1 --no-light -o "$tmp/locked" >"$tmp/o" 2>"$tmp/e"
  check "a folder another sweep writes, replaced by a stand" "2 1" "$? $(grep -c 'another canopy sweep is writing' "$tmp/e")"
  kill "$holder" 2>/dev/null; wait "$holder" 2>/dev/null
fi

help=$("$canopy" sweep --help)
for opt in --plant-spacing --row-spacing --density --steps --seeds --rows --per-row --jitter --retry-failed --no-resolve --sun --sky \
  --sky-directions --light-error --no-light; do
  check "help $opt" "1" "$(grep -q -- "$opt" <<<"$help" && echo 1 || echo 0)"
done
# --no-random-rotation: every plant facing the same way, recorded in sweep.json (both ways given
# at once is refused).
"$canopy" sweep "$g" --plant-spacing 0.3 --steps 10 --seeds 1 --rows 1 --per-row 3 --no-light --backend cpu \
  --no-random-rotation -o "$tmp/nr" >/dev/null 2>&1
check "sweep --no-random-rotation" "0 False" "$? $(python3 -c "import json; print(json.load(open('$tmp/nr/sweep.json')).get('random_rotation', True))")"
"$canopy" sweep "$g" --plant-spacing 0.3 --steps 10 --seeds 1 --rows 1 --per-row 3 --no-light --backend cpu \
  --random-rotation --no-random-rotation -o "$tmp/nr2" >/dev/null 2>&1
check "sweep: both rotations refused" "108" "$?"
# A row the file-size limit cut is cut off again: runs.csv keeps whole rows (the disk filling does
# the same); the run says why.
( ulimit -f 2; "$canopy" sweep "$g" --seeds 12 --rows 2 --per-row 3 --steps 10 --no-light --backend cpu \
  -o "$tmp/xf" >/dev/null 2>"$tmp/e" )
check "sweep past a file-size limit" "1:1" "$?:$(grep -c 'cannot append to .*runs.csv: File too large' "$tmp/e")"
check "sweep past a file-size limit: whole rows" "True" "$(python3 -c "
import csv; r=list(csv.reader(open('$tmp/xf/runs.csv'))); print(len(r) > 2 and all(len(x) == len(r[0]) for x in r))")"

echo "$pass passed, $failures failed"
[ "$failures" -eq 0 ]
