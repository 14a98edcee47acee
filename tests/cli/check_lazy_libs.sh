#!/usr/bin/env bash
# check_lazy_libs.sh LVSIM SRC - the libraries only some commands need are loaded by those
# commands alone (src/io/dl_lib.h, issue 24): `lvsim --version` and `lvsim check` load none of
# libmatio, HDF5, libzip, OpenSSL's libcrypto, SQLite, NLopt, Open MPI or PLplot (the dynamic
# loader's own record, LD_DEBUG=files), while `lvsim fmu` does load libzip and `lvsim mc`
# SQLite - so a wrong name in this test cannot pass unnoticed.
set -uo pipefail
lvsim=$1 src=$2
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $*"; }
bad() { fail=$((fail + 1)); echo "FAILED: $*"; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
lazy='libmatio|libhdf5|libzip|libcrypto|libsqlite3|libnlopt|libmpi|libopen-pal|libplplot'
loaded() { LD_DEBUG=files "$@" 2>&1 >/dev/null | sed -n 's/.*file=\([^ ]*\).*generating link map.*/\1/p' | sort -u; }
mission="$src/examples/dof3-branch/mission.yaml"
for cmd in "--version" "check $mission"; do
  # shellcheck disable=SC2086
  libs=$(loaded "$lvsim" $cmd)
  [ -n "$libs" ] || { bad "lvsim $cmd: LD_DEBUG gave no list of loaded files"; continue; }
  extra=$(grep -E "$lazy" <<<"$libs" | tr '\n' ' ')
  [ -z "$extra" ] && ok "lvsim $cmd loads $(grep -c . <<<"$libs") libraries, none of the lazy ones" \
    || bad "lvsim $cmd loads $extra"
done
libs=$(loaded "$lvsim" fmu "$mission" --phase ascent -o "$work/a.fmu")
grep -q "libzip" <<<"$libs" && ok "lvsim fmu loads libzip" || bad "lvsim fmu: libzip not among: $libs"
libs=$(loaded "$lvsim" mc "$mission" -n 2 -o "$work/mc" --no-plots)
grep -q "libsqlite3" <<<"$libs" && ok "lvsim mc loads SQLite" || bad "lvsim mc: SQLite not among: $libs"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
