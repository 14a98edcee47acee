#!/usr/bin/env python3
"""An unpacked FMU's modelDescription.xml against the FMI 2.0 rules (FMI 2.0.x specification,
section 2.2), read with Python's xml.etree:

- the root: fmiVersion 2.0, a GUID, numberOfEventIndicators a count; ModelExchange and
  CoSimulation with a modelIdentifier that is a C identifier and names binaries/linux64/ID.so;
- unique value references per type (Real, Integer, Boolean, String, Enumeration);
- each ScalarVariable's causality / variability / initial combination allowed by the table of
  section 2.2.7, and its start value present exactly when that table requires it;
- every unit used (unit, declaredType's unit) declared in UnitDefinitions, every declared unit
  with a BaseUnit of integer exponents;
- every `derivative` attribute pointing to a continuous Real variable, and states not repeated;
- ModelStructure: Outputs = exactly the variables with causality output, Derivatives = exactly
  the variables with a `derivative` attribute, InitialUnknowns = exactly the outputs,
  calculated parameters, states and derivatives with initial approx or calculated; indices in
  range and ascending; dependencies (when given) in range;
- nominal > 0; DefaultExperiment startTime <= stopTime.

Usage: check_model_description.py FMU_DIR   (exit 0: conforming; 1: the list of violations)
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

# Section 2.2.7: allowed (causality, variability) pairs and their allowed `initial` values;
# the first one listed is the default when `initial` is absent. None: `initial` not allowed.
ALLOWED = {
    ("parameter", "fixed"): ["exact"],
    ("parameter", "tunable"): ["exact"],
    ("calculatedParameter", "fixed"): ["calculated", "approx"],
    ("calculatedParameter", "tunable"): ["calculated", "approx"],
    ("input", "discrete"): None,
    ("input", "continuous"): None,
    ("output", "constant"): ["exact"],
    ("output", "discrete"): ["calculated", "exact", "approx"],
    ("output", "continuous"): ["calculated", "exact", "approx"],
    ("local", "constant"): ["exact"],
    ("local", "fixed"): ["calculated", "approx"],
    ("local", "tunable"): ["calculated", "approx"],
    ("local", "discrete"): ["calculated", "exact", "approx"],
    ("local", "continuous"): ["calculated", "exact", "approx"],
    ("independent", "continuous"): None,
}
TYPES = ("Real", "Integer", "Boolean", "String", "Enumeration")
BASE = ("kg", "m", "s", "A", "K", "mol", "cd", "rad")


def check(fmu_dir):
    errors = []
    root = ET.parse(os.path.join(fmu_dir, "modelDescription.xml")).getroot()
    err = errors.append
    if root.tag != "fmiModelDescription" or root.get("fmiVersion") != "2.0":
        err("root: not an FMI 2.0 fmiModelDescription")
    if not re.fullmatch(r"\{[0-9a-fA-F-]+\}", root.get("guid", "")):
        err("root: guid missing or malformed: %r" % root.get("guid"))
    nei = root.get("numberOfEventIndicators", "0")
    if not nei.isdigit():
        err("numberOfEventIndicators %r is not a count" % nei)
    kinds = [k for k in ("ModelExchange", "CoSimulation") if root.find(k) is not None]
    if kinds != ["ModelExchange", "CoSimulation"]:
        err("expected both ModelExchange and CoSimulation, found %s" % kinds)
    for k in kinds:
        mid = root.find(k).get("modelIdentifier", "")
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", mid):
            err("%s: modelIdentifier %r is not a C identifier" % (k, mid))
        elif not os.path.isfile(os.path.join(fmu_dir, "binaries", "linux64", mid + ".so")):
            err("%s: binaries/linux64/%s.so is missing" % (k, mid))

    units = {}
    ud = root.find("UnitDefinitions")
    for u in (ud.findall("Unit") if ud is not None else []):
        name = u.get("name")
        if name in units:
            err("unit %r declared twice" % name)
        bu = u.find("BaseUnit")
        if bu is None:
            err("unit %r has no BaseUnit" % name)
        else:
            for a, v in bu.attrib.items():
                if a in BASE and not re.fullmatch(r"-?\d+", v):
                    err("unit %r: BaseUnit %s=%r is not an integer" % (name, a, v))
                elif a not in BASE + ("factor", "offset"):
                    err("unit %r: unknown BaseUnit attribute %r" % (name, a))
            if not any(a in BASE for a in bu.attrib):
                err("unit %r: BaseUnit with no exponent (dimensionless units need none)" % name)
        units[name] = u
    typedefs = {}
    td = root.find("TypeDefinitions")
    for t in (td.findall("SimpleType") if td is not None else []):
        typedefs[t.get("name")] = t

    mv = root.find("ModelVariables")
    svs = mv.findall("ScalarVariable") if mv is not None else []
    if not svs:
        err("no ModelVariables")
    vrs = {t: {} for t in TYPES}
    info = []  # per variable (1-based index - 1): (name, causality, variability, initial, elem)
    for i, sv in enumerate(svs, 1):
        name = sv.get("name")
        causality = sv.get("causality", "local")
        variability = sv.get("variability", "continuous")
        elems = [c for c in sv if c.tag in TYPES]
        if len(elems) != 1:
            err("%s: needs exactly one type element" % name)
            info.append((name, causality, variability, None, None))
            continue
        t = elems[0]
        vr = sv.get("valueReference")
        if vr is None or not vr.isdigit():
            err("%s: valueReference %r" % (name, vr))
        elif vr in vrs[t.tag]:
            err("%s: valueReference %s of %s already used by %s" % (name, vr, t.tag,
                                                                    vrs[t.tag][vr]))
        else:
            vrs[t.tag][vr] = name
        if t.tag != "Real" and variability == "continuous":
            err("%s: only Real variables can be continuous" % name)
        allowed = ALLOWED.get((causality, variability))
        initial = sv.get("initial")
        if (causality, variability) not in ALLOWED:
            err("%s: causality %r with variability %r is not allowed" % (name, causality,
                                                                         variability))
        elif allowed is None:
            if initial is not None:
                err("%s: initial not allowed for %s/%s" % (name, causality, variability))
        else:
            if initial is None:
                initial = allowed[0]
            elif initial not in allowed:
                err("%s: initial=%r not allowed for %s/%s (allowed: %s)" % (
                    name, initial, causality, variability, allowed))
        has_start = t.get("start") is not None
        needs_start = causality in ("parameter", "input") or initial in ("exact", "approx") \
            or variability == "constant"
        if needs_start and not has_start:
            err("%s: a start value is required (%s, %s, initial %s)" % (name, causality,
                                                                        variability, initial))
        if not needs_start and has_start:
            err("%s: a start value is not allowed (%s, %s, initial %s)" % (
                name, causality, variability, initial))
        if t.tag == "Real":
            unit = t.get("unit")
            if unit is None and t.get("declaredType") in typedefs:
                real = typedefs[t.get("declaredType")].find("Real")
                unit = real.get("unit") if real is not None else None
            if unit is not None and unit not in units:
                err("%s: unit %r is not declared in UnitDefinitions" % (name, unit))
            nom = t.get("nominal")
            if nom is not None and not float(nom) > 0:
                err("%s: nominal %s is not > 0" % (name, nom))
            for a in ("start", "nominal", "min", "max"):
                if t.get(a) is not None:
                    float(t.get(a))
        info.append((name, causality, variability, initial, t))

    n = len(info)
    states = []
    deriv_of = {}
    for i, (name, causality, variability, initial, t) in enumerate(info, 1):
        if t is None or t.get("derivative") is None:
            continue
        d = t.get("derivative")
        if not d.isdigit() or not 1 <= int(d) <= n:
            err("%s: derivative=%r is not a variable index" % (name, d))
            continue
        s = info[int(d) - 1]
        if s[4] is None or s[4].tag != "Real" or s[2] != "continuous":
            err("%s: derivative of %s, which is not a continuous Real" % (name, s[0]))
        if int(d) in states:
            err("%s: state %s has two derivatives" % (name, s[0]))
        states.append(int(d))
        deriv_of[i] = int(d)

    ms = root.find("ModelStructure")
    if ms is None:
        err("no ModelStructure")
        return errors

    def unknowns(tag):
        el = ms.find(tag)
        idx = []
        for u in (el.findall("Unknown") if el is not None else []):
            k = u.get("index", "")
            if not k.isdigit() or not 1 <= int(k) <= n:
                err("ModelStructure/%s: index %r out of range 1..%d" % (tag, k, n))
                continue
            idx.append(int(k))
            dep = u.get("dependencies")
            if dep:
                for dd in dep.split():
                    if not dd.isdigit() or not 1 <= int(dd) <= n:
                        err("ModelStructure/%s: dependency %r out of range" % (tag, dd))
        if idx != sorted(idx) or len(set(idx)) != len(idx):
            err("ModelStructure/%s: indices not ascending and unique" % tag)
        return idx

    outs = unknowns("Outputs")
    want_outs = [i for i, v in enumerate(info, 1) if v[1] == "output"]
    if outs != want_outs:
        err("ModelStructure/Outputs %s, variables with causality output %s" % (outs, want_outs))
    ders = unknowns("Derivatives")
    if ders != sorted(deriv_of):
        err("ModelStructure/Derivatives %s, variables with a derivative attribute %s" % (
            ders, sorted(deriv_of)))
    inits = unknowns("InitialUnknowns")
    want_init = []
    for i, (name, causality, variability, initial, t) in enumerate(info, 1):
        calc = initial in ("approx", "calculated")
        if (causality == "output" and calc) or causality == "calculatedParameter" or \
                ((i in states or i in deriv_of) and calc):
            want_init.append(i)
    if inits != want_init:
        err("ModelStructure/InitialUnknowns %s, expected %s" % (inits, want_init))

    de = root.find("DefaultExperiment")
    if de is not None and de.get("startTime") and de.get("stopTime"):
        if float(de.get("startTime")) > float(de.get("stopTime")):
            err("DefaultExperiment: startTime after stopTime")
    return errors


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[-1])
        return 2
    errors = check(sys.argv[1])
    for e in errors:
        print("modelDescription.xml: " + e)
    if errors:
        return 1
    print("modelDescription.xml conforms (%s)" % sys.argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main())
