#!/usr/bin/env bash
# canopy render end to end: a grammar takes canopy stand's options (layout, positions, levels,
# --no-resolve) and finds the same contacts canopy stand writes; a folder is drawn as written,
# refusing the options that would grow, detect or resolve it, a contacts table it cannot read and
# an -o naming one of the stand's own files. Usage: CANOPY=path/to/canopy test_cli_render.sh SOURCE_DIR
set -u
src=$1
canopy=${CANOPY:?set CANOPY to the canopy binary}
source "$(dirname "$0")/check.sh"
g="$src/grammars/tomato.yaml"
cd "$tmp"
run() { timeout 120 "$canopy" "$@" >"$tmp/out" 2>"$tmp/err"; rc=$?; }
rows() { echo $(($(wc -l < "$1") - 1)); }
organs() { python3 -c "import json; print(json.load(open('$1/report.json'))['counts']['organs'])"; }
size=(--size 64x48)

# From a grammar with stand's layout options: the contacts canopy stand finds before resolution.
layout=(--rows 2 --per-row 3 --steps 14 --double-rows 0.3 --no-random-rotation --jitter 0.05 --seed 4 --backend cpu)
run stand "$g" "${layout[@]}" --level organ --no-resolve -o st
check "stand with the layout" "0" "$rc"
run render "$g" "${layout[@]}" --level organ --no-resolve "${size[@]}" -o a.png
check "render --no-resolve --level organ: stand's contacts" "0:$(rows st/contacts.csv) contacts at the organ level (not resolved)" \
  "$rc:$(head -1 "$tmp/out")"
check "render: stand's organs" "$(organs st) organs)" "$(grep -o "[0-9]* organs)" "$tmp/out")"
run stand "$g" "${layout[@]}" -o sr
run render "$g" "${layout[@]}" "${size[@]}" -o b.png
moved=$(python3 -c "import json; print(json.load(open('sr/report.json'))['resolution']['organs_moved'])")
check "render: before and after as stand" \
  "0:before (left): $(rows sr/contacts.csv) contacts; after (right): $(rows sr/contacts_after.csv) contacts, $moved organs turned" \
  "$rc:$(head -1 "$tmp/out" | sed 's/ (mean.*//')"
check "render: a PNG" "PNG" "$(head -c 4 b.png | tail -c 3)"

# A positions file: its plants.
printf 'x,y,rotation,seed\n0,0,0,1\n0.3,0,40,2\n' > pos.csv
run stand "$g" --positions pos.csv --steps 12 --no-resolve --backend cpu -o sp
run render "$g" --positions pos.csv --steps 12 --no-resolve --backend cpu "${size[@]}" -o p.png
check "render --positions" "0:$(organs sp) organs)" "$rc:$(grep -o "[0-9]* organs)" "$tmp/out")"
check "render --positions: stand's contacts" "$(rows sp/contacts.csv) contacts" "$(head -1 "$tmp/out" | cut -d' ' -f1-2)"

# A picture marks organs: plant and leaf levels are refused.
run render "$g" --rows 1 --per-row 2 --level leaf "${size[@]}" -o c.png
check "render --level leaf" "2:canopy: error: --level leaf: a picture marks the organs in contact, found at the organ or exact level" \
  "$rc:$(cat "$tmp/err")"

# A folder is drawn as written: options that would change it are refused, --threads is taken.
for opt in "--rows 3" "--steps 4" "--level organ" "--max-rounds 2" "--no-resolve"; do
  run render sr $opt "${size[@]}" -o d.png
  check "render DIR $opt" "2:1:0" "$rc:$(grep -c "^canopy: error: ${opt%% *}: sr is a folder that holds a stand already" "$tmp/err"):$(ls d.png 2>/dev/null | wc -l)"
done
run render sr --threads 1 "${size[@]}" -o d.png
check "render DIR --threads" "0:1" "$rc:$(ls d.png | wc -l)"

# -o naming the stand's own files is refused, directly or through a link; the table is kept.
cp sr/plants.csv plants.before
ln -s sr/plants.csv link.csv
for out in sr/plants.csv sr/report.json link.csv; do
  run render sr "${size[@]}" -o "$out"
  check "render -o $out" "2:1" "$rc:$(grep -c "that is the stand folder's own" "$tmp/err")"
done
check "plants.csv kept" "0" "$(cmp -s plants.before sr/plants.csv; echo $?)"

# A contacts table that is not one is refused by line, not drawn as a stand without contacts.
cp -r sr bad
echo garbage > bad/contacts_after.csv
run render bad "${size[@]}" -o e.png
check "render: garbage contacts" "1:canopy: error: bad/contacts_after.csv:1: not a stand's contacts table: the header is not organ_a,organ_b,plant_a,plant_b,level" \
  "$rc:$(cat "$tmp/err")"
printf 'organ_a,organ_b,plant_a,plant_b,level\n1,2,0,0,exact\n5,99999999,0,1,exact\n' > bad/contacts_after.csv
run render bad "${size[@]}" -o e.png
check "render: organ past the stand" "1:1" "$rc:$(grep -c "contacts_after.csv:3: column 'organ_b': '99999999' is not -1 or an id below" "$tmp/err")"
printf 'organ_a,organ_b,plant_a,plant_b,level\n1,2,0,0\n' > bad/contacts_after.csv
run render bad "${size[@]}" -o e.png
check "render: short row" "1:1" "$rc:$(grep -c "contacts_after.csv:2: 4 cells where the table has 5" "$tmp/err")"
check "no picture from bad tables" "0" "$(ls e.png 2>/dev/null | wc -l)"

# A contacts table that is a dangling link is refused by name, not passed over for contacts.csv.
cp -r sr dangling && rm dangling/contacts_after.csv && ln -s "$tmp/nowhere.csv" dangling/contacts_after.csv
run render dangling "${size[@]}" -o f.png
check "render: dangling contacts_after.csv" "1:1" "$rc:$(grep -c "contacts_after.csv" "$tmp/err")"

# Refused before any work: -o a folder or in no folder, a clearance nothing reads.
run render "$g" --rows 1 --per-row 2 --steps 8 --backend cpu "${size[@]}" -o sr
check "render -o a folder" "2:canopy: error: -o sr: a folder; name the PNG file to write:" "$rc:$(cat "$tmp/err"):$(cat "$tmp/out")"
run render "$g" --rows 1 --per-row 2 --steps 8 --backend cpu "${size[@]}" -o nowhere/x.png
check "render -o in no folder" "2:canopy: error: -o nowhere/x.png: there is no folder nowhere to write it in" "$rc:$(cat "$tmp/err")"
# Never over what it reads: the grammar or the positions file named as the picture.
cp "$g" own.yaml && printf 'x,y,rotation,seed\n0,0,0,1\n' > own.csv
run render own.yaml --steps 8 --backend cpu "${size[@]}" -o own.yaml
check "render -o its grammar" "2:1:$(md5sum < "$g")" "$rc:$(grep -c "this would replace own.yaml, the grammar this run reads" "$tmp/err"):$(md5sum < own.yaml)"
run render own.yaml --positions own.csv --steps 8 --backend cpu "${size[@]}" -o own.csv
check "render -o its positions" "2:1:x,y,rotation,seed" "$rc:$(grep -c "the positions file this run reads" "$tmp/err"):$(head -1 own.csv)"
run render "$g" --rows 1 --per-row 2 --steps 8 --backend cpu --no-resolve --resolve-clearance 0.05 "${size[@]}" -o g.png
check "render --no-resolve --resolve-clearance" "2:canopy: error: --resolve-clearance: with --no-resolve a picture has no use for it" \
  "$rc:$(cat "$tmp/err")"

echo "$pass passed, $failures failed"
[ "$failures" -eq 0 ]
