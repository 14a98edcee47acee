#!/usr/bin/env bash
# check_help_doc.sh LVSIM SRC: `lvsim help` and docs/cli.md agree (issue 27). The command table
# of docs/cli.md (between "lvsim help --markdown: begin" and ": end") is exactly what `lvsim
# help --markdown` prints from the command table of cli/ (every command, its arguments, the
# summary `lvsim help` shows), and every command but help and version has its section
# "## `lvsim NAME USAGE`" with the usage line `lvsim help NAME` prints. The reference is the
# program's own command table (cli/main.c), which `lvsim help` prints: the page must say the
# same, so neither can drift (as `models` did: the page said it lists the mission model types,
# the program's summary only the built-in models).
set -u
lvsim=$1; doc=$2/docs/cli.md; fails=0
want=$("$lvsim" help --markdown) || { echo "FAIL: lvsim help --markdown exited $?"; exit 1; }
got=$(sed -n '/<!-- lvsim help --markdown: begin -->/,/<!-- lvsim help --markdown: end -->/p' "$doc" | sed '1d;$d')
if [ -z "$got" ]; then
  echo "FAIL: no 'lvsim help --markdown' block in $doc"; fails=$((fails + 1))
elif [ "$want" != "$got" ]; then
  echo "FAIL: the command table of $doc differs from 'lvsim help --markdown' (< the program, > the page):"
  diff <(echo "$want") <(echo "$got") | head -20
  echo "regenerate it: replace the block with the output of 'lvsim help --markdown'"
  fails=$((fails + 1))
fi
# the overview lists the same commands with the same summaries as the table
names=$(echo "$want" | sed -n 's/^| `\([a-z]*\).*/\1/p')
n=0
for c in $names; do
  n=$((n + 1))
  summary=$(echo "$want" | grep "^| \`$c[ \`]" | sed 's/^| `[^`]*` | \(.*\) |$/\1/')
  "$lvsim" help | grep -qF "  $(printf '%-12s' "$c") $summary" || { echo "FAIL: 'lvsim help' does not list '$c' as '$summary'"; fails=$((fails + 1)); }
  [ "$c" = help ] || [ "$c" = version ] && continue
  usage=$("$lvsim" help "$c" | awk 'NR == 1 { sub(/^usage: /, ""); u = $0; next } /^            / { sub(/^ +/, " "); u = u $0; next } { print u; exit }')
  grep -qxF "## \`$usage\`" "$doc" || { echo "FAIL: $doc has no section '## \`$usage\`'"; fails=$((fails + 1)); }
done
[ "$n" -ge 19 ] || { echo "FAIL: only $n commands in 'lvsim help --markdown'"; fails=$((fails + 1)); }
[ "$fails" -eq 0 ] && echo "$doc: as lvsim help --markdown ($n commands, each with its section)"
[ "$fails" -eq 0 ]
