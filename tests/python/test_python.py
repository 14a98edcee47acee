"""test_python.py - the Python package lvsim (python/lvsim) against the C library and the CLI.

Run by ctest (tests/python/python.cmake) with Debian's /usr/bin/python3 -m pytest and
    PYTHONPATH=<build>/python  LVSIM=<build>/lvsim  LV_PY_LAYOUT=<build>/tests/py_layout
    LV_SOURCE_DIR=<source>
Checks: the ctypes mirrors of the C structures; results bit-equal to the CLI's result files
(CSV and MAT) for the same mission; errors for bad input (file:line:column, parameter names,
a failing phase's phase/time with the phases before it kept); a parameter sweep re-simulating
only the phases it reaches; the one-phase call (the paper's Code 1 and Code 2); threads and
the GIL; targeting; Monte Carlo; closing and freeing.
"""
import csv
import ctypes
import gc
import json
import math
import os
import shutil
import subprocess
import sys
import threading
import time

import numpy as np
import pytest
import scipy.io

import lvsim
from lvsim import _lib

ROOT = os.environ.get("LV_SOURCE_DIR") or os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
LVSIM = os.environ.get("LVSIM", os.path.join(ROOT, "build", "lvsim"))
DEMO = os.path.join(ROOT, "examples", "rlv-hthl", "mission.yaml")
PAPER = os.path.join(ROOT, "examples", "paper-test-case", "mission.yaml")
BRANCH = os.path.join(ROOT, "examples", "dof3-branch", "mission.yaml")
LEO_TARGETED = os.path.join(ROOT, "examples", "kourou-leo-targeted", "mission.yaml")
# Under the sanitizers (make test-asan preloads their run-times) the library is ~10x slower:
# the long runs of the thread tests are made shorter there.
SANITIZED = "libasan" in os.environ.get("LD_PRELOAD", "")


def same_finals(a, b):
    """Two finals dicts equal value for value, a NaN (an iip_* output in orbit) equal to a NaN."""
    return a.keys() == b.keys() and all(
        a[k] == b[k] or (math.isnan(a[k]) and math.isnan(b[k])) for k in a)


def bits(a):
    """The bytes of a float64 array: equality of these is equality bit for bit (NaN too)."""
    return np.ascontiguousarray(a, dtype="<f8").tobytes()


# ---- the mirrored structures ------------------------------------------------------------

def test_layout_matches_the_headers():
    exe = os.environ.get("LV_PY_LAYOUT")
    if not exe:
        pytest.skip("LV_PY_LAYOUT not set (ctest sets it)")
    c = {}
    for line in subprocess.run([exe], check=True, capture_output=True, text=True).stdout.split("\n"):
        if line:
            key, kind, n = line.split()
            c[(key, kind)] = int(n)
    checked = 0
    for st in _lib.MIRRORED + _lib.PARTIAL:
        name = st.__name__
        if st in _lib.MIRRORED:
            assert c[(name, "size")] == ctypes.sizeof(st), name
            checked += 1
        for f, _ in st._fields_:
            assert (f"{name}.{f}", "offset") in c, f"{name}.{f} not in py_layout.c"
            assert c[(f"{name}.{f}", "offset")] == getattr(st, f).offset, f"{name}.{f}"
            checked += 1
    # and every field py_layout.c lists is mirrored (a field added in C but not here)
    mirrored = {f"{st.__name__}.{f}" for st in _lib.MIRRORED + _lib.PARTIAL for f, _ in st._fields_}
    for key, kind in c:
        if kind == "offset":
            assert key in mirrored, f"{key}: in the header, not in python/lvsim/_lib.py"
    assert checked > 250


# ---- results equal to the CLI's files ------------------------------------------------------

def read_csv(path):
    with open(path, newline="") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].startswith("#")]
    names, units = [], []
    for h in rows[0]:  # "name [unit]", "name [1]" when dimensionless
        n, _, u = h.partition(" [")
        names.append(n)
        units.append(u[:-1])
    # the CSV holds the shortest text that reads back to the same double (io/numfmt.h)
    return names, units, np.array([[float(x) for x in r] for r in rows[1:]])


def read_mat(path):
    m = scipy.io.loadmat(path, chars_as_strings=False)
    names = ["".join(c).rstrip("\0 ") for c in m["name"].T]
    out = {}
    for i, name in enumerate(names):
        block, col = m["dataInfo"][0, i], m["dataInfo"][1, i]
        if block in (0, 2):  # time (block 0) and the signals (data_2); not the parameters
            out[name] = np.sign(col) * m["data_2"][abs(col) - 1, :]
    return out


@pytest.fixture(scope="module")
def cli_demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "demo"
    subprocess.run([LVSIM, "run", DEMO, "-o", str(out), "--no-plots", "--quiet"], check=True,
                   capture_output=True)
    return out


@pytest.fixture(scope="module")
def demo_run():
    m = lvsim.Mission(DEMO)
    r = m.run()
    yield r
    r.close()
    m.close()


def test_phase_results_equal_the_cli_files(cli_demo, demo_run):
    m = demo_run.mission
    n_values = 0
    for p in m.phases:
        res = demo_run.result(p.name)
        stem = cli_demo / f"phase_{p.index + 1}_{p.name}"
        names, units, values = read_csv(f"{stem}.csv")
        assert res.names == names and res.units == units, p.name
        assert res.values.shape == values.shape, p.name
        assert bits(res.values) == bits(values), f"{p.name}: CSV values differ"
        mat = read_mat(f"{stem}.mat")
        for j, name in enumerate(res.names):
            assert bits(res[name]) == bits(mat[name]), f"{p.name}.{name}: MAT differs"
        n_values += values.size
        # finals: the last row's values (time, states, outputs) as the summary gives them
        for name, v in res.finals.items():
            assert bits(v) == bits(res[name][-1]), (p.name, name)
    assert n_values > 10000


def test_bodies_equal_the_cli_body_files(cli_demo, demo_run):
    m = demo_run.mission
    bodies = demo_run.bodies()
    assert set(bodies) == set(m.stages)
    for stage, b in bodies.items():
        with open(cli_demo / f"body_{stage}.csv", newline="") as fh:
            rows = [r for r in csv.reader(fh) if r and not r[0].startswith("#")]
        head = rows[0]
        # body_<stage>.csv: time, the phase's name (text), then the columns
        assert head[1] == "phase"
        names = [head[0].rsplit(" [", 1)[0]] + [h.rsplit(" [", 1)[0] for h in head[2:]]
        units = [head[0].rsplit(" [", 1)[1][:-1]] + [h.rsplit(" [", 1)[1][:-1] for h in head[2:]]
        values = np.array([[float(r[0])] + [float(x) for x in r[2:]] for r in rows[1:]])
        assert b.names == names and b.units == units, stage
        assert bits(b.values) == bits(values), stage
        assert [b.phase_names[k] for k in b.phase] == [r[1] for r in rows[1:]], stage


def test_summary_matches(cli_demo, demo_run):
    with open(cli_demo / "summary.json") as f:
        summary = json.load(f)
    phases = summary["phases"]
    assert [p["name"] for p in phases] == [p.name for p in demo_run.mission.phases]
    for ph in phases:
        res = demo_run.result(ph["name"])
        assert ph["state"] == res.state == "done"
        # summary.json writes 15 significant digits
        assert res.t_end == pytest.approx(ph["t_end"], rel=1e-14)
        # summary.json leaves a value out that is not finite (an iip_* output in orbit: NaN)
        assert set(ph["final"]) == {k for k, v in res.finals.items() if math.isfinite(v)}
        for k, v in ph["final"].items():
            assert res.finals[k] == pytest.approx(v, rel=1e-13, abs=1e-300), (ph["name"], k)
        assert ph["handoff"].get("states_copied", 0) == res.n_copied
        # the user's names of the events (`end_name: MECO`): the same in both
        assert res.end_label == ph["end"].get("label"), ph["name"]
        assert [e.label for e in res.events] == [e.get("label") for e in ph["events"]], ph["name"]
        for st, book in ph["propellant"].items():
            assert res.propellant_start[st] == pytest.approx(book["start"], rel=1e-14)
            assert res.propellant_end[st] == pytest.approx(book["end"], rel=1e-14)


def test_named_ends(demo_run):
    # examples/rlv-hthl: `end_name: MECO` on the ascent (ended by propellant_left), SECO on the
    # upper stage's burn (ended by sma); the condition's name stays stop_name
    asc, us = demo_run.result("ascent"), demo_run.result("us-ascent")
    assert (asc.end_label, asc.stop_name) == ("MECO", "propellant_left")
    assert (us.end_label, us.stop_name) == ("SECO", "sma")
    assert asc.events[-1].label == "MECO" and all(e.label is None for e in asc.events[:-1])
    assert demo_run.result("ballistic").end_label is None


def test_dataframes_carry_units(demo_run):
    pd = pytest.importorskip("pandas")
    df = demo_run.dataframe("ascent")
    assert isinstance(df, pd.DataFrame)
    res = demo_run.result("ascent")
    assert list(df.columns) == res.names
    assert df.attrs["units"]["h"] == "m" and df.attrs["units"]["time"] == "s"
    assert df.attrs["units"]["m"] == "kg"
    assert bits(df["h"].to_numpy()) == bits(res["h"])
    body = demo_run.body("us").to_dataframe()
    assert body.attrs["units"]["stage_mass"] == "kg"
    assert set(body["phase"]) == {"liftoff", "ascent", "ballistic", "us-ascent"}


def test_mission_description(demo_run):
    m = demo_run.mission
    assert m.name == "rlv-hthl" and m.planet == "earth" and not m.flat_world
    assert [p.name for p in m.phases] == ["liftoff", "ascent", "ballistic", "us-ascent",
                                         "turn-around", "glide-back", "approach", "final",
                                         "flare", "rollout"]
    assert m.phases[3].parent == "ballistic" and m.phases[0].parent is None
    assert m.phases[3].stages == ["us", "payload"]
    p = m.parameter("us.propellant_mass")
    assert p.value == 55000 and p.unit == "kg" and p.line > 0
    res = demo_run.result("us-ascent")
    assert res.state == "done" and res.ok and res.error is None
    assert res.stop_reason == "event" and res.end_index == 0
    assert res.mass_start == pytest.approx(66000, rel=1e-9)  # US + payload, from the stage book
    assert res.dry_mass["us"] == 6000 and res.propellant_start["us"] == 55000
    assert res.stats["steps"] > 0 and res.stats["output_rows"] == len(res)
    assert res.final_units["h"] == "m"
    assert all(p.handoff_rule is None for p in m.phases)  # no change of model
    assert res.absorbed == {}  # a flight-to-flight hand-off carries everything over


def test_level_of_detail_transition_rule():
    # the two-stage example's boost phase is a dof6 child of a dof3 phase and asks for
    # `transition: {rates: curvature}` (docs/models.md, "Level-of-detail transitions")
    with lvsim.Mission(os.path.join(ROOT, "examples", "two-stage-6dof", "mission.yaml")) as m:
        boost = m.phases[1]
        assert boost.name == "boost" and boost.model == "dof6" and boost.parent == "liftoff"
        assert boost.handoff_rule == "rates: curvature"
        # dof6 -> dof3 drops the attitude states: no rule to choose
        assert m.phases[2].model == "dof3" and m.phases[2].handoff_rule is None


def test_reference_drift_of_a_free_fall(tmp_path):
    # a reference that stays where the phase starts, at rest 100 km over a non-rotating
    # point-mass sphere: the phase falls from it, ~g t^2 / 2 away after t (g = GM / r^2; g
    # grows by 2 dh / r ~ 1.5e-4 over the 490 m fallen in 10 s), at the speed g t
    # (docs/optimal-control.md, "Importing an optimiser's trajectory")
    gm, radius, h0, t1 = 3.986004418e14, 6371000.0, 100e3, 10.0
    (tmp_path / "ref.csv").write_text(
        "time [s],h [m],lat [rad],lon [rad],v [m/s],fpa [rad],heading [rad],m [kg]\n"
        f"0,{h0},0,0,0,0,0,500\n{t1},{h0},0,0,0,0,0,500\n")
    (tmp_path / "m.yaml").write_text(
        "mission: {name: fall}\n"
        "environment: {world: planet, planet: {name: sphere, radius: 6371000, "
        "gm: 3.986004418e14, rotation_rate: 0}, gravity: pointmass, atmosphere: none}\n"
        "stages: [{name: s, dry_mass: 500, propellant_mass: 0}]\n"
        "phases:\n"
        "  - {name: fall, model: dof3, stages: [s], stop_time: 10, "
        "reference: {table: ref.csv, start: reference}, integrator: {output_interval: 1}}\n")
    with lvsim.Mission(str(tmp_path / "m.yaml")) as m:
        d = m.run().reference_drift("fall")
        g = gm / (radius + h0) ** 2
        assert d["over"] == "time" and d["start"] == "reference" and d["rows"] == 11
        assert d["position"]["final"] == pytest.approx(0.5 * g * t1 ** 2, rel=1e-3)
        assert d["position"]["t_max"] == t1 and d["velocity"]["final"] == pytest.approx(g * t1, rel=1e-3)
        assert d["mass"]["max"] == 0.0
        with pytest.raises(lvsim.LvsimError, match="no drift"):
            m.run(keep_rows=False).reference_drift("fall")


# ---- errors -----------------------------------------------------------------------------

def test_bad_yaml_names_file_line_column(tmp_path):
    bad = os.path.join(ROOT, "tests", "missions", "bad_syntax.yaml")
    with pytest.raises(lvsim.MissionError) as e:
        lvsim.Mission(bad)
    assert e.value.file == bad and e.value.line is not None and e.value.column is not None
    assert str(e.value).startswith(f"{bad}:{e.value.line}:{e.value.column}: ")
    assert e.value.status == "LV_ERR_INPUT"
    # an unknown key: the line and column where it is written, and a suggestion
    p = tmp_path / "typo.yaml"
    p.write_text("mission: {name: typo}\nstages:\n  - {name: s, dry_mass: 100, propellant_mass: 0}\n"
                 "phases:\n  - {name: coast, model: flat6, stages: [s], stop_tme: 10}\n")
    with pytest.raises(lvsim.MissionError) as e:
        lvsim.Mission(p)
    assert e.value.line == 5 and e.value.column is not None, str(e.value)
    assert "stop_tme" in str(e.value) and "stop_time" in str(e.value)
    with pytest.raises(lvsim.LvsimError) as e:
        lvsim.Mission(tmp_path / "missing.yaml")
    assert "missing.yaml" in str(e.value)


def test_unknown_parameter_and_range(demo_run):
    run = demo_run.mission.create_run()
    with pytest.raises(lvsim.ParameterError) as e:
        run.set("us.propelant_mass", 50000)
    assert e.value.status == "LV_ERR_NOTFOUND" and "us.propellant_mass" in str(e.value)
    with pytest.raises(lvsim.ParameterError) as e:
        run.set("us.propellant_mass", -1)
    assert e.value.status == "LV_ERR_INPUT" and "us.propellant_mass" in str(e.value)
    with pytest.raises(lvsim.ParameterError):
        lvsim.Mission(DEMO).run(params={"nonsense": 1})
    with pytest.raises(lvsim.LvsimError) as e:
        run.result("ascnt")
    assert "ascent" in str(e.value)  # did you mean
    with pytest.raises(lvsim.LvsimError):
        run.execute(phases=["nope"])
    with pytest.raises(lvsim.LvsimError) as e:
        run.final("ascent", "h")  # not run yet
    run.close()


FAILING = """\
mission: {name: fails-late}
stages:
  - {name: a, dry_mass: 100, propellant_mass: 900, engines: [{table: {file: short.csv, extrap: error}}]}
phases:
  - {name: p1, model: flat6, stages: [a], stop_time: 20}
  - {name: p2, model: flat6, stages: [a], from: p1, stop_time: 200}
  - {name: p3, model: flat6, stages: [a], from: p2, stop_time: 300}
"""


def test_failing_phase_keeps_the_phases_before(tmp_path):
    (tmp_path / "short.csv").write_text("t [s], thrust [N], mdot [kg/s]\n0, 30000, 10\n50, 30000, 10\n")
    (tmp_path / "fail.yaml").write_text(FAILING)
    m = lvsim.Mission(tmp_path / "fail.yaml")
    with pytest.raises(lvsim.SimulationError) as e:
        m.run(outdir=tmp_path / "out")
    err = e.value
    assert err.status == "LV_ERR_SOLVER"
    assert err.done == ["p1"] and list(err.failed) == ["p2"] and err.skipped == ["p3"]
    assert "phase 'p2'" in str(err) and "outside" in str(err) and "t = " in str(err)
    run = err.run
    assert run.states == {"p1": "done", "p2": "failed", "p3": "skipped"}
    p1 = run.result("p1")
    assert p1.ok and len(p1) > 10 and p1.finals["time"] == 20
    p2 = run.result("p2")
    assert p2.state == "failed" and "phase 'p2'" in p2.error
    assert 20 < p2.t_end <= 50.0 + 1e-9 and len(p2) > 0  # the rows before the failure
    assert p2.result_files and all(".failed." in f for f in p2.result_files)
    assert all(os.path.exists(f) for f in p2.result_files + p1.result_files)
    # check=False: no exception, the same state
    run2 = m.run(check=False)
    assert not run2.ok and "p2" in run2.failed
    run.close(); run2.close(); m.close()


# ---- parameters and sweeps ---------------------------------------------------------------

def test_parameter_sweep_reruns_only_what_changed():
    m = lvsim.Mission(DEMO)
    run = m.create_run()
    run.execute()
    assert run.simulated == 10
    base = run.finals("us-ascent")
    ascent0 = run.result("ascent").values.copy()
    masses, t_burn = [], []
    for dp in (-4000.0, -2000.0, 0.0):
        run.set("us.propellant_mass", 55000.0 + dp)
        assert run.get("us.propellant_mass") == 55000.0 + dp
        run.execute()
        # the upper stage's propellant is carried from lift-off: every phase flies it
        fin = run.finals("us-ascent")
        masses.append(fin["m"])
        t_burn.append(fin["time"])
    # the same value as the file: the same bits as the first run
    assert bits(run.result("ascent").values) == bits(ascent0)
    assert same_finals(run.finals("us-ascent"), base)
    # a change of a late phase's parameter re-simulates only it and its descendants (the
    # approach, the final glide, the flare and the roll-out)
    names = [p.name for p in m.parameters]
    appr = [n for n in names if n.startswith("approach.")][0]
    run.set(appr, run.get(appr) * 1.001 if run.get(appr) else 1.0)
    run.execute()
    assert run.simulated == 4
    # Mission.run(params=...) equals a run set by hand
    r2 = m.run(params={"us.propellant_mass": 53000.0})
    run.reset()
    run.set("us.propellant_mass", 53000.0)
    run.execute()
    assert bits(r2.result("us-ascent").values) == bits(run.result("us-ascent").values)
    assert len(set(masses)) == 3 and len(set(t_burn)) == 3
    run.close(); r2.close(); m.close()


def test_execute_one_phase_and_until():
    m = lvsim.Mission(DEMO)
    run = m.create_run()
    run.execute(phases="us-ascent")
    assert run.states == {"liftoff": "done", "ascent": "done", "ballistic": "done",
                          "us-ascent": "done", "turn-around": "pending",
                          "glide-back": "pending", "approach": "pending", "final": "pending",
                          "flare": "pending", "rollout": "pending"}
    run.execute(until="turn-around")
    assert run.state("turn-around") == "done" and run.state("glide-back") == "pending"
    assert run.simulated == 1
    run.execute()
    assert run.ok and run.simulated == 5
    run.close(); m.close()


def test_outdir_and_formats(tmp_path):
    m = lvsim.Mission(PAPER)
    r = m.run(outdir=tmp_path / "o", formats=["csv"], keep_rows=False)
    res = r.result(0)
    assert len(res) == 0 and res.finals  # no rows kept, finals still there
    assert [os.path.basename(f) for f in res.result_files] == [f"phase_1_{res.name}.csv"]
    assert os.path.exists(res.result_files[0])
    with pytest.raises(lvsim.LvsimError):
        r.execute(outdir=tmp_path / "x", formats=["hdf5"])
    r.close(); m.close()


def test_progress_callback_and_cancel():
    m = lvsim.Mission(DEMO)
    seen = []
    run = m.run(progress=lambda k, t: seen.append((k, t)) and False)
    assert run.ok and {k for k, _ in seen} == set(range(len(m.phases)))
    # at every row of the output grid: the last one within an interval of the end
    t_end = run.result("rollout").t_end
    assert t_end - 5.0 <= max(t for _, t in seen) <= t_end
    # returning True cancels: the phase running then fails with LV_ERR_CANCELLED
    r2 = m.create_run()
    with pytest.raises(lvsim.CancelledError):
        r2.execute(progress=lambda k, t: t > 100.0, threads=1)
    assert "done" in r2.states.values() and not r2.ok
    # an exception in the callback stops the run and comes out of execute
    r3 = m.create_run()

    def boom(k, t):
        raise RuntimeError("from the callback")
    with pytest.raises(RuntimeError, match="from the callback"):
        r3.execute(progress=boom)
    r3.execute(phases=[np.int64(1)])  # NumPy integers name phases too
    assert r3.state(1) == "done"
    for r in (run, r2, r3):
        r.close()
    m.close()


# ---- one phase by hand: the paper's Code 1 and Code 2 -------------------------------------

def test_simulate_builtin_model_known_answer():
    # vertical ascent: burnout at (m0 - m_final) / mdot; speed there from Tsiolkovsky
    o = lvsim.simulate("vertical_ascent", stop_time=400, tolerance=1e-10, method="dopri5",
                       initial={"thrust": 30000, "mdot": 10, "m0": 1000, "m_final": 400,
                                "g": 9.81, "stop_at_apogee": 1},
                       finals=["time", "h", "v", "m"])
    assert o.ok and o.error is None and o.stop_reason == "event"
    burnout = [e for e in o.events if e.name == "burnout"]
    assert burnout and burnout[0].t == pytest.approx(60.0, abs=1e-7)
    v_bo = 3000.0 * math.log(1000.0 / 400.0) - 9.81 * 60.0
    row = np.flatnonzero(o.rows["time"] == burnout[0].t)[0]
    assert o.rows["v"][row] == pytest.approx(v_bo, rel=1e-7)
    assert o.finals["v"] == pytest.approx(0.0, abs=1e-6)  # stopped at apogee
    assert o.rows.unit("h") == "m"
    # a failure is an outcome with the library's message (model, time, reason)
    f = lvsim.simulate("oscillator", stop_time=1000, finals=["time"])
    g = lvsim.simulate("oscillator", stop_time=1000, finals=["time"], fixed_step=None,
                       tolerance=1e-4, method="dassl", rows=False)
    assert f.ok and g.ok and g.rows is None
    with pytest.raises(lvsim.LvsimError) as e:
        lvsim.simulate("vertical_ascent", initial={"thrustt": 1})
    assert "thrust" in str(e.value)
    with pytest.raises(lvsim.LvsimError):
        lvsim.simulate("no_such_model")
    assert "kepler" in lvsim.models()


def test_phase_call_reproduces_the_runner():
    m = lvsim.Mission(DEMO)
    ref = m.run()
    run = m.create_run()
    for p in m.phases:  # the paper's Code 2: each phase from its parent's final state
        call = run.prepare(p.name)
        assert call.model.states and call.initial
        out = call.simulate()
        assert out.ok, out.error
        assert same_finals(out.finals, ref.finals(p.name))
    for p in m.phases:
        assert bits(run.result(p.name).values) == bits(ref.result(p.name).values), p.name
    # simulateExtendedModel: other start values and extra finals, not recorded
    call = run.prepare("ballistic")
    m0 = call.initial["m"]
    out = call.simulate(initial={"m": m0 - 1000.0}, finals=["time", "h", "der(m)"],
                        record=False)
    assert out.ok and set(out.finals) == {"time", "h", "der(m)"}
    assert out.finals["time"] != ref.final("ballistic", "time")
    assert out.rows.values.shape[1] == len(ref.result("ballistic").names)
    assert bits(run.result("ballistic").values) == bits(ref.result("ballistic").values)
    with pytest.raises(lvsim.LvsimError):
        call.simulate()  # spent
    # a pending call blocks the run until simulated or closed
    call = run.prepare("approach")
    with pytest.raises(lvsim.LvsimError) as e:
        run.execute()
    assert "approach" in str(e.value)
    call.close()
    run.execute()
    # a parent not done: the library's message
    fresh = m.create_run()
    with pytest.raises(lvsim.LvsimError):
        fresh.prepare("ascent")
    for r in (ref, run, fresh):
        r.close()
    m.close()


# ---- threads and the GIL ------------------------------------------------------------------

def test_execute_releases_the_gil():
    """While one thread is inside lv_run_execute, the main thread keeps running Python: the
    largest pause between its samples is far below the call's duration. (With the GIL held
    for the call, the main thread would stop for all of it.)"""
    m = lvsim.Mission(DEMO)
    run = m.create_run()
    # a long call: ~500 000 rows (50 000 under the sanitizers), none kept
    kw = dict(output_interval=0.02 if SANITIZED else 0.002, keep_rows=False)
    t0 = time.perf_counter()
    run.execute(**kw)
    single = time.perf_counter() - t0
    run.set("us.propellant_mass", 54000)  # dirty again: the next execute simulates

    done = threading.Event()
    span = {}

    def worker():
        span["t0"] = time.perf_counter()
        run.execute(phases=None, **kw)
        span["t1"] = time.perf_counter()
        done.set()

    th = threading.Thread(target=worker)
    samples = []
    th.start()
    while not done.is_set():
        samples.append(time.perf_counter())
    th.join()
    inside = [t for t in samples if span["t0"] <= t <= span["t1"]]
    call = span["t1"] - span["t0"]
    gaps = np.diff(inside) if len(inside) > 1 else np.array([call])
    print(f"\nexecute alone {single * 1e3:.0f} ms; in a thread {call * 1e3:.0f} ms, the main "
          f"thread took {len(inside)} samples meanwhile, largest pause {gaps.max() * 1e3:.1f} ms")
    assert call > 0.1, "the call is too short to tell"
    assert len(inside) > 1000 and gaps.max() < 0.5 * call
    run.close(); m.close()


def test_two_threads_run_missions_concurrently():
    m = lvsim.Mission(DEMO)
    kw = dict(output_interval=0.1 if SANITIZED else 0.01, keep_rows=True)
    values = [53000.0, 54000.0]

    def one(v, out, i):
        r = m.run(params={"us.propellant_mass": v}, **kw)
        out[i] = r.result("us-ascent").values
        r.close()

    serial = [None, None]
    t0 = time.perf_counter()
    for i, v in enumerate(values):
        one(v, serial, i)
    t_serial = time.perf_counter() - t0
    conc = [None, None]
    ths = [threading.Thread(target=one, args=(v, conc, i)) for i, v in enumerate(values)]
    t0 = time.perf_counter()
    for t in ths:
        t.start()
    for t in ths:
        t.join()
    t_conc = time.perf_counter() - t0
    print(f"\ntwo runs: serial {t_serial * 1e3:.0f} ms, two threads {t_conc * 1e3:.0f} ms "
          f"(x{t_serial / t_conc:.2f}; {os.cpu_count()} cores, shared)")
    for i in range(2):  # the same bits whatever the thread
        assert bits(conc[i]) == bits(serial[i])
    assert bits(conc[0]) != bits(conc[1])
    m.close()


def test_one_run_from_two_threads_is_serialised():
    m = lvsim.Mission(PAPER)
    run = m.create_run()
    errors = []

    def worker(v):
        try:
            for _ in range(5):
                run.set("start_z", v)
                run.execute()
        except Exception as e:  # noqa: BLE001 - reported below
            errors.append(e)

    ths = [threading.Thread(target=worker, args=(v,)) for v in (0.0, 10.0)]
    for t in ths:
        t.start()
    for t in ths:
        t.join()
    assert not errors and run.ok
    run.close(); m.close()


# ---- targeting and Monte Carlo ------------------------------------------------------------

def test_targeting_meets_the_file_constraints():
    m = lvsim.Mission(LEO_TARGETED)
    t = m.target()
    assert t.variables and t.constraints
    its = []
    res = t.solve(on_iteration=lambda it: its.append(it["iteration"]))
    assert res.converged and all(res.met.values()), res.reason
    assert res.worst <= 1.0 and its and res.iterations >= 1
    # the target's run holds the point: its finals meet each constraint
    for c in t.constraints:
        name = c["name"].split(".", 1)[1]
        deg = name.endswith("_deg")
        v = t.run.final(c["phase"], name[:-4] if deg else name)
        v = math.degrees(v) if deg else v
        assert abs(v - c["value"]) <= c["tol"] * (1 + 1e-9) or c["kind"] != "equal", c
    # the same point set on a run of our own gives the same finals
    r = m.run(params=res.x, phases=[c["phase"] for c in t.constraints])
    for name, v in res.finals.items():
        ph, fin = name.split(".", 1)
        got = r.final(ph, fin[:-4]) if fin.endswith("_deg") else r.final(ph, fin)
        got = math.degrees(got) if fin.endswith("_deg") else got
        assert got == pytest.approx(v, rel=1e-12, abs=1e-9), name
    t.close(); r.close(); m.close()


def test_targeting_writes_the_converged_mission(tmp_path):
    # the converged file is written where the copy is, next to the tables it names
    for d in ("kourou-leo", "kourou-leo-targeted"):
        shutil.copytree(os.path.join(ROOT, "examples", d), tmp_path / d)
    src = tmp_path / "kourou-leo-targeted" / "mission.yaml"
    with lvsim.Mission(src) as m:
        t = m.target()
        res = t.solve()
        out = tmp_path / "kourou-leo-targeted" / "converged.yaml"
        worst = t.write(out)  # lv_target_write reloads and reruns it to check
        assert worst < 1e-3
        text = out.read_text()
        for name, v in res.x.items():
            assert repr(v)[:8] in text or f"{v:.10g}"[:8] in text, name
        with lvsim.Mission(out) as conv:
            r = conv.run(phases=[c["phase"] for c in t.constraints])
            for c in t.constraints:
                fin = c["name"].split(".", 1)[1]
                v = r.final(c["phase"], fin[:-4]) if fin.endswith("_deg") else r.final(c["phase"], fin)
                v = math.degrees(v) if fin.endswith("_deg") else v
                assert abs(v - c["value"]) <= c["tol"], c
            r.close()
        with pytest.raises(lvsim.LvsimError):
            t.write(tmp_path / "kourou-leo-targeted" / "x.yaml", x={"nope": 1.0})


def test_targeting_built_in_python():
    m = lvsim.Mission(DEMO)
    t = m.target(from_file=False)
    t.add_variable("us.propellant_mass", 40000, 60000)
    base = m.run().final("us-ascent", "m")
    t.add_constraint("us-ascent.m", "equal", base + 500.0, 1.0)
    res = t.solve()
    assert res.converged, res.reason
    # more propellant in the US: heavier at lift-off; the stage book burns to the same energy
    assert abs(res.finals["us-ascent.m"] - (base + 500.0)) <= 1.0
    with pytest.raises(lvsim.LvsimError):
        t.add_constraint("us-ascent.m", "around", 1, 1)
    with pytest.raises(lvsim.LvsimError):
        t.add_variable("nope", 0, 1)
    t.close(); m.close()
    with pytest.raises(lvsim.LvsimError):
        lvsim.Mission(PAPER).target()  # no targeting section


LT_OCP = """mission: {name: lt-ocp}
environment:
  world: planet
  planet: {name: flatland, radius: 1.0e10, gm: 9.80665e20, rotation_rate: 0}
  atmosphere: none
parameters: {start_h: 1000, start_vel: 100, start_fpa_deg: 80, start_chi_deg: 90}
stages: [{name: s, dry_mass: 1000, propellant_mass: 100,
          engines: [{thrust_vac: 21574.63, isp_vac: 1.0e9}]}]
phases:
  - {name: climb, model: dof3, stages: [s], stop_time: 60, inputs: {alpha_deg: 0}}
  - {name: coast, model: dof3, from: climb, stages: [s], stop_time: 70, throttle: off}
optimal_control:
  phases: [{name: climb, controls: [{name: alpha_deg, min: -60, max: 60}], nodes: 11}]
  constraints:
    - {final: climb.h, equal: 11000, tolerance: 0.01}
    - {final: climb.v_down, equal: 0, tolerance: 1.0e-4}
  cost: {maximize: coast.v_east}
"""


def test_optimize_same_as_the_cli(tmp_path):
    """lvsim.Optimization (lv_ocp.h) solves an optimal_control section (the linear tangent
    problem of tests/python/test_optimize_cli.py, 11 nodes, a coast flown whole after it) to
    the same point as `lvsim optimize` (the same C code; the Jacobian's groups go to distinct
    columns whatever the thread: bit for bit), writes the optimal mission, and reports the
    outcome and size (docs/optimal-control.md)."""
    path = str(tmp_path / "lt.yaml")
    (tmp_path / "lt.yaml").write_text(LT_OCP)
    with lvsim.Optimization(path) as opt:
        res = opt.solve(threads=2)
        assert res.optimal and res.outcome == "optimal", res
        assert res.violated == [] and res.max_violation < 1.0  # finals: in tolerances
        # 10 segments x 9 states + 11 nodes; 9 links + 9 x 9 defects + 2 finals (no propellant
        # row: neither the throttle nor the duration is free, the burn is the file's)
        assert res.n_vars == 101 and res.n_cons == 92 and res.n_groups > 0
        # the closed form's 985.330256 m/s, less the 11 nodes' discretisation (test_ocp.c)
        assert abs(res.cost - 985.330256) < 0.03, res.cost
        t0, t1 = opt.phase_times(0)
        assert t0 == 0.0 and t1 == 60.0
        out = tmp_path / "opt.yaml"
        opt.write(str(out))
        assert out.exists() and (tmp_path / "opt_climb_controls.csv").exists()
        with pytest.raises(lvsim.LvsimError):
            opt.phase_times(1)  # the coast is flown whole, not optimised
    p = subprocess.run([LVSIM, "optimize", path, "-q"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    cli = float(p.stdout.split("cost: ")[1].split()[0])
    assert cli == float("%.12g" % res.cost), (cli, res.cost)
    m = lvsim.Mission(str(out))  # the written mission loads and flies
    assert abs(m.run().final("coast", "v_east") - res.cost) < 1e-3
    with pytest.raises(lvsim.LvsimError):
        lvsim.Optimization(PAPER)  # no optimal_control section


HOP = """mission: {name: hop}
stages:
  - {name: s, dry_mass: 1000, propellant_mass: 2000,
     engines: [{name: e, thrust_vac: 100000, isp_vac: 300}]}
phases:
  - {name: burn, model: flat6, stages: [s], stop_time: 100,
     end: [{altitude: 2000, direction: rising}, burnout], integrator: {tolerance: 1.0e-10}}
targeting:
  variables: [{name: s.propellant_mass, min: 10, max: 3000, scale: 100}]
  constraints: [{final: burn.time, equal: 5, tolerance: 0.001%s}]
"""


def test_targeting_says_what_end_it_converged_to(tmp_path):
    # issue 27: a vertical hop over flat6's ground whose burn is meant to end at 2 km; a final
    # time of 5 s is met only by a burnout at 5 s, m_p = 5 F / (Isp g0) (the rocket equation
    # in closed form, tests/unit/test_target.c (i))
    mp = 5 * 100000 / (300 * 9.80665)
    src = tmp_path / "hop.yaml"
    src.write_text(HOP % "")
    with lvsim.Mission(src) as m:
        t = m.target()
        notes = []
        res = t.solve(on_iteration=lambda it: notes.append(it["note"] or ""))
        assert res.converged, res.reason
        assert abs(res.x["s.propellant_mass"] - mp) <= 0.001 * mp / 5
        assert len(res.end_mismatches) == 1
        e = res.end_mismatches[0]
        assert (e["phase"], e["expected"], e["actual"]) == ("burn", "altitude", "burnout")
        assert abs(e["t_end"] - 5.0) <= 0.001
        assert any("phase 'burn' ended by burnout" in n for n in notes)
        out = tmp_path / "conv.yaml"
        t.write(out)
        assert "# lvsim target: WARNING: phase 'burn' ended by burnout" in out.read_text()
        # named: nothing to report; an unknown end is refused with the phase's ends
        t.set_end("burn", "burnout")
        assert t.solve().end_mismatches == []
        with pytest.raises(lvsim.LvsimError, match="its ends: altitude, burnout, stop_time"):
            t.set_end("burn", "burnot")
        t.close()
    src.write_text(HOP % ", end: burnout")
    with lvsim.Mission(src) as m, m.target() as t:
        assert t.solve().end_mismatches == []
    with lvsim.Mission(LEO_TARGETED) as m, m.target() as t:
        res = t.solve()
        assert res.converged and res.end_mismatches == []
    with lvsim.Mission(src) as m, m.target(from_file=False) as t:
        t.add_variable("s.propellant_mass", 10, 3000, scale=100)
        t.add_constraint("burn.time", "equal", 5, 0.001, end="stop_time")
        res = t.solve()
        assert [e["expected"] for e in res.end_mismatches] == ["stop_time"]


def test_rtls_worked_example_figures():
    # docs/targeting.md, "A worked example: closing a booster's return (RTLS)": the claims of
    # its table, from examples/kourou-rtls-targeted/sensitivities.py at the converged point
    import importlib.util
    spec = importlib.util.spec_from_file_location(
        "rtls_sens", os.path.join(ROOT, "examples", "kourou-rtls-targeted", "sensitivities.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    res, base, rows = mod.sensitivities()
    assert res.converged and res.end_mismatches == [] and base["miss"] < 0.05
    row = {r["name"].split(".", 2)[2]: r for r in rows}
    os_, lat, lon, pitch = (row["target_overshoot"], row["target_lat_deg"],
                            row["target_lon_deg"], row["pitch_deg"])
    # the end fires when v_t t_fall - d = overshoot (docs/guidance.md): 100 m more is 100 m /
    # t_fall more speed toward the pad, t_fall the vacuum fall time from the burn's end
    # (h, v_up) in the local gravity GM / r^2 (an independent calculation)
    g = 3.986004418e14 / (6378137.0 + base["h"]) ** 2
    t_fall = (base["v_up"] + math.sqrt(base["v_up"] ** 2 + 2 * g * base["h"])) / g
    assert os_["v_east"] == pytest.approx(-100.0 / t_fall, rel=0.03)
    # the landing moves down-range by a little less than the 100 m (drag, the entry burn)
    assert 0.85 < -os_["east"] / 100.0 < 1.0
    # moving the aim east by d is lowering the overshoot by d: one variable, not two
    d_east = mod.radii(math.radians(5.236))[1] * math.cos(math.radians(5.236)) * math.radians(0.001)
    assert lon["east"] / d_east == pytest.approx(-os_["east"] / 100.0, rel=0.01)
    # the aim's latitude acts across, the overshoot along: off-diagonal below 1 %
    assert abs(os_["north"]) < 0.01 * abs(os_["east"]) and abs(lat["east"]) < 0.01 * abs(lat["north"])
    d_north = mod.radii(math.radians(5.236))[0] * math.radians(0.001)
    assert 3.0 < lat["north"] / d_north < 6.0 and lat["v_north"] > 0
    # pitch: the burn's velocity change (vE 1 475 m/s at separation to the end's) tilted by 1 deg
    dv_burn = 1474.9 - base["v_east"]
    assert pitch["v_up"] == pytest.approx(dv_burn * math.sin(math.radians(1.0)), rel=0.1)
    assert pitch["burn"] < 0 and pitch["mass"] < 0


def test_monte_carlo_campaign(tmp_path):
    m = lvsim.Mission(BRANCH)
    assert m.dispersions and m.seed == 20260301
    seen = []
    c = m.monte_carlo(12, tmp_path / "mc.db", threads=2, progress=lambda p: seen.append(p["done"]))
    assert c.total == 12 and c.done == 12 and seen
    runs = c.runs()
    assert list(runs["run"]) == list(range(12))
    # run i's drawn values are the package's draw(seed, i), and a run of our own with them
    # set reaches the campaign's final values
    for i in (0, 7):
        drawn = m.draw(m.seed, i)
        for name, v in drawn.items():
            assert runs[name][i] == v, (i, name)
    leaf = [p.name for p in m.phases if not any(q.parent == p.name for q in m.phases)][0]
    tab = c.phase(leaf)
    r = m.create_run()
    drawn = r.disperse(m.seed, 7)
    assert drawn == m.draw(m.seed, 7)
    r.execute(output_interval=None)
    row = tab[tab["run"] == 7].iloc[0]
    assert row["state"] == "done"
    assert row["time"] == pytest.approx(r.final(leaf, "time"), rel=1e-9)
    stats = c.stats(tmp_path / "stats")
    assert os.path.exists(tmp_path / "stats" / "stats.json") and stats
    with pytest.raises(lvsim.LvsimError):  # the database exists
        m.monte_carlo(12, tmp_path / "mc.db")
    with pytest.raises(lvsim.CancelledError):
        m.monte_carlo(100000, tmp_path / "stop.db", progress=lambda p: True)
    r.close(); m.close()


# ---- lifetime --------------------------------------------------------------------------

def test_close_and_context_managers():
    with lvsim.Mission(PAPER) as m:
        run = m.create_run()
        with m.create_run() as r2:
            r2.execute()
        with pytest.raises(lvsim.LvsimError):
            r2.execute()
    with pytest.raises(lvsim.LvsimError) as e:
        run.execute()  # closed with its mission
    assert "closed" in str(e.value)
    m.close()  # idempotent
    # garbage collection frees in any order: a run keeps its mission alive
    r = lvsim.Mission(PAPER).run()
    gc.collect()
    assert r.result(0).ok
    del r
    gc.collect()


@pytest.mark.skipif(SANITIZED, reason="ASan's quarantine keeps freed memory resident (up to "
                    "256 MB): RSS measures no leak there; LSan and valgrind check the C side")
def test_no_growth_over_many_runs():
    """Creating, running and dropping runs and missions frees their memory: the resident
    size after 150 more cycles is within a few MB of the size after the first 50."""
    def rss():
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")

    def cycle():
        m = lvsim.Mission(PAPER)
        r = m.run()
        r.result(0); r.body(0)
        call = m.create_run().prepare(0)
        call.close()

    warm, more = 50, 150
    for _ in range(warm):
        cycle()
    gc.collect()
    before = rss()
    for _ in range(more):
        cycle()
    gc.collect()
    grown = rss() - before
    print(f"\nRSS growth over {more} cycles: {grown / 1e6:.2f} MB")
    assert grown < 8e6


# ---- the breaker's findings (py-fixes): each test failed before its fix ---------------------

RLV_HEADING = "ascent.guidance.heading_deg"


def test_none_and_bad_names_are_type_errors_not_crashes(tmp_path):
    # None reached C as NULL and crashed the interpreter (SIGSEGV)
    m = lvsim.Mission(DEMO)
    r = m.run(until="ascent", keep_rows=False)
    calls = [lambda: m.phase_index(None), lambda: r.result(None), lambda: r.state(None),
             lambda: r.dataframe(None), lambda: r.final(None, "h"),
             lambda: r.final("ascent", None), lambda: r.execute(phases=[None]),
             lambda: r.prepare(None), lambda: lvsim.simulate(None), lambda: r.set(None, 1.0),
             lambda: r.get(None), lambda: m.parameter(None), lambda: lvsim.Mission(None),
             lambda: r.execute(phases=[True]), lambda: m.phase_index(1.0),
             lambda: r.set("us.propellant_mass", True),
             lambda: r.set("us.propellant_mass", "50000"), lambda: r.body(None),
             lambda: m.monte_carlo(2.7, tmp_path / "x.db"), lambda: r.execute(threads=1.5),
             lambda: r.execute(method=3)]
    for i, f in enumerate(calls):
        with pytest.raises(TypeError):
            f()
            pytest.fail(f"call {i} accepted")
    # an embedded NUL: C would read a shorter name
    for f in (lambda: r.set("us.propellant_mass\x00junk", 1.0),
              lambda: r.result("ascent\x00x"),
              lambda: lvsim.Mission(DEMO + "\x00.bak"),
              lambda: r.execute(outdir=str(tmp_path / "o\x00x")),
              lambda: r.final("ascent", "h\x00x"),
              lambda: m.draw(-1, 0), lambda: r.disperse(0, -1)):
        with pytest.raises(ValueError):
            f()
    assert not (tmp_path / "o").exists()
    # numpy scalars are numbers and indices still
    r.set("us.propellant_mass", np.float32(50000.0))
    assert r.get("us.propellant_mass") == 50000.0
    assert m.phase_index(np.int64(1)) == 1
    r.close(); m.close()


def test_deg_parameter_is_in_degrees_and_round_trips():
    m = lvsim.Mission(DEMO)
    p = m.parameter(RLV_HEADING)
    rad = m.parameter(RLV_HEADING[:-4])
    assert p.name == RLV_HEADING and p.unit == "deg"
    assert rad.name == RLV_HEADING[:-4] and rad.unit == "rad"
    assert p.value == pytest.approx(math.degrees(rad.value), rel=1e-15)
    r = m.run(keep_rows=False)
    assert r.get(RLV_HEADING) == p.value  # what get says, what parameter() says
    for name in (RLV_HEADING, RLV_HEADING[:-4]):
        r.set(name, m.parameter(name).value)  # the round trip changes nothing
        r.execute(keep_rows=False)
        assert r.simulated == 0, name
        assert r.get(RLV_HEADING[:-4]) == rad.value
    r.close(); m.close()


def test_reexecute_applies_new_options_and_reports_stale():
    m = lvsim.Mission(PAPER)
    n = len(m.phases)
    r = m.run(keep_rows=False)
    # body() without rows raises (it returned an empty trajectory)
    with pytest.raises(lvsim.LvsimError, match="keep_rows"):
        r.body(0)
    r.execute(keep_rows=True)  # simulated nothing before: 0 rows
    assert r.simulated == n and len(r.result(0)) > 0 and len(r.body(0)) > 0
    r.execute(tolerance=1e-7)
    assert r.simulated == n and all(r.result(k).tolerance == 1e-7 for k in range(n))
    r.execute(tolerance=1e-7)
    assert r.simulated == 0  # the same options: nothing to do
    r.execute(output_interval=5.0)
    t = r.result(0)["time"]
    assert r.simulated == n and np.all(np.diff(np.unique(t)) <= 5.0 + 1e-9)
    r.execute(method="rk4", output_interval=5.0)
    assert r.simulated == n and r.result(0).method == "rk4"
    r.execute()  # back to the phases' own: again
    assert r.simulated == n and r.result(0).method != "rk4"
    with pytest.raises(lvsim.InputError, match="no-such-method"):
        r.execute(method="no-such-method")
    # set() without execute(): the phases it reaches are stale, not done
    f0 = r.final("P3", "time")
    r.set("P2.stop_time", 281.0)
    assert r.state("P1") == "done" and r.state("P3") == "stale" and not r.ok
    res = r.result("P3")
    assert res.state == "stale" and res.stale and not res.ok and res.finals["time"] == f0
    with pytest.raises(lvsim.LvsimError, match="stale"):
        r.final("P3", "time")
    r.execute()
    assert r.ok and r.simulated == 3 and not r.result("P3").stale
    r.close(); m.close()


def test_disperse_and_execute_reproduce_a_campaign_run_bit_for_bit(tmp_path):
    m = lvsim.Mission(BRANCH)
    c = m.monte_carlo(3, tmp_path / "mc.db", threads=2)
    tabs = {p.name: c.phase(p.name) for p in m.phases}
    r = m.create_run()
    compared = 0
    for i in range(3):
        r.disperse(m.seed, i)
        r.execute(output_interval="ends", keep_rows=False)
        for p in m.phases:
            row = tabs[p.name][tabs[p.name]["run"] == i].iloc[0]
            assert row["state"] == r.state(p.name)
            for name, v in r.finals(p.name).items():
                if name in row.index:  # bit for bit (SQLite keeps no sign of a zero)
                    w = row[name]
                    w = math.nan if w is None else w  # SQLite keeps a NaN as NULL
                    assert (w == v and (w != 0 or v == 0)) or (math.isnan(w) and math.isnan(v)) \
                        or bits(np.array([w])) == bits(np.array([v])), (i, p.name, name, w, v)
                    compared += 1
    assert compared > 20
    # 0 has no second meaning any more: it is refused by both
    with pytest.raises(lvsim.InputError, match="output_interval"):
        r.execute(output_interval=0)
    with pytest.raises(lvsim.InputError, match="output_interval"):
        m.monte_carlo(2, tmp_path / "z.db", output_interval=0)
    r.close(); m.close()


@pytest.mark.parametrize("kw,word", [
    (dict(tolerance=-1), "tolerance"), (dict(tolerance=0), "tolerance"),
    (dict(tolerance=float("nan")), "tolerance"), (dict(tolerance=float("inf")), "tolerance"),
    (dict(tolerance=10), "tolerance"), (dict(tolerance=1e-15), "tolerance"),
    (dict(output_interval=-1), "output_interval"),
    (dict(output_interval=float("nan")), "output_interval"),
    (dict(output_interval="x"), "output_interval"), (dict(threads=-1), "threads"),
    (dict(method=""), "method"), (dict(max_rows=0), "max_rows")])
def test_bad_execute_options_are_refused_up_front(kw, word):
    m = lvsim.Mission(PAPER)
    r = m.create_run()
    with pytest.raises(ValueError, match=word) as e:
        r.execute(**kw)
    assert "liftoff" not in str(e.value) and "phase '" not in str(e.value)
    assert set(r.states.values()) == {"pending"}  # nothing ran
    r.close(); m.close()


def test_simulate_holds_the_library_ranges():
    # issue 22: a tolerance of 10 ran (87 % off), free fall from under the ground missed its
    # impact; both are refused by lv_simulate itself, so Python callers get the same rule
    with pytest.raises(lvsim.LvsimError, match=r"tolerance must be >= 1e-14 and <= 0\.1"):
        lvsim.simulate("free_fall", tolerance=10)
    with pytest.raises(lvsim.LvsimError, match="h = -1 m is below its lower bound 0 m"):
        lvsim.simulate("free_fall", initial={"h": -1.0})


def test_max_rows_refuses_a_huge_output_before_running():
    m = lvsim.Mission(DEMO)
    r = m.create_run()
    t0 = time.monotonic()
    with pytest.raises(lvsim.OutputLimitError, match="max_rows") as e:
        r.execute(output_interval=1e-6)
    assert time.monotonic() - t0 < 5.0 and "phase 1 'liftoff'" in str(e.value)
    assert set(r.states.values()) == {"pending"}
    with pytest.raises(lvsim.OutputLimitError):
        r.execute(max_rows=10)  # the phases' own grids: more than 10 rows
    r.execute(phases="liftoff", max_rows=None, keep_rows=False)
    assert r.state("liftoff") == "done"
    r.close(); m.close()


NEVER = """\
mission: {name: never}
environment: {world: flat, g: 1.0e-9}
stages:
  - {name: s, dry_mass: 100, propellant_mass: 0}
phases:
  - {name: coast, model: flat6, stages: [s], stop_time: 1.0e30, end: [{altitude: 1.0e9}],
     integrator: {output_interval: 1.0}}
"""


def test_max_rows_holds_as_a_phase_with_an_end_runs(tmp_path):
    # the library's one check (lv_run_check_output): a phase with end events is not refused
    # for a generous stop time; one whose end never fires stops at max_rows as it runs: at
    # t = 50 s with a row every second, kept as failed
    p = tmp_path / "never.yaml"
    p.write_text(NEVER)
    m = lvsim.Mission(str(p))
    r = m.create_run()
    with pytest.raises(lvsim.SimulationError, match=r"stopped at t = 50 s by the row limit: "
                                                   r"50 output rows") as e:
        r.execute(max_rows=50)
    assert r.state("coast") == "failed" and "max_rows" in str(e.value)
    r.close(); m.close()
    # dof3-branch with stop times of 1e30 s: the ends (burnout, impact) come first
    text = open(BRANCH).read()
    for a, b in (("stop_time: 400", "stop_time: 1.0e30"), ("stop_time: 2000", "stop_time: 2.0e30"),
                 ("stop_time: 3000", "stop_time: 3.0e30")):
        text = text.replace(a, b)
    for f in ("wind.csv", "aero_ascent.csv", "aero_descent.csv"):
        shutil.copy(os.path.join(os.path.dirname(BRANCH), f), tmp_path / f)
    (tmp_path / "generous.yaml").write_text(text)
    m = lvsim.Mission(str(tmp_path / "generous.yaml"))
    r = m.create_run()
    r.execute()
    assert r.ok and abs(r.result("ascent").t_end - 137.906) < 1e-3
    r.close(); m.close()


def test_campaign_bounds_before_it_runs(tmp_path):
    m = lvsim.Mission(BRANCH)
    with pytest.raises(lvsim.InputError, match=r"a campaign of 1e\+11 runs is too large; its "
                                              r"database would need about .* TB") as e:
        m.monte_carlo(10**11, tmp_path / "huge.db")
    assert "(n_runs)" in str(e.value)
    assert not (tmp_path / "huge.db").exists()
    m.close()


CTRL_C = r"""
import json, os, signal, sys, threading, time
import lvsim
m = lvsim.Mission(sys.argv[1])
r = m.create_run()
mode = sys.argv[2]
threading.Timer(float(sys.argv[3]), lambda: os.kill(os.getpid(), signal.SIGINT)).start()
t0 = time.monotonic()
kw = dict(output_interval=1e-4, max_rows=None, keep_rows=False)  # a run of many seconds
if mode == "progress":
    kw["progress"] = lambda k, t: False
out = {}
try:
    r.execute(**kw)
    out["raised"] = None
except KeyboardInterrupt:
    out["raised"] = "KeyboardInterrupt"
except BaseException as e:
    out["raised"] = type(e).__name__ + ": " + str(e)
out["after"] = time.monotonic() - t0
out["states"] = r.states
r.execute(keep_rows=False, check=False)
out["failed_after"] = r.failed  # the run is consistent: it completes
out["ok_after"] = r.ok
print(json.dumps(out))
"""


@pytest.mark.parametrize("mode", ["plain", "progress"])
def test_ctrl_c_stops_every_branch_and_raises_keyboard_interrupt(tmp_path, mode):
    script = tmp_path / "ctrl_c.py"
    script.write_text(CTRL_C)
    env = dict(os.environ)
    delay = 3.0 if SANITIZED else 0.5
    p = subprocess.run([sys.executable, str(script), DEMO, mode, str(delay)], env=env,
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    assert "Exception ignored" not in p.stderr
    out = json.loads(p.stdout.strip().splitlines()[-1])
    assert out["raised"] == "KeyboardInterrupt", out
    # stopped soon, not when the whole run (tens of seconds at this grid) was over
    assert out["after"] < delay + (20.0 if SANITIZED else 2.0), out
    states = out["states"]
    assert "running" not in states.values() and "pending" in states.values() or \
        "failed" in states.values()
    assert set(states.values()) <= {"done", "failed", "skipped", "pending"}
    assert out["ok_after"] is True, out


def _files(d):
    return sorted(os.listdir(d))


def test_outdir_never_mixes_two_runs(tmp_path):
    (tmp_path / "short.csv").write_text("t [s], thrust [N], mdot [kg/s]\n0, 30000, 10\n50, 30000, 10\n")
    (tmp_path / "fail.yaml").write_text(FAILING)
    m = lvsim.Mission(tmp_path / "fail.yaml")
    out = tmp_path / "out"
    r = m.run(outdir=out, formats=("csv",), check=False)
    assert "phase_2_p2.failed.csv" in _files(out) and "manifest.json" in _files(out)
    assert json.load(open(out / "manifest.json"))["status"] == "failed"
    # a good run into the same folder: the failed run's files are gone
    r.set("p2.stop_time", 25.0)
    r.set("p3.stop_time", 30.0)
    r.execute(outdir=out, formats=("csv",))
    assert r.ok
    names = _files(out)
    assert not [f for f in names if ".failed." in f], names
    assert {"phase_1_p1.csv", "phase_2_p2.csv", "phase_3_p3.csv"} <= set(names)
    # result_files name the results folder, not the staging folder
    assert all(os.path.dirname(f) == str(out) and os.path.exists(f)
               for k in range(3) for f in r.result(k).result_files)
    # re-executing into a new folder writes every phase, not only the re-simulated ones
    r.set("p3.stop_time", 31.0)
    r.execute(outdir=tmp_path / "b", formats=("csv",))
    assert {"phase_1_p1.csv", "phase_2_p2.csv", "phase_3_p3.csv"} <= set(_files(tmp_path / "b"))
    # a folder lvsim did not write is refused, untouched
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "thesis.tex").write_text("keep me")
    with pytest.raises(lvsim.LvsimError, match="mine") as refused:
        r.execute(outdir=foreign)
    assert "--force" not in str(refused.value)  # the CLI's option, none here
    assert _files(foreign) == ["thesis.tex"]
    # an exception in progress: the folder is left as it was
    before = (out / "phase_3_p3.csv").read_bytes()
    r.set("p3.stop_time", 32.0)

    def boom(k, t):
        raise RuntimeError("stop")
    with pytest.raises(RuntimeError):
        r.execute(outdir=out, formats=("csv",), progress=boom)
    assert (out / "phase_3_p3.csv").read_bytes() == before
    assert not [f for f in os.listdir(tmp_path) if "staging" in f]
    r.close(); m.close()


def test_library_dir_that_does_not_hold_the_library_is_an_error():
    env = dict(os.environ, LVSIM_LIBRARY_DIR="/nonexistent")
    p = subprocess.run([sys.executable, "-c", "import lvsim"], env=env, capture_output=True,
                       text=True)
    assert p.returncode != 0 and "ImportError" in p.stderr and "/nonexistent" in p.stderr


def test_library_version_and_structure_sizes_are_checked_at_load():
    lib = _lib.lib
    assert lib.lv_version().decode() == lvsim.__version__
    for st in _lib.MIRRORED:
        assert lib.lv_abi_sizeof(st.__name__.encode()) == ctypes.sizeof(st), st.__name__
    assert lib.lv_abi_sizeof(b"no_such_struct") == 0
    # a mismatch is an ImportError naming the structure (a library whose every struct is
    # 8 bytes), and so is a library without the functions (too old)
    bad = type("BadDLL", (), {})()
    bad._name = "libfake.so"
    bad.lv_version = lib.lv_version
    size = ctypes.CFUNCTYPE(ctypes.c_size_t, ctypes.c_char_p)(lambda name: 8)
    bad.lv_abi_sizeof = size
    with pytest.raises(ImportError, match="struct lv_err is 8 bytes"):
        _lib._check_abi(bad)
    old = type("OldDLL", (), {"_name": "libold.so"})()
    with pytest.raises(ImportError, match="too old"):
        _lib._check_abi(old)


def test_installed_paths_name_the_install_prefix(tmp_path):
    build = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(lvsim.__file__))))
    if not os.path.exists(os.path.join(build, "cmake_install.cmake")):
        pytest.skip("not the build tree's package")
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", build, "--prefix", str(prefix)], check=True,
                   capture_output=True)
    found = [os.path.join(d, f) for d, _, fs in os.walk(prefix) for f in fs if f == "_paths.py"]
    assert len(found) == 1, found
    ns = {}
    exec(open(found[0]).read(), ns)
    assert ns["LIBDIR_ABS"].startswith(str(prefix) + "/"), ns["LIBDIR_ABS"]
    assert os.path.exists(os.path.join(ns["LIBDIR_ABS"], ns["SONAME"]))
    rel = os.path.normpath(os.path.join(os.path.dirname(found[0]), ns["LIBDIR_REL"]))
    assert rel == ns["LIBDIR_ABS"]


def test_clearer_errors(tmp_path):
    m = lvsim.Mission(DEMO)
    r = m.run(until="ballistic", keep_rows=False)
    # a str of finals is one name, not its letters; an unknown one is named, not indexed
    o = r.prepare("us-ascent").simulate(finals="sma", record=False)
    assert list(o.finals) == ["sma"]
    with pytest.raises(lvsim.LvsimError) as e:
        r.prepare("us-ascent").simulate(finals=["time", "nope"], record=False)
    assert "finals[1] 'nope'" in str(e.value) and "finalNames" not in str(e.value)
    # `in` asks for a parameter; a Run is not iterable
    assert "us.dry_mass" in r and "nope" not in r and RLV_HEADING in r
    with pytest.raises(TypeError):
        iter(r)
    # Python argument names in the campaign's message, not the CLI's flags
    b = lvsim.Mission(BRANCH)
    b.monte_carlo(1, tmp_path / "c.db")
    with pytest.raises(lvsim.LvsimError) as e:
        b.monte_carlo(1, tmp_path / "c.db")
    assert "resume=True" in str(e.value) and "overwrite=True" in str(e.value)
    assert "--" not in str(e.value)
    c = lvsim.Campaign(tmp_path / "c.db")  # opened directly: its counts
    assert c.done == 1 and c.total == 1 and c.failed == 0
    # a typed error naming the argument, not ctypes' ArgumentError
    t = lvsim.Mission(LEO_TARGETED).target(from_file=False)
    with pytest.raises(TypeError, match="lo"):
        t.add_variable("upper.dry_mass", "1", 2)
    with pytest.raises(lvsim.LvsimError, match="solve"):
        lvsim.Mission(LEO_TARGETED).target().run  # before solve(), as documented
    # a mission in a folder with ':' in its name: the position is still parsed
    d = tmp_path / "dir:colon"
    d.mkdir()
    (d / "typo.yaml").write_text("mission: {name: typo}\nstages: [{name: s, dry_mass: 100, "
                                 "propellant_mass: 0}]\nphases: [{name: coast, model: flat6, "
                                 "stages: [s], stop_tme: 10}]\n")
    with pytest.raises(lvsim.MissionError) as e:
        lvsim.Mission(d / "typo.yaml")
    assert e.value.file == str(d / "typo.yaml") and e.value.line == 3 and e.value.column
    r.close(); m.close(); b.close()


def test_notebook_copy_finds_the_repository(tmp_path):
    # the notebook's first cells, run from a copy's folder inside the repository (no
    # LV_SOURCE_DIR), then from outside it with LV_SOURCE_DIR: both find the example mission
    nb = json.load(open(os.path.join(ROOT, "examples", "notebook.ipynb")))
    code = "\n".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code")
    code = "\n".join(l for l in code.split("\n") if not l.startswith("%"))
    first = code.split("bodies = run.bodies()")[0] + "\nprint('mission', mission.name)\n"
    script = tmp_path / "nb.py"
    script.write_text(first)
    inside = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(lvsim.__file__)))), "nbcopy-test")
    if not os.path.abspath(inside).startswith(os.path.abspath(ROOT) + os.sep):
        inside = None  # the build tree is outside the sources: only the LV_SOURCE_DIR case
    env = {k: v for k, v in os.environ.items() if k != "LV_SOURCE_DIR"}
    env["MPLBACKEND"] = "Agg"
    cases = [(str(tmp_path), dict(env, LV_SOURCE_DIR=ROOT))]
    if inside:
        os.makedirs(inside, exist_ok=True)
        cases.append((inside, env))
    try:
        for cwd, e in cases:
            p = subprocess.run([sys.executable, str(script)], cwd=cwd, env=e,
                               capture_output=True, text=True, timeout=300)
            assert p.returncode == 0 and "mission rlv-hthl" in p.stdout, (cwd, p.stderr[-1500:])
        # from outside the repository without LV_SOURCE_DIR: a clear error
        p = subprocess.run([sys.executable, str(script)], cwd=str(tmp_path), env=env,
                           capture_output=True, text=True, timeout=300)
        assert p.returncode != 0 and "LV_SOURCE_DIR" in p.stderr
    finally:
        if inside:
            shutil.rmtree(inside, ignore_errors=True)


def test_second_breaker_arguments():
    # a second breaker's pass: seeds beyond uint64 wrapped to another run's draw; bools passed
    # as numbers to simulate(); flags took any value; max_rows was rounded; finals() and
    # dataframe() of a stale phase gave the old values while final() refused
    m = lvsim.Mission(BRANCH)
    with pytest.raises(ValueError, match="seed must be <="):
        m.draw(2**64 + 5, 0)
    run = m.create_run()
    with pytest.raises(ValueError, match="index must be <="):
        run.disperse(1, 2**64)
    for kw in (dict(stop_time=True), dict(tolerance=True), dict(output_interval=False),
               dict(start_time=None), dict(stop_time="10")):
        with pytest.raises(TypeError):
            lvsim.simulate("vertical_ascent", **kw)
    for kw in (dict(check="a"), dict(check=[1]), dict(check=float("nan")), dict(check=None),
               dict(max_rows=1.5), dict(threads=10**30)):
        with pytest.raises((TypeError, ValueError)):
            run.execute(**kw)
    d = lvsim.Mission(DEMO)
    r = d.run(keep_rows=True)
    r.set("us.propellant_mass", 54000.0)
    for f in (lambda: r.final("us-ascent", "m"), lambda: r.finals("us-ascent"),
              lambda: r.dataframe("us-ascent")):
        with pytest.raises(lvsim.LvsimError, match="stale"):
            f()
    assert r.result("us-ascent").stale  # the old rows stay readable, marked


# ---- the result formats and exports, as the libraries register them --------------------------

def test_formats_come_from_the_library(tmp_path):
    fm = lvsim.formats()
    # `lvsim formats` and the package list the same formats, in the same order (both ask
    # lv_result_format_info and lv_export_format_info)
    out = subprocess.run([LVSIM, "formats"], check=True, capture_output=True, text=True).stdout
    listed = [line.split()[0] for line in out.splitlines() if line.startswith("  ")]
    assert listed == list(fm)
    # the order of LV_RESULT_MAT, _CSV and LV_EXPORT_CZML, _KML, _OEM (later ones may follow)
    assert list(lvsim.formats("results"))[:2] == ["mat", "csv"]
    assert list(lvsim.formats("exports"))[:3] == ["czml", "kml", "oem"]
    assert fm["mat"].file == ".mat" and fm["oem"].file == "<stage>.oem" and fm["kml"].description
    with pytest.raises(ValueError):
        lvsim.formats("figures")
    # a run's files: one per registered result format by default, named by its extension
    m = lvsim.Mission(PAPER)
    r = m.run(outdir=tmp_path / "o", keep_rows=False)
    res = r.result(0)
    exts = [f.file for f in lvsim.formats("results").values()]
    assert [os.path.splitext(f)[1] for f in res.result_files] == exts
    assert all(os.path.exists(f) for f in res.result_files)
    with pytest.raises(lvsim.LvsimError, match=r"unknown result format 'xmatx' \(mat, csv"):
        r.execute(outdir=tmp_path / "x", formats=["xmatx"])
    r.close(); m.close()


# ---- the steering and throttle laws, as the library registers them ---------------------------

def test_laws_come_from_the_library():
    laws = lvsim.laws()
    # `lvsim laws` and the package list the same laws, in the same order (both ask lv_laws_get)
    out = subprocess.run([LVSIM, "laws"], check=True, capture_output=True, text=True).stdout
    listed = [line.split(":")[0] for line in out.splitlines()
              if line[:1].isalpha() and ": " in line and not line.startswith("every")]
    assert listed == list(laws)
    assert list(lvsim.laws("throttle")) == ["nominal", "landing", "off"]
    # the gravity turn of docs/guidance.md: rise_time (0 s), kick_deg, kick_time (s), heading_deg
    gt = laws["gravity_turn"]
    assert gt.kind == "steering" and gt.form == "named"
    assert [k.name for k in gt.keys] == ["rise_time", "kick", "kick_time", "heading"]
    kick = gt.key("kick_deg")
    assert kick is gt.key("kick") and kick.angle and kick.unit == "rad" and kick.required
    assert kick.holds(math.pi / 2) and not kick.holds(math.pi / 2 + 1e-12) and not kick.holds(-0.1)
    assert gt.key("rise_time").default == 0.0 and not gt.key("rise_time").required
    with pytest.raises(KeyError, match="no key 'pitch'"):
        gt.key("pitch")
    att = laws["attitude"]
    assert att.key("frame").choices == ["aero", "local", "inertial"]
    assert att.key("frame").default == "local" and att.key("alpha").frames == ["aero"]
    assert laws["heading"].needs_aero and laws["heading"].key("alpha").instead_of == "alpha_table"
    assert laws["nominal"].key("q_gain").needs == "q_max"
    assert laws["off"].form == "word" and laws["off"].keys == []
    with pytest.raises(ValueError):
        lvsim.laws("engine")
    # every guidance and throttle run parameter of the examples is a key of a law, in its unit
    # and within its range (the parser made the slots from the same tables)
    common = {k.name: k for k in lvsim.common_keys("steering")}
    seen = 0
    for mission in (DEMO, LEO_TARGETED, os.path.join(ROOT, "examples", "kourou-rtls",
                                                     "mission.yaml")):
        m = lvsim.Mission(mission)
        for p in m.parameters:
            for section, kind in ((".guidance.", "steering"), (".throttle.", "throttle")):
                if section not in p.name:
                    continue
                rest = p.name.split(section, 1)[1].split(".")
                if len(rest) == 2:  # throttle.landing.altitude: a nested law's key
                    keys = [laws[rest[0]].key(rest[1])]
                else:
                    keys = [k for law in lvsim.laws(kind).values() for k in law.keys
                            if k.name == rest[0]] + ([common[rest[0]]] if rest[0] in common else [])
                assert keys, p.name
                assert any(k.unit == p.unit and k.holds(p.value) for k in keys), p.name
                seen += 1
        m.close()
    assert seen >= 20
