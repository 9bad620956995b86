#!/usr/bin/env bash
# Bad input to every reader and option of canopy: a one-line located `canopy: error:` with a clear
# bound, never a crash, a hang, an unbounded read or a silent default (docs/cli.md, "Limits and
# refusals"). Cases that crashed or ran for ever run under `timeout`, so a regression fails here
# instead of stalling the suite. Usage: CANOPY=path/to/canopy test_cli_input.sh SOURCE_DIR
set -u
src=$1
canopy=${CANOPY:?set CANOPY to the canopy binary}
source "$(dirname "$0")/check.sh"
g="$src/grammars/tomato.yaml"
cd "$tmp"
# run NAME ARGS...: runs canopy (at most 60 s), keeps the exit status in $rc and stderr in $tmp/err.
run() { timeout 60 "$canopy" "$@" >"$tmp/out" 2>"$tmp/err"; rc=$?; }
err() { cat "$tmp/err"; }
lines() { wc -l < "$tmp/err" | tr -d ' '; }

# Expressions nested past the parser's bound: a located error (30,000 '(' was a stack overflow).
python3 -c "print('axiom: A(' + '('*30000 + '1' + ')'*30000 + ')')" > deep.yaml
run derive deep.yaml
check "deep parentheses" "1:canopy: error: deep.yaml:1:266: expression nested too deeply (more than 256 levels of parentheses, unary operators or calls)" "$rc:$(err)"
python3 -c "print('constants:\n  k: ' + '-'*100000 + '1\naxiom: A(k)')" > deep_constant.yaml
run derive deep_constant.yaml
check "deep unary minus in a constant" "1:1" "$rc:$(grep -c '^canopy: error: deep_constant.yaml:2:.*nested too deeply' "$tmp/err")"

# Files that are not regular files are refused at once (/dev/zero was read until memory ran out).
(ulimit -v 4000000; run derive /dev/zero; echo "$rc:$(err)" > devzero)
check "derive /dev/zero" "1:canopy: error: /dev/zero: the grammar file is not a regular file (a device, pipe or socket)" \
  "$(cat devzero)"
run derive "$src/grammars"
check "derive a folder" "1:canopy: error: $src/grammars: the grammar file is a folder, not a file" "$rc:$(err)"

# Steps: 0..100,000 everywhere (a billion ran for many minutes).
run derive "$g" --steps 1000000000
check "derive --steps 1e9" "105:canopy: error: --steps: needs a whole number from 0 to 100000, got 1000000000" "$rc:$(err)"
run derive "$g" --steps -3
check "derive --steps -3: one readable line" "105:canopy: error: --steps: needs a whole number from 0 to 100000, got -3" "$rc:$(err)"
run stand "$g" --steps 1000000000 -o s
check "stand --steps 1e9" "105:canopy: error: --steps: needs a whole number from 0 to 100000, got 1000000000" "$rc:$(err)"
run sweep "$g" --steps 1000000000 -o sw
check "sweep --steps 1e9" "2:canopy: error: --steps: 1000000000 is more than the 100000 steps a plant may grow" "$rc:$(err)"
run derive "$g" --steps 1e3 --stats
check "derive --steps 1e3 reads as 1000" "0" "$rc"

# Range errors say their bound as written, on one line (NonNegativeNumber printed 309 digits).
run stand "$g" --jitter -1 -o s
check "--jitter -1" "105:canopy: error: --jitter: needs a finite number of at least 0, got -1:1" "$rc:$(err):$(lines)"
run stand "$g" --clearance 1e38 -o s
check "--clearance 1e38" "105:canopy: error: --clearance: needs a number from 0 to 100, got 1e38" "$rc:$(err)"
run stand "$g" --resolve-clearance 1e100 -o s
check "--resolve-clearance 1e100" "105:canopy: error: --resolve-clearance: needs a number from 0 to 100, got 1e100" "$rc:$(err)"
run derive "$g" --max-modules 9223372036854775807 --stats
check "--max-modules at the top of its range" "0" "$rc"
run derive "$g" --max-modules 9223372036854775808 --stats
check "--max-modules past its range" "105:canopy: error: --max-modules: needs a whole number from 1 to 9223372036854775807, got 9223372036854775808" "$rc:$(err)"
run stand "$g" --max-device-memory 99999999999999999999G -o s
check "--max-device-memory past a petabyte" "2:canopy: error: --max-device-memory: '99999999999999999999G' is more than 1e15 bytes (1000000G)" "$rc:$(err)"
run stand "$g" --lod 17 -o s
check "--lod 17" "105:canopy: error: --lod: needs a whole number from 1 to 16, got 17" "$rc:$(err)"
run stand "$g" --rows 0 -o s
check "--rows 0" "105:canopy: error: --rows: needs a whole number from 1 to 2147483647, got 0" "$rc:$(err)"
# Whole numbers are decimal: CLI11 read a leading 0 as octal (010 plants were 8) and took 0x.
run stand "$g" --steps 4 --rows 1 --per-row 010 --no-resolve --backend cpu -o s
check "--per-row 010 is ten" "0:1" "$rc:$(grep -c '^stand: 10 plants' "$tmp/out")"
run derive "$g" --steps 09
check "--steps 09 is nine" "0" "$rc"
run derive "$g" --steps 3 --seed 010
cp "$tmp/out" seed010
run derive "$g" --steps 3 --seed 10
check "--seed 010 is ten" "same" "$(cmp -s seed010 "$tmp/out" && echo same || echo different)"
run stand "$g" --max-modules 0x100000 -o s
check "--max-modules 0x100000" "105:canopy: error: --max-modules: needs a whole number from 1 to 9223372036854775807, got 0x100000" "$rc:$(err)"
run light "$g" --sky-directions -1 -o s
check "light --sky-directions -1" "105:canopy: error: --sky-directions: needs a whole number from 0 to 10000, got -1" "$rc:$(err)"
# Options that would be taken and used by no one are refused.
run stand "$g" --no-resolve --max-rounds 5 -o s
check "--no-resolve with --max-rounds" "108:canopy: error: --no-resolve excludes --max-rounds" "$rc:$(err)"
run stand "$g" --resolve-host-search --resolve-device-search -o s
check "host and device search" "108:canopy: error: --resolve-host-search excludes --resolve-device-search" "$rc:$(err)"
run stand "$g" --formats obj --glb-compact -o s
check "--glb-compact without a glb" "2:canopy: error: --glb-compact is a form of stand.glb, and --formats obj writes none: add glb" "$rc:$(err)"
# Linux names are bytes: a folder or grammar named with bytes that are not UTF-8 runs to the end
# (report.json's dump threw there: "[json.exception.type_error.316] invalid UTF-8 byte").
cp "$g" "$(printf 'g\xfe.yaml')"
run stand "$(printf 'g\xfe.yaml')" --steps 4 --rows 1 --per-row 2 --backend cpu -o "$(printf 'bad\xffname')"
check "a name that is not UTF-8" "0:1" "$rc:$(python3 -c "import json; print(json.load(open(b'bad\xffname/report.json'))['config']['out'] == 'bad\ufffdname' and 1 or 0)")"
run sweep "$(printf 'g\xfe.yaml')" --steps 4 --rows 1 --per-row 2 --plant-spacing 0.4 --seeds 1 --no-light --backend cpu -o "$(printf 'sw\xff')"
run sweep "$(printf 'g\xfe.yaml')" --steps 4 --rows 1 --per-row 2 --plant-spacing 0.4 --seeds 2 --no-light --backend cpu -o "$(printf 'sw\xff')"
check "a sweep so named resumes" "0" "$rc"
# plants.csv's grammar cell holds any path: quoted where it has a comma or a quote (the stand was
# written and could not be read back: "expected 7 cells, got 8"); a line break is refused first.
mkdir -p "odd dir"
cp "$g" 'odd dir/a,b"c.yaml'
run stand 'odd dir/a,b"c.yaml' --steps 4 --rows 1 --per-row 2 --backend cpu -o oddname
run detect oddname --backend cpu
check "a grammar path with a comma and a quote reads back" "0" "$rc"
check "its cell as RFC 4180 quotes it" "2" "$(grep -c ',"odd dir/a,b""c.yaml",4$' oddname/plants.csv)"
cp "$g" "$(printf 'n\nl.yaml')"
run stand "$(printf 'n\nl.yaml')" --steps 4 --rows 1 --per-row 2 --backend cpu -o nl
check "a grammar path with a line break" "2:canopy: error: the grammar file's path holds a line break, which plants.csv cannot record: rename it ('n\\nl.yaml')" "$rc:$(err)"
# Standard output is a command's result: one that cannot be written fails the run (detect's table
# was lost with exit 0); a closed one is not handed to the first file opened.
if [ -w /dev/full ]; then
  timeout 60 "$canopy" info >/dev/full 2>"$tmp/err"; rc=$?
  check "info > /dev/full" "1:canopy: error: writing standard output failed: No space left on device" "$rc:$(err)"
  timeout 60 "$canopy" derive "$g" --steps 2 >/dev/full 2>"$tmp/err"; rc=$?
  check "derive > /dev/full" "1:canopy: error: writing standard output failed: No space left on device" "$rc:$(err)"
  # A --csv that cannot be written: the error alone, no table on standard output first.
  "$canopy" stand "$g" --steps 4 --rows 1 --per-row 2 --backend cpu -o csvstand >/dev/null 2>&1
  timeout 60 "$canopy" detect csvstand --backend cpu --csv /dev/full >"$tmp/out" 2>"$tmp/err"; rc=$?
  check "detect --csv /dev/full" "1:canopy: error: writing /dev/full failed: No space left on device:0" "$rc:$(err):$(wc -c < "$tmp/out")"
  for words in "--help" "--version" "stand --help"; do
    timeout 60 "$canopy" $words >/dev/full 2>"$tmp/err"; rc=$?
    check "$words > /dev/full" "1:1" "$rc:$(grep -c '^canopy: error: writing standard output failed' "$tmp/err")"
  done
fi
timeout 60 "$canopy" stand --help >&- 2>"$tmp/err"; rc=$?
check "stand --help >&-" "1" "$rc"
timeout 60 "$canopy" info >&- 2>"$tmp/err"; rc=$?
check "info >&-" "1:canopy: error: writing standard output failed: Bad file descriptor" "$rc:$(err)"
timeout 60 "$canopy" stand "$g" --steps 4 --rows 1 --per-row 2 --backend cpu -o closed >&- 2>"$tmp/err"; rc=$?
check "stand >&-: files as with output" "1:0" "$rc:$(grep -c 'stand:' closed/organs.csv closed/report.json | awk -F: '{s+=$2} END {print s}')"
run stand "$g" --no-such-option -o s
check "unknown option: one line" "109:1:1" "$rc:$(grep -c '^canopy: error: ' "$tmp/err"):$(lines)"

# A constant set twice is refused (the last one was taken, both echoed in report.json).
run derive "$g" --steps 1 --set nodes=10 --set nodes=12
check "--set twice" "2:canopy: error: --set nodes: given twice (10 and 12); give it once" "$rc:$(err)"

# Thread counts: refused past the maximum instead of crashing in libgomp.
run stand "$g" --steps 4 --threads 100000 -o s
check "stand --threads 100000" "105:canopy: error: --threads: needs a whole number from 0 to 1024, got 100000" "$rc:$(err)"
OMP_NUM_THREADS=100000 timeout 60 "$canopy" stand "$g" --steps 4 --backend cpu -o s >/dev/null 2>"$tmp/err"; rc=$?
check "OMP_NUM_THREADS=100000" "2:canopy: error: OMP_NUM_THREADS asks for 100000 threads, more than the 1024 canopy runs at most; set it lower or give a thread count" "$rc:$(err)"
OMP_NUM_THREADS=100000 timeout 60 "$canopy" stand "$g" --steps 4 --backend cpu --threads 2 -o s2 >/dev/null 2>"$tmp/err"; rc=$?
check "OMP_NUM_THREADS=100000 with --threads 2" "0" "$rc"
# libgomp only warns about a count it cannot read and runs on every core.
OMP_NUM_THREADS=abc timeout 60 "$canopy" stand "$g" --steps 4 --backend cpu -o s3 >/dev/null 2>"$tmp/err"; rc=$?
check "OMP_NUM_THREADS=abc" "2:canopy: error: OMP_NUM_THREADS='abc' is not a thread count (a whole number from 1, or a comma-separated list of them); set it right, unset it or give a thread count" "$rc:$(grep canopy "$tmp/err")"
OMP_NUM_THREADS=' 2,1 ' timeout 60 "$canopy" stand "$g" --steps 4 --backend cpu -o s3 >/dev/null 2>"$tmp/err"; rc=$?
check "OMP_NUM_THREADS=' 2,1 '" "0:" "$rc:$(err)"

# Organ parameters: non-finite, negative or past float range are errors at the expression that
# wrote them (1e300 was written as inf and NaN into organs.csv and the meshes, and exit 0).
organs=$'organs:\n  L: {prototype: leaflet, kind: leaflet}\n'
printf '%saxiom: L(1e300,1e300)\n' "$organs" > huge.yaml
run stand huge.yaml --backend cpu -o huge
check "float overflow refused" "1:canopy: error: huge.yaml:3:10: plant 0 (seed 3395948882924712079), module 0 'L(1e+300,1e+300)': leaflet parameter 1 is 1e+300 m, more than the 1000000 m an organ may measure" "$rc:$(err)"
check "float overflow: no organs.csv" "no" "$([ -e huge/organs.csv ] && echo yes || echo no)"
printf '%saxiom: L(-1,-0.5)\n' "$organs" > negative.yaml
run stand negative.yaml --backend cpu -o neg
check "negative size located" "1:canopy: error: negative.yaml:3:10: plant 0 (seed 3395948882924712079), module 0 'L(-1,-0.5)': leaflet parameter 1 must not be negative" "$rc:$(err)"
printf 'axiom: L(1,0.5)\norgans:\n  L: {prototype: leaflet, kind: leaflet, lod: 17}\n' > lod.yaml
run stand lod.yaml --backend cpu -o lod
check "grammar lod 17 located" "1:canopy: error: lod.yaml:3:47: lod must be between 1 and 16, got 17" "$rc:$(err)"

# Positions files: columns by name, cells in range, grammar cells inside the file's folder.
mkdir -p pos/sub
cp "$g" pos/sub/t.yaml
p() { printf "$1" > pos/p.csv; run stand "$g" --positions pos/p.csv --steps 4 --backend cpu "${@:2}" -o ps; }
p 'x,y,rotation,seed,Steps\n0,0,0,1,3\n'
check "positions unknown column" "2:canopy: error: pos/p.csv:1:19: unknown column 'Steps' (the header has x,y,rotation,seed and may add grammar,steps)" "$rc:$(err)"
p 'x,y,rotation,seed,x\n0,0,0,1,3\n'
check "positions duplicate column" "2:canopy: error: pos/p.csv:1:19: column 'x' appears twice in the header (cells 1 and 5)" "$rc:$(err)"
p 'x,y,rotation,seed,steps\n0,0,0,1,1e9\n'
check "positions steps 1e9" "2:canopy: error: pos/p.csv:2:9: column 'steps' needs a whole number from 0 to 100000, got '1e9'" "$rc:$(err)"
p 'x,y,rotation,seed\n'
check "positions: a header alone" "0:canopy: note: pos/p.csv holds a header and no plants: the stand is empty" "$rc:$(err)"
p 'x,y,rotation,seed\n1e400,0,0,1\n'
check "positions out of range" "2:canopy: error: pos/p.csv:2:1: column 'x' needs a finite number, got '1e400', which is out of range" "$rc:$(err)"
printf 'a secret first line\nand a second\n' > not_a_grammar
p 'x,y,rotation,seed,grammar\n0,0,0,1,../not_a_grammar\n'
check "positions grammar above the folder" "2:canopy: error: pos/p.csv:2:9: column 'grammar': '../not_a_grammar' leaves the positions file's folder; a grammar cell names a file in the positions file's folder or below it (--any-grammar-path allows others)" "$rc:$(err)"
p "x,y,rotation,seed,grammar\n0,0,0,1,$tmp/not_a_grammar\n"
check "positions grammar absolute" "2:1" "$rc:$(grep -c "is an absolute path" "$tmp/err")"
# Written inside the folder, a cell may lead out of it through a link: refused as well.
mkdir -p "$tmp/elsewhere" && cp "$src/grammars/tomato_young.yaml" "$tmp/elsewhere/g.yaml"
ln -sfn "$tmp/elsewhere" "$tmp/pos/link"
p 'x,y,rotation,seed,grammar\n0,0,0,1,link/g.yaml\n'
check "positions grammar through a link out" "2:1" "$rc:$(grep -c "'link/g.yaml' leads out of the positions file's folder through a symbolic link" "$tmp/err")"
rm "$tmp/pos/link"
p 'x,y,rotation,seed,grammar\n0,0,0,1,../not_a_grammar\n' --any-grammar-path
check "--any-grammar-path reads it" "1:canopy: error: pos/../not_a_grammar:1:1: a grammar file is a YAML map with keys such as axiom and productions" "$rc:$(err)"
check "its content is not quoted" "0" "$(grep -c secret "$tmp/err")"
printf 'root: x\nsecret: y\n' > not_a_grammar
p 'x,y,rotation,seed,grammar\n0,0,0,1,../not_a_grammar\n' --any-grammar-path
check "a YAML map that is not a grammar" "1:canopy: error: pos/../not_a_grammar:1:1: not a grammar file (none of its keys is a grammar's, such as axiom or productions)" "$rc:$(err)"
p 'x,y,rotation,seed,grammar,steps\n0,0,0,1,sub/t.yaml,4\n0.5,0,0,2,,4\n'
check "a grammar below the folder" "0" "$rc"
p 'x,y,rotation,seed,grammar\n0,0,0,1,\n0.5,0,0,2,sub/none.yaml\n'
check "a missing grammar named with its positions line" "1:canopy: error: pos/sub/none.yaml: cannot open the grammar file (named by pos/p.csv:3, column 'grammar': 'sub/none.yaml')" "$rc:$(err)"
p 'x,y,rotation,seed,grammar\n0,0,0,1,sub\n'
check "a folder named as a grammar, with its positions line" "1:canopy: error: pos/sub: the grammar file is a folder, not a file (named by pos/p.csv:2, column 'grammar': 'sub')" "$rc:$(err)"
run derive "$g" --set a=2*3
check "--set with an expression" "2:canopy: error: --set a=2*3: '2*3' is not a finite number (a value, not an expression: 6, not 2*3)" "$rc:$(err)"
p 'x,y,rotation,seed\n0,0,0,1\n'
mkfifo pos/fifo
run stand "$g" --positions pos/fifo --steps 4 -o ps
check "positions from a pipe" "2:canopy: error: pos/fifo: the positions file is not a regular file (a device, pipe or socket)" "$rc:$(err)"

# The environment's settings are held to their values: a misspelt heap-page choice was taken as
# the default unannounced.
CANOPY_HEAP_PAGES=huge run info
check "CANOPY_HEAP_PAGES=huge" "2:canopy: error: CANOPY_HEAP_PAGES='huge' is neither 'large' nor 'small' (unset it for canopy's own choice)" "$rc:$(err)"
# A self-test asked for passes on every GPU or fails: never silent where there is none to test.
run info --self-test
if grep -q '^backend cuda: device' "$tmp/out"; then
  check "info --self-test on a GPU" "0:$(grep -c '^backend cuda: device' "$tmp/out")" "$rc:$(grep -c 'self test passed' "$tmp/out")"
else
  check "info --self-test without a GPU" "1:1" "$rc:$(grep -c '^canopy: error: --self-test: \(no CUDA device to test\|this build has no CUDA backend\)' "$tmp/err")"
fi

# render --size is two decimal whole numbers and an 'x', nothing more ("100x100abc" rendered 100x100).
for size in 100x100abc 100x100x3 " 100x100" +100x+100 15x16; do
  run render "$tmp" --size "$size" -o "$tmp/r.png"
  check "render --size '$size'" "2:canopy: error: --size: '$size' is not WIDTHxHEIGHT between 16 and 16384" "$rc:$(err)"
done

# An empty value is refused by every option and argument (`detect --csv ""` wrote nothing and
# exited 0; `stand --positions ""` grew the grammar's layout).
run stand "$g" --positions "" -o e1
check "stand --positions ''" "105:canopy: error: --positions: needs a value, got an empty one:0" "$rc:$(err):$(ls -d e1 2>/dev/null | wc -l)"
run detect "$tmp" --csv ""
check "detect --csv ''" "105:canopy: error: --csv: needs a value, got an empty one" "$rc:$(err)"
run stand "$g" -o ""
check "stand -o ''" "105:canopy: error: --out: needs a value, got an empty one" "$rc:$(err)"
run derive ""
check "derive ''" "105:canopy: error: GRAMMAR: needs a value, got an empty one" "$rc:$(err)"
# Whole-number options whose range starts at 0: an empty word was read as 0 (--steps "" grew
# plants of no organs, --threads "" took every core).
# Real numbers are decimal too: strtod read --jitter 0x1p-4 as 0.0625.
run stand "$g" --rows 1 --per-row 2 --jitter 0x1p-4 -o e4
check "stand --jitter 0x1p-4" "105:canopy: error: --jitter: needs a finite number, got 0x1p-4:0" "$rc:$(err):$(ls -d e4 2>/dev/null | wc -l)"
run derive "$g" --steps ""
check "derive --steps ''" "105:canopy: error: --steps: needs a value, got an empty one" "$rc:$(err)"
run stand "$g" --rows 1 --per-row 1 --steps= -o e2
check "stand --steps=" "105:canopy: error: --steps: needs a value, got an empty one:0" "$rc:$(err):$(ls -d e2 2>/dev/null | wc -l)"
run stand "$g" --rows 1 --per-row 1 --threads "" -o e3
check "stand --threads ''" "105:canopy: error: --threads: needs a value, got an empty one:0" "$rc:$(err):$(ls -d e3 2>/dev/null | wc -l)"
# "--csv=" too: CLI11 took the next word as its value ("--csv= --threads=1" wrote a file of that name).
run detect "$tmp" --csv= --threads=1
check "detect --csv= --threads=1" "105:canopy: error: --csv: needs a value, got an empty one:0" "$rc:$(err):$(ls -- "--threads=1" 2>/dev/null | wc -l)"
run derive --bogus= "$g"
check "derive --bogus=: unknown, not empty" "109:canopy: error: The following argument was not expected: --bogus=" "$rc:$(err)"
run derive --help --x=
check "derive --help --x=" "0" "$rc"

# canopy detect reads back only what canopy writes.
run stand "$g" --rows 1 --per-row 2 --steps 6 --backend cpu -o st
check "stand for detect" "0" "$rc"
edit() {  # edit DIR LINE COLUMN VALUE: a copy of st with one organs.csv cell replaced
  rm -rf "$1"; cp -r st "$1"
  python3 -c "
import sys; f='$1/organs.csv'; l=open(f).read().split('\n'); c=l[$2-1].split(','); c[$3-1]='$4'; l[$2-1]=','.join(c); open(f,'w').write('\n'.join(l))"
}
edit nan 2 13 nan
run detect nan --backend cpu
check "detect: NaN transform" "1:canopy: error: nan/organs.csv:2: column 13 'nan' is not a finite number" "$rc:$(err)"
edit big 2 13 1e300
run detect big --backend cpu
check "detect: 1e300 out of range" "1:canopy: error: big/organs.csv:2: column 13 '1e300' is out of range" "$rc:$(err)"
edit area 2 6 nan
run detect area --backend cpu
check "detect: NaN area" "1:canopy: error: area/organs.csv:2: column 6 'nan' is not a finite number" "$rc:$(err)"
edit length 3 7 -1
run detect length --backend cpu
check "detect: negative length" "1:canopy: error: length/organs.csv:3: column 7 '-1' must not be negative" "$rc:$(err)"
# Tables a spreadsheet saved as "CSV UTF-8" start with a byte-order mark: read as without it
# (it was "expected the header ...", the header looking the same).
rm -rf bom; cp -r st bom
for t in plants organs; do printf '\xef\xbb\xbf' | cat - "st/$t.csv" > "bom/$t.csv"; done
"$canopy" detect st --backend cpu --csv "$tmp/st_contacts.csv" >/dev/null 2>&1
run detect bom --backend cpu --csv "$tmp/bom_contacts.csv"
check "detect: tables with a byte-order mark" "0:same" "$rc:$(cmp -s "$tmp/st_contacts.csv" "$tmp/bom_contacts.csv" && echo same)"
# A report.json that is no regular file (a FIFO) is passed over, never waited on.
rm -rf fifo; cp -r st fifo; rm fifo/report.json; mkfifo fifo/report.json
rc=0; timeout 20 "$canopy" detect fifo --backend cpu >"$tmp/out" 2>"$tmp/err" || rc=$?
check "detect: report.json a FIFO" "0" "$rc"
# organs.csv cut at a line end reads as a smaller stand: the report's counts say so.
rm -rf cut; cp -r st cut; head -20 st/organs.csv > cut/organs.csv
run detect cut --backend cpu
check "detect: a table cut short" "0:1" "$rc:$(grep -c "^canopy: note: cut: the tables hold 2 plants and 19 organs, its report.json counted 2 and" "$tmp/err")"
edit parent 3 3 -7
run detect parent --backend cpu
check "detect: parent out of range" "1:canopy: error: parent/organs.csv:3: parent -7 is not an earlier organ of plant 0" "$rc:$(err)"
rm -rf empty; cp -r st empty; : > empty/organs.csv
run detect empty --backend cpu
check "detect: empty organs.csv" "1:1" "$rc:$(grep -c '^canopy: error: empty/organs.csv:1: expected the header id,plant,parent,' "$tmp/err")"
# Blank lines after the last row (an editor's) end a table; one with rows after it is refused.
rm -rf blank; cp -r st blank; printf '\n\n' >> blank/organs.csv; printf '\n' >> blank/plants.csv
run detect blank --backend cpu
check "detect: blank lines at the end" "0" "$rc"
sed -i '3s/^/\n/' blank/organs.csv
run detect blank --backend cpu
check "detect: a blank line inside" "1:canopy: error: blank/organs.csv:3: a blank line inside the table (rows follow on line 4)" "$rc:$(err)"
run detect st --backend cpu --threads 100000
check "detect --threads 100000" "105:canopy: error: --threads: needs a whole number from 0 to 1024, got 100000" "$rc:$(err)"
run detect st --backend cpu
check "detect: the stand as written" "0" "$rc"

# A sweep resumed from files canopy did not write: refused with the file named, never a crash.
sweep() { run sweep "$g" --plant-spacing 0.4 --steps 4 --rows 1 --per-row 2 --backend cpu -o sw "$@"; }
rm -rf sw
sweep --seeds 1
check "sweep" "0" "$rc"
cp sw/runs.csv runs.good
python3 -c "
import csv; r=list(csv.reader(open('sw/runs.csv'))); i=r[0].index('lai'); r[1][i]='abc'
csv.writer(open('sw/runs.csv','w'), lineterminator='\n').writerows(r)"
sweep --seeds 2
check "runs.csv with a word for a number" "2:canopy: error: sw/runs.csv:2: column 'lai' needs a number, got 'abc' (not a runs.csv written by canopy sweep; use another -o)" "$rc:$(err)"
cp runs.good sw/runs.csv
python3 -c "
import csv; r=list(csv.reader(open('sw/runs.csv'))); i=r[0].index('status'); r[1][i]='maybe'
csv.writer(open('sw/runs.csv','w'), lineterminator='\n').writerows(r)"
sweep --seeds 2
check "runs.csv with another status" "2:canopy: error: sw/runs.csv:2: column 'status' needs 'ok' or 'failed', got 'maybe' (not a runs.csv written by canopy sweep; use another -o)" "$rc:$(err)"
cp runs.good sw/runs.csv
# Printing the differing setting recursed once per level: a stack overflow.
python3 -c "print('{\"rows\": ' + '[' * 100000 + ']' * 100000 + '}')" > sw/sweep.json
sweep --seeds 2
check "sweep.json nested 100,000 deep" "2:1" "$rc:$(grep -c "^canopy: error: sw/sweep.json: not a sweep's settings (nested more than 16 levels deep)" "$tmp/err")"
echo '[1, 2]' > sw/sweep.json
sweep --seeds 2
check "sweep.json not an object" "2:canopy: error: sw/sweep.json: not a sweep's settings (not a JSON object)" "$rc:$(err)"

echo "$pass passed, $failures failed"
[ "$failures" -eq 0 ]
