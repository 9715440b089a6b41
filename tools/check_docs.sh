#!/usr/bin/env bash
# Runs every shell command of the README and the docs as written, from the repository's root, so
# that none of them can rot. CI runs it on a fresh clone after the tests.
#
#   tools/check_docs.sh [FILE.md...]     (default: README.md docs/*.md)
#
# What it runs: every line of every ```sh / ```bash block (a line ending in `\` continues on the
# next). A command must exit 0, unless the line ends in a comment `# exit N`, then it must exit N.
# A block right after a line `<!-- check-docs: skip REASON -->` is not run (hardware, a serial
# port, a command that serves until it is stopped); REASON is printed. `./dev.sh test` lines are
# not run again: .ci/run runs them itself. Each command has 20 minutes.
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
  if ((rc != want)); then
    failed=$((failed + 1))
    echo "check-docs: $file:$line: FAILED (exit $rc, expected $want): $cmd"
    tail -n 20 "$log" | sed 's/^/    /'
  else
    echo "check-docs: $file:$line: ok: $cmd"
  fi
}

for file in "${files[@]}"; do
  [[ -f $file ]] || continue
  in_block=0
  skip_next=0
  skip_block=0
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
      if [[ $text =~ ^[[:space:]]*\`\`\`(sh|bash)[[:space:]]*$ ]]; then
        in_block=1
        skip_block=$skip_next
        if ((skip_block)); then
          skipped=$((skipped + 1))
          echo "check-docs: $file:$n: block not run: ${reason% }"
        fi
      elif [[ -n ${text// /} ]]; then
        skip_next=0
      fi
      continue
    fi
    if [[ $text =~ ^[[:space:]]*\`\`\`[[:space:]]*$ ]]; then
      in_block=0
      skip_next=0
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
    run_one "$file" "$pending_line" "$pending"
    pending=""
  done <"$file"
done

echo "check-docs: $((ran - failed)) passed, $failed failed, $skipped skipped"
((failed == 0))
