#!/usr/bin/env bash
# CGAL's exact predicates on exported triangles agree with contacts.csv (stands exported as grown,
# --no-resolve) and with contacts_after.csv (resolved stands: nothing meets but what resolution
# reported left), on a few small stands: a row, a dense random cluster, crowded plants, two plants
# on one spot, with every organ kind taking part (the default) and the check counting every kind;
# one row with --collide narrowed, checked over those kinds. Resolved rows and crowded plants must
# come out clean, and so must the quantized triangles of their compact stand.glb (nothing meets,
# however close). Then the default resolution of seeded dense stands with fruit must leave no
# intersecting non-adjacent organ pair of any kind in stand.obj.
# Usage: CANOPY=... CHECK_CGAL=... test_cgal.sh SOURCE_DIR
set -u
src=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
checks=0
run() {  # run NAME COLLIDE CLEAN STAND_ARGS...   (COLLIDE default: no --collide, every kind; CLEAN=1: nothing left)
  local name=$1 collide=$2 clean=$3; shift 3
  local kinds=()
  [ "$collide" = default ] || kinds=(--collide "$collide")
  checks=$((checks + 3 + clean))
  if ! "$CANOPY" stand "$src/grammars/tomato.yaml" --formats obj "${kinds[@]}" --no-resolve -o "$tmp/$name" "$@" >/dev/null 2>"$tmp/err"; then
    echo "FAIL $name: canopy stand --no-resolve: $(cat "$tmp/err")"; failures=$((failures + 3 + clean)); return; fi
  if ! "$CHECK_CGAL" "$tmp/$name" "${kinds[@]}"; then failures=$((failures + 1)); fi
  if ! "$CANOPY" stand "$src/grammars/tomato.yaml" --formats obj,glb --glb-compact "${kinds[@]}" -o "$tmp/$name.r" "$@" \
      >/dev/null 2>"$tmp/err"; then
    echo "FAIL $name: canopy stand: $(cat "$tmp/err")"; failures=$((failures + 2 + clean)); return; fi
  if ! "$CHECK_CGAL" "$tmp/$name.r" "${kinds[@]}" --contacts contacts_after.csv; then failures=$((failures + 1)); fi
  # A clean stand's compact glb, its own quantized triangles: nothing meets, however close. (Where
  # contacts are left, rounding may move the organs that still meet by micrometres either way.)
  if [ "$clean" = 1 ] && ! "$CHECK_CGAL" "$tmp/$name.r" "${kinds[@]}" --contacts contacts_after.csv --glb --strict; then
    failures=$((failures + 1)); fi
  local left; left=$(($(wc -l < "$tmp/$name.r/contacts_after.csv") - 1))
  if [ "$clean" = 1 ] && [ "$left" -ne 0 ]; then
    echo "FAIL $name: $left contacts left after resolution"; failures=$((failures + 1))
  else
    echo "$name: $(($(wc -l < "$tmp/$name.r/contacts.csv") - 1)) contacts before resolution, $left after"
  fi
}
run row default 1 --rows 2 --per-row 4 --steps 14 --random-rotation --jitter 0.02
run row_narrowed leaflet,petiole,rachis,internode,peduncle 1 --rows 2 --per-row 4 --steps 14 --random-rotation --jitter 0.02
run dense default 1 --rows 3 --per-row 3 --row-spacing 0.25 --plant-spacing 0.25 --steps 12 --random-rotation --seed 5
run crowded default 1 --rows 1 --per-row 3 --steps 14 --set phyllotaxis=15 --set internode_min=0.015 --set internode_max=0.02
printf 'x,y,rotation,seed\n0,0,0,7\n0,0,0,7\n0.2,0.1,45,8\n' > "$tmp/same.csv"
run same_spot default 0 --positions "$tmp/same.csv" --steps 10
run fruit_crowded default 0 --rows 3 --per-row 4 --row-spacing 0.3 --plant-spacing 0.3 --seed 3

# Default resolution leaves no intersecting non-adjacent organ pair of any kind: seeded dense
# stands of 12 plants at the grammar's age (fruit hanging among the leaves), 0.5 m between rows and
# 0.3 m in the row (6.7 plants/m2, twice the densest greenhouse crop) with the grammar entry's
# jitter and rotation, resolved with every default. CGAL's exact predicates on stand.obj, every
# organ kind, must find no pair meeting (and resolution none left). Closer still (0.3 m both ways,
# 11 plants/m2) the grammar's 20-degree joint limits leave up to a dozen pairs of the 466 found:
# the run fruit_crowded checks that what is left is reported, and only that. The quantized
# triangles of the compact stand.glb must meet nowhere either.
for seed in 1 2 3; do
  name=fruit_$seed
  checks=$((checks + 2))
  if ! "$CANOPY" stand "$src/grammars/tomato.yaml" --rows 3 --per-row 4 --row-spacing 0.5 --plant-spacing 0.3 --seed "$seed" \
       --formats obj,glb --glb-compact -o "$tmp/$name" >/dev/null 2>"$tmp/err"; then
    echo "FAIL $name: canopy stand: $(cat "$tmp/err")"; failures=$((failures + 2)); continue; fi
  # The compact glb's quantized triangles: no pair meets either.
  if ! "$CHECK_CGAL" "$tmp/$name" --contacts contacts_after.csv --glb --strict >"$tmp/cgal_glb" 2>&1 ||
     [ "$(sed -n 's/.* \([0-9]*\) meet by CGAL.*/\1/p' "$tmp/cgal_glb")" != 0 ]; then
    echo "FAIL $name: compact glb: $(tail -1 "$tmp/cgal_glb")"; failures=$((failures + 1))
  else
    echo "$name: compact glb: $(tail -1 "$tmp/cgal_glb")"
  fi
  fruit=$(awk -F, '$4=="fruit"' "$tmp/$name/organs.csv" | wc -l)
  left=$(($(wc -l < "$tmp/$name/contacts_after.csv") - 1))
  "$CHECK_CGAL" "$tmp/$name" --contacts contacts_after.csv >"$tmp/cgal" 2>&1
  rc=$?
  meet=$(sed -n 's/.* \([0-9]*\) meet by CGAL.*/\1/p' "$tmp/cgal")
  if [ "$fruit" -eq 0 ] || [ "$left" -ne 0 ] || [ "$rc" -ne 0 ] || [ "${meet:-x}" != 0 ]; then
    echo "FAIL $name: $fruit fruit, $left contacts left, CGAL: $(tail -1 "$tmp/cgal")"; failures=$((failures + 1))
  else
    echo "$name: $fruit fruit, $(($(wc -l < "$tmp/$name/contacts.csv") - 1)) contacts before resolution, none after; $(tail -1 "$tmp/cgal")"
  fi
done
# Its own arguments: --help is usage (exit 0), a folder that is no stand a one-line error (exit 1).
checks=$((checks + 2))
"$CHECK_CGAL" --help >"$tmp/o" 2>&1; rc=$?
if [ "$rc" -ne 0 ] || ! grep -q '^usage: check_cgal DIR' "$tmp/o"; then echo "FAIL check_cgal --help: $rc"; failures=$((failures + 1)); fi
"$CHECK_CGAL" "$tmp/none" >"$tmp/o" 2>&1; rc=$?
if [ "$rc" -ne 1 ] || ! grep -q '^check_cgal: error: .*none/plants.csv: cannot open' "$tmp/o"; then echo "FAIL check_cgal on no stand: $rc"; failures=$((failures + 1)); fi
echo "$((checks - failures)) passed, $failures failed"
[ "$failures" -eq 0 ]
