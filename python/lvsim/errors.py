"""errors.py - the exceptions of the lvsim package. Every one carries the C library's message
unchanged (lv_err.msg: "file:line:column: ..." for a mission file, "phase 'P2': ... t = ..."
for a simulation) and its status code."""
import re

from . import _lib


class LvsimError(Exception):
    """An lvsim call failed. `status` is the C status name ("LV_ERR_INPUT", "LV_ERR_IO",
    "LV_ERR_NOTFOUND", "LV_ERR_SOLVER", "LV_ERR_NOMEM", "LV_ERR_CANCELLED"), `code` its
    number, `message` the library's text (also str(exc))."""

    def __init__(self, message, code=_lib.LV_ERR_INPUT):
        super().__init__(message)
        self.message = message
        self.code = code
        self.status = _lib.STATUS_NAMES.get(code, str(code))


class MissionError(LvsimError):
    """A mission file could not be loaded: YAML syntax, an unknown key, a value out of range,
    a missing table... `file`, `line`, `column` are parsed from the message
    ("path.yaml:12:5: phase 'P2': unknown key 'stop_tme' (did you mean 'stop_time'?)");
    None when the message names no position (a file that cannot be read)."""

    # "FILE:LINE:COLUMN: " where FILE may itself hold ':' (a folder "dir:colon"): the
    # position is the first ":digits:" (and ":digits:") followed by a space after a file name
    # ending in a YAML/CSV extension or not, matched lazily from the left up to that point
    _pos = re.compile(r"^(?P<file>[^\n]+?):(?P<line>\d+):(?:(?P<column>\d+):)? ")

    def __init__(self, message, code=_lib.LV_ERR_INPUT):
        super().__init__(message, code)
        m = self._pos.match(message)
        self.file = m.group("file") if m else None
        self.line = int(m.group("line")) if m else None
        self.column = int(m.group("column")) if m and m.group("column") else None


class ParameterError(LvsimError, ValueError):
    """A run parameter that does not exist (status LV_ERR_NOTFOUND, the message suggests the
    nearest names) or a value outside its range (LV_ERR_INPUT, the message gives the rule)."""


class SimulationError(LvsimError):
    """A run in which some phases failed. Nothing is lost: the phases that succeeded keep
    their results on `run`. `failed` maps each failed phase's name to its message (phase,
    time, reason: "phase 'P3': t = 41.2 s: ..."), `skipped` lists the phases not run because
    an ancestor failed, `done` the phases that succeeded."""

    def __init__(self, message, code, run, failed, skipped, done):
        super().__init__(message, code)
        self.run = run
        self.failed = failed
        self.skipped = skipped
        self.done = done


class InputError(LvsimError, ValueError):
    """An argument out of its range (a tolerance <= 0, an unknown method, a negative count):
    raised before anything runs, the message naming the argument (status LV_ERR_INPUT). A
    ValueError too; an argument of the wrong type is a TypeError."""


class OutputLimitError(InputError):
    """A run would write more output rows than allowed (Run.execute's max_rows, the CLI's
    --max-rows): refused before anything runs; the message names the phase, its rows and
    the max_rows that would allow it."""


class CancelledError(LvsimError):
    """A progress callback asked to stop (status LV_ERR_CANCELLED)."""


def check(status, err, cls=LvsimError):
    """Raises `cls` (CancelledError for LV_ERR_CANCELLED) with err's message unless status is
    LV_OK."""
    if status == _lib.LV_OK:
        return
    msg = err.msg.decode("utf-8", "replace") if err is not None else ""
    if not msg:
        msg = _lib.text(_lib.lib.lv_status_str(status))
    if status == _lib.LV_ERR_CANCELLED:
        raise CancelledError(msg, status)
    raise cls(msg, status)
