#!/usr/bin/env bash
# Instructions per call of one function inside one benchmark, counted by callgrind: a figure that
# does not depend on how busy the machine is (docs/performance.md). Collects only inside FUNCTION
# (a callgrind --toggle-collect pattern, e.g. '*closed_loop_once*') and divides its inclusive
# instructions by its calls. The benchmark must call FUNCTION out of line once per unit of work.
#
#   bench/callgrind_per_call.sh BENCH FILTER FUNCTION
#   e.g. bench/callgrind_per_call.sh build/release/bench/drivecom/bench_drivecom \
#          'BM_ClosedLoopStartUpToEnabled_Mc6000$' 'closed_loop_once'
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ $# -ne 3 ]]; then
  echo "usage: callgrind_per_call.sh BENCH FILTER FUNCTION" >&2
  exit 2
fi
bench=$1 filter=$2 fn=$3
[[ -x $bench ]] || { echo "callgrind_per_call: no $bench (cmake --preset release && cmake --build build/release --target ...)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "callgrind_per_call: valgrind is not installed (apt-get install valgrind)" >&2; exit 2; }
out=$(mktemp)
trap 'rm -f "$out" "$out".*' EXIT
valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect="*$fn*" \
  "$bench" --benchmark_filter="$filter" --benchmark_min_time=0.02 >/dev/null 2>&1
# As in callgrind_master_cycle.sh: the callers' lines "IR (P%)  < CALLER (Nx)" stand right above
# the function's own line "IR (P%)  *  FUNCTION" in the caller tree.
export FN="$fn"
callgrind_annotate --tree=caller --inclusive=yes "$out" 2>/dev/null | perl -ne '
  BEGIN { $fn = quotemeta $ENV{FN} }
  if (/^\s*([\d,]+) .*<.*\(([\d,]+)x\)/) { ($c = $2) =~ tr/,//d; $calls += $c; next }
  if (/^\s*([\d,]+) .*\*\s.*$fn/) { ($ir = $1) =~ tr/,//d; $found = 1; last }
  $calls = 0;
  END {
    if (!$found || !$calls) { print STDERR "callgrind_per_call: no calls of $ENV{FN} found\n"; exit 1 }
    printf "%d instructions per call of %s (%d calls, %d instructions)\n", $ir / $calls, $ENV{FN}, $calls, $ir;
  }'
