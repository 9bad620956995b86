#!/usr/bin/env bash
# CGAL's exact predicates on exported triangles agree with contacts.csv (stands exported as grown,
# --no-resolve) and with contacts_after.csv (resolved stands: nothing meets but what resolution
# reported left), on a few small stands: a row, a dense random cluster with fruit taking part,
# crowded plants, two plants on one spot. Resolved rows and crowded plants must come out clean,
# and so must the quantized triangles of their compact stand.glb (nothing meets, however close).
# Usage: CANOPY=... CHECK_CGAL=... test_cgal.sh SOURCE_DIR
set -u
src=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
checks=0
run() {  # run NAME COLLIDE CLEAN STAND_ARGS...   (CLEAN=1: the resolved stand must have no contact left)
  local name=$1 collide=$2 clean=$3; shift 3
  checks=$((checks + 3 + clean))
  if ! "$CANOPY" stand "$src/grammars/tomato.yaml" --formats obj --collide "$collide" --no-resolve -o "$tmp/$name" "$@" >/dev/null 2>"$tmp/err"; then
    echo "FAIL $name: canopy stand --no-resolve: $(cat "$tmp/err")"; failures=$((failures + 3 + clean)); return; fi
  if ! "$CHECK_CGAL" "$tmp/$name" --collide "$collide"; then failures=$((failures + 1)); fi
  if ! "$CANOPY" stand "$src/grammars/tomato.yaml" --formats obj,glb --glb-compact --collide "$collide" -o "$tmp/$name.r" "$@" \
      >/dev/null 2>"$tmp/err"; then
    echo "FAIL $name: canopy stand: $(cat "$tmp/err")"; failures=$((failures + 2 + clean)); return; fi
  if ! "$CHECK_CGAL" "$tmp/$name.r" --collide "$collide" --contacts contacts_after.csv; then failures=$((failures + 1)); fi
  # A clean stand's compact glb, its own quantized triangles: nothing meets, however close. (Where
  # contacts are left, rounding may move the organs that still meet by micrometres either way.)
  if [ "$clean" = 1 ] && ! "$CHECK_CGAL" "$tmp/$name.r" --collide "$collide" --contacts contacts_after.csv --glb --strict; then
    failures=$((failures + 1)); fi
  local left; left=$(($(wc -l < "$tmp/$name.r/contacts_after.csv") - 1))
  if [ "$clean" = 1 ] && [ "$left" -ne 0 ]; then
    echo "FAIL $name: $left contacts left after resolution"; failures=$((failures + 1))
  else
    echo "$name: $(($(wc -l < "$tmp/$name.r/contacts.csv") - 1)) contacts before resolution, $left after"
  fi
}
run row leaflet,petiole,rachis,internode,peduncle 1 --rows 2 --per-row 4 --steps 14 --random-rotation --jitter 0.02
run dense all 0 --rows 3 --per-row 3 --row-spacing 0.25 --plant-spacing 0.25 --steps 12 --random-rotation --seed 5
run crowded leaflet,petiole,rachis,internode,peduncle 1 --rows 1 --per-row 3 --steps 14 --set phyllotaxis=15 \
  --set internode_min=0.015 --set internode_max=0.02
printf 'x,y,rotation,seed\n0,0,0,7\n0,0,0,7\n0.2,0.1,45,8\n' > "$tmp/same.csv"
run same_spot all 0 --positions "$tmp/same.csv" --steps 10
echo "$((checks - failures)) passed, $failures failed"
[ "$failures" -eq 0 ]
