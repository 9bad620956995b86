#!/usr/bin/env bash
# canopy stand end to end: files written, the Khronos glTF validator and assimp on them, the
# grammar's stand entry, per-plant seeds matching canopy derive, bad input with no partial output.
# Usage: CANOPY=path/to/canopy test_cli_stand.sh SOURCE_DIR
set -u
src=$1
canopy=${CANOPY:?set CANOPY to the canopy binary}
source "$(dirname "$0")/check.sh"

out=$tmp/s
"$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 3 --jitter 0.02 --random-rotation --seed 4 \
  --steps 14 --formats glb,obj,ply -o "$out" >"$tmp/log" 2>&1
check "stand exit" "0" "$?"
check "files" "contacts.csv contacts_after.csv organs.csv plants.csv report.json stand.glb stand.mtl stand.obj stand.ply" "$(ls "$out" | tr '\n' ' ' | sed 's/ $//')"
check "plants.csv rows" "7" "$(wc -l < "$out/plants.csv" | tr -d ' ')"
organs=$(($(wc -l < "$out/organs.csv") - 1))
check "report organs" "$organs" "$(python3 -c "import json;print(json.load(open('$out/report.json'))['counts']['organs'])")"
# The resident peak of each stage, where the kernel lets a process reset its high-water mark.
if python3 -c "
with open('/proc/self/clear_refs', 'w') as f: f.write('5')" 2>/dev/null; then
  check "report peak memory per stage" "detect detect_after export generate resolve total: in (0, 64) GB" \
    "$(python3 -c "import json;m=json.load(open('$out/report.json'))['peak_memory_gb']
print(' '.join(sorted(m)) + (': in (0, 64) GB' if all(0 < v < 64 for v in m.values()) else ': out of range'))")"
  check "terminal peak memory" "1" "$(grep -c '^  peak memory (GB): detect ' "$tmp/log")"
else
  echo "report peak memory: not checked here (/proc/self/clear_refs cannot be written)"
fi

# glTF validator (npm gltf-validator, installed by scripts/setup.sh) and assimp (Debian assimp-utils).
validator="$src/tests/tools/node/validate_gltf.js"
if [ -d "$src/tests/tools/node/node_modules/gltf-validator" ]; then
  node "$validator" "$out/stand.glb" >"$tmp/v" 2>&1
  check "gltf validator" "0" "$?"
  check "gltf validator errors" "1" "$(grep -c '^errors 0 ' "$tmp/v")"
  "$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 2 --steps 10 --glb-instancing -o "$tmp/inst" >/dev/null 2>&1
  node "$validator" "$tmp/inst/stand.glb" >"$tmp/v" 2>&1
  check "gltf validator (instanced)" "0" "$?"
  # A stand of no plants (a positions file with its header alone) is valid glTF in every form.
  printf 'x,y,rotation,seed\n' > "$tmp/none.csv"
  for form in --formats=glb --glb-compact --glb-instancing; do
    "$canopy" stand "$src/grammars/tomato.yaml" --positions "$tmp/none.csv" $form -o "$tmp/none" >/dev/null 2>&1
    node "$validator" "$tmp/none/stand.glb" >"$tmp/v" 2>&1
    check "gltf validator, no plants ($form)" "1" "$(grep -c '^errors 0 ' "$tmp/v")"
  done
else
  check "gltf validator installed (run scripts/setup.sh)" "yes" "no"
fi

# The compact glb (KHR_mesh_quantization): validator-clean, at least 2x smaller than the default
# glb of the same stand (default level of detail) written with 32-bit indices (the default's own
# indices are 16-bit where a plant fits, as the compact's are: it is smaller still, by less than
# 2x), the other files unchanged, and three.js's
# GLTFLoader reads the same meshes, organ ids and positions (within half the largest step,
# 25 um, plus float rounding) as from the default glb.
cstand() { "$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 3 --jitter 0.02 --random-rotation --seed 4 --steps 16 "$@"; }
cstand -o "$tmp/cd" >/dev/null 2>&1
cstand --glb-compact -o "$tmp/cc" >/dev/null 2>&1
check "compact exit" "0" "$?"
# The default glb's bytes with every index 32-bit: its size plus 2 bytes for each 16-bit index.
wide=$(python3 -c "
import json, struct, sys
d = open('$tmp/cd/stand.glb', 'rb').read()
n = struct.unpack_from('<I', d, 12)[0]
g = json.loads(d[20:20 + n])
short = sum(g['accessors'][p['indices']]['count'] for m in g['meshes'] for p in m['primitives']
            if g['accessors'][p['indices']]['componentType'] == 5123)
print(len(d) + 2 * short)")
check "compact 2x smaller than 32-bit indices" "yes" "$(awk -v a="$wide" -v b="$(stat -c %s "$tmp/cc/stand.glb")" \
  'BEGIN { print (b > 0 && 2 * b <= a) ? "yes" : "no (" a " / " b ")" }')"
check "compact smaller than the default" "yes" "$(awk -v a="$(stat -c %s "$tmp/cd/stand.glb")" -v b="$(stat -c %s "$tmp/cc/stand.glb")" \
  'BEGIN { print (b > 0 && b < a) ? "yes" : "no (" a " / " b ")" }')"
for f in organs.csv plants.csv contacts.csv contacts_after.csv; do
  check "compact: $f as the default run's" "same" "$(cmp -s "$tmp/cd/$f" "$tmp/cc/$f" && echo same || echo different)"
done
check "compact: report config" "True" "$(python3 -c "import json;print(json.load(open('$tmp/cc/report.json'))['config']['glb_compact'])")"
if [ -d "$src/tests/tools/node/node_modules/gltf-validator" ]; then
  node "$validator" "$tmp/cc/stand.glb" >"$tmp/v" 2>&1
  check "gltf validator (compact)" "0" "$?"
  check "gltf validator (compact) no warnings" "1" "$(grep -c '^errors 0 warnings 0 ' "$tmp/v")"
fi
if [ -d "$src/tests/tools/node/node_modules/three" ]; then
  node "$src/tests/tools/node/compare_three.mjs" "$tmp/cd/stand.glb" "$tmp/cc/stand.glb" 2.6e-5 >"$tmp/three" 2>&1
  check "three.js reads the compact glb as the default one" "0" "$?"
  grep -q '"ids_differ":0' "$tmp/three"
  check "three.js: organ ids" "0" "$?"
else
  check "three.js installed (run scripts/setup.sh)" "yes" "no"
fi
# Blender's own importer, where Blender is installed (Debian's blender; not required).
if command -v blender >/dev/null; then
  for d in cd cc; do
    timeout 300 blender -b --factory-startup --python "$src/tests/tools/blender_counts.py" -- "$tmp/$d/stand.glb" 2>&1 |
      sed -n 's/^BLENDER //p' >"$tmp/blender_$d"
  done
  check "blender reads the compact glb as the default one" "ok" "$(python3 -c "
import json; a, b = (json.load(open('$tmp/blender_' + d)) for d in ('cd', 'cc'))
same = all(a[k] == b[k] for k in ('meshes', 'vertices', 'triangles')) and a['meshes'] > 0
near = all(abs(x - y) <= 2.6e-5 for k in ('min', 'max') for x, y in zip(a[k], b[k]))
print('ok' if same and near else (a, b))" 2>&1)"
fi
cstand --glb-compact --threads 1 -o "$tmp/cc1" >/dev/null 2>&1
check "compact: threads 1 and default identical" "same" "$(cmp -s "$tmp/cc/stand.glb" "$tmp/cc1/stand.glb" && echo same || echo different)"
if command -v assimp >/dev/null; then
  tris=$(python3 -c "import json;print(json.load(open('$out/report.json'))['counts']['triangles'])")
  for f in stand.obj stand.ply; do
    assimp info "$out/$f" >"$tmp/a" 2>&1
    check "assimp $f" "0" "$?"
    check "assimp $f faces" "$tris" "$(grep -E '^Faces:' "$tmp/a" | awk '{print $2}')"
  done
  check "assimp obj meshes (one per organ)" "$organs" "$(assimp info "$out/stand.obj" 2>/dev/null | grep -E '^Meshes:' | head -1 | awk '{print $2}')"
else
  check "assimp installed (run scripts/setup.sh)" "yes" "no"
fi

# Contacts: sorted, the header of docs/design.md, and the report's exact count.
check "contacts header" "organ_a,organ_b,plant_a,plant_b,level" "$(head -1 "$out/contacts.csv")"
check "contacts sorted" "$(tail -n +2 "$out/contacts.csv" | sort -t, -k1,1n -k2,2n)" "$(tail -n +2 "$out/contacts.csv")"
check "report exact" "$(($(wc -l < "$out/contacts.csv") - 1))" \
  "$(python3 -c "import json;print(json.load(open('$out/report.json'))['contacts_before']['exact']['total'])")"
"$canopy" detect "$out" --backend cpu --csv "$tmp/again.csv" >/dev/null 2>&1
check "detect reads the resolved stand back" "$(cat "$out/contacts_after.csv")" "$(cat "$tmp/again.csv")"

# Resolution: on by default, the report's numbers, nothing left on this row stand; --no-resolve
# exports the stand as grown (detection of the export gives contacts.csv back).
report() { python3 -c "import json;r=json.load(open('$1/report.json'));print($2)"; }
check "resolved: no contact left" "1" "$(wc -l < "$out/contacts_after.csv" | tr -d ' ')"
check "resolved: report after" "0" "$(report "$out" "r['contacts_after']['exact']['total']")"
check "resolved: report fields" "True" "$(report "$out" "all(k in r['resolution'] for k in ['iterations','organs_moved','mean_turn_deg','max_turn_deg','unresolvable'])")"
check "resolved: turned" "True" "$(report "$out" "r['resolution']['organs_moved'] > 0 and 0 < r['resolution']['max_turn_deg'] <= 60")"
grep -q "^resolution: " "$tmp/log"
check "resolved: terminal summary" "0" "$?"
check "resolved: no progress line off a terminal" "0" "$(grep -c 'resolving:' "$tmp/log")"
"$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 3 --jitter 0.02 --random-rotation --seed 4 \
  --steps 14 --no-resolve -o "$tmp/nr" >/dev/null 2>&1
check "no-resolve: contacts.csv as resolved run" "$(cat "$out/contacts.csv")" "$(cat "$tmp/nr/contacts.csv")"
check "no-resolve: contacts_after.csv = contacts.csv" "$(cat "$tmp/nr/contacts.csv")" "$(cat "$tmp/nr/contacts_after.csv")"
# The resolution's fields are there either way (a reader of resolution.iterations found null).
check "no-resolve: resolution not run" "False 0 0 0.0 0 True not run (--no-resolve)" \
  "$(report "$tmp/nr" "r['resolution']['ran'], r['resolution']['iterations'], r['resolution']['organs_moved'], r['resolution']['max_turn_deg'], r['resolution']['unresolvable'], r['resolution']['contacts_before'] == r['resolution']['contacts_after'] == r['contacts_before']['exact']['total'] == $(($(wc -l < "$tmp/nr/contacts.csv") - 1)), r['resolution']['stop']")"
check "resolved: resolution ran" "True" "$(report "$out" "r['resolution']['ran']")"
"$canopy" detect "$tmp/nr" --backend cpu --csv "$tmp/again2.csv" >/dev/null 2>&1
check "detect reads the grown stand back" "$(cat "$tmp/nr/contacts.csv")" "$(cat "$tmp/again2.csv")"

# The same files, byte for byte, on any thread count (report.json aside: timings).
for t in 1 2; do
  "$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 4 --plant-spacing 0.25 --row-spacing 0.3 --jitter 0.02 \
    --random-rotation --seed 9 --steps 16 --formats glb,obj,ply --threads $t -o "$tmp/t$t" >/dev/null 2>&1
done
for f in stand.glb stand.obj stand.ply organs.csv plants.csv contacts.csv contacts_after.csv; do
  cmp -s "$tmp/t1/$f" "$tmp/t2/$f"
  check "threads 1 and 2: $f identical" "0" "$?"
done
check "threads 1 and 2: resolution identical" "$(report "$tmp/t1" "{k: v for k, v in r['resolution'].items() if k != 'rounds'}")" \
  "$(report "$tmp/t2" "{k: v for k, v in r['resolution'].items() if k != 'rounds'}")"
# The CPU backend's device names the run's threads, not the machine's.
for t in 1 2; do
  [ "$(report "$tmp/t$t" "r['backend']")" = cpu ] &&
    check "threads $t: device" "$t CPU threads" "$(report "$tmp/t$t" "r['device']")"
done
"$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 3 --jitter 0.02 --random-rotation --seed 4 --steps 14 \
  --level organ -o "$tmp/lv" >/dev/null 2>&1
check "organ level rows" "1" "$(tail -n +2 "$tmp/lv/contacts.csv" | awk -F, '$5!="organ"' | wc -l | awk '{print ($1==0)}')"
"$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 3 --steps 14 --level leaf -o "$tmp/lf" >/dev/null 2>&1
check "leaf level rows have no organs" "0" "$(tail -n +2 "$tmp/lf/contacts.csv" | awk -F, '$1!=-1 || $2!=-1' | wc -l | tr -d ' ')"

# The grammar's stand entry applies without layout options.
"$canopy" stand "$src/grammars/sunflower.yaml" --steps 4 -o "$tmp/g" >/dev/null 2>&1
check "grammar stand entry" "41" "$(wc -l < "$tmp/g/plants.csv" | tr -d ' ')"
# A stand entry naming a positions file (beside the grammar) lays the plants out from it; row
# options on the command line take its place; row keys beside it are refused.
mkdir -p "$tmp/gp"
printf 'x,y,rotation,seed\n0,0,0,1\n2,0,0,2\n0,3,0,3\n' > "$tmp/gp/pp.csv"
sed 's/^stand:.*/stand: {positions: pp.csv}/' "$src/grammars/sunflower.yaml" > "$tmp/gp/g.yaml"
"$canopy" stand "$tmp/gp/g.yaml" --steps 4 -o "$tmp/gpo" >/dev/null 2>&1
check "grammar positions entry" "0 0,0;2,0;0,3" \
  "$? $(tail -n +2 "$tmp/gpo/plants.csv" | cut -d, -f2,3 | paste -sd';')"
"$canopy" stand "$tmp/gp/g.yaml" --steps 4 --rows 1 --per-row 2 -o "$tmp/gpo" >/dev/null 2>&1
check "row options over a positions entry" "3" "$(wc -l < "$tmp/gpo/plants.csv" | tr -d ' ')"
sed 's/^stand:.*/stand: {positions: pp.csv, rows: 2}/' "$src/grammars/sunflower.yaml" > "$tmp/gp/g2.yaml"
"$canopy" stand "$tmp/gp/g2.yaml" --steps 4 -o "$tmp/gpo2" >/dev/null 2>"$tmp/e"
check "positions entry with rows refused" "1 1" "$? $(grep -c "'rows' is a row layout's" "$tmp/e")"
# Refusals of what the entry gave start with its place: a positions file it names that is not
# there, double rows wider than its row spacing, plants it would place past 1e8 m (they named
# the command-line options, never given, or no place at all).
sed 's/^stand:.*/stand: {positions: gone.csv}/' "$src/grammars/sunflower.yaml" > "$tmp/gp/g3.yaml"
"$canopy" stand "$tmp/gp/g3.yaml" --steps 4 -o "$tmp/gpo3" >/dev/null 2>"$tmp/e"
check "missing positions of an entry: its place" "2 1" \
  "$? $(grep -c "g3.yaml:[0-9]*:[0-9]*: stand: positions: .*gone.csv: cannot open the positions file" "$tmp/e")"
sed 's/^stand:.*/stand: {rows: 2, per_row: 2, double_rows: 5, row_spacing: 1}/' "$src/grammars/sunflower.yaml" > "$tmp/gp/g4.yaml"
"$canopy" stand "$tmp/gp/g4.yaml" --steps 4 -o "$tmp/gpo4" >/dev/null 2>"$tmp/e"
check "entry's double rows: its place" "2 1" \
  "$? $(grep -c "g4.yaml:[0-9]*:[0-9]*: double rows 5 m apart (the stand entry's double_rows)" "$tmp/e")"
sed 's/^stand:.*/stand: {rows: 2, per_row: 3, plant_spacing: 60000000}/' "$src/grammars/sunflower.yaml" > "$tmp/gp/g5.yaml"
"$canopy" stand "$tmp/gp/g5.yaml" --steps 4 -o "$tmp/gpo5" >/dev/null 2>"$tmp/e"
check "entry's reach: its place, no option named" "2 1 0" \
  "$? $(grep -c "g5.yaml:[0-9]*:[0-9]*: the stand entry's per_row 3 x the stand entry's plant_spacing" "$tmp/e") $(grep -c -- '--per-row' "$tmp/e")"
# A row option changes only that field of the grammar's stand entry (tomato.yaml: one row of 100,
# 1.0 m x 0.4 m, random rotation, 2 cm jitter, seed 1): the plants of the entry with every field
# written out but that one, and report.json and the terminal say where each value came from.
entry() {  # the tomato entry's fields as options, with one replaced: entry FIELD VALUE...
  local -A f=([--rows]=1 [--per-row]=100 [--row-spacing]=1.0 [--plant-spacing]=0.4 [--jitter]=0.02 [--seed]=1)
  f[$1]=$2
  for k in "${!f[@]}"; do printf '%s %s ' "$k" "${f[$k]}"; done
  echo --random-rotation
}
for field in "--per-row 5" "--seed 7" "--jitter 0.05" "--plant-spacing 0.3"; do
  read -r opt val <<<"$field"
  rm -rf "$tmp/one" "$tmp/all"
  "$canopy" stand "$src/grammars/tomato.yaml" --steps 6 --no-resolve --level organ $field -o "$tmp/one" >"$tmp/one.log" 2>&1
  # shellcheck disable=SC2046
  "$canopy" stand "$src/grammars/tomato.yaml" --steps 6 --no-resolve --level organ $(entry "$opt" "$val") -o "$tmp/all" >/dev/null 2>&1
  check "$opt alone: plants as the entry with that field changed" "$(cat "$tmp/all/plants.csv")" "$(cat "$tmp/one/plants.csv" 2>&1)"
  key=$(tr -- - _ <<<"${opt#--}")
  check "$opt alone: report sources" "$key:command line" "$(report "$tmp/one" "','.join(k+':'+v for k, v in r['config']['layout']['sources'].items() if v != 'grammar' and k != 'double_rows')")"
  check "$opt alone: terminal" "1" "$(grep -c "^layout: .*$key $val[ m]* (command line)" "$tmp/one.log")"
done
check "rotation from the entry" "1" "$(awk -F, 'NR > 1 && $4 != 0' "$tmp/one/plants.csv" | wc -l | awk '{print ($1 > 0)}')"
"$canopy" stand "$src/grammars/tomato.yaml" --steps 6 --no-resolve --level organ --per-row 5 --no-random-rotation -o "$tmp/norot" >/dev/null 2>&1
check "--no-random-rotation over the entry" "0" "$(awk -F, 'NR > 1 && $4 != 0' "$tmp/norot/plants.csv" | wc -l | tr -d ' ')"
check "--no-random-rotation keeps the entry's jitter" "1" "$(awk -F, 'NR > 1 && $3 != 0' "$tmp/norot/plants.csv" | wc -l | awk '{print ($1 > 0)}')"

# A plant with seed s derives exactly what canopy derive --seed s prints: its organs, counted
# (the organ modules, and the modules the interpretation turns into one organ each: internode
# In, petiole pe, rachis ra, leaflets lf and li).
seed=$(sed -n '4p' "$out/plants.csv" | cut -d, -f5)
want=$("$canopy" derive "$src/grammars/tomato.yaml" --steps 14 --seed "$seed" --stats | python3 -c "
import json,sys; c=json.load(sys.stdin)['counts']; print(sum(c.get(k,0) for k in ['I','P','R','L','Li','D','Fr','In','pe','ra','lf','li']))")
check "plant seed derives the same" "$want" "$(awk -F, '$2==2' "$out/organs.csv" | wc -l | tr -d ' ')"

# Bad input: one line, non-zero exit, no partial output.
expect_error() {  # expect_error NAME PATTERN ARGS...
  local name=$1 pattern=$2; shift 2
  rm -rf "$tmp/bad"
  "$canopy" stand "$@" -o "$tmp/bad" >"$tmp/o" 2>"$tmp/e"
  local rc=$?
  check "$name exit" "1" "$([ $rc -ne 0 ] && echo 1 || echo 0)"
  check "$name message" "1" "$(grep -c -- "$pattern" "$tmp/e")"
  check "$name one line" "1" "$(wc -l < "$tmp/e" | tr -d ' ')"
  check "$name no files" "0" "$(ls "$tmp/bad" 2>/dev/null | wc -l | tr -d ' ')"
}
printf 'axiom: I(1, 0.1)\nsteps: 1\nproductions:\n  - I(a, b) -> I(a - 2, b)\norgans:\n  I: {prototype: cylinder, kind: internode}\n' > "$tmp/neg.yaml"
expect_error "negative length" "module 0 'I(-1,0.1)': cylinder parameter 1 must not be negative" "$tmp/neg.yaml"
printf 'axiom: L(1)\norgans:\n  L: {prototype: leaflet, kind: leaflet}\n' > "$tmp/arity.yaml"
expect_error "organ arity" "arity.yaml:1:8: organ 'L' is a leaflet and takes 2 to 5 parameters, but is used with 1" "$tmp/arity.yaml"
printf 'x,y,seed\n0,0,1\n' > "$tmp/pos.csv"
expect_error "positions columns" "pos.csv:1: missing column 'rotation'" "$src/grammars/tomato.yaml" --positions "$tmp/pos.csv"
printf 'x,y,rotation,seed\n0,zero,0,1\n' > "$tmp/pos2.csv"
expect_error "positions cell" "pos2.csv:2:3: column 'y' needs a finite number, got 'zero'" "$src/grammars/tomato.yaml" --positions "$tmp/pos2.csv"
expect_error "too large" "needs about .* [GM]B .* more than the .* [GM]B available" "$src/grammars/tomato.yaml" --rows 100000 --per-row 100000
expect_error "formats" "unknown format 'fbx'" "$src/grammars/tomato.yaml" --formats glb,fbx
expect_error "collide" "unknown organ kind 'root'" "$src/grammars/tomato.yaml" --collide leaflet,root
expect_error "collide all in a list" "'all' stands alone (every kind), not in a list of kinds ('all,leaflet')" "$src/grammars/tomato.yaml" --collide all,leaflet
expect_error "two glb forms" "--glb-instancing and --glb-compact are two forms of stand.glb: choose one" \
  "$src/grammars/tomato.yaml" --rows 1 --per-row 2 --glb-instancing --glb-compact
# A run into a folder of an earlier one in other formats: the earlier meshes go (the folder holds
# one stand), and the run says so; a failed run removes nothing.
rm -rf "$tmp/again"
"$canopy" stand "$src/grammars/tomato.yaml" --rows 1 --per-row 2 --steps 10 --formats obj,ply -o "$tmp/again" >/dev/null 2>&1
"$canopy" stand "$src/grammars/tomato.yaml" --rows 1 --per-row 2 --steps 10 --formats glb -o "$tmp/again" --collide root >/dev/null 2>&1
check "failed run keeps earlier meshes" "stand.mtl stand.obj stand.ply" "$(cd "$tmp/again" && echo stand.*)"
"$canopy" stand "$src/grammars/tomato.yaml" --rows 1 --per-row 2 --steps 10 --formats glb -o "$tmp/again" >"$tmp/o" 2>&1
check "stale meshes removed" "stand.glb" "$(cd "$tmp/again" && echo stand.*)"
check "stale meshes named" "1" "$(grep -c 'removed stand.obj, stand.mtl, stand.ply left by an earlier run' "$tmp/o")"

# Real-number options refuse NaN and infinities (CLI11's own checks compare, and let NaN through:
# a NaN --clearance found no contact, a NaN --resolve-step never ended).
for opt in "--clearance nan" "--resolve-clearance inf" "--resolve-step nan" "--jitter nan" "--row-spacing -inf"; do
  rm -rf "$tmp/bad"
  timeout 60 "$canopy" stand "$src/grammars/tomato.yaml" --rows 1 --per-row 2 $opt -o "$tmp/bad" >/dev/null 2>"$tmp/e"
  rc=$?
  check "$opt refused" "1" "$([ $rc -ne 0 ] && [ $rc -ne 124 ] && echo 1 || echo 0)"
  check "$opt message" "1" "$(grep -c -- "${opt%% *}: needs a finite number, got ${opt##* }" "$tmp/e")"
  check "$opt no files" "0" "$(ls "$tmp/bad" 2>/dev/null | wc -l | tr -d ' ')"
done
# A clearance of 0.1 m or more runs, with a note that it is in metres (millimetres typed where
# metres are read make most organ pairs a contact); a usual one says nothing.
"$canopy" stand "$src/grammars/tomato.yaml" --rows 1 --per-row 2 --steps 8 --clearance 0.5 --resolve-clearance 2 --no-resolve \
  -o "$tmp/far" >/dev/null 2>"$tmp/e"
check "large clearance runs" "0" "$?"
check "large clearance noted" "1" "$(grep -c -- '--clearance is in metres: 0.5 is 500 mm (for 0.5 mm write 0.0005)' "$tmp/e")"
check "large resolve clearance noted" "1" "$(grep -c -- '--resolve-clearance is in metres: 2 is 2000 mm' "$tmp/e")"
"$canopy" stand "$src/grammars/tomato.yaml" --rows 1 --per-row 2 --steps 8 --clearance 0.002 --no-resolve -o "$tmp/near" >/dev/null 2>"$tmp/e"
check "usual clearance quiet" "0" "$(grep -c 'in metres' "$tmp/e")"
"$canopy" stand "$src/grammars/tomato.yaml" -o /proc/canopy-no >/dev/null 2>"$tmp/e"
check "unwritable exit" "1" "$?"
check "unwritable message" "1" "$(grep -c 'cannot create the output folder /proc/canopy-no' "$tmp/e")"

# Positions files may mix grammars and ages.
printf 'x,y,rotation,seed,grammar,steps\n0,0,0,1,tomato.yaml,10\n0.5,0,90,2,sunflower.yaml,6\n' > "$tmp/mixed.csv"
cp "$src/grammars/tomato.yaml" "$src/grammars/sunflower.yaml" "$tmp/"
"$canopy" stand "$src/grammars/tomato.yaml" --positions "$tmp/mixed.csv" -o "$tmp/m" >/dev/null 2>"$tmp/e"
check "mixed exit" "0" "$?"
check "mixed plants" "1,0.5,0,90,2,sunflower.yaml,6" "$(sed -n 3p "$tmp/m/plants.csv")"

# The heap's pages: small unless asked for or the run uses the GPU; a run in large pages (the
# program runs itself again with glibc.malloc.hugetlb=1, where the kernel offers them) writes the
# same files.
check "heap pages small" "1" "$(CANOPY_HEAP_PAGES=small "$canopy" info | grep -c '^heap pages: small')"
if [ ! -e /dev/nvidiactl ]; then
  check "heap pages without a GPU" "1" "$(env -u CANOPY_HEAP_PAGES "$canopy" info | grep -c '^heap pages: small')"
fi
# Large only where the machine can give them, decided as the program does (heap_pages_possible):
# the kernel's setting readable and not [never] (unreadable where /sys is not mounted), glibc
# 2.35 or later, /proc/self/exe there.
thp=/sys/kernel/mm/transparent_hugepage/enabled
glibc=$(getconf GNU_LIBC_VERSION 2>/dev/null | awk '{print $2}')
if [ -r "$thp" ] && ! grep -q '\[never\]' "$thp" && [ -x /proc/self/exe ] &&
   [ "$(printf '%s\n' 2.35 "${glibc:-0}" | sort -V | head -1)" = 2.35 ]; then want=large; else want=small; fi
check "heap pages large" "1" "$(CANOPY_HEAP_PAGES=large "$canopy" info | grep -c "^heap pages: $want")"
# With the kernel's setting out of sight (as in a root without /sys), small, and the run goes on;
# checked where this machine can hide it (a mount namespace).
if unshare -rm true 2>/dev/null && [ -d "$(dirname "$thp")" ]; then
  check "heap pages without /sys" "heap pages: small" \
    "$(CANOPY_HEAP_PAGES=large unshare -rm sh -c "mount -t tmpfs none $(dirname "$thp") && exec \"$canopy\" info" | grep '^heap pages' | cut -d' ' -f1-3)"
fi
for pages in small large; do
  CANOPY_HEAP_PAGES=$pages "$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 3 --jitter 0.02 --random-rotation \
    --seed 4 --steps 14 --formats obj --backend cpu -o "$tmp/heap_$pages" >/dev/null 2>&1
  check "heap pages $pages exit" "0" "$?"
done
for f in organs.csv contacts.csv contacts_after.csv stand.obj; do
  check "heap pages same $f" "same" "$(cmp -s "$tmp/heap_small/$f" "$tmp/heap_large/$f" && echo same || echo different)"
done

# OpenMP waits: a stand run runs itself again with OMP_WAIT_POLICY=passive (tools/process_rerun.hpp)
# unless the user set a policy or a spin count; the files are the same either way.
waits_of() {  # ENV...: OMP_WAIT_POLICY in the environment of a running canopy stand, once it has rerun
  env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT -u CANOPY_RERUN "$@" "$canopy" stand "$src/grammars/tomato.yaml" \
    --rows 4 --per-row 100 --steps 14 --no-resolve --backend cpu -o "$tmp/waits" >/dev/null 2>&1 &
  local pid=$! seen="" i
  for i in $(seq 200); do
    local e
    e=$(tr '\0' '\n' 2>/dev/null <"/proc/$pid/environ") || break
    [ -n "$e" ] && seen=$e
    grep -q '^CANOPY_RERUN=' <<<"$e" && break
    sleep 0.01
  done
  wait "$pid"
  grep '^OMP_WAIT_POLICY=' <<<"$seen" || echo unset
}
check "waits passive by default" "OMP_WAIT_POLICY=passive" "$(waits_of)"
check "waits as the user set them" "OMP_WAIT_POLICY=active" "$(waits_of OMP_WAIT_POLICY=active)"
check "a spin count is left alone" "unset" "$(waits_of GOMP_SPINCOUNT=1000)"
check "info says so" "1" "$(env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$canopy" info | grep -c '^openmp waits: passive in stand')"
GOMP_SPINCOUNT=300000 "$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 3 --jitter 0.02 --random-rotation \
  --seed 4 --steps 14 --formats obj --backend cpu -o "$tmp/spinning" >/dev/null 2>&1
for f in organs.csv contacts.csv contacts_after.csv stand.obj; do
  check "waits same $f" "same" "$(cmp -s "$tmp/heap_small/$f" "$tmp/spinning/$f" && echo same || echo different)"
done

# --resolve-stats: where resolution's time went, on stderr, phase by phase and lane by lane (the
# library collects, the tool prints); the files those of the same run without it.
"$canopy" stand "$src/grammars/tomato.yaml" --rows 2 --per-row 3 --jitter 0.02 --random-rotation --seed 4 --steps 14 \
  --formats obj --backend cpu --resolve-stats -o "$tmp/stats" >"$tmp/stats.out" 2>"$tmp/stats.err"
check "resolve-stats exit" "0" "$?"
check "resolve-stats phases" "1" "$(grep -c '^resolution phases (s): setup [0-9.]*, witnesses' "$tmp/stats.err")"
check "resolve-stats page faults" "1" "$(grep -c '^resolution minor page faults (thousands): setup' "$tmp/stats.err")"
check "resolve-stats lane" "1" "$(grep -c '^planning lane 0: ' "$tmp/stats.err")"
check "resolve-stats not on stdout" "0" "$(grep -c 'resolution phases' "$tmp/stats.out")"
check "no resolve-stats, no statistics" "0" "$(grep -c 'resolution phases' "$tmp/log")"
for f in organs.csv contacts.csv contacts_after.csv stand.obj; do
  check "resolve-stats same $f" "same" "$(cmp -s "$tmp/heap_small/$f" "$tmp/stats/$f" && echo same || echo different)"
done

# A glb past the format's 4 GiB is refused before detection, not at the export.
"$canopy" stand "$src/grammars/tomato.yaml" --rows 15 --per-row 100 --lod 16 -o "$tmp/big" >/dev/null 2>"$tmp/e"
check "glb past 4 GiB refused early" "1 1 0 absent" \
  "$? $(grep -c 'stand.glb would exceed 4 GiB' "$tmp/e") $(grep -c detection "$tmp/e") $([ -e "$tmp/big" ] && echo present || echo absent)"

# --backend cuda on a machine without a GPU: an error of the run (exit 1), nothing written.
if [ ! -e /dev/nvidiactl ]; then
  "$canopy" stand "$src/grammars/tomato.yaml" --rows 1 --per-row 2 --steps 10 --backend cuda -o "$tmp/nogpu" \
    >"$tmp/o" 2>"$tmp/e"
  check "--backend cuda without a GPU refused" "1 1 absent" \
    "$? $(grep -c 'no usable GPU' "$tmp/e") $([ -e "$tmp/nogpu" ] && echo present || echo absent)"
fi

# Help lines for every option.
help=$("$canopy" stand --help)
for opt in --out --steps --set --lod --formats --threads --rows --per-row --row-spacing --plant-spacing \
           --double-rows --jitter --random-rotation --no-random-rotation --seed --positions --max-modules --glb-instancing \
           --glb-compact \
           --level --clearance --collide --backend --no-resolve --max-rounds --resolve-clearance --resolve-level \
           --resolve-stats --max-device-memory; do
  check "help $opt" "1" "$(grep -q -- "$opt" <<<"$help" && echo 1 || echo 0)"
done

echo "$pass passed, $failures failed"
[ "$failures" -eq 0 ]
