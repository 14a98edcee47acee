"""_run.py - one run of a mission (lv_run.h): a value per parameter slot, each phase's result,
execution of the phases that need it (threads, a results folder, the row limit, Ctrl-C),
bodies' trajectories and the one-phase call.

Units are SI; every array returned is a copy owned by NumPy.
"""
import ctypes
import math
import signal
import threading
from ctypes import POINTER, byref, c_double, c_int, c_size_t, c_ubyte, c_uint64, c_void_p

import numpy as np

from . import _lib
from ._lib import lib, enc, text, name_arg, path_arg, real_arg, int_arg, bool_arg, U64_MAX
from .errors import (InputError, LvsimError, OutputLimitError, ParameterError, SimulationError,
                     check)

from ._results import (Phase, PhaseResult, Trajectory, PHASE_STATES, _err)
from ._simulate import METHODS, PhaseCall

_check = check

DEFAULT_MAX_ROWS = 1e6  # output rows one phase may write (the CLI's --max-rows default)


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
    def execute(self, phases=None, *, until=None, outdir=None, formats=None,
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
            "failed" in the manifest. None: no files. formats: which result formats, names of
            lvsim.formats("results") ("mat", "csv"); None: all of them; empty: none.
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
            names = [name for name, _, _ in _lib.RESULT_FORMATS]
            if formats is None:
                formats = names
            elif isinstance(formats, str):
                formats = [formats]
            for f in formats:
                if f not in names:
                    raise InputError(f"unknown result format {f!r} ({', '.join(names)})")
                fm |= 1 << names.index(f)
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
                st = post.lv_outdir_begin(outdir, path_arg(m.path), 0, byref(od), byref(err))
                # the CLI's --force has no counterpart here: a user's files are never replaced
                err.msg = err.msg.replace(b", or add --force to replace lvsim's files and keep "
                                          b"these", b"")
                _check(st, err)
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

    def reference_drift(self, phase):
        """The drift of phase `phase` from its `reference:` (an optimiser's trajectory;
        docs/optimal-control.md) in the last execute, as summary.json's `reference` block:
        dict with over ("time" or "tau"), start ("reference" or "parent"), rows (result rows
        compared), t_first, t_final [s], position, velocity, mass: each a dict of max,
        t_max, final (m, m/s, kg; s), and end: the reference's last axis value and the
        phase's end on that axis (s, or tau: below 1 when the phase ended before its
        stop_time). LvsimError when the phase has no reference, is stale,
        or ran without rows (execute(keep_rows=False))."""
        k = self.mission.phase_index(phase)
        with self._lock:
            self._not_stale(k)
            d = _lib.lv_ref_drift()
            err = _err()
            check(lib.lv_run_reference_drift(self._handle(), k, byref(d), byref(err)), err)
        return {"over": "tau" if d.over_tau else "time",
                "start": "reference" if d.start_from_reference else "parent",
                "rows": d.n_rows, "t_first": d.t_first, "t_final": d.t_final,
                "position": {"max": d.pos_max, "t_max": d.pos_max_t, "final": d.pos_final},
                "velocity": {"max": d.vel_max, "t_max": d.vel_max_t, "final": d.vel_final},
                "mass": {"max": d.mass_max, "t_max": d.mass_max_t, "final": d.mass_final},
                "end": {"reference": d.ref_end, "phase": d.phase_end}}

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
                units = [text(t.units[i]) or "1" for i in range(nc)]
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
