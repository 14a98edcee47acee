#!/usr/bin/env bash
# Runs every unit-test executable of BUILD_DIR under valgrind (memcheck, full leak check);
# fails on any error or definite leak. Usage: scripts/valgrind-tests.sh BUILD_DIR
set -euo pipefail
build="${1:-build}"
export LV_SOURCE_DIR="$(pwd)"
cd "$build/tests"
fail=0
for t in ./test_*; do
  [ -x "$t" ] && [ -f "$t" ] || continue
  # tests/valgrind.supp: caches of fontconfig/pango/glib that PLplot's cairo driver keeps
  if valgrind -q --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite \
       --suppressions="$LV_SOURCE_DIR/tests/valgrind.supp" \
       "$t" > "/tmp/valgrind_$(basename "$t").log" 2>&1; then
    echo "valgrind ok:     $t"
  else
    echo "valgrind FAILED: $t (see /tmp/valgrind_$(basename "$t").log)"; fail=1
  fi
done
exit $fail
