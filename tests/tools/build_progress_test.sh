#!/usr/bin/env bash
# dev.sh's build progress (tools/build_progress.sh, issue 36.1) over fake builds: the progress on
# standard error, nothing on standard output, the build's whole output kept and shown only when it
# fails, a line split by a quiet second joined again, and on a terminal one line rewritten in place
# and cleared. Nothing here depends on how fast the machine is: the checks are on what is printed.
#
#   tests/tools/build_progress_test.sh SOURCE_DIR
set -euo pipefail
source "$1/tools/build_progress.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() {
  echo "FAILED: $*" >&2
  failures=$((failures + 1))
}
expect_grep() {  # file pattern what
  grep -qE -- "$2" "$1" || { fail "$3: no /$2/ in:"; sed 's/^/    /' "$1" >&2; }
}

fake_build() {
  echo "-- Configuring done"
  echo "[ 10%] Building CXX object sim/CMakeFiles/ibs_sim.dir/src/simulator.cpp.o"
  echo "sim/src/simulator.cpp:1: warning: something to read when it fails" >&2
  echo "[ 50%] Linking CXX executable ibs"
  printf '[100%%] Built target ibs'  # the last line without its newline
}
failing_build() {
  echo "[ 10%] Building CXX object tools/ibs/CMakeFiles/ibs.dir/main.cpp.o"
  echo "tools/ibs/main.cpp:7:3: error: 'x' was not declared in this scope" >&2
  return 3
}
# A line cut by more than a second of silence (read's timeout): it must still be one line.
slow_build() {
  printf '[ 20%%] Building CXX obj'
  sleep 1.5
  printf 'ect base/CMakeFiles/ibs_base.dir/src/time.cpp.o\n'
}

# 1. Not a terminal, a line at every step: one per percentage, then the total; stdout untouched.
status=0
IBS_PROGRESS_EVERY=0 quiet_build fake fake_build >"$work/out" 2>"$work/err" || status=$?
((status == 0)) || fail "a build that succeeded: quiet_build returned $status"
[[ ! -s "$work/out" ]] || fail "standard output is not the caller's: $(cat "$work/out")"
expect_grep "$work/err" '^dev\.sh: building fake: 10% after [0-9]+s$' "the first step"
expect_grep "$work/err" '^dev\.sh: building fake: 50% after [0-9]+s$' "the link"
expect_grep "$work/err" '^dev\.sh: building fake: 100% after [0-9]+s$' "the unterminated last line"
expect_grep "$work/err" '^dev\.sh: built fake in [0-9]+s$' "the total"
[[ $(wc -l <"$work/err") -eq 4 ]] || fail "more than the progress and the total on standard error: $(cat "$work/err")"
grep -q "warning" "$work/err" && fail "a build that succeeded showed its output"

# 2. Not a terminal, a long interval: a build quicker than it says only that it is built.
IBS_PROGRESS_EVERY=100000 quiet_build fake fake_build 2>"$work/err" >/dev/null
[[ $(cat "$work/err") =~ ^dev\.sh:\ built\ fake\ in\ [0-9]+s$ ]] || fail "more than the total within the interval: $(cat "$work/err")"

# 3. A failed build: its whole output, what failed, exit 1; still nothing on standard output.
status=0
quiet_build broken failing_build >"$work/out" 2>"$work/err" || status=$?
((status == 1)) || fail "a failed build: quiet_build returned $status, not 1"
[[ ! -s "$work/out" ]] || fail "a failed build wrote to standard output"
expect_grep "$work/err" "main\.cpp:7:3: error: 'x' was not declared" "the compiler's error"
expect_grep "$work/err" '^\[ 10%\] Building CXX object tools/ibs/CMakeFiles/ibs\.dir/main\.cpp\.o$' "the build's log"
expect_grep "$work/err" '^dev\.sh: the build of broken failed \(exit 3\)' "the failure"
grep -q '^dev\.sh: built ' "$work/err" && fail "a failed build was reported built"

# 4. A line cut by a quiet second is joined again, in the log and in the progress.
status=0
IBS_PROGRESS_EVERY=0 quiet_build slow slow_build 2>"$work/err" >/dev/null || status=$?
((status == 0)) || fail "the slow build: $status"
expect_grep "$work/err" '^dev\.sh: building slow: 20% after [0-9]+s$' "the joined line"
log="$work/slow.log"
: >"$log"
slow_build | build_progress "$log" slow 2>/dev/null
[[ $(cat "$log") == "[ 20%] Building CXX object base/CMakeFiles/ibs_base.dir/src/time.cpp.o" ]] \
  || fail "the log holds the cut line as: $(cat "$log")"

# 5. On a terminal (script(1) gives the build a pseudo-terminal): one line rewritten in place with
# the file being compiled, cleared at the end; the total stays.
if command -v script >/dev/null; then
  # A script of its own, not exported functions: script(1) runs its command with $SHELL, and a
  # shell other than bash (dash when SHELL is unset, as under CI) drops bash's exported functions.
  {
    echo "source '$1/tools/build_progress.sh'"
    declare -f fake_build
    echo "quiet_build fake fake_build"
  } >"$work/on_tty.sh"
  script -qec "bash '$work/on_tty.sh'" /dev/null >"$work/tty" 2>&1 </dev/null || fail "the build on a terminal failed"
  esc=$'\033'
  grep -qF $'\r'"${esc}[Kdev.sh: building fake: 10% (simulator.cpp), " "$work/tty" || fail "no in-place line with the file: $(cat -v "$work/tty")"
  grep -qF $'\r'"${esc}[Kdev.sh: building fake: 50% (linking ibs), " "$work/tty" || fail "no in-place line for the link: $(cat -v "$work/tty")"
  grep -qF $'\r'"${esc}[Kdev.sh: built fake in " "$work/tty" || fail "the line is not cleared before the total: $(cat -v "$work/tty")"
  grep -q "warning" "$work/tty" && fail "a build that succeeded showed its output on the terminal"
else
  echo "build_progress_test: script(1) not installed: the terminal case is not run" >&2
fi

if ((failures > 0)); then
  echo "build_progress_test: $failures check(s) failed" >&2
  exit 1
fi
echo "build_progress_test: passed"
