# shellcheck shell=bash
# A build that says how far it is (issue 36.1), for dev.sh (sourced; bash). The build's own output
# goes to a log, shown whole only when the build fails; standard error gets its progress, and
# standard output nothing, so that what the caller runs next keeps its output to itself.
#
#   quiet_build LABEL COMMAND...   runs COMMAND (a CMake configure and build) and reports:
#     on a terminal, one line rewritten in place -- "dev.sh: building LABEL: 45% (timing_cmd.cpp), 1m05s"
#       -- and cleared when the build ends;
#     elsewhere (a pipe, a CI log), a line when the percentage has moved, at most one every
#       IBS_PROGRESS_EVERY seconds (default 10) and none in the first ones, so that a long build shows
#       it is alive in a short log and a build with nothing to do says only that it is done;
#     then "dev.sh: built LABEL in 1m23s". When COMMAND fails: its whole output, and the exit status 1.
#
# The percentage is CMake's (Makefile generator: "[ 45%] Building CXX object ..."); before the first
# one the build is "configuring". Tests: tests/tools/build_progress_test.sh, with a fake build.

# "1m05s" or "12s"
progress_duration() {
  local s=$1
  if ((s >= 60)); then printf '%dm%02ds' $((s / 60)) $((s % 60)); else printf '%ds' "$s"; fi
}

# build_progress LOG LABEL: reads the build's output on standard input, appends it to LOG.
build_progress() {
  local log=$1 label=$2
  local every=${IBS_PROGRESS_EVERY:-10}
  local tty=0 width=80
  if [[ -t 2 ]]; then
    tty=1
    width=$(tput cols 2>/dev/null || echo 80)
    ((width > 20)) || width=80
  fi
  local start=$SECONDS pct="" what="configuring" shown_pct="" shown_at=0 buf="" line status ended=0
  while ((!ended)); do
    line=""
    if IFS= read -r -t 1 line; then
      line=$buf$line
      buf=""
    else
      status=$?
      if ((status > 128)); then  # a second without a whole line: keep what came, report the time
        buf+=$line
        line=""
      else  # the end of the output (a last line without its newline is still a line)
        line=$buf$line
        ended=1
      fi
    fi
    if [[ -n $line ]]; then
      printf '%s\n' "$line" >>"$log"
      if [[ $line =~ ^\[\ *([0-9]+)%\]\ (.*)$ ]]; then
        pct=${BASH_REMATCH[1]}
        what=${BASH_REMATCH[2]}
        if [[ $what =~ ^Building\ [A-Z]+\ object\ (.*)\.o$ ]]; then
          what=${BASH_REMATCH[1]##*/}
        elif [[ $what =~ ^Linking\ [A-Z]+\ [a-z\ ]+\ (.*)$ ]]; then
          what="linking ${BASH_REMATCH[1]##*/}"
        fi
      fi
    fi
    local elapsed=$((SECONDS - start)) text
    if ((tty)); then
      text="dev.sh: building $label: ${pct:+$pct% }($what), $(progress_duration "$elapsed")"
      printf '\r\033[K%s' "${text:0:$((width - 1))}" >&2
    elif [[ -n $pct && $pct != "$shown_pct" ]] && ((elapsed - shown_at >= every)); then
      echo "dev.sh: building $label: $pct% after $(progress_duration "$elapsed")" >&2
      shown_pct=$pct
      shown_at=$elapsed
    fi
  done
  ((tty)) && printf '\r\033[K' >&2
  return 0
}

quiet_build() {
  local label=$1
  shift
  local log start=$SECONDS
  log=$(mktemp)
  local status=0
  { "$@" 2>&1 | build_progress "$log" "$label"; status=${PIPESTATUS[0]}; } || true
  if ((status != 0)); then
    cat "$log" >&2
    rm -f "$log"
    echo "dev.sh: the build of $label failed (exit $status); its output is above" >&2
    return 1
  fi
  rm -f "$log"
  echo "dev.sh: built $label in $(progress_duration $((SECONDS - start)))" >&2
}
