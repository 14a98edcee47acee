#!/usr/bin/env bash
# `lvsim fmu` with bad input: each case exits nonzero with a message naming what is wrong, and
# leaves no file behind. Usage: test_fmu_cli.sh LVSIM SOURCE_DIR
set -u
LVSIM=$1
SRC=$2
M="$SRC/examples/kourou-leo/mission.yaml"
T=$(mktemp -d)
trap 'chmod -R u+w "$T"; rm -rf "$T"' EXIT
fails=0
# expect CODE TEXT -- ARGS...: the exit code and a piece of the message on stderr
expect() {
  local code=$1 text=$2
  shift 3
  "$LVSIM" fmu "$@" > "$T/out" 2> "$T/err"
  local rc=$?
  if [ "$rc" -ne "$code" ] || ! grep -qF -- "$text" "$T/err"; then
    echo "FAIL: lvsim fmu $*: exit $rc (want $code), stderr:"; cat "$T/err"
    echo "  (wanted: $text)"
    fails=$((fails + 1))
  else
    echo "ok: lvsim fmu $* -> $rc: $(head -1 "$T/err")"
  fi
}
expect 2 "unknown phase 'nope'" -- "$M" --phase nope -o "$T/a.fmu"
expect 2 "needs the output file: -o" -- "$M" --phase ascent
expect 2 "needs the phase to export" -- "$M" -o "$T/a.fmu"
expect 2 "needs a mission file" -- --phase ascent -o "$T/a.fmu"
expect 2 "missing value for option" -- "$M" --phase ascent -o
expect 2 "unknown option" -- "$M" --phase ascent -o "$T/a.fmu" --bogus
expect 2 "no-such.yaml" -- "$T/no-such.yaml" --phase ascent -o "$T/a.fmu"
expect 2 "does not exist" -- "$M" --phase ascent -o "$T/no/dir/a.fmu"
mkdir "$T/ro" && chmod a-w "$T/ro"
if [ "$(id -u)" -ne 0 ]; then  # root writes anywhere
  expect 2 "is not writable" -- "$M" --phase ascent -o "$T/ro/a.fmu"
fi
mkdir "$T/dir.fmu"
expect 2 "is a folder" -- "$M" --phase ascent -o "$T/dir.fmu"
expect 2 "does not end in '.fmu'" -- "$M" --phase ascent -o "$T/a.zip"
expect 2 "not a C identifier" -- "$M" --phase ascent -o "$T/a.fmu" --model-identifier 9x
# a data file named by an absolute path cannot travel in the FMU
sed "s|table: aero_ascent.csv|table: $SRC/examples/kourou-leo/aero_ascent.csv|" "$M" > "$T/abs.yaml"
expect 2 "absolute path" -- "$T/abs.yaml" --phase ascent -o "$T/b.fmu"
if ls "$T"/*.fmu "$T"/*.tmp 2> /dev/null | grep -v "/dir.fmu" | grep -q .; then
  echo "FAIL: a file was left behind:"; ls "$T"; fails=$((fails + 1))
fi
expect 2 "too long (130 characters; max 127)" -- "$M" --phase ascent -o "$T/a.fmu" --model-identifier "$(printf 'x%.0s' $(seq 130))"
expect 2 "is a folder" -- "$SRC/examples/kourou-leo" --phase ascent -o "$T/a.fmu"
# repeated options are refused, not silently the last one
expect 2 "--phase given twice" -- "$M" --phase ascent --phase upper-burn-1 -o "$T/a.fmu"
expect 2 "-o given twice" -- "$M" --phase ascent -o "$T/a.fmu" -o "$T/b.fmu"
# the output is never the mission or one of its data files, by any spelling (a copy here)
mkdir "$T/m" && cp "$SRC"/examples/kourou-leo/* "$T/m/"
cp "$T/m/mission.yaml" "$T/m/keep.yaml"
# the --max-rows guard of check and run: an output interval of 1e-6 s
sed 's|output_interval: 1.0}|output_interval: 1.0e-6}|' "$M" > "$T/m/dense.yaml"
if grep -q "output_interval: 1.0e-6" "$T/m/dense.yaml"; then
  expect 2 "more than the limit" -- "$T/m/dense.yaml" --phase ascent -o "$T/d.fmu"
else
  echo "FAIL: no output_interval in $M to make dense"; fails=$((fails + 1))
fi
ln -s mission.yaml "$T/m/mission.fmu"
ln -s aero_ascent.csv "$T/m/aero.fmu"
expect 2 "is the mission's file" -- "$T/m/mission.yaml" --phase ascent -o "$T/m/mission.yaml" --force
expect 2 "is the mission's data file" -- "$T/m/mission.yaml" --phase ascent -o "$T/m/aero_ascent.csv"
expect 2 "is the mission's file" -- "$T/m/mission.yaml" --phase ascent -o "$T/m/mission.fmu"
expect 2 "is the mission's data file" -- "$T/m/mission.yaml" --phase ascent -o "$T/m/../m/aero.fmu"
expect 2 "is the mission's file" -- "$T/m/mission.yaml" --phase ascent -o "$T/m/mission.fmu" --force
if ! cmp -s "$T/m/mission.yaml" "$T/m/keep.yaml" || ! cmp -s "$T/m/aero_ascent.csv" "$SRC/examples/kourou-leo/aero_ascent.csv"; then
  echo "FAIL: the mission or its data file was changed"; fails=$((fails + 1))
fi
rm -rf "$T/m"
# and a good one, for contrast
if "$LVSIM" fmu "$M" --phase ascent -o "$T/ok.fmu" > "$T/out" 2>&1 && [ -s "$T/ok.fmu" ]; then
  echo "ok: $(head -1 "$T/out")"
else
  echo "FAIL: the good export"; cat "$T/out"; fails=$((fails + 1))
fi
# an existing file of the name is refused (lvsim cannot prove it wrote it), replaced with --force
before=$(sha256sum < "$T/ok.fmu")
expect 2 "ok.fmu' exists: lvsim does not replace a file it cannot prove it wrote" -- "$M" --phase upper-burn-1 -o "$T/ok.fmu"
[ "$before" = "$(sha256sum < "$T/ok.fmu")" ] || { echo "FAIL: a refused export changed ok.fmu"; fails=$((fails + 1)); }
if "$LVSIM" fmu "$M" --phase upper-burn-1 -o "$T/ok.fmu" --force > "$T/out" 2>&1 && unzip -l "$T/ok.fmu" | grep -q kourou_leo_upper_burn_1.so; then
  echo "ok: an existing .fmu replaced with --force"
else
  echo "FAIL: replacing an existing .fmu with --force"; cat "$T/out"; fails=$((fails + 1))
fi
# a 6-DoF phase with a controller: its gains are rad/rad, a ratio of like units, which get no
# unit attribute (an empty BaseUnit is refused by the compliance checkers; breaker, issue 27)
S6="$SRC/examples/two-stage-6dof/mission.yaml"
if "$LVSIM" fmu "$S6" --phase boost -o "$T/b6.fmu" > "$T/out" 2>&1 && mkdir -p "$T/b6" &&
   unzip -q -o "$T/b6.fmu" -d "$T/b6" &&
   /usr/bin/python3 "$SRC/tests/fmi/check_model_description.py" "$T/b6" > "$T/chk" 2>&1 &&
   ! grep -q 'unit="rad/rad"' "$T/b6/modelDescription.xml"; then
  echo "ok: the dof6 FMU's modelDescription.xml conforms"
else
  echo "FAIL: the dof6 FMU"; cat "$T/out" "$T/chk" 2> /dev/null | tail -5; fails=$((fails + 1))
fi
[ "$fails" -eq 0 ] && echo "test_fmu_cli: all passed" || echo "test_fmu_cli: $fails failed"
exit $((fails > 0))
