#!/usr/bin/env bash
# Writes docs/cli.md, the reference of every command and option of `ibs`, from the command tree
# itself (`ibs reference markdown`, the same definitions as --help and `man ibs`). Run it after
# changing a command or an option; HelpReference.DocsCliMdIsWhatTheToolPrints fails until you do.
#
#   tools/cli_reference.sh [IBS]    IBS: a built ibs to ask (default: build the release one first)
set -euo pipefail
cd "$(dirname "$0")/.."
ibs=${1:-}
if [[ -z $ibs ]]; then
  ibs=build/release/tools/ibs/ibs
  [[ -f build/release/CMakeCache.txt ]] || cmake --preset release >/dev/null
  cmake --build --preset release --target ibs -j "$(nproc 2>/dev/null || echo 2)" >/dev/null
fi
tmp=$(mktemp docs/.cli.md.XXXXXX)
trap 'rm -f "$tmp"' EXIT
"$ibs" reference markdown >"$tmp"
chmod 644 "$tmp"
mv "$tmp" docs/cli.md
echo "tools/cli_reference.sh: docs/cli.md written by $ibs" >&2
