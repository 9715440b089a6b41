#!/usr/bin/env bash
# Runs the libFuzzer targets (docs/robustness.md, "Fuzzing").
#
#   fuzz/run.sh [--jobs N] [--keep DIR] [SECONDS] [TARGET...]
#
# Builds the `fuzz` preset if needed, then runs each TARGET (default: every target listed by
# fuzz/CMakeLists.txt) for SECONDS (default 10) on a copy of its seed corpus fuzz/corpus/TARGET/
# in a temporary directory, with its dictionary fuzz/dict/TARGET.dict if there is one, its
# MAX_LEN and -timeout=10. The repository is never written to: new inputs stay in the temporary
# copy (or go to DIR/TARGET/ with --keep DIR). --jobs N runs N targets at a time (default 1).
#
# Prints, per target, the executions, the final coverage (cov: edges, ft: features), the corpus
# growth and whether it found anything. A finding (a crash, a violated invariant, a timeout, a
# leak or running out of memory) is saved under build/fuzz/findings/TARGET/ with its log and the
# command that reproduces it; the script then exits 1. Exit 2: bad arguments or no build.
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=1
keep=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --jobs) jobs=${2:?--jobs needs a number}; shift 2 ;;
    --keep) keep=${2:?--keep needs a directory}; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) break ;;
  esac
done
seconds=${1:-10}
[[ $# -gt 0 ]] && shift
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || ((seconds < 1)); then
  echo "fuzz/run.sh: SECONDS must be a whole number >= 1, not '$seconds'" >&2
  exit 2
fi
if ! [[ "$jobs" =~ ^[0-9]+$ ]] || ((jobs < 1)); then
  echo "fuzz/run.sh: --jobs must be a whole number >= 1" >&2
  exit 2
fi

build=build/fuzz
werror=()
[[ "${CI:-}" == "true" ]] && werror=(-DIBS_WERROR=ON)
if [[ ! -f "$build/CMakeCache.txt" || -n "${werror[*]}" ]]; then
  cmake --preset fuzz "${werror[@]}" >/dev/null
fi
log=$(mktemp)
if ! cmake --build --preset fuzz -j "$(nproc 2>/dev/null || echo 2)" >"$log" 2>&1; then
  cat "$log" >&2
  rm -f "$log"
  echo "fuzz/run.sh: the fuzz build failed" >&2
  exit 2
fi
rm -f "$log"

# NAME MAX_LEN per line, written by fuzz/CMakeLists.txt (ibs_add_fuzzer).
declare -A max_len=()
all=()
while read -r name len; do
  [[ -z "$name" || "$name" == \#* ]] && continue
  max_len[$name]=$len
  all+=("$name")
done <"$build/fuzz/targets.txt"

targets=("$@")
((${#targets[@]} == 0)) && targets=("${all[@]}")
for t in "${targets[@]}"; do
  if [[ -z "${max_len[$t]:-}" ]]; then
    echo "fuzz/run.sh: no target '$t'; the targets are: ${all[*]}" >&2
    exit 2
  fi
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Runs one target; writes its summary line to $work/T.summary and returns 1 on a finding.
run_one() {
  local t=$1 dir="$work/$1"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  cp -r "fuzz/corpus/$t/." "$dir/corpus/"
  local seeds
  seeds=$(find "$dir/corpus" -type f | wc -l)
  local args=(-max_total_time="$seconds" -max_len="${max_len[$t]}" -timeout=10 -rss_limit_mb=4096
              -print_final_stats=1 -artifact_prefix="$dir/artifacts/")
  [[ -f "fuzz/dict/$t.dict" ]] && args+=(-dict="fuzz/dict/$t.dict")
  local rc=0
  "$build/fuzz/$t" "${args[@]}" "$dir/corpus" >"$dir/log" 2>&1 || rc=$?

  # The final statistics, or the last status line when the run ended early.
  local execs cov ft status
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log" | tail -1)
  [[ -z "$execs" ]] && execs=$({ grep -oE '^#[0-9]+' "$dir/log" || true; } | tail -1 | tr -d '#')
  cov=$({ grep -oE 'cov: [0-9]+' "$dir/log" || true; } | tail -1 | cut -d' ' -f2)
  ft=$({ grep -oE 'ft: [0-9]+' "$dir/log" || true; } | tail -1 | cut -d' ' -f2)
  local corpus
  corpus=$(find "$dir/corpus" -type f | wc -l)
  local found
  found=$(find "$dir/artifacts" -type f | head -1)
  if [[ -n "$found" || $rc -ne 0 ]]; then
    local keepdir="$build/findings/$t"
    mkdir -p "$keepdir"
    cp "$dir/log" "$keepdir/log.txt"
    local saved=""
    if [[ -n "$found" ]]; then
      saved="$keepdir/$(basename "$found")"
      cp "$found" "$saved"
    fi
    local why
    why=$(grep -m1 -E '==ibs-fuzz== INVARIANT VIOLATED|ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:|SUMMARY:' "$dir/log" || true)
    status="FINDING: ${why:-exit code $rc}"
    {
      printf '%-22s %8s execs  cov %5s  ft %6s  corpus %3s -> %-5s %s\n' "$t" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$seeds" "$corpus" "$status"
      [[ -n "$saved" ]] && printf '%22s input: %s\n%22s reproduce: %s %s\n' "" "$saved" "" "$build/fuzz/$t" "$saved"
      printf '%22s log: %s\n' "" "$keepdir/log.txt"
    } >"$work/$t.summary"
  else
    printf '%-22s %8s execs  cov %5s  ft %6s  corpus %3s -> %-5s no findings\n' "$t" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$seeds" "$corpus" >"$work/$t.summary"
  fi
  if [[ -n "$keep" ]]; then
    mkdir -p "$keep/$t"
    cp -r "$dir/corpus/." "$keep/$t/"
  fi
  [[ -z "$found" && $rc -eq 0 ]]
}

echo "fuzz/run.sh: ${#targets[@]} target(s), $seconds s each, $jobs at a time ($build)"
failed=0
running=0
for t in "${targets[@]}"; do
  run_one "$t" &
  running=$((running + 1))
  if ((running >= jobs)); then
    wait -n || failed=$((failed + 1))
    running=$((running - 1))
  fi
done
while ((running > 0)); do
  wait -n || failed=$((failed + 1))
  running=$((running - 1))
done
for t in "${targets[@]}"; do cat "$work/$t.summary"; done
if ((failed > 0)); then
  echo "fuzz/run.sh: $failed target(s) found something; inputs and logs are under $build/findings/" >&2
  exit 1
fi
echo "fuzz/run.sh: no findings"
