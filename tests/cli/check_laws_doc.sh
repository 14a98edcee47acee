#!/usr/bin/env bash
# check_laws_doc.sh LVSIM SRC: the key tables of docs/guidance.md (between the markers
# "lvsim laws --markdown: begin" and ": end") are exactly what `lvsim laws --markdown` prints
# from the registered laws' key tables, so the documentation cannot drift from the code.
set -u
lvsim=$1; doc=$2/docs/guidance.md
want=$("$lvsim" laws --markdown) || { echo "FAIL: lvsim laws --markdown exited $?"; exit 1; }
got=$(sed -n '/<!-- lvsim laws --markdown: begin -->/,/<!-- lvsim laws --markdown: end -->/p' "$doc" \
      | sed '1d;$d')
[ -n "$got" ] || { echo "FAIL: no 'lvsim laws --markdown' block in $doc"; exit 1; }
if [ "$want" != "$got" ]; then
  echo "FAIL: the key tables of $doc differ from 'lvsim laws --markdown' (< the program, > the page):"
  diff <(echo "$want") <(echo "$got") | head -20
  echo "regenerate them: replace the block with the output of 'lvsim laws --markdown'"
  exit 1
fi
echo "docs/guidance.md key tables: as lvsim laws --markdown ($(echo "$want" | grep -c '^| ') rows)"
