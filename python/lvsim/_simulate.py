"""_simulate.py - one model simulated on its own (lv_sim.h, lv_models.h): the built-in
reference models, simulate() (the paper's Code 1: Dymola's simulateExtendedModel), and a
prepared phase of a run simulated with the caller's start values (PhaseCall).

Units are SI; every array returned is a copy owned by NumPy.
"""
import ctypes
import re
from ctypes import POINTER, byref, c_char_p, c_double, c_int, c_void_p

from . import _lib
from ._lib import lib, enc, text, name_arg, path_arg, real_arg, int_arg, bool_arg
from .errors import LvsimError, check

from ._results import Event, Table, STOP_REASONS, _copy_result, _err

_check = check


def _methods():
    arr = lib.lv_sim_methods()
    out, i = [], 0
    while arr[i]:
        out.append(text(arr[i]))
        i += 1
    return tuple(out)


METHODS = _methods()  # the integration methods (lv_sim_methods): "dassl", "rk4", ...


class Variable:
    """A model variable: `name`, `unit` (SI), `description`, `start` (default start value or
    parameter value), `nominal` (states: the magnitude scaling the absolute tolerance), `kind`
    ("state", "parameter", "output")."""

    __slots__ = ("name", "unit", "description", "start", "nominal", "kind")

    def __init__(self, v, kind):
        self.name = text(v.name)
        self.unit = text(v.unit) or "1"
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
    relative `tolerance` (default 1e-4), output every `output_interval` s or
    `number_of_intervals` (default 500),
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
