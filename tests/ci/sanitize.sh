#!/usr/bin/env bash
# Builds the unit tests with AddressSanitizer + UndefinedBehaviorSanitizer and runs them: the
# grammar engine's, and the collision suite's resolution (the batched turn search too) and hard-case tests.
# Usage: sanitize.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1 build=$2
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCANOPY_SANITIZE=ON \
  -DCANOPY_CUDA=OFF -DCANOPY_TOOLS=OFF >"$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" --target test_lsystem test_collision
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
"$build/tests/test_lsystem"
"$build/tests/test_collision" -tc="*resol*,*batched*,joints*,*hard*,*coplanar*,*touching*,*sliver*,*inside*,*zero*,*hundred*,*same spot*,*parallel*"
