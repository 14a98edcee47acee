#!/usr/bin/env bash
# check_units.sh LVSIM SRC PYTHONPATH: one convention for dimensionless units everywhere (issue
# 27): "1" (the SI Brochure's "unit one", Modelica's unit="1"), shown "[1]" where units are
# bracketed. The strings themselves are checked in every model's table by test_units; here the
# renderings: `lvsim vars` of every model and type, `lvsim params` of every example, `lvsim
# laws`, the CSV headers and .mat descriptions of a run, and the Python package's units. None
# may write a dimensionless unit as "-", "" or "[-]", and the quantities dimensionless by
# definition (Mach number, load factors, eccentricity, throttle) must read "1" / "[1]".
set -u
lvsim=$1; src=$2; pypath=${3:-}
py=${LV_PYTHON:-/usr/bin/python3}  # Debian's, which sees python3-numpy and -scipy
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fails=0; pass=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }

# lvsim vars: kind, name, unit, ... for every model and type; the unit column is never "-"
for m in $("$lvsim" models | awk '!/^#/ { print $1 }'); do
  "$lvsim" vars "$m" > "$work/vars.txt" || { bad "lvsim vars $m"; continue; }
  n=$(awk '$1 ~ /^(state|derivative|parameter|output|mission)$/ && ($3 == "-" || $3 == "[-]" || $3 == "\"\"")' "$work/vars.txt" | wc -l)
  [ "$n" = 0 ] && ok || bad "lvsim vars $m: $n units written '-'"
  for v in mach n_axial ecc throttle throttle_in; do
    line=$(awk -v v="$v" '$1 ~ /^(parameter|output)$/ && $2 == v' "$work/vars.txt")
    [ -z "$line" ] && continue
    [ "$(awk '{ print $3 }' <<<"$line")" = 1 ] && ok || bad "lvsim vars $m: $v: '$line' (unit 1 expected)"
  done
done
grep -q "^output     mach             1 " <("$lvsim" vars dof3) && ok || bad "lvsim vars dof3: mach's unit"

# lvsim params: name, value, unit, allowed, line; a tolerance and a throttle limit are "1"
for y in "$src"/examples/*/mission.yaml; do
  "$lvsim" params "$y" > "$work/params.txt" || { bad "lvsim params $y"; continue; }
  n=$(awk '!/^#/ && ($3 == "-" || $3 == "")' "$work/params.txt" | wc -l)
  [ "$n" = 0 ] && ok || bad "lvsim params $y: $n units written '-'"
  n=$(awk '!/^#/ && $1 ~ /integrator\.tolerance$|throttle_m(in|ax)$/ && $3 != "1"' "$work/params.txt" | wc -l)
  [ "$n" = 0 ] && ok || bad "lvsim params $y: $n dimensionless parameters not '1'"
  "$lvsim" params "$y" --json | "$py" -c '
import json, sys
bad = [p["name"] for p in json.load(sys.stdin) if p["unit"] in ("", "-")]
sys.exit(1 if bad else 0)' && ok || bad "lvsim params --json $y: a unit '' or '-'"
done

# lvsim params is a table: on every line of every example the value ends, and the unit and the
# allowed values start, in the same column (the names', units' and rules' widths are the
# widest's), so that a reader or `cut` sees columns
for y in "$src"/examples/*/mission.yaml; do
  "$lvsim" params "$y" | "$py" -c '
import re, sys
lines = [l.rstrip("\n") for l in sys.stdin if not l.startswith("# mission")]
cols = set()
for l in lines:
    m = re.match(r"^(#?\s*\S+\s+)(\S+)(\s+)(\S+)(\s+)", l)
    value_end = m.end(2); unit_start = m.end(3); rule_start = m.end(5)
    cols.add((value_end, unit_start, rule_start))
sys.exit(0 if len(cols) == 1 else 1)' && ok || bad "lvsim params $y: the columns are not aligned"
done

# lvsim laws: a number key's unit is never "-" ("-" only for a table or a choice: no unit)
"$lvsim" laws > "$work/laws.txt"
n=$(awk '/^  [a-z]/ && $2 == "-" && $3 !~ /\|/ && $3 != "table"' "$work/laws.txt" | wc -l)
[ "$n" = 0 ] && ok || { bad "lvsim laws: $n number keys with unit '-'"; awk '/^  [a-z]/ && $2 == "-" && $3 !~ /\|/ && $3 != "table"' "$work/laws.txt"; }
grep -q "^  g_limit          1 " "$work/laws.txt" && ok || bad "lvsim laws: g_limit's unit"

# a run's files: every CSV header field is "name [unit]", dimensionless "[1]" (a body file's
# `phase` column holds the phase's name: text, no unit); the .mat
# descriptions end in "[unit]" the same way
"$lvsim" run "$src/examples/dof3-branch/mission.yaml" -o "$work/run" --no-plots --quiet >/dev/null 2>&1 || bad "lvsim run dof3-branch"
for f in "$work"/run/phase_*.csv "$work"/run/body_*.csv; do
  [ -e "$f" ] || continue
  head -1 "$f" | "$py" -c '
import csv, re, sys
head = next(csv.reader(sys.stdin))
badf = [h for h in head if h != "phase" and not re.fullmatch(r".+ \[[A-Za-z0-9/^.]+\]", h)]
sys.exit(1 if badf else 0)' && ok || bad "$f: a header field without its unit: $(head -1 "$f" | cut -c1-200)"
done
head -1 "$work"/run/phase_1_*.csv | tr ',' '\n' | grep -qx 'mach \[1\]' && ok || bad "CSV header: 'mach [1]'"
"$py" - "$work"/run/phase_*.mat <<'PY' && ok || bad ".mat descriptions: a unit missing or not '[1]'"
import re, sys
import scipy.io
for path in sys.argv[1:]:
    m = scipy.io.loadmat(path, chars_as_strings=False)
    names = ["".join(c).rstrip("\0 ") for c in m["name"].T]
    descs = ["".join(c).rstrip("\0 ") for c in m["description"].T]
    for n, d in zip(names, descs):
        assert re.search(r"\[[A-Za-z0-9/^.]+\]$", d), (path, n, d)
        if n in ("mach", "n_axial", "ecc", "throttle_in"):
            assert d.endswith("[1]"), (path, n, d)
PY

# Python: the units the package gives (PhaseResult, Trajectory, model variables, parameters)
if [ -n "$pypath" ] && [ -d "$pypath/lvsim" ]; then
  PYTHONPATH="$pypath" "$py" - "$src/examples/dof3-branch/mission.yaml" <<'PY' && ok || bad "Python: units"
import sys
import lvsim
m = lvsim.Mission(sys.argv[1])
run = m.run(keep_rows=True)
n = 0
for k in range(len(m.phases)):
    ph = run.result(k)
    assert ph.unit("mach") == "1" and ph.unit("h") == "m", (ph.unit("mach"), ph.unit("h"))
    assert all(u not in ("", "-") for u in ph.units), ph.units
    n += len(ph.units)
body = run.body("upper")
assert body.unit("mach") == "1" and all(u not in ("", "-") for n_, u in zip(body.names, body.units) if n_ != "phase"), body.units
assert all(p.unit not in ("", "-") for p in m.parameters), [p.name for p in m.parameters if p.unit in ("", "-")]
assert m.parameter("upper-engine.throttle_max").unit == "1"
print("python: %d phase columns, a body's %d, %d parameters: SI units, dimensionless '1'"
      % (n, len(body.units), len(m.parameters)))
PY
fi

echo "check_units: $pass passed, $fails failed"
[ "$fails" -eq 0 ]
