#!/usr/bin/env bash
# The benchmark programs' arguments: --help prints a usage line and exits 0, an unknown option or
# one missing its value exits 2, a grammar that cannot be read exits 1, and in every such case
# nothing is run and the CSV named with --csv is left as it was (bench_derive --help used to
# truncate it, bench_generate --help to run the whole benchmark over it).
# Usage: BENCH_DIR=folder/of/the/bench/programs test_bench_args.sh SOURCE_DIR
set -u
src=$1
dir=${BENCH_DIR:?set BENCH_DIR to the folder of the benchmark programs}
source "$(dirname "$0")/check.sh"
cd "$src" || exit 1

csv=$tmp/kept.csv
earlier=$'earlier,rows\n1,2'  # what the CSV holds before each run, and must hold after it
kept() { printf '%s\n' "$earlier" > "$csv"; }
for prog in bench_derive bench_generate bench_detect bench_resolve bench_scale bench_light bench_stand bench_architecture; do
  [ -x "$dir/$prog" ] || { echo "skip $prog (not built here)"; continue; }
  kept
  out=$(timeout 60 "$dir/$prog" --csv "$csv" --help 2>/dev/null); rc=$?
  check "$prog --help exit" "0" "$rc"
  check "$prog --help usage" "1" "$(grep -c -m1 '^usage: ' <<<"$out")"
  check "$prog --help leaves the CSV" "$earlier" "$(cat "$csv")"
  kept
  timeout 60 "$dir/$prog" --csv "$csv" --no-such-option >/dev/null 2>&1; rc=$?
  check "$prog unknown option exit" "2" "$rc"
  check "$prog unknown option leaves the CSV" "$earlier" "$(cat "$csv")"
done
if [ -x "$dir/bench_light" ]; then
  kept
  timeout 60 "$dir/bench_light" --plants 10,abc --csv "$csv" >/dev/null 2>&1; rc=$?
  check "bench_light bad number exit" "2" "$rc"
  check "bench_light bad number leaves the CSV" "$earlier" "$(cat "$csv")"
fi
if [ -x "$dir/bench_derive" ]; then
  kept
  timeout 60 "$dir/bench_derive" grammars/classic/abop_1_24a.yaml "$tmp/missing.yaml" --repeats 1 --csv "$csv" >/dev/null 2>"$tmp/err"; rc=$?
  check "bench_derive missing grammar exit" "1" "$rc"
  check "bench_derive missing grammar message" "1" "$(grep -c "missing.yaml: cannot open the grammar file" "$tmp/err")"
  check "bench_derive missing grammar leaves the CSV" "$earlier" "$(cat "$csv")"
  timeout 60 "$dir/bench_derive" grammars/classic/abop_1_24a.yaml --csv >/dev/null 2>&1; rc=$?
  check "bench_derive --csv without a value exit" "2" "$rc"
  timeout 60 "$dir/bench_derive" grammars/classic/abop_1_24a.yaml:2 --repeats 1 --csv "$csv" >/dev/null 2>&1; rc=$?
  check "bench_derive run exit" "0" "$rc"
  check "bench_derive run rows" "grammar,engine,steps,final_modules|grammars/classic/abop_1_24a.yaml,canopy,2,61" \
    "$(head -2 "$csv" | cut -d, -f1-4 | paste -sd'|')"
fi
if [ -x "$dir/bench_generate" ]; then
  kept
  timeout 60 "$dir/bench_generate" --csv "$csv" --sizes >/dev/null 2>&1; rc=$?
  check "bench_generate --sizes without a value exit" "2" "$rc"
  check "bench_generate --sizes without a value leaves the CSV" "$earlier" "$(cat "$csv")"
fi
if [ -x "$dir/bench_detect" ]; then
  # With one thread available it runs the one-thread rows once (it used to run none at all).
  OMP_NUM_THREADS=1 timeout 120 "$dir/bench_detect" --sizes 20 --fcl-max 0 --repeats 1 --csv "$csv" >/dev/null 2>&1; rc=$?
  check "bench_detect on one thread exit" "0" "$rc"
  check "bench_detect on one thread: its query row" "1" "$(grep -c '^20,[^,]*,[^,]*,1,mbvt,query(exact),' "$csv")"
  check "bench_detect on one thread: no other thread count" "0" "$(grep -vc '^plants,\|^20,[^,]*,[^,]*,1,' "$csv")"
fi
if [ -x "$dir/bench_stand" ]; then
  # A tiny run: one row of canopy stand's stages (times never asserted), in a folder of its own
  # that it leaves as it found it; a size the default stand cannot have is refused.
  kept
  timeout 60 "$dir/bench_stand" --csv "$csv" --sizes 150 >/dev/null 2>"$tmp/err"; rc=$?
  check "bench_stand odd size exit" "2" "$rc"
  check "bench_stand odd size message" "1" "$(grep -c 'not a size of the default stand' "$tmp/err")"
  check "bench_stand odd size leaves the CSV" "$earlier" "$(cat "$csv")"
  mkdir -p "$tmp/stand"
  timeout 300 "$dir/bench_stand" --sizes 3 --steps 8 --backend cpu --disk-mb 4 --dir "$tmp/stand" --csv "$csv" >"$tmp/out" 2>&1; rc=$?
  check "bench_stand run exit" "0" "$rc"
  check "bench_stand run rows" "2" "$(wc -l < "$csv" | tr -d ' ')"
  check "bench_stand run header" "plants,organs_per_plant,triangles_per_plant,backend,device,threads,formats,end_to_end_s,startup_s" \
    "$(head -1 "$csv" | cut -d, -f1-9)"
  check "bench_stand run fields" "34 34" "$(awk -F, '{print NF}' "$csv" | paste -sd' ')"
  check "bench_stand run row" "3,cpu,glb" "$(sed -n 2p "$csv" | cut -d, -f1,4,7)"
  check "bench_stand run contacts after" "0" "$(sed -n 2p "$csv" | cut -d, -f29)"
  if python3 -c "
with open('/proc/self/clear_refs', 'w') as f: f.write('5')" 2>/dev/null; then
    check "bench_stand peaks (run, grow, detect, resolve, export) above 0" "5" \
      "$(sed -n 2p "$csv" | cut -d, -f22-26 | tr ',' '\n' | awk '$1 > 0' | wc -l | tr -d ' ')"
  fi
  check "bench_stand leaves its folder empty" "" "$(ls -A "$tmp/stand")"
fi

echo "$pass passed, $failures failed"
[ "$failures" -eq 0 ]
