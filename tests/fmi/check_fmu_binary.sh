#!/usr/bin/env bash
# check_fmu_binary.sh LVSIM SOURCE_DIR - the binary inside an exported FMU is self-contained
# (issue 27: "the FMU binary needs Debian's SUNDIALS, libyaml and Nettle installed where it
# runs"): exported with `lvsim fmu`, unpacked with unzip, then
#  - readelf -d: its NEEDED list is libc.so.6 and libm.so.6, nothing else (SUNDIALS, libyaml,
#    ERFA and Nettle are linked in statically; libmatio is loaded with dlopen only for MAT
#    tables, so it is no NEEDED entry);
#  - ldd resolves it with no "not found" and loads nothing beyond the C library, libm and the
#    dynamic loader (the kernel's vDSO aside);
#  - nm -D: every symbol it defines and exports is an fmi2* function (FMI 2.0.4, 2.1: the
#    binary exports the standard's functions), and all of the standard's Model Exchange and
#    Co-Simulation functions are among them.
set -uo pipefail
LVSIM=$1
SRC=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $*"; }
bad() { fail=$((fail + 1)); echo "FAILED: $*"; }

"$LVSIM" fmu "$SRC/examples/kourou-leo/mission.yaml" --phase upper-burn-1 -o "$T/u.fmu" > /dev/null ||
  { echo "FAILED: lvsim fmu"; exit 1; }
unzip -q "$T/u.fmu" -d "$T/u" || { echo "FAILED: unzip"; exit 1; }
so=$(ls "$T"/u/binaries/linux64/*.so)

needed=$(readelf -d "$so" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | sort | tr '\n' ' ')
if [ "$needed" = "libc.so.6 libm.so.6 " ]; then
  ok "NEEDED: $needed"
else
  bad "NEEDED is '$needed', expected 'libc.so.6 libm.so.6 '"
fi

# liblvsim loads SUNDIALS and Nettle on first use (src/io/dl_lib.h): were those forwarders
# linked in, the binary would have no NEEDED entry for them yet dlopen them where it runs
sonames=$(strings "$so" | grep -E '^lib(sundials_[a-z]+|nettle)\.so' | tr '\n' ' ')
if [ -z "$sonames" ]; then
  ok "no library name to dlopen for SUNDIALS or Nettle: linked in"
else
  bad "the binary would dlopen: $sonames"
fi

lddout=$(ldd "$so" 2>&1)
if grep -q 'not found' <<<"$lddout"; then
  bad "ldd: $lddout"
fi
others=$(awk '{print $1}' <<<"$lddout" | grep -v -E '^(linux-vdso\.so\.1|libc\.so\.6|libm\.so\.6|/lib64/ld-linux-x86-64\.so\.2|/lib/ld-linux-x86-64\.so\.2)$' || true)
if [ -z "$others" ]; then
  ok "ldd: $(awk '{print $1}' <<<"$lddout" | tr '\n' ' ')"
else
  bad "ldd loads more than libc, libm and the loader: $others"
fi

exported=$(nm -D --defined-only "$so" | awk '$2 ~ /^[TDBRVW]$/ {print $3}' | sort -u)
nonfmi=$(grep -v '^fmi2' <<<"$exported" || true)
if [ -z "$nonfmi" ]; then
  ok "$(grep -c . <<<"$exported") exported symbols, all fmi2*"
else
  bad "exported symbols other than fmi2*: $(tr '\n' ' ' <<<"$nonfmi")"
fi
# the functions of FMI 2.0.4 sections 2.1 (common), 3.2 (Model Exchange), 4.2 (Co-Simulation)
for fn in GetTypesPlatform GetVersion SetDebugLogging Instantiate FreeInstance SetupExperiment \
  EnterInitializationMode ExitInitializationMode Terminate Reset GetReal GetInteger GetBoolean \
  GetString SetReal SetInteger SetBoolean SetString GetFMUstate SetFMUstate FreeFMUstate \
  SerializedFMUstateSize SerializeFMUstate DeSerializeFMUstate GetDirectionalDerivative \
  EnterEventMode NewDiscreteStates EnterContinuousTimeMode CompletedIntegratorStep SetTime \
  SetContinuousStates GetDerivatives GetEventIndicators GetContinuousStates \
  GetNominalsOfContinuousStates SetRealInputDerivatives GetRealOutputDerivatives DoStep \
  CancelStep GetStatus GetRealStatus GetIntegerStatus GetBooleanStatus GetStringStatus; do
  grep -qx "fmi2$fn" <<<"$exported" || bad "fmi2$fn is not exported"
done
ok "the standard's 44 functions are exported"

echo "check_fmu_binary: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
