#!/usr/bin/env bash
# Runs every shell command of the README and the docs as written, from the repository's root, so
# that none of them can rot. CI runs it on a fresh clone after the tests.
#
#   tools/check_docs.sh [FILE.md...]     (default: README.md docs/*.md)
#
# What it runs: every line of every ```sh / ```bash block (a line ending in `\` continues on the
# next). A command must exit 0, unless the line ends in a comment `# exit N`, then it must exit N.
# A block right after a line `<!-- check-docs: skip REASON -->` is not run (hardware, a real
# serial port); REASON is printed. A block right after `<!-- check-docs: script -->` runs as one
# shell script, so that its lines share variables and background jobs (an emulator started with
# `&` and stopped with `kill %1`); each of its lines is still checked for its exit status.
# A ```cpp block right after `<!-- check-docs: cpp PREFIX PACKAGE -->` is a complete program: it is
# compiled with `g++ -std=c++20 -Wall -Wextra -Werror` and `pkg-config PACKAGE` of the installation
# under PREFIX (an earlier block of the same pages installs it), then run; it must exit 0.
# A command whose output says "No tests were found" (a ctest that selects nothing) fails.
# `./dev.sh test` lines are not run again: .ci/run runs them itself. Each command (or script) has
# 20 minutes.
set -uo pipefail
cd "$(dirname "$0")/.."

files=("$@")
((${#files[@]} == 0)) && files=(README.md docs/*.md)

log=$(mktemp)
trap 'rm -f "$log"' EXIT
ran=0
failed=0
skipped=0

run_one() {  # file line command
  local file=$1 line=$2 cmd=$3 want=0
  if [[ $cmd =~ \#[[:space:]]*exit[[:space:]]+([0-9]+)[[:space:]]*$ ]]; then want=${BASH_REMATCH[1]}; fi
  if [[ $cmd =~ ^[[:space:]]*\./dev\.sh[[:space:]]+test ]]; then
    echo "check-docs: $file:$line: not run again (.ci/run runs it): $cmd"
    return
  fi
  ran=$((ran + 1))
  timeout 1200 bash -c "$cmd" >"$log" 2>&1 </dev/null
  local rc=$?
  # A ctest that selects nothing exits 0 (CMake 3.25 has no CTEST_NO_TESTS_ACTION): a documented
  # test command that runs no test is a failure all the same.
  if ((rc == 0)) && grep -q '^No tests were found' "$log"; then
    rc=8
    echo "    (ran no test)" >>"$log"
  fi
  if ((rc != want)); then
    failed=$((failed + 1))
    echo "check-docs: $file:$line: FAILED (exit $rc, expected $want): $cmd"
    tail -n 20 "$log" | sed 's/^/    /'
  else
    echo "check-docs: $file:$line: ok: $cmd"
  fi
}

# A program block: compiled against an installation and run (the `cpp PREFIX PACKAGE` marker).
program=""
compile_one() {  # file line prefix package
  local file=$1 line=$2 prefix=$3 package=$4 dir
  ran=$((ran + 1))
  dir=$(mktemp -d)
  printf '%s' "$program" >"$dir/program.cpp"
  local pc="$prefix/lib/pkgconfig:$prefix/lib/x86_64-linux-gnu/pkgconfig"
  # shellcheck disable=SC2046
  if ! (export PKG_CONFIG_PATH=$pc && g++ -std=c++20 -Wall -Wextra -Werror "$dir/program.cpp" -o "$dir/program" \
          $(pkg-config --cflags --libs "$package")) >"$log" 2>&1; then
    failed=$((failed + 1))
    echo "check-docs: $file:$line: FAILED to compile against $package in $prefix"
    tail -n 20 "$log" | sed 's/^/    /'
  else
    timeout 120 "$dir/program" >"$log" 2>&1 </dev/null
    local rc=$?
    if ((rc != 0)); then
      failed=$((failed + 1))
      echo "check-docs: $file:$line: FAILED: the program exited $rc"
      tail -n 20 "$log" | sed 's/^/    /'
    else
      echo "check-docs: $file:$line: ok: program compiled against $package and run"
    fi
  fi
  rm -rf "$dir"
  program=""
}

# A script block: every command followed by a check of its exit status; `cmd &` is not checked.
script=""
script_lines=0
add_to_script() {  # line command
  local line=$1 cmd=$2 want=0
  if [[ $cmd =~ \#[[:space:]]*exit[[:space:]]+([0-9]+)[[:space:]]*$ ]]; then want=${BASH_REMATCH[1]}; fi
  script_lines=$((script_lines + 1))
  if [[ $cmd =~ \&[[:space:]]*(\#.*)?$ ]]; then
    script+="$cmd"$'\n'
    return
  fi
  script+="$cmd"$'\n'"__rc=\$?; if [ \$__rc -ne $want ]; then echo \"check-docs: line $line: exit \$__rc, expected $want\" >&2; __failed=1; fi"$'\n'
}
run_script() {  # file first-line
  local file=$1 line=$2
  ran=$((ran + 1))
  timeout 1200 bash -c "__failed=0"$'\n'"$script"$'\n'"wait; exit \$__failed" >"$log" 2>&1 </dev/null
  local rc=$?
  if ((rc == 0)) && grep -q '^No tests were found' "$log"; then
    rc=8
    echo "check-docs: a ctest in the script ran no test" >>"$log"
  fi
  if ((rc != 0)); then
    failed=$((failed + 1))
    echo "check-docs: $file:$line: FAILED (script of $script_lines commands, exit $rc)"
    grep -E '^check-docs: line' "$log" | sed 's/^/    /'
    tail -n 20 "$log" | sed 's/^/    /'
  else
    echo "check-docs: $file:$line: ok: script of $script_lines commands"
  fi
  script=""
  script_lines=0
}

for file in "${files[@]}"; do
  [[ -f $file ]] || continue
  in_block=0
  skip_next=0
  skip_block=0
  script_next=0
  script_block=0
  cpp_next=""
  cpp_block=""
  block_line=0
  pending=""
  pending_line=0
  n=0
  while IFS= read -r text || [[ -n $text ]]; do
    n=$((n + 1))
    if ((in_block == 0)); then
      if [[ $text =~ ^[[:space:]]*\<\!--[[:space:]]*check-docs:[[:space:]]*skip[[:space:]]*(.*)--\>[[:space:]]*$ ]]; then
        skip_next=1
        reason=${BASH_REMATCH[1]}
        continue
      fi
      if [[ $text =~ ^[[:space:]]*\<\!--[[:space:]]*check-docs:[[:space:]]*script[[:space:]]*--\>[[:space:]]*$ ]]; then
        script_next=1
        continue
      fi
      if [[ $text =~ ^[[:space:]]*\<\!--[[:space:]]*check-docs:[[:space:]]*cpp[[:space:]]+([^[:space:]]+)[[:space:]]+([^[:space:]]+)[[:space:]]*--\>[[:space:]]*$ ]]; then
        cpp_next="${BASH_REMATCH[1]} ${BASH_REMATCH[2]}"
        continue
      fi
      if [[ -n $cpp_next && $text =~ ^[[:space:]]*\`\`\`cpp[[:space:]]*$ ]]; then
        in_block=1
        block_line=$n
        cpp_block=$cpp_next
        cpp_next=""
        skip_block=0
        continue
      fi
      if [[ $text =~ ^[[:space:]]*\`\`\`(sh|bash)[[:space:]]*$ ]]; then
        in_block=1
        block_line=$n
        script_block=$script_next
        script_next=0
        skip_block=$skip_next
        if ((skip_block)); then
          skipped=$((skipped + 1))
          echo "check-docs: $file:$n: block not run: ${reason% }"
        fi
      elif [[ -n ${text// /} ]]; then
        skip_next=0
        script_next=0
        cpp_next=""
      fi
      continue
    fi
    if [[ -n $cpp_block ]]; then
      if [[ $text =~ ^[[:space:]]*\`\`\`[[:space:]]*$ ]]; then
        in_block=0
        # shellcheck disable=SC2086
        compile_one "$file" "$block_line" $cpp_block
        cpp_block=""
      else
        program+="$text"$'\n'
      fi
      continue
    fi
    if [[ $text =~ ^[[:space:]]*\`\`\`[[:space:]]*$ ]]; then
      in_block=0
      skip_next=0
      if ((script_block && !skip_block)); then run_script "$file" "$block_line"; fi
      script_block=0
      continue
    fi
    ((skip_block)) && continue
    [[ -z ${text// /} || $text =~ ^[[:space:]]*# ]] && continue
    if [[ -z $pending ]]; then pending_line=$n; fi
    if [[ $text =~ \\$ ]]; then
      pending+="${text%\\} "
      continue
    fi
    pending+=$text
    if ((script_block)); then
      add_to_script "$pending_line" "$pending"
    else
      run_one "$file" "$pending_line" "$pending"
    fi
    pending=""
  done <"$file"
done

echo "check-docs: $((ran - failed)) passed, $failed failed, $skipped skipped"
((failed == 0))
