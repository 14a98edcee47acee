"""_mission.py - missions, runs, phase results, bodies' trajectories and the one-phase call
(lv_mission.h) for Python.

Units are the library's: SI throughout (m, s, kg, N, Pa, rad), each column's unit given with
it; "NAME_deg" parameters take degrees. Frames: docs/frames.md (ECI, ECEF, geodetic, NED).
Every array returned is a copy owned by NumPy: it stays valid whatever the run does next.
"""
import ctypes
import math
import re
import os
import signal
import threading
import weakref
from ctypes import POINTER, byref, c_char_p, c_double, c_int, c_size_t, c_ubyte, c_uint64, c_void_p

import numpy as np

from . import _lib
from ._lib import lib, enc, text, name_arg, path_arg, real_arg, int_arg, bool_arg, U64_MAX
from .errors import (InputError, LvsimError, MissionError, OutputLimitError, ParameterError,
                     SimulationError, check)

_check = check


_DEG = math.pi / 180.0  # rad per degree (LV_DEG)
DEFAULT_MAX_ROWS = 1e6  # output rows one phase may write (the CLI's --max-rows default)

def _methods():
    arr = lib.lv_sim_methods()
    out, i = [], 0
    while arr[i]:
        out.append(text(arr[i]))
        i += 1
    return tuple(out)


METHODS = _methods()  # the integration methods (lv_sim_methods): "dassl", "rk4", ...

PHASE_STATES = {0: "pending", 1: "done", 2: "failed", 3: "skipped"}
STOP_REASONS = {0: "stop_time", 1: "event", 2: "failed"}


def _err():
    return _lib.lv_err()


def _pandas():
    """pandas, imported on first use (it is optional, and its import costs ~0.3 s)."""
    try:
        import pandas
    except ImportError:
        raise LvsimError("pandas is not installed (Debian: python3-pandas); use .values",
                         -2) from None
    return pandas


def _dataframe(names, units, values, extra=None):
    df = _pandas().DataFrame(values, columns=list(names))
    if extra:
        for k, v in extra.items():
            df[k] = v
    df.attrs["units"] = dict(zip(names, units))
    return df


def _copy_result(res):
    """An lv_result (memory sink) -> (names, units, values[rows, cols]) copied."""
    n = lib.lv_result_rows(res)
    c = lib.lv_result_signals(res)
    names = [text(lib.lv_result_name(res, i)) for i in range(c)]
    units = [text(lib.lv_result_unit(res, i)) for i in range(c)]
    data = lib.lv_result_data(res)
    if n == 0 or not data:
        values = np.empty((0, c))
    else:
        values = np.ctypeslib.as_array(data, shape=(n * c,)).copy().reshape(n, c)
    return names, units, values


class Table:
    """Rows of named columns with units: `names` (list of str), `units` (list of str, SI,
    "" dimensionless), `values` (float64 ndarray of shape (rows, len(names)), row-major, a
    copy). t["h"] is a column; len(t) the row count. Event instants appear twice (the row
    before and the row after the event, same time), as in the result files."""

    def __init__(self, names, units, values):
        self.names = list(names)
        self.units = list(units)
        self.values = values
        self._col = {n: i for i, n in enumerate(self.names)}

    def __len__(self):
        return self.values.shape[0]

    def __contains__(self, name):
        return name in self._col

    def __getitem__(self, name):
        """The column `name` (a 1-D ndarray view of `values`); KeyError lists the names."""
        try:
            return self.values[:, self._col[name]]
        except KeyError:
            raise KeyError(f"no column '{name}'; columns: {', '.join(self.names)}") from None

    def unit(self, name):
        """The unit of column `name` (SI; "" dimensionless)."""
        self[name]
        return self.units[self._col[name]]

    def to_dataframe(self):
        """A pandas DataFrame of the rows, units in df.attrs["units"] (column -> unit)."""
        return _dataframe(self.names, self.units, self.values)


class Event:
    """One event a phase handled: `t` (s), `name` ("burnout", a table breakpoint...), `kind`
    ("state" or "time"), `direction` (+1 rising, -1 falling, 0 time event), `index` (state
    event function index, -1 for time events)."""

    __slots__ = ("t", "name", "kind", "direction", "index")

    def __init__(self, rec):
        self.t = rec.t
        self.name = rec.name.decode("utf-8", "replace")
        self.kind = "state" if rec.is_state else "time"
        self.direction = rec.direction
        self.index = rec.index

    def __repr__(self):
        return f"Event(t={self.t!r}, name={self.name!r}, kind={self.kind!r})"


class PhaseResult(Table):
    """What one phase did in a run, copied out of the run (lv_phase_result).

    Attributes: `index` (run order, from 0; its result files are named phase_<index+1>_...),
    `name`, `state` ("pending", "done", "failed", "skipped", or "stale": done, but an input
    changed since - Run.set() without execute() - so the values are those of the earlier
    inputs; `stale` True then), `error` (phase, time and reason when failed or skipped, else None),
    `t_start`, `t_end`, `t_stop` (s), `method`, `tolerance`, `stop_reason` ("stop_time",
    "event", "failed"), `stop_name` (the event that ended it), `end_index` (the `end:`
    condition that fired, 0-based in file order, or -1), `end_value`, `stats` (dict of the
    integrator's counters: steps, rhs_evals, state_events, ..., cpu_time in s), `events`
    (list of Event), `finals` (dict name -> value: time, every state and output; SI),
    `final_units` (name -> unit where the rows name it), the hand-off (`n_copied`,
    `mass_from_stages`, `mass_start` in kg, `set` the overrides, `absorbed`: dict name ->
    (value, unit) of what the hand-off could not carry over, e.g. a touchdown's "sink_rate"
    in m/s on a runway roll-out), the stage book
    (`propellant_start`, `propellant_end`, `dry_mass`: dict stage -> kg; `payload` kg),
    `result_files` (the files written, or []).
    As a Table: the phase's rows (time, states, der(states), outputs) when the run kept
    them (Run.execute(keep_rows=True), the default); else no rows and no columns."""

    def __init__(self, run, k):
        r = lib.lv_run_result(run._h, k).contents
        rows = lib.lv_run_rows(run._h, k)
        if rows:
            names, units, values = _copy_result(rows)
        else:
            names, units, values = [], [], np.empty((0, 0))
        super().__init__(names, units, values)
        m = run.mission
        self.index = k
        self.name = text(r.name)
        self.state = PHASE_STATES.get(r.state, str(r.state))
        # a done phase whose inputs changed since it ran (Run.set without execute, or options
        # that change results): its values are those of the earlier inputs
        self.stale = bool(r.state == 1 and lib.lv_run_stale(run._h, k))
        if self.stale:
            self.state = "stale"
        self.error = r.error.decode("utf-8", "replace") or None
        self.t_start, self.t_end, self.t_stop = r.t_start, r.t_end, r.t_stop
        self.method = text(r.method)
        self.tolerance = r.tolerance
        rep = r.report
        self.stop_reason = STOP_REASONS.get(rep.reason, str(rep.reason))
        self.stop_name = rep.stop_name.decode("utf-8", "replace")
        self.stats = {f: getattr(rep.stats, f) for f, _ in _lib.lv_sim_stats._fields_}
        self.events = [Event(rep.event_log[i]) for i in range(rep.n_event_log)]
        self.end_index = r.end_index
        self.end_value = r.end_value
        self.finals = {text(r.final_names[i]): r.final_values[i] for i in range(r.n_final)}
        self.final_units = {n: u for n, u in zip(self.names, self.units) if n in self.finals}
        self.n_copied = r.n_copied
        self.mass_from_stages = r.mass_from_stages
        self.mass_start = r.mass_start
        self.set = {text(r.set_names[i]): r.set_values[i] for i in range(r.n_set)}
        self.absorbed = {text(r.absorbed_names[i]): (r.absorbed_values[i], text(r.absorbed_units[i]))
                         for i in range(r.n_absorbed)}
        stages = m.stages
        book = r.state != 0 and bool(r.dry_mass)
        self.propellant_start = {s: r.propellant_start[i] for i, s in enumerate(stages)} if book else {}
        self.propellant_end = {s: r.propellant_end[i] for i, s in enumerate(stages)} if book else {}
        self.dry_mass = {s: r.dry_mass[i] for i, s in enumerate(stages)} if book else {}
        self.payload = r.payload
        stem = text(r.result_stem)
        if stem and run._stage_map and stem.startswith(run._stage_map[0] + "/"):
            stem = run._stage_map[1] + stem[len(run._stage_map[0]):]  # staged, then committed
        self.result_files = []
        if stem:
            failed = self.state == "failed"
            for bit, ext in ((_lib.LV_RESULT_MAT, "mat"), (_lib.LV_RESULT_CSV, "csv")):
                if r.result_formats & bit:
                    self.result_files.append(f"{stem}.failed.{ext}" if failed else f"{stem}.{ext}")

    @property
    def ok(self):
        """True when the phase is done and up to date."""
        return self.state == "done"

    def __repr__(self):
        return (f"PhaseResult({self.name!r}, state={self.state!r}, t={self.t_start:g}..{self.t_end:g} s, "
                f"rows={len(self)})")


class Trajectory(Table):
    """One stage's trajectory merged across the phases it flies in (lv_run_body_trajectory):
    every row of every done phase of the stage, in time order, with the stage's own mass
    (`stage_mass`, kg). `stage` the stage's name; `phase` (ndarray of int, per row) the
    phase index each row comes from and `phase_names` the matching names."""

    def __init__(self, stage, names, units, values, phase, phase_names):
        super().__init__(names, units, values)
        self.stage = stage
        self.phase = phase
        self.phase_names = phase_names

    def to_dataframe(self):
        """DataFrame of the rows plus a "phase" column (the phase's name); units in
        df.attrs["units"]."""
        df = _dataframe(self.names, self.units, self.values,
                        {"phase": [self.phase_names[int(k)] for k in self.phase]})
        return df


class Variable:
    """A model variable: `name`, `unit` (SI), `description`, `start` (default start value or
    parameter value), `nominal` (states: the magnitude scaling the absolute tolerance), `kind`
    ("state", "parameter", "output")."""

    __slots__ = ("name", "unit", "description", "start", "nominal", "kind")

    def __init__(self, v, kind):
        self.name = text(v.name)
        self.unit = text(v.unit) or ""
        self.description = text(v.description) or ""
        self.start = v.start
        self.nominal = v.nominal
        self.kind = kind

    def __repr__(self):
        return f"Variable({self.name!r}, {self.unit!r}, {self.kind})"


class Model:
    """A simulation model's interface (lv_model.h): `name`, `description`, `states`,
    `parameters`, `outputs` (lists of Variable), `events` (state-event names)."""

    def __init__(self, ptr):
        d = ptr.contents
        self._ptr = ptr
        self.name = text(d.name)
        self.description = text(d.description) or ""
        self.states = [Variable(d.states[i], "state") for i in range(d.n_states)]
        self.parameters = [Variable(d.params[i], "parameter") for i in range(d.n_params)]
        self.outputs = [Variable(d.outputs[i], "output") for i in range(d.n_outputs)]
        self.events = [text(d.events[i].name) for i in range(d.n_events)]

    def __repr__(self):
        return (f"Model({self.name!r}: {len(self.states)} states, {len(self.parameters)} "
                f"parameters, {len(self.outputs)} outputs)")


class Outcome:
    """What one lv_simulate returned (simulateExtendedModel's result): `ok` (bool), `error`
    (the library's message: model, time, reason; None when ok), `status`, `finals` (dict
    name -> value of the final names asked for, SI), `end_time` (s), `stop_reason`
    ("stop_time", "event", "failed"), `stop_name`, `stats` (integrator counters), `events`
    (list of Event), `rows` (a Table of every output row and event instant)."""

    def __repr__(self):
        return f"Outcome(ok={self.ok}, end_time={self.end_time!r}, finals={self.finals!r})"


def _simulate(model_ptr, inst, base, initial, finals, overrides, want_rows, progress):
    """lv_simulate on a copy of the settings `base` (an lv_sim_settings): `initial` (dict)
    appended to / replacing its start values, `finals` (names) read after the run, the scalar
    `overrides` applied; a memory sink of our own added for the rows. Returns
    (status, err, report, finals values list, rows Table or None, the exception a progress
    callback raised or None)."""
    s = _lib.lv_sim_settings()
    ctypes.memmove(byref(s), byref(base), ctypes.sizeof(s))  # a copy: `base` stays as it was
    keep = []
    for key, val in overrides.items():
        if val is None:
            continue
        if key in ("method", "result_file"):
            b = enc(val, key) if key == "method" else path_arg(val, key)
            keep.append(b)
            setattr(s, key, b)
        elif key == "number_of_intervals":
            setattr(s, key, int_arg(val, key, 0))
        else:
            setattr(s, key, real_arg(val, key))
    # start values: the base's, then the caller's (by name; a name given twice: the last)
    names = [s.initial_names[i] for i in range(s.n_initial)]
    values = [s.initial_values[i] for i in range(s.n_initial)]
    for n, v in (initial or {}).items():
        b = name_arg(n, "initial value name")
        v = real_arg(v, f"initial value of '{n}'")
        if b in names:
            values[names.index(b)] = v
        else:
            names.append(b)
            values.append(v)
    keep.append(names)
    na = (c_char_p * max(1, len(names)))(*names)
    va = (c_double * max(1, len(values)))(*values)
    s.n_initial, s.initial_names, s.initial_values = len(names), na, va
    fn = [name_arg(f, "final name") for f in finals]
    fa = (c_char_p * max(1, len(fn)))(*fn)
    s.n_final, s.final_names = len(fn), fa
    out = (c_double * max(1, len(fn)))()
    res = c_void_p()
    sinks = None
    if want_rows:
        e = _err()
        mem = _lib.lv_sink()
        # lv_sink_memory_create(lv_result **, lv_sink *, lv_err *)
        check(lib.lv_sink_memory_create(byref(res), byref(mem), byref(e)), e)
        sinks = (_lib.lv_sink * (s.n_sinks + 1))()
        for i in range(s.n_sinks):
            sinks[i] = s.sinks[i]
        sinks[s.n_sinks] = mem
        s.n_sinks, s.sinks = s.n_sinks + 1, sinks
    cb_state = {}
    if progress is not None:
        def _prog(t, user):
            try:
                return 1 if progress(t) else 0
            except BaseException as exc:  # stop the run; raised after it
                cb_state["exc"] = exc
                return 1
        cb = _lib.SIM_PROGRESS_FN(_prog)
        keep.append(cb)
        s.progress = cb
    rep = _lib.lv_sim_report()
    err = _err()
    try:
        st = lib.lv_simulate(model_ptr, inst, byref(s), out, byref(rep), byref(err))
        rows = None
        if res:
            rows = Table(*_copy_result(res))
    finally:
        if res:
            lib.lv_sink_destroy(byref(mem))
            lib.lv_result_free(res)
    return st, err, rep, [out[i] for i in range(len(fn))], rows, cb_state.get("exc")


def _outcome(st, err, rep, names, vals, rows):
    o = Outcome()
    o.ok = st == _lib.LV_OK
    o.status = _lib.STATUS_NAMES.get(st, str(st))
    o.error = None if o.ok else (err.msg.decode("utf-8", "replace") or o.status)
    o.finals = dict(zip(names, vals))
    o.end_time = rep.end_time
    o.stop_reason = STOP_REASONS.get(rep.reason, str(rep.reason))
    o.stop_name = rep.stop_name.decode("utf-8", "replace")
    o.stats = {f: getattr(rep.stats, f) for f, _ in _lib.lv_sim_stats._fields_}
    o.events = [Event(rep.event_log[i]) for i in range(rep.n_event_log)]
    o.rows = rows
    return o


_proto_done = False


def _more_protos():
    global _proto_done
    if not _proto_done:
        _lib._proto(lib, "lv_sink_memory_create", c_int, POINTER(c_void_p),
                    POINTER(_lib.lv_sink), POINTER(_lib.lv_err))
        _lib._proto(lib, "lv_sink_destroy", None, POINTER(_lib.lv_sink))
        _lib._proto(lib, "lv_result_free", None, c_void_p)
        _proto_done = True


_more_protos()


def models():
    """The built-in reference models (lv_models.h) by name: {"vertical_ascent": Model, ...}."""
    out = {}
    arr = lib.lv_models_all()
    i = 0
    while arr[i]:
        mdl = Model(arr[i])
        out[mdl.name] = mdl
        i += 1
    return out


def simulate(model, *, start_time=0.0, stop_time=1.0, number_of_intervals=None,
             output_interval=None, method=None, tolerance=None, fixed_step=None,
             result_file=None, initial=None, finals=(), rows=True, progress=None):
    """lv_simulate of a built-in model by name (the paper's Code 1, Dymola's
    simulateExtendedModel): integrates from `start_time` to `stop_time` (s) with `method`
    ("dassl" default, "cvode-adams", "dopri5", "rk4", "euler", "dp5", "dop853", "auto") at
    relative `tolerance` (default 1e-4), output every `output_interval` s or `number_of_intervals` (default 500),
    start values `initial` (dict: states or parameters by name, SI), and returns an Outcome
    with the values of `finals` (names: "time", states, derivatives "der(h)", parameters,
    outputs) at the end. `result_file` (a path without extension) also writes .mat and .csv.
    `progress(t)` is called at every output row (returning True cancels the run).
    Errors of the inputs (an unknown name, a negative tolerance) raise LvsimError; a failing
    integration is an Outcome with ok False and its message."""
    ptr = lib.lv_models_find(name_arg(model, "model"))
    if not ptr:
        raise LvsimError(f"no built-in model '{model}'; models: {', '.join(models())}", _lib.LV_ERR_NOTFOUND)
    base = _lib.lv_sim_settings()
    lib.lv_sim_settings_default(byref(base))
    base.result_file = None
    ov = dict(start_time=real_arg(start_time, "start_time"),
              stop_time=real_arg(stop_time, "stop_time"),
              number_of_intervals=number_of_intervals, output_interval=output_interval,
              method=method, tolerance=tolerance, fixed_step=fixed_step, result_file=result_file)
    finals = [finals] if isinstance(finals, str) else list(finals)
    st, err, rep, vals, tab, exc = _simulate(ptr, None, base, initial, finals, ov, rows,
                                             progress)
    o = _outcome(st, err, rep, finals, vals, tab)
    lib.lv_sim_report_clear(byref(rep))
    if exc is not None:
        raise exc
    if st != _lib.LV_OK and st != _lib.LV_ERR_SOLVER:  # bad inputs raise (and a cancel); a failed run is an outcome
        check(st, err)
    return o


class Phase:
    """A phase of a mission: `index` (run order), `name`, `model` (its model type, "dof3"),
    `parent` (the phase it starts from, a name, or None: from the parameter set), `stages`
    (the stages it carries, bottom first), `method` (integration method), `file_index`,
    `handoff_rule` (the rule of its conversion from a parent of another model, "rates: zero",
    or None)."""

    __slots__ = ("index", "name", "model", "parent", "stages", "method", "file_index",
                 "handoff_rule")

    def __repr__(self):
        return f"Phase({self.index}, {self.name!r}, model={self.model!r}, parent={self.parent!r})"


class Parameter:
    """A run parameter (a number of the mission file a run may vary): `name`
    ("stage2.propellant_mass", "P2.set.theta"), `unit` (SI; "" dimensionless), `value` (the
    file's value, SI), `line` (where the file writes it; 0: a default), `rule` (">= 0")."""

    __slots__ = ("name", "unit", "value", "line", "rule")

    def __repr__(self):
        return f"Parameter({self.name!r}, {self.value!r} {self.unit})"


class Dispersion:
    """A dispersed parameter of the mission's `dispersions:` section (lv_dispersion.h):
    `name`, `unit`, `dist` ("normal", "truncated_normal", "uniform"), `relative`, `nominal`,
    `mean`, `sigma`, `min`, `max`, `group` (correlation group or -1), `line`, `column`."""

    def __init__(self, d):
        self.name, self.unit, self.dist = text(d.name), text(d.unit), text(d.dist)
        self.relative = bool(d.relative)
        self.nominal, self.mean, self.sigma = d.nominal, d.mean, d.sigma
        self.min, self.max = d.min, d.max
        self.group, self.line, self.column = d.group, d.line, d.column

    def __repr__(self):
        return f"Dispersion({self.name!r}, {self.dist})"


class Mission:
    """A mission loaded from its YAML file (lv_mission_load): immutable, shared by any number
    of runs and threads.

        m = lvsim.Mission("examples/rlv-hthl/mission.yaml")
        run = m.run(params={"ms.propellant_mass": 255000})   # executed

    Raises MissionError ("file:line:column: message", `.file`, `.line`, `.column`) for a bad
    file, LvsimError (LV_ERR_IO) for one that cannot be read. Use as a context manager or
    call close(); runs still open are closed with it."""

    def __init__(self, path):
        self._h = None
        self._runs = weakref.WeakSet()  # runs and targets, closed with the mission
        self._deps = 0                  # C objects borrowing the mission, not yet freed
        self._dead = False              # close() or __del__ asked for the free
        self._lock = threading.RLock()
        h = c_void_p()
        err = _err()
        st = lib.lv_mission_load(path_arg(path, "mission path"), byref(h), byref(err))
        check(st, err, MissionError)
        self._h = h
        self._free = lib.lv_mission_free
        info = _lib.lv_mission_info()
        lib.lv_mission_get_info(h, byref(info))
        self.name = text(info.name)
        self.description = text(info.description)
        self.path = text(info.path)
        self.epoch = text(info.epoch)
        self.flat_world = bool(info.flat_world)
        self.planet = text(info.planet)
        self.site_lat, self.site_lon = info.site_lat, info.site_lon
        self.stages = [text(lib.lv_mission_stage_name(h, s)) for s in range(info.n_stages)]
        self.phases = []
        for k in range(info.n_phases):
            pi = _lib.lv_phase_info()
            lib.lv_mission_phase_info(h, k, byref(pi))
            p = Phase()
            p.index, p.name, p.model = k, text(pi.name), text(pi.model)
            p.parent = pi.parent  # index for now
            p.stages = [self.stages[pi.stages[i]] for i in range(pi.n_stages)]
            p.method, p.file_index = text(pi.method), pi.file_index
            p.handoff_rule = text(pi.handoff_rule) if pi.handoff_rule else None
            self.phases.append(p)
        for p in self.phases:
            p.parent = None if p.parent < 0 else self.phases[p.parent].name
        self.parameters = []
        for i in range(info.n_params):
            pi = _lib.lv_param_info()
            lib.lv_mission_param_info(h, i, byref(pi))
            p = Parameter()
            p.name, p.unit, p.value = text(pi.name), text(pi.unit) or "", pi.value
            p.line, p.rule = pi.line, text(pi.rule)
            self.parameters.append(p)
        self.dispersions = []
        for j in range(lib.lv_mission_disp_count(h)):
            d = _lib.lv_disp_info()
            lib.lv_mission_disp_info(h, j, byref(d))
            self.dispersions.append(Dispersion(d))

    # ---- lifetime ----
    def _handle(self):
        if self._h is None or self._dead:
            raise LvsimError("mission is closed")
        return self._h

    # A run or target borrows the C mission (lv_mission_free: "no run of it may be left").
    # Each holds a reference to the Mission, but the garbage collector finalises the objects
    # of an unreachable cycle in any order: a run caught in a cycle may be finalised after
    # its mission. So the C mission is freed when it is released AND its last borrower is
    # freed, whichever comes last (_acquire/_release count the borrowers).
    def _acquire(self):
        with self._lock:
            self._deps += 1

    def _release(self):
        with self._lock:
            self._deps -= 1
            self._maybe_free()

    def _maybe_free(self):
        if self._dead and self._deps == 0 and self._h is not None:
            self._free(self._h)
            self._h = None

    def close(self):
        """Frees the mission, closing its runs and targets first. Idempotent."""
        with self._lock:
            for r in list(self._runs):
                r.close()
            self._dead = True
            self._maybe_free()  # now, or when its last borrower is freed

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        if getattr(self, "_h", None) is not None:
            self._dead = True
            self._maybe_free()

    def __repr__(self):
        return f"Mission({self.name!r}: {len(self.phases)} phases, {len(self.stages)} stages)"

    # ---- names ----
    def phase_index(self, phase):
        """Run-order index of a phase given by name (or index, checked). NotFound: an
        LvsimError (LV_ERR_NOTFOUND) whose message suggests the nearest names."""
        if isinstance(phase, (bool, np.bool_)):
            raise TypeError(f"phase must be a name (str), an index (int) or a Phase, not {phase!r}")
        if isinstance(phase, (int, np.integer)):
            if not 0 <= phase < len(self.phases):
                raise LvsimError(f"phase index {phase} out of range (0..{len(self.phases) - 1})", _lib.LV_ERR_INPUT)
            return int(phase)
        if isinstance(phase, Phase):
            return phase.index
        k = c_size_t()
        err = _err()
        if not isinstance(phase, (str, bytes)):
            raise TypeError("phase must be a name (str), an index (int) or a Phase, not "
                            f"{type(phase).__name__} ({phase!r})")
        check(lib.lv_mission_phase_find(self._handle(), name_arg(phase, "phase name"), byref(k),
                                        byref(err)), err)
        return k.value

    def stage_index(self, stage):
        """Index of a stage by name (or index)."""
        if isinstance(stage, (bool, np.bool_)) or not isinstance(stage, (str, int, np.integer)):
            raise TypeError(f"stage must be a name (str) or an index (int), not "
                            f"{type(stage).__name__} ({stage!r})")
        if isinstance(stage, (int, np.integer)):
            if not 0 <= stage < len(self.stages):
                raise LvsimError(f"stage index {stage} out of range (0..{len(self.stages) - 1})", _lib.LV_ERR_INPUT)
            return int(stage)
        name_arg(stage, "stage name")
        try:
            return self.stages.index(stage)
        except ValueError:
            raise LvsimError(f"no stage '{stage}'; stages: {', '.join(self.stages)}", _lib.LV_ERR_NOTFOUND) from None

    def parameter(self, name):
        """The Parameter `name`; ParameterError (LV_ERR_NOTFOUND, with suggestions).

        An angle asked for as "NAME_deg" comes in degrees, as Run.get/Run.set take it: a
        Parameter named "NAME_deg", unit "deg", value the file's value in degrees. So
        run.set(n, m.parameter(n).value) sets the file's value for either spelling."""
        i = c_size_t()
        deg = c_int()
        err = _err()
        check(lib.lv_mission_param_find(self._handle(), name_arg(name, "parameter name"),
                                        byref(i), byref(deg), byref(err)), err, ParameterError)
        p = self.parameters[i.value]
        if not deg.value:
            return p
        q = Parameter()
        q.name, q.unit, q.line, q.rule = p.name + "_deg", "deg", p.line, p.rule
        q.value = p.value / _DEG
        return q

    # ---- runs ----
    def create_run(self, params=None):
        """A new Run (nothing executed), with `params` (dict name -> value, SI; "NAME_deg"
        in degrees) set."""
        r = Run(self)
        if params:
            r.update(params)
        return r

    def run(self, params=None, **execute):
        """A new Run with `params` set, executed (Run.execute's keyword arguments). Raises
        SimulationError when a phase fails (its .run keeps what succeeded), unless
        check=False."""
        r = self.create_run(params)
        r.execute(**execute)
        return r

    def draw(self, seed, index):
        """The values run `index` of a Monte Carlo campaign with `seed` draws for the
        dispersed parameters (lv_mission_disp_draw): dict name -> value in its written unit
        (degrees for *_deg)."""
        seed = int_arg(seed, "seed", 0, U64_MAX)
        index = int_arg(index, "index", 0, U64_MAX)
        n = len(self.dispersions)
        vals = (c_double * max(1, n))()
        lib.lv_mission_disp_draw(self._handle(), c_uint64(seed), c_uint64(index), vals)
        return {d.name: vals[j] for j, d in enumerate(self.dispersions)}

    @property
    def seed(self):
        """The file's `seed:` for its dispersions, or None."""
        s = c_uint64()
        return s.value if lib.lv_mission_disp_seed(self._handle(), byref(s)) else None

    def target(self, *, from_file=True):
        """A Target (lv_target.h): the mission's `targeting:` section (from_file=True;
        LvsimError when it has none), or an empty problem to build with add_variable,
        add_constraint and set_cost."""
        from ._target import Target
        return Target(self, from_file)

    def monte_carlo(self, n_runs, db_path, **kw):
        """Runs a Monte Carlo campaign of the mission's `dispersions:` (lv_campaign_run):
        see lvsim.Campaign.run for the keyword arguments."""
        from ._campaign import Campaign
        return Campaign.run(self, n_runs, db_path, **kw)


class Run:
    """One run of a mission (lv_run): a value for every parameter and each phase's result.
    Re-executing simulates only the phases whose inputs changed and their descendants.

    One Run is used by one thread at a time (a lock serialises calls on it); runs of one
    mission may execute in parallel threads: execute() releases the GIL. Close it (or use
    `with`) to free it at once; otherwise it is freed when garbage-collected."""

    def __init__(self, mission):
        self._h = None
        self._pending = None
        self._lock = threading.RLock()
        self.mission = mission
        h = c_void_p()
        err = _err()
        check(lib.lv_run_create(mission._handle(), byref(h), byref(err)), err)
        self._h = h
        self._free = lib.lv_run_free
        self._ran_with = {}     # phase index -> the result-shaping options it ran with
        self._stage_map = None  # (staging folder, results folder) of the last outdir
        mission._acquire()
        mission._runs.add(self)

    def _handle(self):
        if self._h is None:
            raise LvsimError("run is closed")
        if self._pending is not None and self._pending._c is not None:
            raise LvsimError(f"phase '{self._pending.phase}' was prepared and not simulated: "
                             "call its simulate() or close() first")
        return self._h

    def _dispose(self):
        # a pending phase call first (it was built from the run), then the run, then the
        # mission's count of borrowers
        p = self._pending
        if p is not None:
            p.close()
            self._pending = None
        if self._h is not None:
            self._free(self._h)
            self._h = None
            self.mission._release()

    def close(self):
        """Frees the run (and a prepared, unsimulated phase call). Idempotent."""
        with self._lock:
            self._dispose()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        if getattr(self, "_h", None) is not None:
            self._dispose()

    # ---- parameters ----
    def set(self, name, value):
        """Sets parameter `name` (SI; "NAME_deg": degrees). ParameterError: unknown name
        (with "did you mean"), or a value outside the parameter's range (with its rule)."""
        with self._lock:
            err = _err()
            check(lib.lv_run_set(self._handle(), name_arg(name, "parameter name"),
                                 real_arg(value, f"value of '{name}'"), byref(err)), err,
                  ParameterError)

    def get(self, name):
        """This run's value of parameter `name` (SI; degrees for "NAME_deg")."""
        with self._lock:
            v = c_double()
            err = _err()
            check(lib.lv_run_get(self._handle(), name_arg(name, "parameter name"), byref(v),
                                 byref(err)), err, ParameterError)
            return v.value

    __getitem__ = get
    __setitem__ = set

    def __contains__(self, name):
        """True when `name` is a parameter of the run's mission ("NAME_deg" for an angle)."""
        if not isinstance(name, str):
            return False
        try:
            self.mission.parameter(name)
            return True
        except (ParameterError, ValueError):
            return False

    # A Run is not a sequence: without this, iter(run) would call run[0], run[1]...
    __iter__ = None

    def update(self, params):
        """Sets every (name, value) of a dict; stops at the first error."""
        for k, v in dict(params).items():
            self.set(k, v)

    def reset(self):
        """Every parameter back to the mission file's value."""
        with self._lock:
            lib.lv_run_reset(self._handle())

    def disperse(self, seed, index):
        """Draws Monte Carlo run `index`'s values (campaign `seed`) and sets them on this
        run; returns them (dict name -> value, written unit). ParameterError when a drawn
        value is outside its parameter's range (the run keeps its earlier values)."""
        seed = int_arg(seed, "seed", 0, U64_MAX)
        index = int_arg(index, "index", 0, U64_MAX)
        with self._lock:
            n = len(self.mission.dispersions)
            vals = (c_double * max(1, n))()
            err = _err()
            check(lib.lv_run_disperse(self._handle(), c_uint64(seed), c_uint64(index), vals,
                                      byref(err)), err, ParameterError)
            return {d.name: vals[j] for j, d in enumerate(self.mission.dispersions)}

    # ---- executing ----
    def execute(self, phases=None, *, until=None, outdir=None, formats=("mat", "csv"),
                threads=0, output_interval=None, method=None, tolerance=None,
                keep_rows=True, progress=None, check=True, max_rows=DEFAULT_MAX_ROWS):
        """Simulates the phases whose inputs changed (all, the first time), and those whose
        results the options below would change.

        phases: names (or indices) of the phases wanted: only those and their ancestors run
            (the others whose inputs changed stay pending); None: every phase.
        until: a phase name: every phase up to it in run order (ancestors included).
        outdir: a results folder, written as `lvsim run -o` writes one: every phase is
            simulated again and its files phase_<k>_<name>.mat/.csv (k = index + 1) go into a
            private staging folder that replaces `outdir` as a whole at the end, with a
            manifest.json; so a folder never mixes two runs. `outdir` may exist only empty or
            as an lvsim results folder (anything else: LvsimError); an interrupted or
            cancelled run leaves it as it was; a run with failed phases is kept, marked
            "failed" in the manifest. None: no files. formats: which of "mat", "csv" (empty:
            none).
        threads: worker threads for independent branches (0: 2).
        output_interval: None: each phase's own output grid; a number > 0 (s): every phase's
            grid; "ends": only each phase's start and end rows, the fastest, as Monte Carlo
            campaigns run (Campaign.run's default): run.disperse(seed, i);
            run.execute(output_interval="ends") gives campaign run i's finals bit for bit.
        method (one of lvsim.METHODS), tolerance (1e-14 to 0.1): override every phase's.
        keep_rows: keep each phase's rows in memory (PhaseResult rows, Run.body); False is
            faster when only finals are read.
            A phase that ran with other method, tolerance, output_interval or keep_rows than
            these is simulated again (so are its descendants).
        progress: progress(phase_index, t) called at every output row from the thread that
            runs the phase (it takes the GIL: costly); returning True cancels the run.
        check: raise SimulationError when a phase fails (the others keep their results);
            False: return normally, see .failed.
        max_rows: the most output rows one phase may keep or write (default 1e6, as the
            CLI's --max-rows), with keep_rows=True or an outdir (keep_rows=False without
            outdir keeps no rows: no limit). A phase that only its stop time ends and whose
            output grid over its longest possible duration is larger raises
            OutputLimitError before anything runs; a phase with end events (burnout,
            altitude, ...) is not refused for a generous stop time but fails
            (SimulationError, "row limit") if it reaches max_rows rows before an end fires.
            None: no limit.

        Ctrl-C (SIGINT) while it runs, from the main thread: every branch stops within an
        integrator step and KeyboardInterrupt is raised; the phases completed before keep their
        results, the interrupted ones are left failed (cancelled) and run at the next
        execute().

        Returns self. TypeError/ValueError for bad arguments (naming the argument);
        LvsimError for an output folder that cannot be made; CancelledError when progress
        cancelled."""
        m = self.mission
        n = len(m.phases)
        # ---- the arguments, all checked before anything runs ----
        want = None
        if phases is not None or until is not None:
            want = (c_ubyte * n)()
            if isinstance(phases, (str, bytes, int, np.integer, Phase)):
                phases = [phases]
            for p in phases or []:
                want[m.phase_index(p)] = 1
            if until is not None:
                for k in range(m.phase_index(until) + 1):
                    want[k] = 1
        threads = int_arg(threads, "threads", 0, 1024)
        check = bool_arg(check, "check")
        if output_interval is None:
            oi = 0.0
        elif isinstance(output_interval, str):
            if output_interval != "ends":
                raise InputError(f"output_interval {output_interval!r}: a number of seconds "
                                 "> 0, None (each phase's own) or 'ends' (start and end rows)")
            oi = 1e300  # one interval longer than any phase: its start and end rows only
        else:
            oi = real_arg(output_interval, "output_interval")
            if not (oi > 0.0 and math.isfinite(oi)):
                raise InputError(f"output_interval must be > 0 s and finite, got {oi!r} (None: "
                                 "each phase's own grid; 'ends': start and end rows only)")
        if method is not None:
            if not isinstance(method, str):
                raise TypeError(f"method must be a str, not {type(method).__name__}")
            if method not in METHODS:
                raise InputError(f"unknown method {method!r}; methods: {', '.join(METHODS)}")
        if tolerance is not None:
            tolerance = real_arg(tolerance, "tolerance")
            if not _lib.LV_TOLERANCE_MIN <= tolerance <= _lib.LV_TOLERANCE_MAX:
                raise InputError(f"tolerance must be from {_lib.LV_TOLERANCE_MIN:g} to "
                                 f"{_lib.LV_TOLERANCE_MAX:g}, got {tolerance!r}")
        if not isinstance(keep_rows, (bool, np.bool_)):
            raise TypeError(f"keep_rows must be True or False, not {keep_rows!r}")
        keep_rows = bool(keep_rows)
        if max_rows is not None:
            max_rows = real_arg(max_rows, "max_rows")
            if max_rows == max_rows and max_rows != float("inf") and max_rows != int(max_rows):
                raise InputError(f"max_rows must be a whole number of rows, got {max_rows!r}")
            if not max_rows >= 1:
                raise InputError(f"max_rows must be >= 1 (or None: no limit), got {max_rows!r}")
        if progress is not None and not callable(progress):
            raise TypeError(f"progress must be callable, not {type(progress).__name__}")
        fm = 0
        if outdir is not None:
            outdir = path_arg(outdir, "outdir")
            if isinstance(formats, str):
                formats = [formats]
            for f in formats or ():
                if f not in ("mat", "csv"):
                    raise InputError(f"unknown result format {f!r} (mat, csv)")
                fm |= _lib.LV_RESULT_MAT if f == "mat" else _lib.LV_RESULT_CSV
        key = (method, tolerance, oi, keep_rows)

        opt = _lib.lv_run_options()
        keep = []
        opt.threads = threads
        opt.output_interval = oi
        if method is not None:
            opt.method = method.encode()
            keep.append(opt.method)
        if tolerance is not None:
            opt.tolerance = tolerance
        opt.no_rows = 0 if keep_rows else 1
        # the row limit holds where rows are kept or written (rows that are neither cost only
        # time): refused before anything runs for a phase only its stop time ends, enforced
        # as it runs for one with end events (lv_run_options.max_rows)
        if max_rows is not None and (keep_rows or outdir is not None):
            opt.max_rows = max_rows
        if want is not None:
            opt.want = ctypes.cast(want, POINTER(c_ubyte))
        # the stop flag (lv_run_options.stop): set by Ctrl-C or by an exception in
        # `progress`, it stops every branch within an integrator step, at no cost until then
        cb_state = {}
        stop = c_int(0)
        opt.stop = ctypes.pointer(stop)
        if progress is not None:
            def _prog(run, k, t, user):
                if stop.value:
                    return 1
                try:
                    return 1 if progress(k, t) else 0
                except BaseException as exc:  # stop everything; raised after the run
                    cb_state.setdefault("exc", exc)
                    stop.value = 1
                    return 1
            cb = _lib.RUN_PROGRESS_FN(_prog)
            keep.append(cb)
            opt.progress = cb

        with self._lock:
            h = self._handle()
            # results the options would change run again (phases that ran otherwise)
            err = _err()
            for k in range(n):
                if k in self._ran_with and self._ran_with[k] != key:
                    _check(lib.lv_run_invalidate(h, k, byref(err)), err)
            if outdir is not None:  # a complete results folder: every phase, written anew
                _check(lib.lv_run_invalidate(h, _lib.LV_RUN_ALL_PHASES, byref(err)), err)
            if opt.max_rows > 0.0 and lib.lv_run_check_output(h, byref(opt), byref(err)) != 0:
                raise OutputLimitError(err.msg.decode("utf-8", "replace"), _lib.LV_ERR_INPUT)
            od = None
            if outdir is not None:
                post = _lib.post()
                od = c_void_p()
                _check(post.lv_outdir_begin(outdir, path_arg(m.path), 0, byref(od), byref(err)), err)
                stage = post.lv_outdir_path(od)
                keep.append(stage)
                opt.outdir = stage
                opt.result_formats = fm if fm else _lib.LV_RUN_NO_PHASE_FILES
            try:
                try:
                    st = self._execute_interruptible(h, opt, err, stop)
                finally:  # also when interrupted: what each phase now holds ran with these
                    for k in range(n):
                        if PHASE_STATES[lib.lv_run_result(h, k).contents.state] != "pending" \
                                and not lib.lv_run_stale(h, k):
                            self._ran_with[k] = key
                if od is not None:
                    interrupted = "exc" in cb_state or stop.value or st == _lib.LV_ERR_CANCELLED
                    if not interrupted:
                        rec = _lib.lv_outdir_record()
                        rec.command = b"python"
                        rec.status = b"ok" if st == _lib.LV_OK else b"failed"
                        rec.mission_name = enc(m.name)
                        cerr = _err()
                        cst = post.lv_outdir_commit(od, byref(rec), byref(cerr))
                        if cst == _lib.LV_OK:
                            self._stage_map = (text(stage), text(post.lv_outdir_final(od)))
                        else:
                            _check(cst, cerr)
            finally:
                if od is not None:
                    post.lv_outdir_free(od)  # uncommitted: staging removed, outdir untouched
        if "exc" in cb_state:
            raise cb_state["exc"]
        if st == _lib.LV_ERR_SOLVER:  # some phases failed, the others are complete
            if check:
                failed = self.failed
                skipped = [p.name for p in m.phases if self.state(p.index) == "skipped"]
                done = [p.name for p in m.phases if self.state(p.index) == "done"]
                msg = "; ".join(failed.values()) or err.msg.decode("utf-8", "replace")
                if skipped:
                    msg += f" (skipped: {', '.join(skipped)})"
                raise SimulationError(msg, st, self, failed, skipped, done)
            return self
        _check(st, err)
        return self

    def _execute_interruptible(self, h, opt, err, stop):
        """lv_run_execute, stoppable by Ctrl-C. From the main thread (the only one Python
        delivers SIGINT to) the C call runs in a helper thread while this one waits: SIGINT
        sets the C run's stop flag (`stop`, lv_run_options.stop), which cancels every running
        phase within an integrator step and starts no other; once the run has stopped (the run
        consistent), KeyboardInterrupt is raised."""
        if threading.current_thread() is not threading.main_thread():
            return lib.lv_run_execute(h, byref(opt), byref(err))
        box = {}

        def _go():
            try:
                box["st"] = lib.lv_run_execute(h, byref(opt), byref(err))
            except BaseException as exc:  # pragma: no cover - ctypes itself failing
                box["exc"] = exc
        t = threading.Thread(target=_go, name="lvsim-execute", daemon=True)
        got = []
        old = signal.getsignal(signal.SIGINT)
        if old is signal.default_int_handler:
            # Python's own handler: replaced for the run by one that only asks the run to
            # stop, so no KeyboardInterrupt can fly while the run is still going
            def _on_sigint(signum, frame):
                got.append(KeyboardInterrupt())
                stop.value = 1
            signal.signal(signal.SIGINT, _on_sigint)
            try:
                t.start()
                while t.is_alive():
                    t.join(0.05)
            finally:
                signal.signal(signal.SIGINT, old)
        else:  # the caller's own handler: its exception stops the run, raised after it
            t.start()
            while True:
                try:
                    while t.is_alive():
                        t.join(0.05)
                    break
                except BaseException as exc:
                    got.append(exc)
                    stop.value = 1
        if "exc" in box:
            raise box["exc"]
        if got:
            raise got[0]
        return box["st"]

    def invalidate(self, phase=None):
        """Marks `phase` (None: every phase) to be simulated again at the next execute(),
        with its descendants; until then its result reads as "stale"."""
        with self._lock:
            h = self._handle()
            k = _lib.LV_RUN_ALL_PHASES if phase is None else self.mission.phase_index(phase)
            err = _err()
            check(lib.lv_run_invalidate(h, k, byref(err)), err)

    @property
    def simulated(self):
        """How many phases the last execute() simulated."""
        with self._lock:
            return lib.lv_run_simulated(self._handle())

    def state(self, phase):
        """"pending", "done", "failed", "skipped" (an ancestor failed) or "stale" (done, but
        an input of it or of an ancestor changed since: set() without execute(); its values
        are those of the earlier inputs, and final() refuses them)."""
        k = self.mission.phase_index(phase)
        with self._lock:
            h = self._handle()
            st = PHASE_STATES[lib.lv_run_result(h, k).contents.state]
            return "stale" if st == "done" and lib.lv_run_stale(h, k) else st

    @property
    def states(self):
        """dict phase name -> state, in run order."""
        return {p.name: self.state(p.index) for p in self.mission.phases}

    @property
    def ok(self):
        """True when every phase is done."""
        return all(s == "done" for s in self.states.values())

    @property
    def failed(self):
        """dict failed phase name -> its message (phase, time, reason)."""
        out = {}
        with self._lock:
            for p in self.mission.phases:
                r = lib.lv_run_result(self._handle(), p.index).contents
                if r.state == 2:
                    out[p.name] = r.error.decode("utf-8", "replace")
        return out

    # ---- results ----
    def result(self, phase):
        """Phase `phase`'s PhaseResult (a copy: rows, finals, events, statistics)."""
        k = self.mission.phase_index(phase)
        with self._lock:
            self._handle()
            return PhaseResult(self, k)

    def results(self):
        """Every phase's PhaseResult, dict name -> result, in run order."""
        return {p.name: self.result(p.index) for p in self.mission.phases}

    def _not_stale(self, k):
        """LvsimError when done phase k is stale (an input changed since it ran)."""
        h = self._handle()
        if lib.lv_run_result(h, k).contents.state == 1 and lib.lv_run_stale(h, k):
            raise LvsimError(f"phase '{self.mission.phases[k].name}' is stale: an input "
                             "changed since it ran (set() without execute()); call "
                             "execute() first", _lib.LV_ERR_INPUT)

    def dataframe(self, phase):
        """Phase `phase`'s rows as a pandas DataFrame (units in df.attrs["units"]).
        LvsimError when the phase is stale (as final()); result(phase) still gives the old
        rows with .stale True."""
        k = self.mission.phase_index(phase)
        with self._lock:
            self._not_stale(k)
        return self.result(k).to_dataframe()

    def final(self, phase, name):
        """A final value of a done phase by name ("time", "h", "m", ...), SI. LvsimError
        when the phase is not done, is stale (an input changed since it ran: execute()
        first) or has no such final."""
        k = self.mission.phase_index(phase)
        b = name_arg(name, "final name")
        with self._lock:
            self._not_stale(k)
            h = self._handle()
            v = c_double()
            err = _err()
            check(lib.lv_run_final(h, k, b, byref(v), byref(err)), err)
            return v.value

    def finals(self, phase):
        """dict name -> final value of phase `phase` (time, states, outputs; SI). LvsimError
        when the phase is stale (as final())."""
        k = self.mission.phase_index(phase)
        with self._lock:
            self._not_stale(k)
        return self.result(k).finals

    def body(self, stage):
        """Stage `stage`'s (name or index) merged Trajectory across the done phases it flies
        in (needs keep_rows=True at execute). LvsimError when it flew in no done phase, or
        when one of them kept no rows (execute(keep_rows=False)) or is stale."""
        m = self.mission
        s = m.stage_index(stage)
        with self._lock:
            h = self._handle()
            ks = (c_size_t * max(1, len(m.phases)))()
            for j in range(lib.lv_run_body_phases(h, s, ks)):
                k = ks[j]
                if not lib.lv_run_rows(h, k):
                    raise LvsimError(f"stage '{m.stages[s]}': phase '{m.phases[k].name}' kept "
                                     "no rows (execute(keep_rows=False)); execute("
                                     "keep_rows=True) for its trajectory", _lib.LV_ERR_INPUT)
                if lib.lv_run_stale(h, k):
                    raise LvsimError(f"stage '{m.stages[s]}': phase '{m.phases[k].name}' is "
                                     "stale (an input changed since it ran); call execute() "
                                     "first", _lib.LV_ERR_INPUT)
            b = POINTER(_lib.lv_body_traj)()
            err = _err()
            check(lib.lv_run_body_trajectory(self._handle(), s, byref(b), byref(err)), err)
            try:
                t = b.contents
                nr, nc = t.n_rows, t.n_cols
                names = [text(t.names[i]) for i in range(nc)]
                units = [text(t.units[i]) or "" for i in range(nc)]
                if nr:
                    vals = np.ctypeslib.as_array(t.values, shape=(nr * nc,)).copy().reshape(nr, nc)
                    ph = np.ctypeslib.as_array(t.phase, shape=(nr,)).astype(np.int64)
                else:
                    vals, ph = np.empty((0, nc)), np.empty(0, dtype=np.int64)
                stage_name = text(t.stage)
            finally:
                lib.lv_body_traj_free(b)
        return Trajectory(stage_name, names, units, vals, ph, [p.name for p in m.phases])

    def bodies(self):
        """dict stage name -> Trajectory for every stage that flew in a done phase; LvsimError
        as body() (rows not kept, a stale phase)."""
        out = {}
        for s, name in enumerate(self.mission.stages):
            with self._lock:
                cap = (c_size_t * max(1, len(self.mission.phases)))()
                n = lib.lv_run_body_phases(self._handle(), s, cap)
            if n:
                out[name] = self.body(s)
        return out

    # ---- one phase by hand (the paper's Code 2) ----
    def prepare(self, phase):
        """Phase `phase` ready to simulate by hand (lv_run_prepare): a PhaseCall with its
        model built from this run's values, its settings and the hand-off as start values.
        Its parent must be done in this run. Until the call is simulated or closed, the run
        refuses other calls."""
        k = self.mission.phase_index(phase)
        with self._lock:
            h = self._handle()
            self._ran_with.pop(k, None)  # what it holds next comes from a hand-made call
            c = c_void_p()
            err = _err()
            check(lib.lv_run_prepare(h, k, byref(c), byref(err)), err)
            call = PhaseCall(self, k, c)
            self._pending = call
            return call


class PhaseCall:
    """One phase of a run, prepared (lv_run_prepare), to simulate with your own start values,
    times, method and final names: the simulateExtendedModel call on the phase's model.

    `phase` (name), `model` (Model: states, parameters, outputs), `initial` (dict: the
    hand-off's start values by name, SI), `settings` (dict: start_time, stop_time (s),
    output_interval, number_of_intervals, method, tolerance), `final_names` (what the run
    records: time, every state and output). simulate() once; then the call is spent."""

    def __init__(self, run, k, c):
        self._run = run
        self._c = c
        self.index = k
        self.phase = run.mission.phases[k].name
        self.model = Model(lib.lv_phase_call_model(c))
        s = lib.lv_phase_call_settings(c).contents
        self.initial = {text(s.initial_names[i]): s.initial_values[i] for i in range(s.n_initial)}
        self.settings = dict(start_time=s.start_time, stop_time=s.stop_time,
                             output_interval=s.output_interval,
                             number_of_intervals=s.number_of_intervals,
                             method=text(s.method), tolerance=s.tolerance)
        self.final_names = [text(s.final_names[i]) for i in range(s.n_final)]

    def close(self):
        """Frees the call without simulating it (lv_phase_call_free). Idempotent."""
        if self._c is not None:
            lib.lv_phase_call_free(self._c)
            self._c = None
        if self._run is not None and self._run._pending is self:
            self._run._pending = None  # no cycle left between the run and its call

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        if getattr(self, "_c", None) is not None:
            lib.lv_phase_call_free(self._c)
            self._c = None

    def simulate(self, initial=None, finals=None, *, start_time=None, stop_time=None,
                 output_interval=None, number_of_intervals=None, method=None,
                 tolerance=None, result_file=None, record=True, progress=None):
        record = bool_arg(record, "record")
        """lv_simulate of the phase's model (simulateExtendedModel): `initial` (dict name ->
        value, SI) overrides or adds start values (states or model parameters) over the
        hand-off; `finals` (names, default final_names) are returned in Outcome.finals;
        `start_time`, `stop_time` (s), `output_interval` (s), `number_of_intervals`,
        `method`, `tolerance` override the phase's; `result_file` (a path without extension)
        writes .mat and .csv.

        record=True hands the outcome to the run (lv_run_complete) as this phase's result:
        Run.result(phase) then has it and its children can be prepared. record=False leaves
        the run as it was (a what-if). Returns an Outcome (ok False with the message when
        the integration failed); LvsimError for bad inputs (an unknown name)."""
        if self._c is None:
            raise LvsimError(f"phase call '{self.phase}' already simulated or closed")
        run = self._run
        c = self._c
        sp = lib.lv_phase_call_settings(c)
        s = sp.contents
        initial = dict(initial or {})
        # overrides of hand-off names go into the call itself too: the run records the
        # start mass from them (lv_run_complete)
        for i in range(s.n_initial):
            nm = text(s.initial_names[i])
            if nm in initial:
                s.initial_values[i] = real_arg(initial.pop(nm), f"initial value of '{nm}'")
        scal = dict(start_time=start_time, stop_time=stop_time,
                    output_interval=output_interval, tolerance=tolerance)
        for k, v in scal.items():
            if v is not None:
                setattr(s, k, real_arg(v, k))
        if number_of_intervals is not None:
            s.number_of_intervals = int_arg(number_of_intervals, "number_of_intervals", 0)
        keep = []
        if method is not None:
            b = enc(method, "method")
            keep.append(b)
            s.method = b
        if result_file is not None:
            b = path_arg(result_file, "result_file")
            keep.append(b)
            s.result_file = b
        if isinstance(finals, str):
            finals = [finals]  # one name, not its letters
        want = list(finals) if finals is not None else list(self.final_names)
        for f in want:
            name_arg(f, "final name")
        names = self.final_names + want  # the run's finals first, so they can be recorded
        model = lib.lv_phase_call_model(c)
        inst = lib.lv_phase_call_inst(c)
        with run._lock:
            try:
                st, err, rep, vals, rows, exc = _simulate(model, inst, s, initial, names, {},
                                                          True, progress)
            except BaseException:
                self.close()
                run._pending = None
                raise
            n0 = len(self.final_names)
            fin = lib.lv_phase_call_finals(c)
            for i in range(n0):
                fin[i] = vals[i]
            o = _outcome(st, err, rep, want, vals[n0:], rows)
            if exc is not None or (st != _lib.LV_OK and st != _lib.LV_ERR_SOLVER):
                # bad inputs (an unknown start-value name...), a cancel, an exception in
                # progress: nothing recorded, the call is spent either way
                lib.lv_sim_report_clear(byref(rep))
                self.close()
                run._pending = None
                if exc is not None:
                    raise exc
                msg = err.msg.decode("utf-8", "replace")
                mt = re.match(r"finalNames\[(\d+)\]: ", msg)
                if mt:  # the index counts the run's own finals first: name the caller's
                    i = int(mt.group(1))
                    which = (f"finals[{i - n0}] '{want[i - n0]}'" if i >= n0
                             else f"final '{names[i]}'")
                    err.msg = (which + ": " + msg[mt.end():]).encode()[:_lib.LV_ERR_MSG_MAX - 1]
                check(st, err)
            if record:
                e2 = _err()
                cst = lib.lv_run_complete(run._h, c, st, byref(err), byref(rep), byref(e2))
                self._c = None  # lv_run_complete frees the call
                lib.lv_sim_report_clear(byref(rep))
                run._pending = None
                check(cst, e2)
            else:
                lib.lv_sim_report_clear(byref(rep))
                self.close()
                run._pending = None
        return o
