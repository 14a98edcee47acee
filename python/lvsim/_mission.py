"""_mission.py - a mission loaded from its file (lv_mission.h) for Python: its phases,
parameters and dispersions, and the runs made from it (_run.py).

Units are the library's: SI throughout (m, s, kg, N, Pa, rad); "NAME_deg" parameters take
degrees. Frames: docs/frames.md (ECI, ECEF, geodetic, NED).
"""
import math
import threading
import weakref
from ctypes import byref, c_double, c_int, c_size_t, c_uint64, c_void_p

import numpy as np

from . import _lib
from ._lib import lib, text, name_arg, path_arg, int_arg, U64_MAX
from .errors import LvsimError, MissionError, ParameterError, check

from ._results import Dispersion, Parameter, Phase, _err
from ._run import Run

_check = check

_DEG = math.pi / 180.0  # rad per degree (LV_DEG)


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
