#!/usr/bin/env bash
# Every test on a fresh machine: install, build in Release, run all suites through ctest
# (unit, command line, CUDA (skipped without a GPU), sanitized unit tests, a minute of fuzzing).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
ctest --test-dir build --output-on-failure
