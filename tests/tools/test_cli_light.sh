#!/usr/bin/env bash
# canopy light end to end: the files and their keys, the same figures from a grammar and from its
# folder and on any thread count, the tile of a row layout, positions files, the sun's position,
# bad options refused with the folder left as it was; report.json's leaf angles; a stand grown
# to a target LAI or ground cover.
# Usage: CANOPY=path/to/canopy test_cli_light.sh SOURCE_DIR
set -u
src=$1
canopy=${CANOPY:?set CANOPY to the canopy binary}
source "$(dirname "$0")/check.sh"
g="$src/grammars/tomato.yaml"
rows=(--rows 2 --per-row 3 --steps 12 --random-rotation --jitter 0.02 --seed 3 --backend cpu)
light=(--sun 60,180 --sun 35,100 --sky-directions 12 --error 0.004)
json() { python3 -c "import json; j=json.load(open('$1')); print($2)"; }

"$canopy" light "$g" "${rows[@]}" "${light[@]}" -o "$tmp/a" >"$tmp/log" 2>&1
check "from a grammar: exit" "0" "$?"
check "files" "contacts.csv contacts_after.csv light.csv light.json organs.csv plants.csv report.json stand.glb" \
  "$(ls "$tmp/a" | tr '\n' ' ' | sed 's/ $//')"
check "keys" "True" "$(json "$tmp/a/light.json" "all(k in j for k in ('tile','lai','ground_cover','star','direct','diffuse','leaf_angles'))")"
check "direct entries" "[['elevation', 'azimuth', 'intercepted_fraction', 'rays', 'standard_error'], ['elevation', 'azimuth', 'intercepted_fraction', 'rays', 'standard_error']]" \
  "$(json "$tmp/a/light.json" "[list(d) for d in j['direct']]")"
check "diffuse" "soc 12 True" "$(json "$tmp/a/light.json" "j['diffuse']['sky'], j['diffuse']['directions'], 0 < j['diffuse']['intercepted_fraction'] < 1")"
check "errors reached" "True" "$(json "$tmp/a/light.json" "all(d['standard_error'] <= 0.004 for d in j['direct'] + [j['diffuse']]) and j['ground_cover_standard_error'] <= 0.004")"
check "tile: the rows' lattice" "[-0.2, -0.5, 1.0, 1.5]" "$(json "$tmp/a/light.json" "j['tile']")"
check "lai over the tile" "True" "$(json "$tmp/a/light.json" "abs(j['lai'] - j['leaf_area'] / 2.4) < 1e-12")"
check "light.csv: a row per plant" "7" "$(wc -l < "$tmp/a/light.csv" | tr -d ' ')"
check "light.csv: shares sum to one" "True" "$(python3 -c "
import csv; r=list(csv.DictReader(open('$tmp/a/light.csv'))); print(all(abs(sum(float(x[c]) for x in r) - 1) < 1e-9 for c in ('sun1_share','sun2_share','diffuse_share')))")"
check "light.csv: plants average to the stand" "True" "$(python3 -c "
import csv, json; r=list(csv.DictReader(open('$tmp/a/light.csv'))); j=json.load(open('$tmp/a/light.json'))
print(abs(sum(float(x['sun1_fraction']) for x in r) / len(r) - j['direct'][0]['intercepted_fraction']) < 1e-12)")"
check "profile sums to the stand" "True" "$(json "$tmp/a/light.json" "abs(sum(l['direct'][0]['intercepted_fraction'] for l in j['profile']['layers']) - j['direct'][0]['intercepted_fraction']) < 1e-9")"
check "kinds sum to the stand" "True" "$(json "$tmp/a/light.json" "abs(sum(k['diffuse']['intercepted_fraction'] for k in j['kinds'].values()) - j['diffuse']['intercepted_fraction']) < 1e-9")"

# The folder gives the same figures; so does any thread count (light.csv byte for byte).
cp "$tmp/a/light.json" "$tmp/grammar.json"; cp "$tmp/a/light.csv" "$tmp/grammar.csv"
"$canopy" light "$tmp/a" "${light[@]}" --threads 1 --backend cpu >"$tmp/log" 2>&1
check "from the folder: exit" "0" "$?"
strip() { python3 -c "import json; j=json.load(open('$1')); j.pop('timings_s'); j.pop('source'); print(json.dumps(j))"; }
check "folder = grammar" "$(strip "$tmp/grammar.json")" "$(strip "$tmp/a/light.json")"
cmp -s "$tmp/grammar.csv" "$tmp/a/light.csv"
check "light.csv: one thread = all" "0" "$?"
# An isolated stand: a tile that leaves out a plant is refused before any ray; a fraction above
# 1 (the stand's shadow longer than its tile) is said.
"$canopy" light "$tmp/a" --no-periodic --tile 0,0,0.1,0.1 --backend cpu >"$tmp/o" 2>"$tmp/e"
check "isolated: tile leaving plants out refused" "2 1" "$? $(grep -c 'must hold every plant.s base; plant 0 stands at' "$tmp/e")"
"$canopy" light "$tmp/a" --no-periodic --sun 3,0 --sky-directions 0 --backend cpu >"$tmp/o" 2>"$tmp/e"
check "isolated: a fraction above 1 is said" "0 1 True" "$? $(grep -c 'note: the isolated stand intercepts light from beyond its tile' "$tmp/e") \
$(json "$tmp/a/light.json" "j['direct'][0]['intercepted_fraction'] > 1")"
# The lattice tile comes from report.json's layout: one that is not of this stand's plants, or not
# a layout canopy stand writes, is refused naming report.json.
cp -r "$tmp/a" "$tmp/rl"
python3 -c "import json; p='$tmp/rl/report.json'; j=json.load(open(p)); j['config']['layout']['rows']=1; json.dump(j,open(p,'w'))"
"$canopy" light "$tmp/rl" --backend cpu >"$tmp/o" 2>"$tmp/e"
check "report's layout of other plants refused" "2 1" "$? $(grep -c 'report.json: its layout (1 rows of 3 plants) does not match the 6 plants of plants.csv' "$tmp/e")"
# The same count in another shape (3 rows of 2 for 2 rows of 3) lit it over another tile.
rm -rf "$tmp/rl"; cp -r "$tmp/a" "$tmp/rl"
python3 -c "import json; p='$tmp/rl/report.json'; j=json.load(open(p)); l=j['config']['layout']; l['rows'],l['per_row']=l['per_row'],l['rows']; json.dump(j,open(p,'w'))"
"$canopy" light "$tmp/rl" --backend cpu >"$tmp/o" 2>"$tmp/e"
check "report's layout of another shape refused" "2 1" "$? $(grep -c 'report.json: its layout (3 rows of 2 plants) places plant 2 at' "$tmp/e")"
python3 -c "import json; p='$tmp/rl/report.json'; j=json.load(open(p)); j['config']['layout']['rows']=2.5; json.dump(j,open(p,'w'))"
"$canopy" light "$tmp/rl" --backend cpu >"$tmp/o" 2>"$tmp/e"
check "report's rows 2.5 refused" "2 1" "$? $(grep -c 'report.json: config.layout.rows must be a whole number from 1 to 2147483647, got 2.5' "$tmp/e")"
# A folder of the user's under a light file's name is refused before any work, never removed.
cp -r "$tmp/a" "$tmp/uf"; rm "$tmp/uf/light.json"; mkdir -p "$tmp/uf/light.json/mine"; echo kept > "$tmp/uf/light.json/mine/a.txt"
"$canopy" light "$tmp/uf" "${light[@]}" --backend cpu >"$tmp/o" 2>"$tmp/e"
check "a folder named light.json: refused, kept" "1 1 kept" \
  "$? $(grep -c 'light.json is a folder there' "$tmp/e") $(cat "$tmp/uf/light.json/mine/a.txt")"

# Rays answered by drawing the stand (--caster raster) or traced one by one (trace): the same rays,
# the same fractions but for rays grazing an edge.
"$canopy" light "$tmp/a" "${light[@]}" --backend cpu --caster trace >"$tmp/log" 2>&1
check "trace: no ray drawn" "0 None" "$(json "$tmp/a/light.json" "j['rays_rasterized'], j['raster_device']")"
cp "$tmp/a/light.json" "$tmp/traced.json"
"$canopy" light "$tmp/a" "${light[@]}" --backend cpu --caster raster >"$tmp/log" 2>&1
check "raster: exit" "0" "$?"
check "raster: every ray drawn, on the host" "True host raster" "$(json "$tmp/a/light.json" "j['rays_rasterized'] == j['rays'], j['raster_device'], j['config']['caster']")"
check "raster: the traced fractions" "True" "$(python3 -c "
import json; a=json.load(open('$tmp/traced.json')); b=json.load(open('$tmp/a/light.json'))
print(all(abs(x['intercepted_fraction'] - y['intercepted_fraction']) < 1e-3 for x, y in zip(a['direct'] + [a['diffuse']], b['direct'] + [b['diffuse']])))")"
"$canopy" light "$tmp/a" --caster rays >"$tmp/o" 2>"$tmp/e"
check "unknown caster refused" "1 1" "$([ $? -ne 0 ] && echo 1 || echo 0) $(grep -c 'caster' "$tmp/e")"
if [ ! -e /dev/nvidiactl ]; then
  "$canopy" light "$tmp/a" --backend cuda --sky-directions 0 >"$tmp/o" 2>"$tmp/e"
  check "--backend cuda without a GPU refused" "1 1" "$? $(grep -c 'no usable GPU' "$tmp/e")"
fi

# report.json's leaf angles: 18 bins of 5 degrees whose fractions sum to one; the same in light.json.
check "leaf angles bins" "18 True" "$(json "$tmp/a/report.json" "len(j['leaf_angles']['bins']), abs(sum(b['fraction'] for b in j['leaf_angles']['bins']) - 1) < 1e-12")"
check "leaf angles in both" "True" "$(python3 -c "
import json; print(json.load(open('$tmp/a/report.json'))['leaf_angles'] == json.load(open('$tmp/a/light.json'))['leaf_angles'])")"

# The sun from latitude, day and hours: at noon of day 172 at 52 N, 90 - 52 + 23.45 degrees, due south.
"$canopy" light "$tmp/a" --latitude 52 --day 172 --hours 12 --sky-directions 0 --error 0.01 >"$tmp/log" 2>&1
check "solar: exit" "0" "$?"
check "solar: position" "61.45 180.0 12.0" "$(json "$tmp/a/light.json" "'%.2f %.1f %.1f' % (j['direct'][0]['elevation'], j['direct'][0]['azimuth'], j['direct'][0]['solar_hour'])")"
check "no sky: no diffuse, no star" "None None" "$(json "$tmp/a/light.json" "j['diffuse'], j['star']")"

# light.json's tile is the tile as given, or the lattice as made, in world coordinates (it was
# carried through the jittered first plant's origin and back: -1 came out -0.9999999999999999).
"$canopy" light "$tmp/a" --tile -1,-1,2,2 --sun 90,0 --sky-directions 0 --error 0.01 >/dev/null 2>&1
check "--tile echoed exactly" "[-1.0, -1.0, 2.0, 2.0]" "$(json "$tmp/a/light.json" "j['tile']")"
"$canopy" light "$tmp/a" --sun 90,0 --sky-directions 0 --error 0.01 >/dev/null 2>&1
check "lattice tile exactly" "[-0.2, -0.5, 1.0, 1.5]" "$(json "$tmp/a/light.json" "j['tile']")"
# A positions file needs its tile; --tile or --no-periodic.
printf 'x,y,rotation,seed\n0,0,0,1\n0.5,0.1,90,2\n' > "$tmp/pos.csv"
"$canopy" stand "$g" --positions "$tmp/pos.csv" --steps 10 --backend cpu -o "$tmp/p" >/dev/null 2>&1
"$canopy" light "$tmp/p" --sky-directions 0 >"$tmp/o" 2>"$tmp/e"
check "positions: exit" "2" "$?"
check "positions: message" "1" "$(grep -c 'has no lattice: give its tile with --tile' "$tmp/e")"
"$canopy" light "$tmp/p" --sky-directions 0 --tile -0.3,-0.5,0.8,0.5 --error 0.01 >/dev/null 2>&1
check "positions with --tile" "[-0.3, -0.5, 0.8, 0.5] True" "$(json "$tmp/p/light.json" "j['tile'], j['periodic']")"
"$canopy" light "$tmp/p" --sky-directions 0 --no-periodic --error 0.01 >/dev/null 2>&1
check "positions isolated" "False" "$(json "$tmp/p/light.json" "j['periodic']")"
# From a grammar, what is refused once the stand is grown leaves no folder: the light is made
# with the stand's files and put in place with them (a tile under which the stand repeats 7e5
# times was refused after the stand was written).
"$canopy" light "$g" --rows 1 --per-row 2 --steps 10 --backend cpu --tile 0,0,0.001,0.001 -o "$tmp/tiny" >"$tmp/o" 2>"$tmp/e"
check "tiny tile: refused, no folder" "2 1 0" "$? $(grep -c 'copies of the stand over each point' "$tmp/e") $(ls -d "$tmp/tiny" "$tmp"/.tiny* 2>/dev/null | wc -l)"
# A sun so near the horizon that its rays cross more than 10,000 copies of the tile: refused at
# once (at 1e-6 degrees the trace ran for minutes and its memory grew without bound), naming the
# lowest elevation taken; one just above it is traced. The same from a sunrise hour.
timeout 60 "$canopy" light "$tmp/p" --sky-directions 0 --tile -0.3,-0.5,0.8,0.5 --sun 1e-6,0 >"$tmp/o" 2>"$tmp/e"
check "sun at the horizon refused" "2 1" "$? $(grep -c 'copies of the 1.1 x 1 m tile .*at most 10000).* give one above' "$tmp/e")"
low=$(sed -n 's/.*give one above \([0-9.e-]*\) degrees.*/\1/p' "$tmp/e")
timeout 60 "$canopy" light "$tmp/p" --sky-directions 0 --tile -0.3,-0.5,0.8,0.5 --sun "$(python3 -c "print($low * 1.01)"),0" --error 0.05 >/dev/null 2>&1
check "sun just above the bound traced" "0" "$?"
timeout 60 "$canopy" light "$tmp/p" --sky-directions 0 --tile -0.3,-0.5,0.8,0.5 --latitude 52 --day 172 --hours 3.7517 >/dev/null 2>"$tmp/e"
check "sunrise hour refused" "2 1" "$? $(grep -c 'a sun (--sun, --hours) at elevation' "$tmp/e")"
# A stand without leaflets has no STAR and no leaf angles: null in the JSON, empty in light.csv,
# "none" on the terminal (they read 0, as if its leaflets were all flat and lit nothing).
printf 'name: t\naxiom: I(0.3,0.01)\norgans:\n  I: {prototype: cylinder, kind: internode}\n' > "$tmp/bare.yaml"
"$canopy" light "$tmp/bare.yaml" --rows 2 --per-row 2 --sun 60,180 --sky-directions 8 --error 0.05 -o "$tmp/bare" >"$tmp/o" 2>&1
check "no leaflets: undefined, not 0" "0 None None None None 2" \
  "$? $(json "$tmp/bare/light.json" "j['star'], j['star_standard_error']") $(json "$tmp/bare/report.json" "j['leaf_angles']['mean_inclination_deg'], j['leaf_angles']['g'][0]['g']") $(grep -c 'none (no leaflets)' "$tmp/o")"
check "no leaflets: light.csv star empty" ",," "$(sed -n 2p "$tmp/bare/light.csv" | grep -o ',,$')"
# A sun given twice is refused, as an hour given twice is (it was traced twice, two suns).
"$canopy" light "$tmp/p" --sky-directions 0 --tile -0.3,-0.5,0.8,0.5 --sun 60,180 --sun 60.0,180 >/dev/null 2>"$tmp/e"
check "sun given twice" "2 canopy: error: --sun 60.0,180: given twice; give each sun once" "$? $(cat "$tmp/e")"
# A grammar whose stand entry is a positions file has no lattice either: refused before growing.
mkdir -p "$tmp/gp"
sed 's/^stand:.*$//' "$g" > "$tmp/gp/t.yaml"
printf '\nstand: {positions: pos.csv}\n' >> "$tmp/gp/t.yaml"
cp "$tmp/pos.csv" "$tmp/gp/pos.csv"
"$canopy" light "$tmp/gp/t.yaml" --steps 10 --backend cpu -o "$tmp/gpo" >"$tmp/o" 2>"$tmp/e"
check "grammar's positions: refused, no folder" "2 1 0" "$? $(grep -c 'has no lattice' "$tmp/e") $(ls -d "$tmp/gpo" 2>/dev/null | wc -l)"

# Bad options: exit 2, one line, light.json left as it was.
cp "$tmp/a/light.json" "$tmp/before.json"
bad() {  # bad NAME PATTERN ARGS...
  local name=$1 pattern=$2; shift 2
  "$canopy" light "$tmp/a" "$@" >"$tmp/o" 2>"$tmp/e"
  check "$name exit" "2" "$?"
  check "$name message" "1" "$(grep -c -- "$pattern" "$tmp/e")"
  cmp -s "$tmp/before.json" "$tmp/a/light.json"
  check "$name: light.json untouched" "0" "$?"
}
bad "sun below the horizon" "elevation 0 is not above the horizon" --sun 0,10
bad "sun not a pair" "'60;10' is not ELEVATION,AZIMUTH" --sun "60;10"
bad "sun in hexadecimal" "'0x3c,180' is not ELEVATION,AZIMUTH" --sun 0x3c,180
bad "error zero" "\-\-error: 0 is not in" --error 0
bad "plant error" "\-\-plant-error: 2 is not in" --plant-error 2
bad "rays per m2" "\-\-rays-per-m2: -1 is not in" --rays-per-m2 -1
bad "sky" "\-\-sky: 'clear' is not uniform or soc" --sky clear
bad "hours alone" "\-\-latitude, \-\-day and \-\-hours go together" --hours 12
bad "night" "at 23 h the sun is" --latitude 52 --day 172 --hours 23
"$canopy" light "$tmp/a" --latitude 52 --day 172.5 --hours 12 >"$tmp/o" 2>"$tmp/e"
check "day not a whole number" "105 1" "$? $(grep -c -- '--day: needs a whole number from 1 to 366, got 172.5' "$tmp/e")"
bad "tile" "\-\-tile: '1,2,3' is not XMIN,YMIN,XMAX,YMAX" --tile 1,2,3
bad "tile inverted" "has XMAX <= XMIN" --tile 1,0,0,1
bad "too many rays" "rays in one direction (the limit is" --rays-per-m2 1e9 --sky-directions 0
bad "grammar options on a folder" "\-\-rows: .* is a folder that holds a stand already" --rows 3
bad "detection options on a folder" "\-\-level: .* is a folder that holds a stand already" --level organ
bad "resolution options on a folder" "\-\-max-rounds: .* is a folder that holds a stand already" --max-rounds 3
"$canopy" light "$tmp/nowhere" >"$tmp/o" 2>"$tmp/e"
check "missing source exit" "1" "$([ $? -ne 0 ] && echo 1 || echo 0)"

# From a grammar, a bad light option fails before the stand is grown: no folder.
"$canopy" light "$g" --rows 3 --per-row 3 --steps 12 --double-rows 0.3 --backend cpu --sky-directions 0 --error 0.01 -o "$tmp/dr" >"$tmp/o" 2>"$tmp/e"
check "odd double rows refused" "2 1" "$? $(grep -c 'double rows repeat by pairs, and the stand has 3 rows' "$tmp/e")"
check "odd double rows: no folder" "0" "$([ -e "$tmp/dr" ] && echo 1 || echo 0)"
"$canopy" light "$g" "${rows[@]}" --sun 95,0 -o "$tmp/bs" >"$tmp/o" 2>"$tmp/e"
check "bad sun from a grammar: no folder" "2 0" "$? $([ -e "$tmp/bs" ] && echo 1 || echo 0)"

# A stand to a target: LAI exactly (the spacing found gives the same files as asking for it), and
# ground cover within its standard error (canopy light on the folder sees the same estimate).
"$canopy" stand "$g" --rows 3 --per-row 3 --steps 12 --random-rotation --backend cpu --target-lai 1.5 -o "$tmp/t" >"$tmp/log" 2>&1
check "target lai: exit" "0" "$?"
check "target lai: reached" "True" "$(json "$tmp/t/report.json" "abs(j['config']['target']['reached'] - 1.5) < 1e-6")"
check "target lai: the spacing's source" "--target-lai 1" \
  "$(json "$tmp/t/report.json" "j['config']['layout']['sources']['plant_spacing']") $(grep -c 'plant_spacing .* (--target-lai)' "$tmp/log")"
ps=$(json "$tmp/t/report.json" "repr(j['config']['layout']['plant_spacing'])")
"$canopy" stand "$g" --rows 3 --per-row 3 --steps 12 --random-rotation --backend cpu --plant-spacing "$ps" -o "$tmp/t2" >/dev/null 2>&1
cmp -s "$tmp/t/organs.csv" "$tmp/t2/organs.csv" && cmp -s "$tmp/t/plants.csv" "$tmp/t2/plants.csv"
check "target lai: the same stand as its spacing" "0" "$?"
"$canopy" stand "$g" --rows 3 --per-row 3 --steps 12 --random-rotation --backend cpu --target-ground-cover 0.5 -o "$tmp/gc" >"$tmp/log" 2>&1
check "target ground cover: exit" "0" "$?"
check "target ground cover: reached" "True" "$(json "$tmp/gc/report.json" "abs(j['config']['target']['reached'] - 0.5) <= max(j['config']['target']['standard_error'], 0.02)")"
"$canopy" light "$tmp/gc" --sky-directions 0 >/dev/null 2>&1
check "target ground cover: light agrees" "True" "$(python3 -c "
import json; r=json.load(open('$tmp/gc/report.json'))['config']['target']; l=json.load(open('$tmp/gc/light.json'))
print(abs(l['ground_cover'] - r['reached']) <= 4 * (l['ground_cover_standard_error'] + r['standard_error']))")"
"$canopy" stand "$g" --rows 2 --per-row 2 --steps 10 --target-lai 2 --plant-spacing 0.3 -o "$tmp/x" >"$tmp/o" 2>"$tmp/e"
check "target with --plant-spacing refused" "2 1" "$? $(grep -c 'leave out --plant-spacing' "$tmp/e")"
"$canopy" stand "$g" --rows 2 --per-row 2 --steps 10 --target-ground-cover 1.5 -o "$tmp/x" >"$tmp/o" 2>"$tmp/e"
check "target ground cover out of range" "2 1" "$? $(grep -c 'is not in (0, 1)' "$tmp/e")"
# --target-error alone was taken and ignored, -1 too.
"$canopy" stand "$g" --rows 2 --per-row 2 --steps 10 --target-error 0.01 -o "$tmp/x" >"$tmp/o" 2>"$tmp/e"
check "target error without a target refused" "2 1" "$? $(grep -c 'give that target too' "$tmp/e")"
"$canopy" stand "$g" --rows 2 --per-row 2 --steps 10 --target-lai 1 --target-error 0.3 -o "$tmp/x" >"$tmp/o" 2>"$tmp/e"
check "target error with a leaf area target refused" "2 1" "$? $(grep -c "target-lai's leaf area is exact" "$tmp/e")"
"$canopy" stand "$g" --rows 2 --per-row 2 --steps 10 --target-error -1 -o "$tmp/x" >"$tmp/o" 2>"$tmp/e"
check "target error out of range refused" "2 1" "$? $(grep -c 'is not in 1e-05..0.5' "$tmp/e")"

# A stand with no organs (0 steps) meets nothing: its first passes say so (a re-pass for a stand
# far smaller than its tile cast 3.8 billion rays over 15 empty plants, two minutes).
"$canopy" stand "$src/grammars/tomato_young.yaml" --rows 3 --per-row 5 --steps 0 --backend cpu -o "$tmp/e0" >/dev/null 2>&1
"$canopy" light "$tmp/e0" --sun 60,180 --backend cpu >"$tmp/o" 2>"$tmp/e"
check "empty stand: light at once" "0 0.0 0.0 True" \
  "$? $(json "$tmp/e0/light.json" "j['ground_cover'], j['direct'][0]['intercepted_fraction'], j['rays'] < 1e6" | tr -d '(),')"

help=$("$canopy" light --help)
for opt in --sun --latitude --day --hours --sky --sky-directions --tile --no-periodic --error --plant-error --rays-per-m2 --layer \
  --target-lai --target-ground-cover; do
  check "help $opt" "1" "$(grep -q -- "$opt" <<<"$help" && echo 1 || echo 0)"
done
echo "$pass passed, $failures failed"
[ "$failures" -eq 0 ]
