#!/usr/bin/env bash
# Installs the canopy Python package for the system Python (/usr/bin/python3): what is missing
# from Debian, a Release build, then the CMake install step of the `python` component into that
# interpreter's site-packages, so `import canopy` works without setting any path. Safe to rerun.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
cmake --install build --component python
/usr/bin/python3 -c "import canopy; print('canopy', canopy.__version__, 'installed at', canopy.__file__)"
