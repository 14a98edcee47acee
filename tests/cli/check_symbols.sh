#!/usr/bin/env bash
# check_symbols.sh LIB - every symbol liblvsim exports starts with lv_ (STYLE.md: the library
# builds with -fvisibility=hidden and marks its API with LV_API).
set -euo pipefail
lib="$1"
syms=$(nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBRV]$/ {print $3}')
bad=$(grep -v '^lv_' <<<"$syms" | grep -v '^_' || true)
n=$(wc -l <<<"$syms")
if [ -n "$bad" ]; then
  echo "exported symbols without the lv_ prefix:"; echo "$bad"
  echo "0 passed, 1 failed"; exit 1
fi
echo "$n exported symbols, all lv_*"
echo "1 passed, 0 failed"
