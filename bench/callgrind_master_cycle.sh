#!/usr/bin/env bash
# Instructions per master cycle on the full bus (64 MC6000, SUPI 12 / IBCNF 2, 256 words each
# way), counted by callgrind: a figure that does not depend on how busy the machine is
# (docs/performance.md). Runs bench_sim's BM_MasterCycleFullBus under valgrind, collects only
# inside MasterLoop::cycle, and divides its instructions by its calls.
#
#   bench/callgrind_master_cycle.sh [BENCH_SIM]     (default: build/release/bench/sim/bench_sim)
set -euo pipefail
cd "$(dirname "$0")/.."
bench=${1:-build/release/bench/sim/bench_sim}
if [[ ! -x $bench ]]; then
  echo "callgrind_master_cycle: no $bench (cmake --preset release && cmake --build --preset release --target bench_sim)" >&2
  exit 2
fi
command -v valgrind >/dev/null || { echo "callgrind_master_cycle: valgrind is not installed (apt-get install valgrind)" >&2; exit 2; }
out=$(mktemp)
trap 'rm -f "$out" "$out".*' EXIT
valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect='*MasterLoop::cycle*' \
  "$bench" --benchmark_filter='BM_MasterCycleFullBus$' --benchmark_min_time=0.02 >/dev/null 2>&1
# The cycle's inclusive cost and its call count, from the caller tree: the callers' lines
# "IR (P%)  < CALLER (Nx)" stand right above the function's own line "IR (P%)  *  FUNCTION".
# Perl, because callgrind_annotate is a Perl script: wherever it runs, so does this.
callgrind_annotate --tree=caller --inclusive=yes "$out" 2>/dev/null | perl -ne '
  if (/^\s*([\d,]+) .*<.*\(([\d,]+)x\)/) { ($c = $2) =~ tr/,//d; $calls += $c; next }
  if (/^\s*([\d,]+) .*\*\s.*MasterLoop::cycle/) { ($ir = $1) =~ tr/,//d; $found = 1; last }
  $calls = 0;
  END {
    if (!$found || !$calls) { print STDERR "callgrind_master_cycle: no calls of MasterLoop::cycle found\n"; exit 1 }
    printf "%d instructions per master cycle (%d cycles, %d instructions)\n", $ir / $calls, $calls, $ir;
  }'
