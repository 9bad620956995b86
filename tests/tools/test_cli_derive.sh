#!/usr/bin/env bash
# canopy derive end to end: output, --stats, --steps/--seed/--set, located errors, exit codes, and
# no partial output on failure. Usage: CANOPY=path/to/canopy test_cli_derive.sh SOURCE_DIR
set -u
src=$1
canopy=${CANOPY:?set CANOPY to the canopy binary}
source "$(dirname "$0")/check.sh"

check "1.24a two steps" "F[+F]F[-F]F[+F[+F]F[-F]F]F[+F]F[-F]F[-F[+F]F[-F]F]F[+F]F[-F]F" \
  "$("$canopy" derive "$src/grammars/classic/abop_1_24a.yaml" --steps 2)"
check "1.24a stats" '{"modules": 7811, "counts": {"+": 781, "-": 781, "F": 3125, "[": 1562, "]": 1562}}' \
  "$("$canopy" derive "$src/grammars/classic/abop_1_24a.yaml" --stats)"
check "1.30 step 5" "CB(0)B(8)A(1.1428571428571428,0)" "$("$canopy" derive "$src/grammars/classic/abop_1_30.yaml")"
a=$("$canopy" derive "$src/grammars/tomato.yaml" --seed 3)
b=$("$canopy" derive "$src/grammars/tomato.yaml" --seed 3)
c=$("$canopy" derive "$src/grammars/tomato.yaml" --seed 4)
check "seed reproducible" "$a" "$b"
check "seeds differ" "1" "$([ "$a" != "$c" ] && echo 1 || echo 0)"
check "--set" "A(5,15)" "$(printf 'constants: {a: 2, b: a * 3}\naxiom: A(a, b)\n' > "$tmp/s.yaml"; "$canopy" derive "$tmp/s.yaml" --set a=5)"

# Errors: one located line on stderr, non-zero exit, nothing on stdout.
printf 'steps: 2\naxiom: A(1)\nproductions:\n  - A(x) -> A(x / (x - 1))\n' > "$tmp/div.yaml"
out=$("$canopy" derive "$tmp/div.yaml" 2>"$tmp/err"); rc=$?
check "division exit" "1" "$rc"
check "division stdout" "" "$out"
check "division message" "canopy: error: $tmp/div.yaml:4:17: division by zero in 'x / (x - 1)'" "$(cat "$tmp/err")"
printf 'axiom: A\nsteps: 100\nproductions:\n  - A -> AA\n' > "$tmp/exp.yaml"
out=$("$canopy" derive "$tmp/exp.yaml" --max-modules 100000 2>"$tmp/err"); rc=$?
check "cap exit" "1" "$rc"
check "cap stdout" "" "$out"
check "cap message" "1" "$(grep -c "^canopy: error: $tmp/exp.yaml:4:5: the derived string exceeds the module cap of 100000 modules at step 17" "$tmp/err")"
# A repeatable option takes one value a use: options may come before the grammar (the grammar
# after --set was taken as a second --set, and the command refused for want of a grammar).
check "--set before the grammar" "A(5,6)" "$("$canopy" derive --set a=5 --set b=6 "$tmp/s.yaml")"
check "--set before the grammar, an option after" '{"modules": 1, "counts": {"A": 1}}' "$("$canopy" derive --set a=5 "$tmp/s.yaml" --stats)"
out=$("$canopy" derive "$tmp/s.yaml" --set a=5 b=6 2>"$tmp/err"); rc=$?
check "--set takes one value a use" "109" "$rc"
out=$("$canopy" derive "$tmp/s.yaml" --set zz=1 2>"$tmp/err"); rc=$?
check "--set unknown exit" "2" "$rc"
check "--set unknown message" "canopy: error: --set zz: $tmp/s.yaml has no constant 'zz' (its constants: a, b)" "$(cat "$tmp/err")"
"$canopy" derive "$tmp/missing.yaml" >/dev/null 2>"$tmp/err"; rc=$?
check "missing file" "1:canopy: error: $tmp/missing.yaml: cannot open the grammar file" "$rc:$(cat "$tmp/err")"
printf 'axiom: [F\n' > "$tmp/bad.yaml"
"$canopy" derive "$tmp/bad.yaml" >/dev/null 2>"$tmp/err"; rc=$?
check "bad yaml" "1" "$(grep -c "^canopy: error: $tmp/bad.yaml:2:1: malformed YAML" "$tmp/err")"
check "one line" "1" "$(wc -l < "$tmp/err" | tr -d ' ')"

# Seeds are whole numbers in [0, 2^64): CLI11 alone took -1 and 2^64 to 2^64 - 1.
"$canopy" derive "$tmp/s.yaml" --seed 18446744073709551615 >/dev/null 2>&1
check "largest seed" "0" "$?"
for seed in -1 18446744073709551616 1.5 0x10; do
  "$canopy" derive "$tmp/s.yaml" --seed "$seed" >/dev/null 2>"$tmp/err"; rc=$?
  check "seed $seed refused" "105" "$rc"
  check "seed $seed named" "1" "$(grep -c -- "--seed: needs a whole number from 0 to 18446744073709551615, got $seed" "$tmp/err")"
done

# Every option has a --help line.
help=$("$canopy" derive --help)
for opt in --steps --seed --set --stats --max-modules --interpreted; do
  check "help $opt" "1" "$(grep -q -- "$opt" <<<"$help" && echo 1 || echo 0)"
done

# An organ no rule writes (a misspelt symbol): a located note on stderr, the run goes on; the
# same from canopy stand.
sed 's/^  L:  {prototype: leaflet/  Lf: {prototype: leaflet/' "$src/grammars/tomato.yaml" > "$tmp/typo.yaml"
line=$(grep -n '^  Lf:' "$tmp/typo.yaml" | cut -d: -f1)
note="canopy: note: $tmp/typo.yaml:$line:3: organ 'Lf' is written by neither the axiom nor any rule, so the plants have none (a misspelt symbol?)"
"$canopy" derive "$tmp/typo.yaml" --steps 2 >/dev/null 2>"$tmp/err"
check "note: unwritten organ" "0:$note" "$?:$(cat "$tmp/err")"
"$canopy" stand "$tmp/typo.yaml" --rows 1 --per-row 1 --steps 4 --backend cpu -o "$tmp/typo" >/dev/null 2>"$tmp/err"
check "note: unwritten organ, stand" "0:$note" "$?:$(cat "$tmp/err")"
"$canopy" derive "$src/grammars/tomato.yaml" --steps 2 >/dev/null 2>"$tmp/err"
check "no note for the tomato" "" "$(cat "$tmp/err")"

echo "$pass passed, $failures failed"
[ "$failures" -eq 0 ]
