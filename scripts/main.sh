#!/usr/bin/env bash
# The main job on a fresh machine: install, build, and derive the default tomato grammar.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
mkdir -p out
build/tools/canopy derive grammars/tomato.yaml > out/tomato.lsys
build/tools/canopy derive grammars/tomato.yaml --stats | tee out/tomato.stats.json
echo "main: derived string in out/tomato.lsys"
