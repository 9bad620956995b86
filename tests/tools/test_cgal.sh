#!/usr/bin/env bash
# CGAL's exact predicates on exported triangles agree with contacts.csv, on a few small stands:
# a row, a dense random cluster with fruit taking part, crowded plants, two plants on one spot.
# Usage: CANOPY=... CHECK_CGAL=... test_cgal.sh SOURCE_DIR
set -u
src=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
run() {  # run NAME CHECK_ARGS -- STAND_ARGS...
  local name=$1 collide=$2; shift 2
  if ! "$CANOPY" stand "$src/grammars/tomato.yaml" --formats obj --collide "$collide" -o "$tmp/$name" "$@" >/dev/null 2>"$tmp/err"; then
    echo "FAIL $name: canopy stand: $(cat "$tmp/err")"; failures=$((failures + 1)); return; fi
  if ! "$CHECK_CGAL" "$tmp/$name" --collide "$collide"; then failures=$((failures + 1)); fi
}
run row leaflet,petiole,rachis,internode,peduncle --rows 2 --per-row 4 --steps 14 --random-rotation --jitter 0.02
run dense all --rows 3 --per-row 3 --row-spacing 0.25 --plant-spacing 0.25 --steps 12 --random-rotation --seed 5
run crowded leaflet,petiole,rachis,internode,peduncle --rows 1 --per-row 3 --steps 14 --set phyllotaxis=15 \
  --set internode_min=0.015 --set internode_max=0.02
printf 'x,y,rotation,seed\n0,0,0,7\n0,0,0,7\n0.2,0.1,45,8\n' > "$tmp/same.csv"
run same_spot all --positions "$tmp/same.csv" --steps 10
echo "$((4 - failures)) passed, $failures failed"
[ "$failures" -eq 0 ]
