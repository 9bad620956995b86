#!/usr/bin/env bash
# Derivation benchmark: canopy and, side by side, the lindenmayer npm package (1.5.4).
# Writes bench/results/derive.csv (both engines). Run from the repository root after scripts/build.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p bench/results
build/tools/bench_derive grammars/tomato.yaml grammars/classic/abop_1_24a.yaml:9 grammars/classic/abop_1_24d.yaml:7 \
  grammars/classic/algae.yaml:30 grammars/classic/abop_1_31a.yaml:30 grammars/classic/abop_2_6.yaml:16 \
  --csv bench/results/derive.csv
if command -v node >/dev/null; then
  (cd bench && npm install --no-audit --no-fund --silent)
  node bench/lindenmayer_bench.js bench/results/.lindenmayer.csv
  tail -n +2 bench/results/.lindenmayer.csv >> bench/results/derive.csv
  rm -f bench/results/.lindenmayer.csv
fi
