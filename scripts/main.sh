#!/usr/bin/env bash
# The main job on a fresh machine: install, build, and grow the default tomato stand (the
# grammar's stand entry: 100 plants) into out/ as glb, obj and ply with its tables and report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
build/tools/canopy stand grammars/tomato.yaml --formats glb,obj,ply -o out
