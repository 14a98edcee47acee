"""_optimize.py - optimal control over a mission's phase tree (lv_ocp.h) for Python: the
mission file's `optimal_control:` section solved by direct multiple shooting with IPOPT in C
(the GIL released while it runs). docs/optimal-control.md."""
import threading
from ctypes import byref, c_double, c_void_p, create_string_buffer

from . import _lib
from ._lib import lib, path_arg, text
from .errors import LvsimError, check

OUTCOMES = ("optimal", "infeasible", "not converged", "stopped")


class OptimizationResult:
    """A solve's outcome (lv_ocp_result): `outcome` ("optimal", "infeasible", "not converged",
    "stopped"), `optimal` (bool), `ipopt` (IPOPT's status name), `iterations`, `cost` (the
    cost's final in its unit; NaN without a cost), `cost_start`, `max_violation`, `violated`
    (list of (text, violation) at the point returned, largest first), `n_vars`, `n_cons`,
    `nnz_jac`, `n_groups`, `segments`, `evaluations`, `wall`, `cpu` (s), `last_failure`."""

    def __repr__(self):
        return (f"OptimizationResult(outcome={self.outcome!r}, cost={self.cost!r}, "
                f"iterations={self.iterations})")


class Optimization:
    """An optimal control problem: the `optimal_control:` section of the mission file at
    `path` (lv_ocp_create: the mission is loaded and flown once as written for the start
    point; LvsimError / MissionError when the file or the section is wrong).

        opt = lvsim.Optimization("examples/goddard/mission.yaml")
        res = opt.solve()                       # OptimizationResult
        opt.write("goddard-optimal.yaml")       # the optimal mission and its tables
    """

    def __init__(self, path):
        self._h = None
        self._lock = threading.RLock()
        h = c_void_p()
        err = _lib.lv_err()
        check(lib.lv_ocp_create(path_arg(path, "mission path"), byref(h), byref(err)), err)
        self._h = h
        self._free = lib.lv_ocp_free
        self.path = path

    def _handle(self):
        if self._h is None:
            raise LvsimError("optimization is closed")
        return self._h

    def close(self):
        """Frees the problem. Idempotent."""
        with self._lock:
            if self._h is not None:
                self._free(self._h)
                self._h = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        if getattr(self, "_h", None) is not None:
            self._free(self._h)
            self._h = None

    def solve(self, *, threads=2, max_iterations=0):
        """Solves the NLP (lv_ocp_solve) with `threads` workers for the Jacobian (1 to 15) and
        at most `max_iterations` IPOPT iterations (0: the section's). Returns an
        OptimizationResult; an infeasible or unconverged problem is an outcome, not an
        error."""
        if not isinstance(threads, int) or not 1 <= threads <= 15:
            raise ValueError("threads: an integer from 1 to 15")
        if not isinstance(max_iterations, int) or not 0 <= max_iterations <= 100000:
            raise ValueError("max_iterations: an integer from 0 to 100000")
        with self._lock:
            s = _lib.lv_ocp_settings(threads=threads, max_iterations=max_iterations)
            r = _lib.lv_ocp_result()
            err = _lib.lv_err()
            check(lib.lv_ocp_solve(self._handle(), byref(s), byref(r), byref(err)), err)
            res = OptimizationResult()
            res.outcome = OUTCOMES[r.outcome]
            res.optimal = r.outcome == 0
            res.ipopt = text(r.ipopt_text)
            for f in ("iterations", "cost", "cost_start", "max_violation", "n_vars", "n_cons",
                      "nnz_jac", "n_groups", "segments", "evaluations", "wall", "cpu"):
                setattr(res, f, getattr(r, f))
            res.last_failure = text(r.last_failure)
            res.violated = []
            buf = create_string_buffer(512)
            v = c_double()
            for i in range(r.n_violated):
                check(lib.lv_ocp_violation(self._handle(), i, buf, 512, byref(v), byref(err)),
                      err)
                res.violated.append((text(buf.value), v.value))
            return res

    def phase_times(self, k):
        """(t0, t1) [s] of optimised phase k (its index in run order) at the point returned."""
        if not isinstance(k, int) or k < 0:
            raise ValueError("k: a phase index >= 0")
        t0, t1 = c_double(), c_double()
        err = _lib.lv_err()
        with self._lock:
            check(lib.lv_ocp_phase_times(self._handle(), k, byref(t0), byref(t1), byref(err)),
                  err)
        return t0.value, t1.value

    def write(self, path, *, force=False):
        """Writes the optimal mission at `path` (.yaml) with its controls and reference tables
        beside it (lv_ocp_write); an existing file lvsim optimize did not write is refused
        unless force, and so is a problem whose last solve did not end optimal."""
        err = _lib.lv_err()
        with self._lock:
            check(lib.lv_ocp_write(self._handle(), path_arg(path), 1 if force else 0,
                                   byref(err)), err)
