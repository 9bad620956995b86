#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer: one build tree (CUDA, MPI, render and benchmarks
# left out) with three unit suites, the canopy program and the Python module, at -O1 -g1 (a third of
# -O2 -g's compile time; what the sanitizers' authors advise). The output folders' code runs
# under the sanitizers through the command-line suites (cli_output above all).
# Usage: sanitize.sh build|unit|cli SOURCE_DIR BUILD_DIR
#   build  configure (once) and build the tree: scripts/test.sh does it before ctest, so the
#          suites below only run (ctest builds it itself when it is missing or stale);
#   unit   the grammar engine's suite, the collision suite's hard-case and memory-bound tests, the
#          resolution suite's resolution tests (the batched turn search too);
#   cli    the command-line suites and the Python suite against the sanitized program and module.
set -euo pipefail
mode=$1 src=$2 build=$3
# Configured every time with every option named (a no-op when nothing changed), so that a tree
# configured otherwise before (without the program, say) is brought to this one.
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DCANOPY_SANITIZE=ON -DCANOPY_CUDA=OFF -DCANOPY_MPI=OFF -DCANOPY_RENDER=OFF -DCANOPY_TOOLS=ON -DCANOPY_TESTS=ON \
  >"$build.configure.log" 2>&1 || { cat "$build.configure.log"; rm -f "$build/CMakeCache.txt"; exit 1; }
targets=(test_lsystem test_collision test_resolution canopy)
# The Python module where this machine has pybind11, NumPy and Python's headers.
if cmake --build "$build" --target help | grep -q '^_canopy:'; then targets+=(_canopy canopy_python_files); fi
cmake --build "$build" --target "${targets[@]}"
[ "$mode" = build ] && exit 0

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
case "$mode" in
  unit)
    "$build/tests/test_lsystem"
    # The same filter on both suites: their test cases split as the source folders do.
    filter="*resol*,*batched*,joints*,*hard*,*coplanar*,*touching*,*sliver*,*inside*,*zero*,*hundred*,*same spot*,*parallel*,*memory*,*counted without*"
    "$build/tests/test_collision" -tc="$filter"
    "$build/tests/test_resolution" -tc="$filter"
    ;;
  cli)
    failed=0
    for suite in cli_derive cli_sweep cli_stand cli_output; do
      echo "== $suite (sanitized)"
      CANOPY="$build/tools/canopy" bash "$src/tests/tools/test_$suite.sh" "$src" || failed=1
    done
    if [ -f "$build/python/canopy/__init__.py" ]; then
      echo "== python (sanitized)"
      # The interpreter is not instrumented: the runtime is loaded first, and libstdc++ with it
      # (else ASan finds no __cxa_throw to wrap and aborts at the first C++ exception); the
      # interpreter's own allocations are not canopy's leaks.
      # The interpreter the module was built for, as the python suite takes it.
      py=$(sed -n 's/^_\{0,1\}Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt" | head -1)
      LD_PRELOAD="$(g++ -print-file-name=libasan.so) $(g++ -print-file-name=libstdc++.so)" ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
        PYTHONPATH="$build/python" CANOPY="$build/tools/canopy" CANOPY_SOURCE_DIR="$src" \
        "${py:-python3}" -m pytest -q -p no:cacheprovider "$src/tests/python" || failed=1
    fi
    exit $failed
    ;;
  *) echo "sanitize.sh: unknown mode '$mode' (build, unit or cli)"; exit 2 ;;
esac
