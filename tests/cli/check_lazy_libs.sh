#!/usr/bin/env bash
# check_lazy_libs.sh LVSIM SRC - the libraries only some commands need are loaded by those
# commands alone (src/io/dl_lib.h, issue 24): `lvsim --version` and `lvsim check` load none of
# libmatio, HDF5, libzip, OpenSSL's libcrypto, SQLite, NLopt, Open MPI, PLplot or SUNDIALS (the
# dynamic loader's own record, LD_DEBUG=files), while `lvsim fmu` does load libzip, `lvsim mc`
# SQLite and `lvsim simulate` CVODE (dassl) or ARKODE (dopri5) - so a wrong name in this test
# cannot pass unnoticed.
set -uo pipefail
lvsim=$1 src=$2
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $*"; }
bad() { fail=$((fail + 1)); echo "FAILED: $*"; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
lazy='libmatio|libhdf5|libzip|libcrypto|libsqlite3|libnlopt|libmpi|libopen-pal|libplplot|libsundials|libnettle'
loaded() { LD_DEBUG=files "$@" 2>&1 >/dev/null | sed -n 's/.*file=\([^ ]*\).*generating link map.*/\1/p' | sort -u; }
mission="$src/examples/dof3-branch/mission.yaml"
# kourou-leo's phases name no method (auto: lvsim's own DOP853); dof3-branch's ask for dassl and
# dopri5, whose SUNDIALS integrators `check` creates to try each phase's start but never steps
# (integrator.c sets them up at the first step)
for cmd in "--version" "check $src/examples/kourou-leo/mission.yaml" "check $mission"; do
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
libs=$(loaded "$lvsim" simulate free_fall --stop 1 -o "$work/ff" --method dassl)
grep -q "libsundials_cvode" <<<"$libs" && ok "lvsim simulate --method dassl loads CVODE" \
  || bad "lvsim simulate --method dassl: CVODE not among: $libs"
grep -q "libsundials_arkode" <<<"$libs" && bad "lvsim simulate --method dassl loads ARKODE too" \
  || ok "lvsim simulate --method dassl does not load ARKODE"
libs=$(loaded "$lvsim" simulate free_fall --stop 1 -o "$work/ff2" --method dopri5)
grep -q "libsundials_arkode" <<<"$libs" && ok "lvsim simulate --method dopri5 loads ARKODE" \
  || bad "lvsim simulate --method dopri5: ARKODE not among: $libs"
libs=$(loaded "$lvsim" simulate free_fall --stop 1 -o "$work/ff3" --method dop853)
grep -q "libsundials" <<<"$libs" && bad "lvsim simulate --method dop853 loads SUNDIALS" \
  || ok "lvsim simulate --method dop853 loads no SUNDIALS library"
libs=$(loaded "$lvsim" run "$src/examples/sounding-rocket/mission.yaml" -o "$work/run" --no-plots -q)
grep -q "libnettle" <<<"$libs" && ok "lvsim run loads Nettle (the manifest's SHA-256)" \
  || bad "lvsim run: Nettle not among: $libs"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
