"""lvsim - mission-dependent sequential simulation of launch vehicles, from Python.

A thin layer over the C library liblvsim through ctypes (no compiler at import time). Every
call into the library releases the GIL (ctypes.CDLL), so missions run in several Python
threads at once. Units are SI (m, s, kg, N, Pa, rad; "NAME_deg" parameters in degrees), each
column's unit travels with it. Documentation: docs/python.md.

    import lvsim
    m = lvsim.Mission("examples/rlv-hthl/mission.yaml")
    run = m.run()                                   # every phase
    ascent = run.result("ascent")                   # PhaseResult: rows, finals, events
    ascent["h"], ascent.unit("h")                   # a column (ndarray), "m"
    run.body("us").to_dataframe()                   # a stage across its phases (pandas)
    run.set("us.propellant_mass", 50000); run.execute()   # only the affected phases rerun

Classes: Mission, Run, PhaseResult, Trajectory, Table, PhaseCall, Outcome, Model, Target,
Optimization, Campaign, Law, Format. Functions: simulate (a built-in model, the paper's Code 1), models, laws
(the steering and throttle laws with their keys, as the library registers them), formats (the
result formats and exports, likewise). Exceptions:
LvsimError, MissionError, ParameterError, SimulationError, CancelledError.
"""
from ._paths import VERSION as __version__
from .errors import (CancelledError, InputError, LvsimError, MissionError, OutputLimitError,
                     ParameterError, SimulationError)
from ._results import Dispersion, Event, Parameter, Phase, PhaseResult, Table, Trajectory
from ._simulate import METHODS, Model, Outcome, PhaseCall, Variable, models, simulate
from ._run import Run
from ._mission import Mission
from ._target import Target, TargetResult
from ._optimize import Optimization, OptimizationResult
from ._campaign import Campaign
from ._laws import Law, LawKey, common_keys, laws
from ._formats import Format, formats

library_path = None


def _library_path():
    """The file liblvsim was loaded from."""
    from . import _lib
    return _lib.lib._name


library_path = _library_path()

__all__ = ["Mission", "Run", "PhaseResult", "Trajectory", "Table", "PhaseCall", "Outcome",
           "Model", "Variable", "Phase", "Parameter", "Dispersion", "Event", "Target",
           "TargetResult", "Campaign", "simulate", "models", "laws", "common_keys", "Law",
           "LawKey", "formats", "Format", "LvsimError", "MissionError",
           "ParameterError", "SimulationError", "CancelledError", "InputError", "OutputLimitError",
           "METHODS", "library_path",
           "__version__"]
