#!/usr/bin/env bash
# Every test on a fresh machine: install, build in Release, build the sanitized and the fuzz trees
# (here, not inside the test run, where their compiling counted against the suites' limits), run
# all suites through ctest (unit, command line, CUDA (skipped without a GPU), the unit, command-line
# and Python suites under AddressSanitizer + UndefinedBehaviorSanitizer, a minute of fuzzing).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
bash tests/ci/sanitize.sh build "$PWD" "$PWD/build/sanitize"
CANOPY_CHECK_BUILD_ONLY=1 bash tests/ci/fuzz.sh "$PWD" "$PWD/build/fuzz"
ctest --test-dir build --output-on-failure
