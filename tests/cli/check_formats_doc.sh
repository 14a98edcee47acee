#!/usr/bin/env bash
# check_formats_doc.sh LVSIM SRC: the format tables of docs/result-files.md and docs/exports.md
# (between the markers "lvsim formats --markdown KIND: begin" and ": end") are exactly what
# `lvsim formats --markdown KIND` prints from the registered formats, so the documentation
# cannot drift from the tables (src/io/result_formats.c, src/post/export.c).
set -u
lvsim=$1; fails=0
for pair in results:result-files.md exports:exports.md; do
  kind=${pair%%:*}; doc=$2/docs/${pair#*:}
  want=$("$lvsim" formats --markdown "$kind") || { echo "FAIL: lvsim formats --markdown $kind exited $?"; exit 1; }
  got=$(sed -n "/<!-- lvsim formats --markdown $kind: begin -->/,/<!-- lvsim formats --markdown $kind: end -->/p" "$doc" \
        | sed '1d;$d')
  if [ -z "$got" ]; then
    echo "FAIL: no 'lvsim formats --markdown $kind' block in $doc"; fails=$((fails + 1))
  elif [ "$want" != "$got" ]; then
    echo "FAIL: the table of $doc differs from 'lvsim formats --markdown $kind' (< the program, > the page):"
    diff <(echo "$want") <(echo "$got") | head -20
    echo "regenerate it: replace the block with the output of 'lvsim formats --markdown $kind'"
    fails=$((fails + 1))
  else
    echo "$doc: as lvsim formats --markdown $kind ($(echo "$want" | grep -c '^| `') formats)"
  fi
done
[ "$fails" -eq 0 ]
