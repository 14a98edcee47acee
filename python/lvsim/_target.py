"""_target.py - targeting and optimisation over a mission's runs (lv_target.h) for Python:
the mission file's `targeting:` section or a problem built here, solved by damped Newton,
NLopt's SLSQP or COBYLA in C (the GIL released while it runs). docs/targeting.md."""
import threading
from ctypes import POINTER, byref, c_double, c_void_p

from . import _lib
from ._lib import lib, name_arg, path_arg, real_arg, text
from ._run import Run
from .errors import LvsimError, check

METHODS = {"auto": 0, "newton": 1, "slsqp": 2, "cobyla": 3}
DIFFERENCES = {"auto": 0, "forward": 1, "central": 2}
KINDS = {"equal": 0, "min": 1, "max": 2}


class TargetResult:
    """A solve's outcome (lv_target_result): `converged` (every constraint met, and for an
    optimiser a local optimum), `cancelled`, `reason` (one sentence), `method` ("newton",
    "newton+slsqp"...), `x` (dict variable -> value in the variable's unit: degrees for a
    *_deg name, else SI), `finals` (dict constraint -> value), `residual` (dict constraint ->
    residual in tolerances), `met` (dict constraint -> bool), `cost` (NaN without a cost),
    `worst` (max |residual|), `iterations`, `runs`, `phases` (phase simulations), `wall` (s),
    `end_mismatches`: the phases that ended at `x` otherwise than the constraints assume (a
    list of dicts with `phase`, `expected` and `actual` (end names: "sma", "burnout",
    "stop_time") and `t_end` (s)), empty when every checked phase ended as assumed: a point
    met on another trajectory than the one targeted (docs/targeting.md)."""

    def __repr__(self):
        return (f"TargetResult(converged={self.converged}, method={self.method!r}, "
                f"iterations={self.iterations}, x={self.x!r})")


class _TargetRun(Run):
    """The target's own run (lv_target_run): owned by the target, never freed here."""

    def __init__(self, target, h):  # no lv_run_create
        self._h = h
        self._pending = None
        self._lock = threading.RLock()
        self._target = target  # keeps the target (the run's owner) alive
        self.mission = target.mission
        self._ran_with = {}
        self._stage_map = None

    def _dispose(self):  # the target frees its run (lv_target_free)
        self._h = None


class Target:
    """A targeting problem over a mission (lv_target_create / lv_target_create_empty).

        t = mission.target()                      # the file's `targeting:` section
        res = t.solve()                           # TargetResult
        t.run.result("us-ascent").finals          # the converged point's phases

    `variables` (list of dicts: name, unit, lo, hi, start, scale, step), `constraints` (name,
    unit, phase, kind "equal"/"min"/"max", value, tol), `cost` (dict or None). Not for two
    threads at once (a lock serialises); separate targets of one mission may solve in
    parallel threads."""

    def __init__(self, mission, from_file=True):
        self._h = None
        self._lock = threading.RLock()
        self.mission = mission
        h = c_void_p()
        err = _lib.lv_err()
        fn = lib.lv_target_create if from_file else lib.lv_target_create_empty
        check(fn(mission._handle(), byref(h), byref(err)), err)
        self._h = h
        self._free = lib.lv_target_free
        self._run = None
        self._result = None
        mission._acquire()  # borrows the mission (see Mission._acquire)
        mission._runs.add(self)  # closed with the mission

    def _handle(self):
        if self._h is None:
            raise LvsimError("target is closed")
        return self._h

    def close(self):
        """Frees the target (and its run). Idempotent."""
        with self._lock:
            if self._run is not None:
                self._run._h = None
                self._run = None
            if self._h is not None:
                self._free(self._h)
                self._h = None
                self.mission._release()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        if getattr(self, "_h", None) is not None:
            self._free(self._h)
            self._h = None
            self.mission._release()

    # ---- the problem ----
    def add_variable(self, name, lo, hi, start=float("nan"), scale=float("nan"),
                     step=float("nan")):
        """A variable: run parameter `name` ("P1.guidance.kick_deg": degrees; else SI)
        within [lo, hi]; start NaN: the file's value; scale/step NaN: from the bounds.
        TypeError for a name that is not a str or a bound that is not a number."""
        b = name_arg(name, "variable name")
        lo, hi = real_arg(lo, "lo"), real_arg(hi, "hi")
        start, scale, step = real_arg(start, "start"), real_arg(scale, "scale"), real_arg(step, "step")
        with self._lock:
            err = _lib.lv_err()
            check(lib.lv_target_add_var(self._handle(), b, lo, hi, start, scale, step,
                                        byref(err)), err)

    def add_constraint(self, final, kind, value, tol, end=None):
        """A constraint on final value "PHASE.NAME" ("us-ascent.peri_alt"; "_deg" for an
        angle in degrees): kind "equal", "min" or "max" `value`, met within `tol` > 0. `end`:
        the end the phase is assumed to end by (set_end); None: its first end written."""
        b = name_arg(final, "constraint final")
        if kind not in KINDS:
            raise LvsimError(f"constraint kind '{kind}': equal, min or max", _lib.LV_ERR_INPUT)
        value, tol = real_arg(value, "value"), real_arg(tol, "tol")
        e = None if end is None else name_arg(end, "end")
        with self._lock:
            err = _lib.lv_err()
            check(lib.lv_target_add_con(self._handle(), b, KINDS[kind], value, tol,
                                        byref(err)), err)
        if e is not None:
            self.set_end(final.split(".", 1)[0], end)

    def set_end(self, phase, end):
        """The end `phase` is assumed to end by (lv_target_set_end): one of its `end:` entries
        by name ("sma", "burnout", "altitude_2"), "stop_time" or "any" (not checked). By
        default each phase a constraint or the cost reads is assumed to end by its first end
        written; the result's `end_mismatches` lists those that ended otherwise."""
        p, e = name_arg(phase, "phase"), name_arg(end, "end")
        with self._lock:
            err = _lib.lv_err()
            check(lib.lv_target_set_end(self._handle(), p, e, byref(err)), err)

    def set_cost(self, final, maximize=True, scale=float("nan"), end=None):
        """The cost: final "PHASE.NAME" maximised (or minimised); scale: a significant
        change (NaN: from the start point); end: as add_constraint's."""
        b = name_arg(final, "cost final")
        scale = real_arg(scale, "scale")
        e = None if end is None else name_arg(end, "end")
        with self._lock:
            err = _lib.lv_err()
            check(lib.lv_target_set_cost(self._handle(), b, 1 if maximize else 0,
                                         scale, byref(err)), err)
        if e is not None:
            self.set_end(final.split(".", 1)[0], end)

    @property
    def variables(self):
        """The variables, in order: a list of dicts with `name` (the run parameter; "_deg":
        degrees), `unit`, `lo`, `hi` (bounds), `start` (NaN: the file's value), `scale` (a
        significant change) and `step` (the finite-difference step), in the variable's unit."""
        out = []
        with self._lock:
            for i in range(lib.lv_target_var_count(self._handle())):
                v = _lib.lv_target_var_info()
                lib.lv_target_var_info_get(self._h, i, byref(v))
                out.append(dict(name=text(v.name), unit=text(v.unit), lo=v.lo, hi=v.hi,
                                start=v.start, scale=v.scale, step=v.step))
        return out

    @property
    def constraints(self):
        """The constraints, in order: a list of dicts with `name` ("PHASE.FINAL"), `unit`,
        `phase` (the phase whose final it is), `kind` ("equal", "min", "max"), `value` (the
        target or bound) and `tol` (met within it), in the final's unit."""
        kinds = {v: k for k, v in KINDS.items()}
        out = []
        with self._lock:
            for i in range(lib.lv_target_con_count(self._handle())):
                c = _lib.lv_target_con_info()
                lib.lv_target_con_info_get(self._h, i, byref(c))
                out.append(dict(name=text(c.name), unit=text(c.unit),
                                phase=self.mission.phases[c.phase].name,
                                kind=kinds.get(c.kind, str(c.kind)), value=c.value, tol=c.tol))
        return out

    @property
    def cost(self):
        """The cost, or None: a dict with `name` ("PHASE.FINAL"), `unit`, `phase`,
        `maximize` (bool) and `scale` (a significant change)."""
        with self._lock:
            c = _lib.lv_target_cost_info()
            lib.lv_target_cost_info_get(self._handle(), byref(c))
        if not c.present:
            return None
        return dict(name=text(c.name), unit=text(c.unit),
                    phase=self.mission.phases[c.phase].name, maximize=bool(c.maximize),
                    scale=c.scale)

    # ---- solving ----
    def solve(self, *, method=None, differences=None, max_iterations=0, xtol=0.0, ftol=0.0,
              restarts=0, threads=0, on_iteration=None):
        """Solves (lv_target_solve) and returns a TargetResult, met or not (`converged`).
        method: "auto", "newton", "slsqp", "cobyla" (None: the file's); differences: "auto",
        "forward", "central"; 0 / None: the file's or the library's defaults (docs/
        targeting.md). on_iteration(dict) is called at each iteration (iteration, solver,
        event, note, x, finals, residual, cost, worst, ...). LvsimError (LV_ERR_SOLVER) when
        the start point itself fails, with the phase and why."""
        s = _lib.lv_target_settings()
        lib.lv_target_settings_default(byref(s))
        if method is not None:
            if method not in METHODS:
                raise LvsimError(f"method '{method}': {', '.join(METHODS)}", _lib.LV_ERR_INPUT)
            s.method = METHODS[method]
        if differences is not None:
            if differences not in DIFFERENCES:
                raise LvsimError(f"differences '{differences}': {', '.join(DIFFERENCES)}", _lib.LV_ERR_INPUT)
            s.differences = DIFFERENCES[differences]
        s.max_iterations, s.xtol, s.ftol = int(max_iterations), float(xtol), float(ftol)
        s.restarts, s.threads = int(restarts), int(threads)
        names = [v["name"] for v in self.variables]
        cons = [c["name"] for c in self.constraints]
        state = {}
        if on_iteration is not None:
            def _it(t, it, user):
                if "exc" in state:
                    return
                i = it.contents
                try:
                    on_iteration(dict(
                        iteration=i.iteration, solver=text(i.solver), event=text(i.event),
                        note=text(i.note), x={n: i.x[j] for j, n in enumerate(names)},
                        finals={n: i.finals[j] for j, n in enumerate(cons)},
                        residual={n: i.residual[j] for j, n in enumerate(cons)},
                        cost=i.cost, worst=i.worst, damping=i.damping, step=i.step,
                        runs_total=i.runs_total, phases_total=i.phases_total, wall=i.wall))
                except BaseException as exc:  # raised after the solve
                    state["exc"] = exc
            cb = _lib.TARGET_ITER_FN(_it)
            s.on_iteration = cb
        out = POINTER(_lib.lv_target_result)()
        err = _lib.lv_err()
        with self._lock:
            st = lib.lv_target_solve(self._handle(), byref(s), byref(out), byref(err))
            if "exc" in state:
                raise state["exc"]
            check(st, err)
            r = out.contents
            res = TargetResult()
            res.converged, res.cancelled = bool(r.converged), bool(r.cancelled)
            res.reason = r.reason.decode("utf-8", "replace")
            res.method = text(r.method)
            res.x = {n: r.x[j] for j, n in enumerate(names)}
            res.finals = {n: r.finals[j] for j, n in enumerate(cons)}
            res.residual = {n: r.residual[j] for j, n in enumerate(cons)}
            res.met = {n: bool(r.met[j]) for j, n in enumerate(cons)}
            res.cost, res.worst = r.cost, r.worst
            res.iterations, res.runs, res.phases, res.wall = r.iterations, r.runs, r.phases, r.wall
            res.end_mismatches = [dict(phase=text(e.phase_name), expected=text(e.expected),
                                       actual=text(e.actual), t_end=e.t_end)
                                  for e in (r.end_mismatch[i] for i in range(r.n_end_mismatch))]
            self._result = res
        return res

    @property
    def run(self):
        """The run holding the last point evaluated (after a solve: the result's point; after
        a cancelled one the last point tried, whose phases may have been cut short), as a Run
        (owned by the target; valid until it is closed). LvsimError before solve()."""
        with self._lock:
            h = lib.lv_target_run(self._handle())
            if not h or self._result is None:
                raise LvsimError("the target has evaluated no point yet: solve() first", _lib.LV_ERR_INPUT)
            if self._run is None or self._run._h is None or self._run._h.value != h:
                self._run = _TargetRun(self, c_void_p(h))
            return self._run

    def write(self, path, x=None):
        """Writes the mission file with the variables set to `x` (dict name -> value;
        default: the last solve's point), comments and layout kept, then checks that the
        written file reproduces the finals (lv_target_write). Returns the largest
        difference in tolerances. LvsimError (LV_ERR_INPUT, LV_ERR_IO, LV_ERR_SOLVER)."""
        names = [v["name"] for v in self.variables]
        if x is None:
            if self._result is None:
                raise LvsimError("no point to write: solve() first or pass x", _lib.LV_ERR_INPUT)
            x = self._result.x
        missing = [n for n in names if n not in x]
        if missing:
            raise LvsimError(f"x has no value for {', '.join(missing)}", _lib.LV_ERR_INPUT)
        arr = (c_double * max(1, len(names)))(*[float(x[n]) for n in names])
        worst = c_double()
        err = _lib.lv_err()
        with self._lock:
            check(lib.lv_target_write(self._handle(), arr, path_arg(path, "path"), byref(worst),
                                      byref(err)),
                  err)
        return worst.value
