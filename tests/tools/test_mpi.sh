#!/usr/bin/env bash
# Tiled runs over MPI, for fields beyond one machine: `mpirun -np P canopy stand` on 1, 2
# and 4 ranks (oversubscribed on this machine) writes the same files, byte for byte, as one
# process (report.json compared without its timings and device); stands whose contacts cross
# tile borders, with and without resolution; a tile with no plants; plants exactly on a border;
# a rank that fails stops every rank with the error and leaves no files; sweeps spread over ranks.
# Usage: CANOPY=path/to/canopy test_mpi.sh SOURCE_DIR
set -u
src=$1
canopy=${CANOPY:?set CANOPY to the canopy binary}
source "$(dirname "$0")/check.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_NUM_THREADS=1
mpi() { local np=$1; shift; timeout 600 mpirun --oversubscribe -np "$np" "$canopy" "$@"; }

# Where mpirun itself cannot start two processes (no OpenMPI runtime in a container, say), say
# so and report the suite as skipped (exit 77), not passed.
if ! timeout 120 mpirun --oversubscribe -np 2 true >"$tmp/mpirun.log" 2>&1; then
  echo "mpi: SKIPPED: mpirun cannot start two processes here:"
  head -20 "$tmp/mpirun.log"
  exit 77
fi

# The report without what may differ between runs: timings, the device name, per-round seconds,
# the output folder.
strip_report() {
  python3 -c "
import json, sys
j = json.load(open(sys.argv[1]))
j.pop('timings_s', None); j.pop('peak_memory_gb', None); j.pop('device', None); j['config'].pop('out', None)
r = j.get('resolution')
if r:
    for x in r['rounds']: x.pop('plan_s'); x.pop('detect_s')
print(json.dumps(j, indent=1))" "$1"
}
# Every file of $2 equals $1's; prints the names that differ.
same_files() {
  local diffs=""
  [ "$(ls "$1" | tr '\n' ' ')" == "$(ls "$2" | tr '\n' ' ')" ] || diffs="file list"
  for f in "$1"/*; do
    b=$(basename "$f")
    if [ "$b" == report.json ]; then
      [ "$(strip_report "$f")" == "$(strip_report "$2/$b" 2>/dev/null)" ] || diffs="$diffs $b"
    else
      cmp -s "$f" "$2/$b" || diffs="$diffs $b"
    fi
  done
  echo "${diffs:-same}"
}
# Runs `canopy stand ARGS` in one process and on each rank count, compares the folders.
compare() {
  local name=$1 ranks=$2; shift 2
  "$canopy" stand "$@" -o "$tmp/$name-1p" >"$tmp/$name-1p.log" 2>&1
  check "$name: one process" "0" "$?"
  for np in $ranks; do
    mpi "$np" stand "$@" -o "$tmp/$name-$np" >"$tmp/$name-$np.log" 2>&1
    check "$name: $np ranks exit" "0" "$?"
    check "$name: $np ranks files" "same" "$(same_files "$tmp/$name-1p" "$tmp/$name-$np")"
  done
}
contacts() { echo $(($(wc -l < "$1/contacts.csv") - 1)); }

g="$src/grammars/tomato.yaml"
# Two long dense rows: 4 strips of 30 plants, halos (about 5 m) shorter than the field (18 m),
# so tiles hold only part of it and contacts cross every border; resolution on.
compare rows "1 2 4" "$g" --rows 2 --per-row 60 --plant-spacing 0.3 --jitter 0.02 --random-rotation --seed 3 --formats glb,ply
check "rows: contacts found" "yes" "$([ "$(contacts "$tmp/rows-1p")" -gt 500 ] && echo yes || echo no)"
check "rows: tiles smaller than the field" "yes" \
  "$(grep -q 'tiles: 4 ranks, strips across x' "$tmp/rows-4.log" && ! grep -q '; 120 plants here' "$tmp/rows-4.log" && echo yes || echo no)"
# Many short rows (strips across y), detection only, at the leaf level, with OBJ and the compact glb.
compare leaf "2 4" "$g" --rows 16 --per-row 4 --row-spacing 0.5 --plant-spacing 0.35 --steps 16 --no-resolve --level leaf \
  --formats obj,glb --glb-compact
# A clearance and organ-level resolution on 3 ranks.
compare clear "3" "$g" --rows 1 --per-row 40 --plant-spacing 0.28 --steps 18 --clearance 0.002 --resolve-level organ --formats ply

# A positions file: four ranks for three plants (a tile with no plants), and plants exactly on
# the border between two tiles (same x: one goes to each tile), touching each other.
cat >"$tmp/pos.csv" <<'CSV'
x,y,rotation,seed
0,0,0,1
0.3,0,40,2
0.3,0.2,80,3
CSV
compare empty_tile "4" "$g" --positions "$tmp/pos.csv"
cat >"$tmp/border.csv" <<'CSV'
x,y,rotation,seed
0,0,0,1
0.35,0,0,2
0.7,0,30,3
0.7,0.25,60,4
1.05,0,0,5
1.4,0,90,6
CSV
compare border "2" "$g" --positions "$tmp/border.csv"
check "border: contacts between the two plants on it" "yes" \
  "$(awk -F, '($3==2&&$4==3)||($3==3&&$4==2){f=1} END{print f?"yes":"no"}' "$tmp/border-1p/contacts.csv")"

# A rank that fails (its plant's grammar is malformed): every rank says so, nothing is written.
printf 'name: bad\naxiom: A\nproductions: [\n' >"$tmp/bad.yaml"
cat >"$tmp/bad.csv" <<CSV
x,y,rotation,seed,grammar
0,0,0,1,
5,0,0,2,
10,0,0,3,
15,0,0,4,bad.yaml
CSV
mpi 2 stand "$g" --positions "$tmp/bad.csv" -o "$tmp/failed" >"$tmp/failed.log" 2>&1
check "failing rank: exit code" "nonzero" "$([ $? -ne 0 ] && echo nonzero || echo zero)"
check "failing rank: every rank reports it" "2" "$(grep -c 'rank 1 of 2 failed: .*bad.yaml:4:1' "$tmp/failed.log")"
check "failing rank: no files" "" "$(ls -A "$tmp/failed" 2>/dev/null)"
# Tiled runs swap their folder in as one process does: nothing of theirs is left beside it.
check "no staging folders left" "0" "$(ls -A "$tmp" | grep -c '\.canopy-')"

# Sweeps: runs spread over the ranks give the rows one process gives (times aside), and a sweep
# resumed under mpirun with more seeds makes only the new runs.
untimed() { python3 -c "
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    print(','.join(v for k, v in r.items() if not k.endswith('_s') and k != 'run'))" "$1"; }
sweep=(sweep "$g" --plant-spacing 0.3,0.5 --steps 14 --rows 2 --per-row 3)
"$canopy" "${sweep[@]}" --seeds 3 -o "$tmp/sweep-1p" >/dev/null 2>&1
check "sweep: one process" "0" "$?"
mpi 3 "${sweep[@]}" --seeds 2 -o "$tmp/sweep-3" >"$tmp/sweep-3.log" 2>&1
check "sweep: 3 ranks exit" "0" "$?"
mpi 2 "${sweep[@]}" --seeds 3 -o "$tmp/sweep-3" >"$tmp/sweep-3b.log" 2>&1
check "sweep: resumed on 2 ranks exit" "0" "$?"
check "sweep: resumed makes only the new runs" "1" "$(grep -c '^sweep: 2 runs made now (0 failed), 6 in' "$tmp/sweep-3b.log")"
check "sweep: rows as one process" "$(untimed "$tmp/sweep-1p/runs.csv" | sort)" "$(untimed "$tmp/sweep-3/runs.csv" | sort)"
check "sweep: summary written" "yes" "$([ -s "$tmp/sweep-3/summary.csv" ] && echo yes || echo no)"

echo "mpi: $pass passed, $failures failed"
[ "$failures" -eq 0 ]
