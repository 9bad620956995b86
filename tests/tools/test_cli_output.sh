#!/usr/bin/env bash
# Output folders and failures (docs/design.md): positions past the bound refused by name, a
# failed run leaves the file system as it was, a run replaces a folder's stand as one unit and
# keeps the rest, a run stopped by SIGINT, SIGTERM or SIGKILL leaves nothing (SIGINT and SIGTERM
# say so), plants on one spot refused before their contact lists outgrow memory.
# Usage: CANOPY=path/to/canopy test_cli_output.sh SOURCE_DIR
set -u
src=$(cd "$1" && pwd)
canopy=${CANOPY:?set CANOPY to the canopy binary}
source "$(dirname "$0")/check.sh"
g=$src/grammars/tomato.yaml
small=(--rows 1 --per-row 3 --steps 10 --backend cpu)
hidden() { ls -A "$1" | grep -c '\.canopy-'; }  # staging folders and probes beside an output

# Positions, spacings and jitter that the exports cannot write faithfully: refused by name, up
# front (1e57 wrote 860 bytes of stack memory into stand.obj and exited 0).
printf 'x,y,rotation,seed\n1e57,0,0,1\n' >"$tmp/far.csv"
"$canopy" stand "$g" --positions "$tmp/far.csv" --steps 8 -o "$tmp/far" >"$tmp/o" 2>"$tmp/e"
check "far position exit" "2" "$?"
check "far position message" "canopy: error: $tmp/far.csv:2:1: column 'x' is 1e57 m: plants may stand at most 1e+08 m from the origin" "$(cat "$tmp/e")"
check "far position no folder" "no" "$([ -e "$tmp/far" ] && echo yes || echo no)"
"$canopy" stand "$g" --rows 1 --per-row 2 --plant-spacing 1e300 --steps 8 -o "$tmp/far" >"$tmp/o" 2>"$tmp/e"
check "far spacing exit" "2" "$?"
check "far spacing message" "1" "$(grep -c -- '^canopy: error: --plant-spacing 1e+300 m: plants may stand at most 1e+08 m' "$tmp/e")"
"$canopy" stand "$g" --rows 1 --per-row 1 --jitter 1e9 --steps 8 -o "$tmp/far" >"$tmp/o" 2>"$tmp/e"
check "far jitter message" "1" "$(grep -c -- '^canopy: error: --jitter 1e+09 m:' "$tmp/e")"
# At 10^7 m the OBJ holds the coordinates as text, nothing else.
printf 'x,y,rotation,seed\n1e7,-1e7,0,1\n' >"$tmp/utm.csv"
"$canopy" stand "$g" --positions "$tmp/utm.csv" --steps 8 --formats obj --backend cpu -o "$tmp/utm" >/dev/null 2>&1
check "far stand exit" "0" "$?"
check "far stand obj is text" "0" "$(LC_ALL=C grep -c '[^[:print:][:space:]]' "$tmp/utm/stand.obj")"
check "far stand obj coordinates" "1" "$(grep -m1 '^v ' "$tmp/utm/stand.obj" | awk '{print ($2 > 9999998 && $2 < 10000002 && $3 < -9999998 && $3 > -10000002)}')"

# A failed run leaves the file system as it was: no empty output folder, no folder above it.
printf 'axiom: I(1, 0.1)\nsteps: 1\nproductions:\n  - I(a, b) -> I(a - 2, b)\norgans:\n  I: {prototype: cylinder, kind: internode}\n' >"$tmp/neg.yaml"
"$canopy" stand "$tmp/neg.yaml" -o "$tmp/made/above/out" >/dev/null 2>"$tmp/e"
check "failed run exit" "1" "$?"
check "failed run: no folder made" "no" "$([ -e "$tmp/made" ] && echo yes || echo no)"
check "failed run: nothing beside" "0" "$(hidden "$tmp")"

# A replaced stand folder: the earlier stand's files go as a set (meshes in formats not written
# again, light tables computed from it), the user's files (the same inode) and folders stay.
out=$tmp/keep
"$canopy" stand "$g" "${small[@]}" --formats glb,ply -o "$out" >/dev/null 2>&1
echo mine >"$out/notes.txt"
mkdir -p "$out/renders/old" && echo png >"$out/renders/old/a.png"
echo 0.5 >"$out/light.csv" && echo '{}' >"$out/light.json"
inode=$(stat -c %i "$out/notes.txt")
"$canopy" stand "$g" "${small[@]}" --seed 7 -o "$out" >"$tmp/o" 2>&1
check "replace exit" "0" "$?"
check "replace: files" "contacts.csv contacts_after.csv notes.txt organs.csv plants.csv renders report.json stand.glb" "$(LC_ALL=C ls "$out" | tr '\n' ' ' | sed 's/ $//')"
check "replace: user file the same" "$inode" "$(stat -c %i "$out/notes.txt")"
check "replace: user folder" "png" "$(cat "$out/renders/old/a.png")"
check "replace: meshes named" "1" "$(grep -c '^removed stand.ply left by an earlier run (a format not asked for this time)' "$tmp/o")"
check "replace: light named" "1" "$(grep -c '^removed light.csv, light.json, which described the earlier stand' "$tmp/o")"
check "replace: new seed" "7" "$(python3 -c "import json;print(json.load(open('$out/report.json'))['seed'])")"
check "replace: nothing beside" "0" "$(hidden "$tmp")"
# The working folder is written in place (a swap would leave the shell in a removed folder): the
# same folder, the new set, the user's files kept, nothing hidden left in it or beside it.
folder_inode=$(stat -c %i "$out")
(cd "$out" && "$canopy" stand "$g" "${small[@]}" --seed 9 -o . >/dev/null 2>"$tmp/e")
check "working folder: exit" "0" "$?"
check "working folder: the same folder" "$folder_inode" "$(stat -c %i "$out")"
check "working folder: new seed" "9" "$(python3 -c "import json;print(json.load(open('$out/report.json'))['seed'])")"
check "working folder: user file" "$inode" "$(stat -c %i "$out/notes.txt")"
check "working folder: nothing hidden" "0 0" "$(hidden "$tmp") $(hidden "$out")"
(cd "$out" && "$canopy" detect . --backend cpu >/dev/null 2>&1)
check "working folder: read back" "0" "$?"

# SIGINT and SIGTERM during a run: the run ends by the signal, said on stderr, nothing of it is
# left on disk (its files have no name until the set is complete), the earlier stand untouched.
# (Job control on: a script's background jobs ignore SIGINT.)
set -m
sums() { (cd "$1" && md5sum organs.csv plants.csv report.json stand.glb); }
before=$(sums "$out")
long=(--rows 3 --per-row 100 --backend cpu --formats glb,obj,ply)
# Waits until process $1 writes its files (it then holds unnamed files: its open files read
# "(deleted)"), at most 20 s.
writing() {
  for _ in $(seq 1 4000); do
    ls -l /proc/$1/fd 2>/dev/null | grep -q '(deleted)' && return 0
    sleep 0.005
  done
  return 1
}
for sig in INT TERM; do
  "$canopy" stand "$g" "${long[@]}" -o "$out" >/dev/null 2>"$tmp/e$sig" &
  pid=$!
  writing $pid
  kill -$sig $pid
  wait $pid
  rc=$?
  check "SIG$sig exit" "$([ $sig = INT ] && echo 130 || echo 143)" "$rc"
  check "SIG$sig said" "1" "$(grep -c "^canopy: stopped by SIG$sig" "$tmp/e$sig")"
  check "SIG$sig nothing beside" "0" "$(hidden "$tmp")"
  check "SIG$sig earlier stand whole" "$before" "$(sums "$out")"
done
# SIGKILL cannot be caught: still nothing is left, also when it comes while the files are being
# written (the process then holds unnamed files: its open files read "(deleted)").
for when in start export; do
  "$canopy" stand "$g" "${long[@]}" -o "$out" >/dev/null 2>&1 &
  pid=$!
  if [ $when = start ]; then sleep 0.1; else writing $pid; fi
  kill -KILL $pid 2>/dev/null
  wait $pid 2>/dev/null
  rc=$?
  if [ $rc = 137 ]; then
    check "SIGKILL at $when: nothing beside" "0" "$(hidden "$tmp")"
    check "SIGKILL at $when: earlier stand whole" "$before" "$(sums "$out")"
  else
    echo "SIGKILL at $when: not checked (the run ended before the signal, status $rc)"
    before=$(sums "$out")
  fi
done
set +m

# Killed at any moment, a folder holds one whole stand: its tables agree with its report.
for delay in 0.2 0.5 0.9 1.4 2.0 0.05 0.35 0.7; do
  per=$((3 + 10#${delay//[^0-9]/} % 4))
  timeout -s KILL "$delay" "$canopy" stand "$g" --rows 1 --per-row $per --steps 12 --backend cpu --formats glb,obj -o "$tmp/mix" >/dev/null 2>&1
  if [ -d "$tmp/mix" ]; then
    whole=$(python3 - "$tmp/mix" <<'EOF'
import json, sys
d = sys.argv[1]
r = json.load(open(d + "/report.json"))
plants = sum(1 for _ in open(d + "/plants.csv")) - 1
organs = sum(1 for _ in open(d + "/organs.csv")) - 1
print(plants == r["counts"]["plants"] and organs == r["counts"]["organs"])
EOF
)
    check "killed after $delay s: one whole stand" "True" "$whole"
  fi
done
"$canopy" stand "$g" "${small[@]}" -o "$tmp/mix" >/dev/null 2>&1
check "after the kills: nothing beside" "0" "$(hidden "$tmp")"

# A run never writes over what it reads: positions given as the output folder's plants.csv (or a
# link to it), a grammar named as one of its files. The user's file stays as it was.
mkdir -p "$tmp/field" && printf 'x,y,rotation,seed\n0,0,0,1\n1,0,0,2\n' > "$tmp/field/plants.csv"
sums_pos=$(md5sum < "$tmp/field/plants.csv")
"$canopy" stand "$g" --positions "$tmp/field/plants.csv" --steps 8 --backend cpu -o "$tmp/field" >"$tmp/o" 2>"$tmp/e"
check "positions in the output folder refused" "2 1 $sums_pos 0" \
  "$? $(grep -c "this would replace $tmp/field/plants.csv, the positions file this run reads" "$tmp/e") $(md5sum < "$tmp/field/plants.csv") $(wc -c < "$tmp/o")"
ln -s "$tmp/field/plants.csv" "$tmp/pos_link.csv"
"$canopy" stand "$g" --positions "$tmp/pos_link.csv" --steps 8 --backend cpu -o "$tmp/field" >/dev/null 2>"$tmp/e"
check "positions through a link refused" "2 $sums_pos" "$? $(md5sum < "$tmp/field/plants.csv")"
cp "$g" "$tmp/field/report.json"
"$canopy" stand "$tmp/field/report.json" --rows 1 --per-row 2 --steps 8 --backend cpu -o "$tmp/field" >/dev/null 2>"$tmp/e"
check "grammar in the output folder refused" "2 1" "$? $(grep -c "report.json, the grammar this run reads" "$tmp/e")"

# A folder named with 240 bytes (a name may have 255): its staging folder's name is shortened to
# fit (it passed the limit: "File name too long"); made, then replaced, nothing left beside it.
mkdir -p "$tmp/long" && long="$tmp/long/$(printf 'a%.0s' $(seq 240))"
"$canopy" stand "$g" --rows 1 --per-row 2 --steps 8 --backend cpu -o "$long" >/dev/null 2>"$tmp/e" &&
  "$canopy" stand "$g" --rows 1 --per-row 3 --steps 8 --backend cpu -o "$long" >/dev/null 2>>"$tmp/e"
check "240-byte folder name" "0 4 1" "$? $(wc -l < "$long/plants.csv") $(ls -A "$tmp/long" | wc -l)"

# A folder of the user's that holds no stand (no organs.csv): their files of a stand file's name
# stay unless the run writes them again.
mkdir -p "$tmp/mine" && echo "my mesh" > "$tmp/mine/stand.obj" && echo "notes" > "$tmp/mine/notes.txt"
"$canopy" stand "$g" "${small[@]}" -o "$tmp/mine" >/dev/null 2>&1
check "user's folder: their stand.obj kept" "0 my mesh|notes" "$? $(cat "$tmp/mine/stand.obj")|$(cat "$tmp/mine/notes.txt")"
# canopy detect --csv: never over the stand it reads; a link stays a link, a FIFO a FIFO.
sums_nr=$(md5sum < "$tmp/mine/organs.csv")
"$canopy" detect "$tmp/mine" --csv "$tmp/mine/organs.csv" >/dev/null 2>"$tmp/e"
check "detect --csv over organs.csv refused" "2 1 $sums_nr" "$? $(grep -c "stand folder's own organs.csv" "$tmp/e") $(md5sum < "$tmp/mine/organs.csv")"
# ... nor into a folder, nor in a folder that is not there: said before detecting, nothing printed.
"$canopy" detect "$tmp/mine" --csv "$tmp/nodir/x.csv" >"$tmp/o" 2>"$tmp/e"
check "detect --csv in no folder" "2 0 canopy: error: --csv $tmp/nodir/x.csv: there is no folder $tmp/nodir to write it in" \
  "$? $(wc -c < "$tmp/o") $(cat "$tmp/e")"
"$canopy" detect "$tmp/mine" --csv "$tmp/mine" >"$tmp/o" 2>"$tmp/e"
check "detect --csv a folder" "2 0 canopy: error: --csv $tmp/mine: a folder; name the CSV file to write" \
  "$? $(wc -c < "$tmp/o") $(cat "$tmp/e")"
echo old > "$tmp/target.csv" && ln -sf target.csv "$tmp/link.csv"
"$canopy" detect "$tmp/mine" --csv "$tmp/link.csv" >/dev/null 2>&1
check "detect --csv through a link" "link organ_a,organ_b,plant_a,plant_b,level" \
  "$([ -L "$tmp/link.csv" ] && echo link || echo replaced) $(head -1 "$tmp/target.csv")"
echo "before" > "$tmp/log.txt"
"$canopy" detect "$tmp/mine" --csv /dev/stdout >>"$tmp/log.txt" 2>/dev/null
check "detect --csv /dev/stdout appends to the redirected file" "before 1" \
  "$(head -1 "$tmp/log.txt") $(grep -c '^organ_a,organ_b,plant_a,plant_b,level$' "$tmp/log.txt")"
mkfifo "$tmp/fifo"
timeout 20 cat "$tmp/fifo" > "$tmp/from_fifo" &
timeout 20 "$canopy" detect "$tmp/mine" --csv "$tmp/fifo" >/dev/null 2>&1
wait $!
check "detect --csv into a FIFO" "fifo organ_a,organ_b,plant_a,plant_b,level" \
  "$([ -p "$tmp/fifo" ] && echo fifo || echo replaced) $(head -1 "$tmp/from_fifo")"

# Plants on one spot: refused before their contact lists outgrow memory (100,000 took the
# machine's memory; 200 already make 2.1 million contacts).
# Checked where 100,000 plants' 5e9 pairs outgrow the memory (below 320 GB available).
if [ "$(awk '/^MemAvailable:/ {print ($2 < 300e6)}' /proc/meminfo)" = 1 ]; then
python3 -c "
print('x,y,rotation,seed')
for i in range(100000): print(f'0,0,{i * 7 % 360},{i + 1}')" >"$tmp/spot.csv"
timeout 600 "$canopy" stand "$g" --positions "$tmp/spot.csv" --steps 3 --backend cpu -o "$tmp/spot" >/dev/null 2>"$tmp/e"
check "one spot exit" "1" "$?"
check "one spot message" "1" "$(grep -c "^canopy: error: the plants' bounds meet in more than .* pairs (plants on or near one spot?)" "$tmp/e")"
check "one spot no folder" "no" "$([ -e "$tmp/spot" ] && echo yes || echo no)"
fi

# -o through a link and "..": the folder the kernel names (L/../Z with L -> X/Y is X/Z), never
# the ./Z that reading the path as text gave.
mkdir -p "$tmp/dd/X/Y" && ln -s X/Y "$tmp/dd/L"
"$canopy" stand "$g" --rows 1 --per-row 2 --steps 6 -o "$tmp/dd/Z" >/dev/null 2>&1
(cd "$tmp/dd" && "$canopy" stand "$g" --rows 1 --per-row 3 --steps 6 -o L/../Z >/dev/null 2>&1)
check "-o L/../Z: the kernel's folder" "0:3:2" "$?:$(($(wc -l < "$tmp/dd/X/Z/plants.csv") - 1)):$(($(wc -l < "$tmp/dd/Z/plants.csv") - 1))"

# A file-size limit (ulimit -f) killed the run by SIGXFSZ without a word, leaving its temporaries:
# the write fails instead, and the run ends as on any write error.
mkdir -p "$tmp/xfsz"
( ulimit -f 1000; "$canopy" stand "$g" --rows 2 --per-row 5 --seed 4 -o "$tmp/xfsz/st" >/dev/null 2>"$tmp/e" )
check "file-size limit: one line, exit 1" "1:1" "$?:$(grep -c '^canopy: error: writing .*: File too large$' "$tmp/e")"
check "file-size limit: nothing left" "" "$(ls -A "$tmp/xfsz")"

echo "$pass passed, $failures failed"
[ "$failures" -eq 0 ]
