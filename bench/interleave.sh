#!/usr/bin/env bash
# CPU-time medians of one benchmark in two builds, run alternately (A, B, A, B, ...) so that both
# see the same load: how a figure measured on another machine is carried over to this one
# (docs/performance.md, "Against the issue's machine"). A is usually a build of an older commit
# whose time elsewhere is known, B the current one; the ratio of the two medians does not depend
# on the machine as much as either time does.
#
#   bench/interleave.sh BENCH_A BENCH_B FILTER [ROUNDS]
#   e.g. bench/interleave.sh /tmp/base/build/release/bench/pcp/ibs_pcp_bench \
#          build/release/bench/pcp/ibs_pcp_bench 'BM_Read/4$' 3
#
# FILTER must select exactly one benchmark. Prints one line per round and the medians (ns).
set -euo pipefail
if [[ $# -lt 3 || $# -gt 4 ]]; then
  echo "usage: interleave.sh BENCH_A BENCH_B FILTER [ROUNDS]" >&2
  exit 2
fi
a=$1 b=$2 filter=$3 rounds=${4:-3}
[[ $rounds =~ ^[1-9][0-9]?$ ]] || { echo "interleave: ROUNDS must be 1..99, not '$rounds'" >&2; exit 2; }
for x in "$a" "$b"; do
  [[ -x $x ]] || { echo "interleave: no executable $x" >&2; exit 2; }
done

# One run: the CPU time in ns of the one benchmark FILTER selects.
cpu_ns() {
  local out
  out=$("$1" --benchmark_filter="$filter" --benchmark_min_time=0.5 --benchmark_format=csv 2>/dev/null) ||
    { echo "interleave: $1 failed" >&2; return 1; }
  # CSV: name,iterations,real_time,cpu_time,time_unit,...; one row after the header.
  awk -F, -v f="$filter" -v bin="$1" '
    NR == 1 || /^name,/ { next }
    { n++; t = $4; u = $5 }
    END {
      if (n != 1) { printf "interleave: %s: the filter %s selects %d benchmarks, not 1\n", bin, f, n > "/dev/stderr"; exit 1 }
      s = (u == "us") ? 1000 : (u == "ms") ? 1e6 : (u == "s") ? 1e9 : 1
      printf "%.2f\n", t * s
    }' <<<"$out"
}

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

ta=() tb=()
for ((i = 1; i <= rounds; i++)); do
  x=$(cpu_ns "$a")
  y=$(cpu_ns "$b")
  ta+=("$x") tb+=("$y")
  printf 'round %d: A %s ns, B %s ns\n' "$i" "$x" "$y"
done
ma=$(printf '%s\n' "${ta[@]}" | median)
mb=$(printf '%s\n' "${tb[@]}" | median)
printf 'median: A %s ns, B %s ns, B/A %.3f (load average %s)\n' "$ma" "$mb" \
  "$(awk -v a="$ma" -v b="$mb" 'BEGIN { print b / a }')" "$(cut -d' ' -f1 /proc/loadavg)"
