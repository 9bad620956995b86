#!/usr/bin/env bash
# Rendering speed and memory: canopy render of the default stand (read back from a folder written
# by canopy stand --no-resolve) at 1920x1080, for each plant count given. Writes
# bench/results/render.csv. Usage: bash bench/render.sh [1000 10000 ...]
set -euo pipefail
cd "$(dirname "$0")/.."
canopy=build/tools/canopy
out=bench/results/render.csv
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "plants,organs,width,height,render_s,peak_rss_gb,cpu_threads" > "$out"
for n in "${@:-1000 10000}"; do
  rows=$(( n >= 100 ? n / 100 : 1 )); per=$(( n >= 100 ? 100 : n ))
  "$canopy" stand grammars/tomato.yaml --rows "$rows" --per-row "$per" --random-rotation --jitter 0.02 --no-resolve \
    --formats ply -o "$tmp/s" >/dev/null
  /usr/bin/time -v "$canopy" render "$tmp/s" -o "$tmp/p.png" --size 1920x1080 >"$tmp/log" 2>&1
  line=$(grep '^wrote' "$tmp/log")
  organs=$(sed -E 's/.*, ([0-9]+) organs\).*/\1/' <<<"$line")
  secs=$(sed -E 's/.* in ([0-9.]+) s,.*/\1/' <<<"$line")
  rss=$(awk '/Maximum resident/ {printf "%.2f", $6 / 1048576}' "$tmp/log")
  echo "$n,$organs,1920,1080,$secs,$rss,$(nproc)" | tee -a "$out"
  rm -rf "$tmp/s"
done
