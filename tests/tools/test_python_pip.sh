#!/usr/bin/env bash
# The Python package installed as Python users install it (pyproject.toml, setup.py): a virtual
# environment made with --system-site-packages from the build's Python, then
# `pip install SOURCE --no-build-isolation --no-index` with CANOPY_BUILD_DIR naming this build
# (configured for the same Python, so the library is not compiled a second time). From outside
# the source tree the package must be the environment's copy, report the build's version, derive
# as the command line does, and write the command line's files byte for byte; pip uninstall must
# take it out of the environment again.
# Usage: PYTHON=interpreter CANOPY=path/to/canopy CANOPY_BUILD_DIR=build test_python_pip.sh SOURCE_DIR
set -u
src=$(realpath "$1")
source "$(dirname "$0")/check.sh"
py=${PYTHON:?set PYTHON to the interpreter the build found}
canopy=${CANOPY:?set CANOPY to the canopy program}
unset PYTHONPATH
if ! "$py" -c 'import venv, ensurepip' >/dev/null 2>&1; then
  echo "no venv or ensurepip for $py (Debian python3-venv): skipped"
  exit 77
fi

env=$tmp/env
"$py" -m venv --system-site-packages "$env" > "$tmp/venv.log" 2>&1
check "venv made" 0 $?
"$env/bin/python" -m pip install --no-build-isolation --no-index "$src" > "$tmp/pip.log" 2>&1
rc=$?
check "pip install exit" 0 $rc
[ $rc = 0 ] || tail -30 "$tmp/pip.log"

cd "$tmp" || exit 1
run() { "$env/bin/python" -c "$1" 2>&1; }
where=$(run 'import canopy, os; print(os.path.realpath(canopy.__file__))')
check "imported from the environment" "$(realpath "$env")" "${where%%/lib/python*}"
check "version" "$("$canopy" --version)" "$(run 'import canopy; print(canopy.__version__)')"
check "derive" "$("$canopy" derive "$src/grammars/classic/algae.yaml" --steps 6)" \
  "$(run "import canopy; print(canopy.derive('$src/grammars/classic/algae.yaml', steps=6))")"

opts=(--rows 2 --per-row 3 --steps 14 --random-rotation --jitter 0.02 --backend cpu --formats ply)
"$canopy" stand "$src/grammars/tomato.yaml" "${opts[@]}" -o "$tmp/cli" > /dev/null 2>&1
run "import canopy; canopy.stand('$src/grammars/tomato.yaml', '$tmp/py', rows=2, per_row=3, steps=14,
     random_rotation=True, jitter=0.02, backend='cpu', formats='ply')" > "$tmp/py.log"
for f in stand.ply organs.csv plants.csv contacts.csv contacts_after.csv; do
  cmp -s "$tmp/cli/$f" "$tmp/py/$f"
  check "$f as the command line writes it" 0 $?
done

"$env/bin/python" -m pip uninstall -y canopy > "$tmp/uninstall.log" 2>&1
check "pip uninstall exit" 0 $?
# Gone from the environment (a system-wide copy, if any, may answer the import now).
after=$(run 'import os
try:
    import canopy; print(os.path.realpath(canopy.__file__))
except ModuleNotFoundError:
    print("none")')
case $after in "$(realpath "$env")"/*) after="still in the environment: $after" ;; *) after=gone ;; esac
check "gone from the environment after uninstall" gone "$after"

echo "$pass passed, $failures failed"
[ "$failures" -eq 0 ]
