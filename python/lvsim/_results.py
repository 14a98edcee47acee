"""_results.py - what a mission and its runs describe, for Python: a phase's rows, finals and
events (PhaseResult), a stage's trajectory across its phases (Trajectory), the table both are
(Table), and the mission's phases, parameters and dispersions as records (lv_mission.h,
lv_run.h).

Units are the library's: SI throughout (m, s, kg, N, Pa, rad), each column's unit given with
it. Every array returned is a copy owned by NumPy: it stays valid whatever the run does next.
"""

import numpy as np

from . import _lib
from ._lib import lib, text
from .errors import LvsimError, check

_check = check


PHASE_STATES = {0: "pending", 1: "done", 2: "failed", 3: "skipped", 4: "crashed"}
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
    "1" dimensionless), `values` (float64 ndarray of shape (rows, len(names)), row-major, a
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
        """The unit of column `name` (SI; "1" dimensionless)."""
        self[name]
        return self.units[self._col[name]]

    def to_dataframe(self):
        """A pandas DataFrame of the rows, units in df.attrs["units"] (column -> unit)."""
        return _dataframe(self.names, self.units, self.values)


class Event:
    """One event a phase handled: `t` (s), `name` ("burnout", a table breakpoint...), `kind`
    ("state" or "time"), `direction` (+1 rising, -1 falling, 0 time event), `index` (state
    event function index, -1 for time events), `label` (the user's name of the event,
    `name: MECO` in the mission file, or None)."""

    __slots__ = ("t", "name", "kind", "direction", "index", "label")

    def __init__(self, rec, label=None):
        self.label = label
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
    "event", "failed"), `stop_name` (the event that ended it), `end_label` (the user's name
    of that end, `name:` or `end_name:`, or None), `end_index` (the `end:`
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
        self.events = [Event(rep.event_log[i], text(r.event_labels[i]) if r.event_labels
                             and r.event_labels[i] else None) for i in range(rep.n_event_log)]
        self.end_label = text(r.end_label) if r.end_label else None
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
            for i, (_, ext, _) in enumerate(_lib.RESULT_FORMATS):
                if r.result_formats & (1 << i):
                    self.result_files.append(f"{stem}.failed{ext}" if failed else f"{stem}{ext}")

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
    ("stage2.propellant_mass", "P2.set.theta"), `unit` (SI; "1" dimensionless), `value` (the
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
