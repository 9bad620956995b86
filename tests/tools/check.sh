# Shared by the command-line test scripts (sourced): a temporary folder removed on exit, pass and
# failure counters, and check NAME EXPECTED ACTUAL.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
pass=0
check() {
  if [ "$2" == "$3" ]; then pass=$((pass + 1)); else
    failures=$((failures + 1)); printf 'FAIL %s\n  expected: %s\n  actual:   %s\n' "$1" "$2" "$3"; fi
}
