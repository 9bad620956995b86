#!/usr/bin/env bash
# A/B timing on one machine: the command lines given run in turn, ROUNDS times, so that each sees
# the same stretch of the machine (GPU machines of one kind differ by up to a third from one to
# the next, and drift within one). Run from the repository root; on a GPU machine the bundle of
# scripts/device_bundle.sh (.devbin/) is carried and its environment sourced first.
#
#   OUT=DIR ROUNDS=3 GREP='^cuda' bash scripts/device_ab.sh \
#     '.devbin/bin/bench_resolve --backends cuda --sizes 10000 --dense-sizes "" --levels exact --csv /dev/null' \
#     '.devbin/bin/bench_resolve_old --backends cuda --sizes 10000 --dense-sizes "" --levels exact --csv /dev/null' \
#     'CANOPY_HEAP_PAGES=small .devbin/bin/bench_resolve --backends cuda --sizes 10000 --dense-sizes "" --levels exact --csv /dev/null'
#
# A command line may start with environment assignments (a setting to compare) and name another
# build's program (an older commit's binary copied beside this one's). ROUNDS (default 3) rounds;
# each run's whole output goes to $OUT/ab/ROUND-N.log; the lines matching GREP (an extended
# regular expression; default: each run's last line) are printed with the round and the command's
# number, and collected with the commands in $OUT/ab/summary.txt.
set -uo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 2; }
[ -f .devbin/env.sh ] && source .devbin/env.sh
OUT=${OUT:-device-ab}
ROUNDS=${ROUNDS:-3}
dir=$OUT/ab
mkdir -p "$dir"
{
  [ -x "$(command -v nvidia-smi)" ] && nvidia-smi -L
  lscpu | grep -E 'Model name|^CPU\(s\)'
  n=0
  for c in "$@"; do n=$((n + 1)); echo "command $n: $c"; done
} | tee "$dir/summary.txt"
for r in $(seq "$ROUNDS"); do
  n=0
  for c in "$@"; do
    n=$((n + 1))
    log=$dir/$r-$n.log
    (eval "$c") > "$log" 2>&1
    rc=$?
    if [ -n "${GREP:-}" ]; then lines=$(grep -E "$GREP" "$log"); else lines=$(tail -1 "$log"); fi
    while IFS= read -r line; do
      echo "round $r, command $n$([ $rc = 0 ] || echo " (exit $rc)"): $line"
    done <<< "$lines"
  done
done | tee -a "$dir/summary.txt"
