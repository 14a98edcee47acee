"""_lib.py - the C libraries through ctypes: loading, the structures of the public headers
(include/lvsim/*.h) mirrored field by field, and the functions' prototypes.

The structures are written by hand, in the headers' order: ctypes has no header parser, and
Debian ships no cffi/ctypesgen that would read them at build time without a compiler at import
time. tests/python/test_python.py checks every mirrored structure's size and field offsets
against a C program compiled from the real headers (tests/python/py_layout.c), and
tests/python/check_signatures.py every function prototype set here against the headers' LV_API
declarations, so a header change that is not made here too fails the suite. The status codes
are not re-typed: they come from the library (lv_status_name).

Calls go through ctypes.CDLL, which releases the GIL for the duration of every foreign call
(ctypes.PyDLL would hold it): a mission run in one Python thread lets the others go on.
"""
import ctypes
import os
from ctypes import (CFUNCTYPE, POINTER, Structure, c_char, c_char_p, c_double, c_int,
                    c_long, c_size_t, c_ubyte, c_uint, c_uint64, c_void_p)

from . import _paths

LV_ERR_MSG_MAX = 1024
LV_EVENT_NAME_MAX = 96

LV_TOLERANCE_MIN = 1e-14  # lv_sim.h: the relative tolerances lv_simulate accepts
LV_TOLERANCE_MAX = 0.1
LV_RUN_NO_PHASE_FILES = 0x100
LV_RUN_ALL_PHASES = (1 << (8 * ctypes.sizeof(c_size_t))) - 1


class lv_err(Structure):
    _fields_ = [("code", c_int), ("msg", c_char * LV_ERR_MSG_MAX)]


class lv_var(Structure):
    _fields_ = [("name", c_char_p), ("unit", c_char_p), ("description", c_char_p),
                ("start", c_double), ("nominal", c_double)]


class lv_event_def(Structure):
    _fields_ = [("name", c_char_p), ("description", c_char_p), ("direction", c_int),
                ("ends_run", c_int)]


class lv_model_def(Structure):
    # only the leading fields are read (names and counts of the variables); the callbacks
    # after them are never called from Python, so the structure is not mirrored past them
    _fields_ = [("name", c_char_p), ("description", c_char_p),
                ("n_states", c_size_t), ("n_params", c_size_t), ("n_outputs", c_size_t),
                ("n_events", c_size_t),
                ("states", POINTER(lv_var)), ("params", POINTER(lv_var)),
                ("outputs", POINTER(lv_var)), ("events", POINTER(lv_event_def)),
                ("inst_size", c_size_t)]


class lv_mission_info(Structure):
    _fields_ = [("name", c_char_p), ("description", c_char_p), ("path", c_char_p),
                ("epoch", c_char_p), ("flat_world", c_int), ("planet", c_char_p),
                ("site_lat", c_double), ("site_lon", c_double),
                ("n_phases", c_size_t), ("n_stages", c_size_t), ("n_params", c_size_t)]


class lv_phase_info(Structure):
    _fields_ = [("name", c_char_p), ("model", c_char_p), ("parent", c_int),
                ("n_stages", c_size_t), ("stages", POINTER(c_size_t)), ("method", c_char_p),
                ("file_index", c_size_t), ("handoff_rule", c_char_p)]


class lv_param_info(Structure):
    _fields_ = [("name", c_char_p), ("unit", c_char_p), ("value", c_double), ("line", c_int),
                ("rule", c_char_p)]


class lv_sim_stats(Structure):
    _fields_ = [("steps", c_long), ("rhs_evals", c_long), ("jac_evals", c_long),
                ("err_test_fails", c_long), ("nonlin_fails", c_long), ("g_evals", c_long),
                ("state_events", c_long), ("time_events", c_long), ("restarts", c_long),
                ("output_rows", c_long), ("cpu_time", c_double),
                ("rhs_evals_steps", c_long), ("rhs_evals_output", c_long),
                ("row_evals", c_long)]


class lv_event_record(Structure):
    _fields_ = [("t", c_double), ("is_state", c_int), ("index", c_int), ("direction", c_int),
                ("name", c_char * LV_EVENT_NAME_MAX)]


class lv_sim_report(Structure):
    _fields_ = [("stats", lv_sim_stats), ("reason", c_int), ("end_time", c_double),
                ("stop_event", c_int), ("stop_name", c_char * LV_EVENT_NAME_MAX),
                ("n_states", c_size_t), ("n_event_log", c_size_t),
                ("event_log", POINTER(lv_event_record)),
                ("method_used", c_char * LV_EVENT_NAME_MAX),
                ("method_why", c_char * LV_EVENT_NAME_MAX)]


class lv_phase_result(Structure):
    _fields_ = [("name", c_char_p), ("state", c_int), ("error", c_char * LV_ERR_MSG_MAX),
                ("t_start", c_double), ("t_end", c_double), ("t_stop", c_double),
                ("method", c_char_p), ("tolerance", c_double), ("report", lv_sim_report),
                ("end_index", c_int), ("end_value", c_double),
                ("n_final", c_size_t), ("final_names", POINTER(c_char_p)),
                ("final_values", POINTER(c_double)), ("result_stem", c_char_p),
                ("n_event_names", c_size_t), ("event_names", POINTER(c_char_p)),
                ("n_copied", c_size_t), ("mass_from_stages", c_double),
                ("mass_start", c_double), ("n_set", c_size_t),
                ("set_names", POINTER(c_char_p)), ("set_values", POINTER(c_double)),
                ("propellant_start", POINTER(c_double)), ("propellant_end", POINTER(c_double)),
                ("dry_mass", POINTER(c_double)), ("payload", c_double),
                ("result_formats", c_uint), ("n_absorbed", c_size_t),
                ("absorbed_names", POINTER(c_char_p)), ("absorbed_units", POINTER(c_char_p)),
                ("absorbed_values", POINTER(c_double)),
                ("end_label", c_char_p), ("event_labels", POINTER(c_char_p))]


ON_PHASE_FN = CFUNCTYPE(None, c_void_p, c_size_t, POINTER(lv_phase_result), c_void_p)
RUN_PROGRESS_FN = CFUNCTYPE(c_int, c_void_p, c_size_t, c_double, c_void_p)


class lv_run_options(Structure):
    _fields_ = [("outdir", c_char_p), ("threads", c_int), ("on_phase", ON_PHASE_FN),
                ("user", c_void_p), ("output_interval", c_double), ("method", c_char_p),
                ("tolerance", c_double), ("progress", RUN_PROGRESS_FN), ("no_rows", c_int),
                ("result_formats", c_uint), ("want", POINTER(c_ubyte)),
                ("stop", POINTER(c_int)), ("max_rows", c_double)]


class lv_body_traj(Structure):
    _fields_ = [("stage", c_char_p), ("n_rows", c_size_t), ("n_cols", c_size_t),
                ("names", POINTER(c_char_p)), ("units", POINTER(c_char_p)),
                ("values", POINTER(c_double)), ("phase", POINTER(c_size_t))]


class lv_sink(Structure):
    _fields_ = [("vt", c_void_p), ("self", c_void_p)]


class lv_sim_stop(Structure):
    _fields_ = [("name", c_char_p), ("variable", c_char_p), ("value", c_double),
                ("direction", c_int)]


SIM_PROGRESS_FN = CFUNCTYPE(c_int, c_double, c_void_p)


class lv_sim_settings(Structure):
    _fields_ = [("start_time", c_double), ("stop_time", c_double),
                ("number_of_intervals", c_int), ("output_interval", c_double),
                ("method", c_char_p), ("tolerance", c_double), ("fixed_step", c_double),
                ("result_file", c_char_p), ("result_formats", c_uint),
                ("n_initial", c_size_t), ("initial_names", POINTER(c_char_p)),
                ("initial_values", POINTER(c_double)),
                ("n_final", c_size_t), ("final_names", POINTER(c_char_p)),
                ("max_steps", c_long), ("max_step_size", c_double),
                ("n_sinks", c_size_t), ("sinks", POINTER(lv_sink)),
                ("progress", SIM_PROGRESS_FN), ("progress_user", c_void_p),
                ("n_stops", c_size_t), ("stops", POINTER(lv_sim_stop)),
                ("stop", POINTER(c_int)), ("max_rows", c_double)]


# ---- targeting (lv_target.h) --------------------------------------------------------------

class lv_target_var_info(Structure):
    _fields_ = [("name", c_char_p), ("unit", c_char_p), ("param", c_size_t), ("deg", c_int),
                ("lo", c_double), ("hi", c_double), ("start", c_double), ("scale", c_double),
                ("step", c_double)]


class lv_target_con_info(Structure):
    _fields_ = [("name", c_char_p), ("unit", c_char_p), ("phase", c_size_t), ("kind", c_int),
                ("value", c_double), ("tol", c_double)]


class lv_target_cost_info(Structure):
    _fields_ = [("present", c_int), ("name", c_char_p), ("unit", c_char_p),
                ("phase", c_size_t), ("maximize", c_int), ("scale", c_double)]


class lv_target_iter(Structure):
    _fields_ = [("iteration", c_size_t), ("solver", c_char_p), ("event", c_char_p),
                ("note", c_char_p), ("x", POINTER(c_double)), ("finals", POINTER(c_double)),
                ("residual", POINTER(c_double)), ("cost", c_double), ("worst", c_double),
                ("damping", c_double), ("step", c_double), ("runs", c_size_t),
                ("phases", c_size_t), ("runs_total", c_size_t), ("phases_total", c_size_t),
                ("wall", c_double)]


class lv_target_eval(Structure):
    _fields_ = [("iteration", c_size_t), ("purpose", c_char_p), ("var", c_char_p),
                ("runs_total", c_size_t), ("phases_total", c_size_t), ("wall", c_double)]


TARGET_ITER_FN = CFUNCTYPE(None, c_void_p, POINTER(lv_target_iter), c_void_p)
TARGET_EVAL_FN = CFUNCTYPE(c_int, c_void_p, POINTER(lv_target_eval), c_void_p)


class lv_target_settings(Structure):
    _fields_ = [("method", c_int), ("differences", c_int), ("max_iterations", c_int),
                ("xtol", c_double), ("ftol", c_double), ("restarts", c_int),
                ("threads", c_int), ("on_iteration", TARGET_ITER_FN),
                ("on_evaluation", TARGET_EVAL_FN), ("user", c_void_p),
                ("stop", POINTER(c_int)), ("max_rows", c_double)]


class lv_target_end_mismatch(Structure):
    _fields_ = [("phase", c_size_t), ("phase_name", c_char_p), ("expected", c_char_p),
                ("actual", c_char_p), ("t_end", c_double)]


class lv_target_result(Structure):
    _fields_ = [("converged", c_int), ("cancelled", c_int),
                ("reason", c_char * LV_ERR_MSG_MAX), ("method", c_char_p),
                ("n_vars", c_size_t), ("n_cons", c_size_t), ("x", POINTER(c_double)),
                ("finals", POINTER(c_double)), ("residual", POINTER(c_double)),
                ("met", POINTER(c_int)), ("cost", c_double), ("worst", c_double),
                ("iterations", c_size_t), ("runs", c_size_t), ("phases", c_size_t),
                ("wall", c_double), ("n_end_mismatch", c_size_t),
                ("end_mismatch", POINTER(lv_target_end_mismatch))]


# ---- optimal control (lv_ocp.h) -------------------------------------------------------------

class lv_ocp_iteration(Structure):
    _fields_ = [("iteration", c_int), ("cost", c_double), ("inf_pr", c_double),
                ("inf_du", c_double), ("mu", c_double), ("step", c_double), ("wall", c_double),
                ("segments", c_long), ("restoration", c_int)]


OCP_ITER_FN = CFUNCTYPE(c_int, POINTER(lv_ocp_iteration), c_void_p)


class lv_ocp_settings(Structure):
    _fields_ = [("threads", c_int), ("max_iterations", c_int), ("print_level", c_int),
                ("on_iteration", OCP_ITER_FN), ("user", c_void_p), ("stop", POINTER(c_int))]


class lv_ocp_result(Structure):
    _fields_ = [("outcome", c_int), ("ipopt_status", c_int), ("ipopt_text", c_char * 80),
                ("iterations", c_int), ("cost", c_double), ("cost_start", c_double),
                ("max_violation", c_double), ("n_violated", c_size_t), ("n_vars", c_size_t),
                ("n_cons", c_size_t), ("nnz_jac", c_size_t), ("n_groups", c_size_t),
                ("segments", c_long), ("evaluations", c_long), ("wall", c_double),
                ("cpu", c_double), ("wall_jac", c_double), ("wall_eval", c_double),
                ("last_failure", c_char * 512)]


# ---- dispersions and campaigns (lv_dispersion.h, lv_campaign.h) ----------------------------

class lv_disp_info(Structure):
    _fields_ = [("name", c_char_p), ("unit", c_char_p), ("dist", c_char_p), ("kind", c_int),
                ("relative", c_int), ("nominal", c_double), ("mean", c_double),
                ("sigma", c_double), ("min", c_double), ("max", c_double),
                ("param", c_size_t), ("group", c_int), ("stream", c_uint64),
                ("line", c_int), ("column", c_int)]


class lv_campaign_progress(Structure):
    _fields_ = [("total", c_uint64), ("done", c_uint64), ("this_session", c_uint64),
                ("failed", c_uint64), ("elapsed", c_double), ("rate", c_double),
                ("eta", c_double), ("impacts", c_uint64), ("crashed", c_uint64)]


CAMPAIGN_PROGRESS_FN = CFUNCTYPE(None, POINTER(lv_campaign_progress), c_void_p)


class lv_campaign_options(Structure):
    _fields_ = [("n_runs", c_uint64), ("seed", c_uint64), ("threads", c_int),
                ("db_path", c_char_p), ("resume", c_int), ("overwrite", c_int),
                ("keep_runs", c_uint64), ("keep_dir", c_char_p), ("method", c_char_p),
                ("tolerance", c_double), ("output_interval", c_double),
                ("progress", CAMPAIGN_PROGRESS_FN), ("user", c_void_p),
                ("stop", POINTER(c_int)), ("max_rows", c_double)]


class lv_output_estimate(Structure):
    _fields_ = [("duration", c_double), ("rows", c_double), ("n_signals", c_size_t),
                ("bytes_mat", c_double), ("bytes_csv", c_double), ("bounded", c_int)]


class lv_outdir_record(Structure):
    _fields_ = [("command", c_char_p), ("status", c_char_p), ("mission_name", c_char_p),
                ("n_notes", c_size_t), ("notes", POINTER(c_char_p))]


class lv_law_key(Structure):  # lv_guidance.h: a key of a steering or throttle law
    _fields_ = [("name", c_char_p), ("type", c_int), ("unit", c_char_p), ("lo", c_double),
                ("hi", c_double), ("lo_open", c_int), ("hi_open", c_int), ("dflt", c_double),
                ("flags", c_uint), ("frames", c_uint), ("instead_of", c_char_p),
                ("needs", c_char_p), ("choices", POINTER(c_char_p)), ("offset", c_size_t),
                ("description", c_char_p)]


class lv_law_info(Structure):
    _fields_ = [("name", c_char_p), ("description", c_char_p), ("kind", c_int), ("form", c_int),
                ("needs_aero", c_char_p), ("n_keys", c_size_t), ("keys", POINTER(lv_law_key))]


class lv_ref_drift(Structure):
    _fields_ = [("n_rows", c_size_t), ("over_tau", c_int), ("start_from_reference", c_int),
                ("t_first", c_double), ("t_final", c_double),
                ("pos_max", c_double), ("pos_max_t", c_double), ("pos_final", c_double),
                ("vel_max", c_double), ("vel_max_t", c_double), ("vel_final", c_double),
                ("mass_max", c_double), ("mass_max_t", c_double), ("mass_final", c_double),
                ("ref_end", c_double), ("phase_end", c_double)]


# The structures the layout test compares with the C compiler's view of the headers.
MIRRORED = [lv_err, lv_var, lv_event_def, lv_mission_info, lv_phase_info, lv_param_info,
            lv_sim_stats, lv_event_record, lv_sim_report, lv_phase_result, lv_run_options,
            lv_body_traj, lv_sink, lv_sim_stop, lv_sim_settings, lv_target_var_info,
            lv_target_con_info, lv_target_cost_info, lv_target_iter, lv_target_eval,
            lv_target_settings, lv_target_end_mismatch, lv_target_result, lv_ocp_iteration,
            lv_ocp_settings, lv_ocp_result, lv_disp_info, lv_campaign_progress,
            lv_campaign_options, lv_output_estimate, lv_outdir_record, lv_law_key, lv_law_info,
            lv_ref_drift]
# lv_model_def is mirrored only up to inst_size: its leading offsets are checked, not its size.
PARTIAL = [lv_model_def]

# ---- loading ------------------------------------------------------------------------------

_here = os.path.dirname(os.path.abspath(__file__))


def _candidates(soname):
    """Where the library is looked for, in order: $LVSIM_LIBRARY_DIR alone when it is set
    (a folder that does not hold the library is an error, never a silent fall-back to
    another copy), else the library folder relative to this package (the build tree's or
    the installation's layout), the folder it was built or installed in, then the dynamic
    loader's own search (LD_LIBRARY_PATH, ld.so.cache)."""
    env = os.environ.get("LVSIM_LIBRARY_DIR")
    if env:
        return [os.path.join(env, soname)], False
    out = [os.path.normpath(os.path.join(_here, _paths.LIBDIR_REL, soname))]
    if _paths.LIBDIR_ABS:
        out.append(os.path.join(_paths.LIBDIR_ABS, soname))
    return out, True


def _load(soname):
    tried = []
    paths, loader = _candidates(soname)
    for path in paths:
        if os.path.exists(path):
            try:
                return ctypes.CDLL(path)
            except OSError as e:
                tried.append(f"{path}: {e}")
        else:
            tried.append(f"{path}: not found")
    if not loader:
        raise ImportError(f"lvsim: LVSIM_LIBRARY_DIR={os.environ.get('LVSIM_LIBRARY_DIR')!r} "
                          f"does not hold a loadable {soname} (" + "; ".join(tried)
                          + "); unset it to use the library the package was built with")
    try:
        return ctypes.CDLL(soname)
    except OSError as e:
        tried.append(f"{soname} (dynamic loader): {e}")
    raise ImportError(f"lvsim: cannot load {soname}; tried " + "; ".join(tried)
                      + " (set LVSIM_LIBRARY_DIR to the folder holding it)")


def _check_abi(dll):
    """The library must be the one this package mirrors: same version (lv_version) and every
    mirrored structure the same size as the library was compiled with (lv_abi_sizeof).
    ImportError naming the file and the first mismatch otherwise."""
    where = getattr(dll, "_name", "liblvsim")
    try:
        ver = dll.lv_version
        size = dll.lv_abi_sizeof
    except AttributeError:
        raise ImportError(f"lvsim {_paths.VERSION}: {where} is too old for this package "
                          "(it has no lv_version/lv_abi_sizeof); rebuild or reinstall lvsim, "
                          "or point LVSIM_LIBRARY_DIR at the matching library") from None
    ver.restype, ver.argtypes = c_char_p, []
    size.restype, size.argtypes = c_size_t, [c_char_p]
    v = ver().decode("utf-8", "replace")
    if v != _paths.VERSION:
        raise ImportError(f"lvsim: the package is version {_paths.VERSION} but {where} is "
                          f"version {v}; install matching versions")
    for st in MIRRORED:
        n = size(st.__name__.encode())
        if n != ctypes.sizeof(st):
            raise ImportError(f"lvsim: {where} does not match this package: struct "
                              f"{st.__name__} is {n} bytes in the library, "
                              f"{ctypes.sizeof(st)} in python/lvsim/_lib.py; rebuild both "
                              "from the same sources")


lib = _load(_paths.SONAME)
_check_abi(lib)
_post = None


def post():
    """liblvsim_post (Monte Carlo campaigns), loaded on first use from the folder liblvsim
    came from."""
    global _post
    if _post is None:
        _post = _load(_paths.POST_SONAME)
        _proto(_post, "lv_campaign_options_default", None, POINTER(lv_campaign_options))
        _proto(_post, "lv_export_format_info", c_char_p, c_size_t, POINTER(c_char_p),
               POINTER(c_char_p))
        _proto(_post, "lv_campaign_run", c_int, c_void_p, POINTER(lv_campaign_options),
               POINTER(lv_campaign_progress), POINTER(lv_err))
        _proto(_post, "lv_campaign_stats", c_int, c_char_p, c_char_p, POINTER(lv_err))
        _proto(_post, "lv_campaign_check_size", c_int, c_void_p, POINTER(lv_campaign_options),
               c_int, c_void_p, POINTER(lv_err))
        _proto(_post, "lv_outdir_begin", c_int, c_char_p, c_char_p, c_uint, POINTER(c_void_p),
               POINTER(lv_err))
        _proto(_post, "lv_outdir_open_live", c_int, c_char_p, c_char_p, c_uint,
               POINTER(c_char_p), POINTER(c_void_p), POINTER(lv_err))
        _proto(_post, "lv_outdir_stage", c_int, c_void_p, POINTER(lv_err))
        _proto(_post, "lv_outdir_path", c_char_p, c_void_p)
        _proto(_post, "lv_outdir_final", c_char_p, c_void_p)
        _proto(_post, "lv_outdir_commit", c_int, c_void_p, POINTER(lv_outdir_record),
               POINTER(lv_err))
        _proto(_post, "lv_outdir_free", None, c_void_p)
    return _post


def _proto(dll, name, restype, *argtypes):
    f = getattr(dll, name)
    f.restype = restype
    f.argtypes = list(argtypes)


E = POINTER(lv_err)
P = c_void_p
_proto(lib, "lv_status_str", c_char_p, c_int)
_proto(lib, "lv_status_name", c_char_p, c_int)
_proto(lib, "lv_result_format_info", c_char_p, c_size_t, POINTER(c_char_p), POINTER(c_char_p))


def format_table(info):
    """A format table of the library, [(name, file, description), ...] in flag order (entry i
    is the flag 1 << i): lv_result_format_info (file: the extension, ".mat") or
    lv_export_format_info (file: what it writes, "mission.czml")."""
    out = []
    f, d = c_char_p(), c_char_p()
    while True:
        name = info(len(out), ctypes.byref(f), ctypes.byref(d))
        if name is None:
            return out
        out.append((name.decode(), f.value.decode(), d.value.decode()))


# The result formats a run writes per phase (lv_io.h), from the library, not re-typed.
RESULT_FORMATS = format_table(lib.lv_result_format_info)

# lv_status (lv_status.h), from the library, not re-typed: {code: "LV_ERR_INPUT", ...} (the
# codes are 0 and small negative numbers), and the codes the package tests by name.
STATUS_NAMES = {code: lib.lv_status_name(code).decode() for code in range(-64, 1)
                if lib.lv_status_name(code) is not None}
_code = {name: code for code, name in STATUS_NAMES.items()}
LV_OK, LV_ERR_INPUT, LV_ERR_SOLVER = _code["LV_OK"], _code["LV_ERR_INPUT"], _code["LV_ERR_SOLVER"]
LV_ERR_NOTFOUND, LV_ERR_CANCELLED = _code["LV_ERR_NOTFOUND"], _code["LV_ERR_CANCELLED"]
_proto(lib, "lv_mission_load", c_int, c_char_p, POINTER(c_void_p), E)
_proto(lib, "lv_mission_free", None, P)
_proto(lib, "lv_mission_get_info", None, P, POINTER(lv_mission_info))
_proto(lib, "lv_mission_phase_count", c_size_t, P)
_proto(lib, "lv_mission_phase_info", None, P, c_size_t, POINTER(lv_phase_info))
_proto(lib, "lv_mission_phase_find", c_int, P, c_char_p, POINTER(c_size_t), E)
_proto(lib, "lv_mission_stage_count", c_size_t, P)
_proto(lib, "lv_mission_stage_name", c_char_p, P, c_size_t)
_proto(lib, "lv_mission_param_count", c_size_t, P)
_proto(lib, "lv_mission_param_info", None, P, c_size_t, POINTER(lv_param_info))
_proto(lib, "lv_mission_param_find", c_int, P, c_char_p, POINTER(c_size_t), POINTER(c_int), E)
_proto(lib, "lv_run_create", c_int, P, POINTER(c_void_p), E)
_proto(lib, "lv_run_free", None, P)
_proto(lib, "lv_run_set", c_int, P, c_char_p, c_double, E)
_proto(lib, "lv_run_get", c_int, P, c_char_p, POINTER(c_double), E)
_proto(lib, "lv_run_reset", None, P)
_proto(lib, "lv_run_execute", c_int, P, POINTER(lv_run_options), E)
_proto(lib, "lv_run_simulated", c_size_t, P)
_proto(lib, "lv_phase_state_name", c_char_p, c_int)
_proto(lib, "lv_run_invalidate", c_int, P, c_size_t, E)
_proto(lib, "lv_run_stale", c_int, P, c_size_t)
_proto(lib, "lv_run_estimate_output", c_int, P, c_size_t, c_double, POINTER(lv_output_estimate),
       E)
_proto(lib, "lv_run_check_output", c_int, P, POINTER(lv_run_options), E)
_proto(lib, "lv_sim_methods", POINTER(c_char_p))
_proto(lib, "lv_run_result", POINTER(lv_phase_result), P, c_size_t)
_proto(lib, "lv_run_final", c_int, P, c_size_t, c_char_p, POINTER(c_double), E)
_proto(lib, "lv_mission_phase_has_reference", c_int, P, c_size_t)
_proto(lib, "lv_run_reference_drift", c_int, P, c_size_t, POINTER(lv_ref_drift), E)
_proto(lib, "lv_run_rows", c_void_p, P, c_size_t)
_proto(lib, "lv_run_body_phases", c_size_t, P, c_size_t, POINTER(c_size_t))
_proto(lib, "lv_run_body_trajectory", c_int, P, c_size_t, POINTER(POINTER(lv_body_traj)), E)
_proto(lib, "lv_body_traj_free", None, POINTER(lv_body_traj))
_proto(lib, "lv_run_prepare", c_int, P, c_size_t, POINTER(c_void_p), E)
_proto(lib, "lv_phase_call_model", POINTER(lv_model_def), P)
_proto(lib, "lv_phase_call_inst", c_void_p, P)
_proto(lib, "lv_phase_call_settings", POINTER(lv_sim_settings), P)
_proto(lib, "lv_phase_call_finals", POINTER(c_double), P)
_proto(lib, "lv_run_complete", c_int, P, P, c_int, E, POINTER(lv_sim_report), E)
_proto(lib, "lv_phase_call_free", None, P)
_proto(lib, "lv_simulate", c_int, POINTER(lv_model_def), c_void_p, POINTER(lv_sim_settings),
       POINTER(c_double), POINTER(lv_sim_report), E)
_proto(lib, "lv_sim_report_clear", None, POINTER(lv_sim_report))
_proto(lib, "lv_sim_settings_default", None, POINTER(lv_sim_settings))
_proto(lib, "lv_models_find", POINTER(lv_model_def), c_char_p)
_proto(lib, "lv_models_all", POINTER(POINTER(lv_model_def)))
_proto(lib, "lv_result_rows", c_size_t, P)
_proto(lib, "lv_result_signals", c_size_t, P)
_proto(lib, "lv_result_name", c_char_p, P, c_size_t)
_proto(lib, "lv_result_unit", c_char_p, P, c_size_t)
_proto(lib, "lv_result_data", POINTER(c_double), P)
_proto(lib, "lv_result_failure", c_char_p, P)
_proto(lib, "lv_target_create", c_int, P, POINTER(c_void_p), E)
_proto(lib, "lv_target_create_empty", c_int, P, POINTER(c_void_p), E)
_proto(lib, "lv_target_free", None, P)
_proto(lib, "lv_target_add_var", c_int, P, c_char_p, c_double, c_double, c_double, c_double,
       c_double, E)
_proto(lib, "lv_target_add_con", c_int, P, c_char_p, c_int, c_double, c_double, E)
_proto(lib, "lv_target_set_cost", c_int, P, c_char_p, c_int, c_double, E)
_proto(lib, "lv_target_set_end", c_int, P, c_char_p, c_char_p, E)
_proto(lib, "lv_target_var_count", c_size_t, P)
_proto(lib, "lv_target_con_count", c_size_t, P)
_proto(lib, "lv_target_var_info_get", None, P, c_size_t, POINTER(lv_target_var_info))
_proto(lib, "lv_target_con_info_get", None, P, c_size_t, POINTER(lv_target_con_info))
_proto(lib, "lv_target_cost_info_get", None, P, POINTER(lv_target_cost_info))
_proto(lib, "lv_target_settings_default", None, POINTER(lv_target_settings))
_proto(lib, "lv_target_solve", c_int, P, POINTER(lv_target_settings),
       POINTER(POINTER(lv_target_result)), E)
_proto(lib, "lv_target_run", c_void_p, P)
_proto(lib, "lv_target_write", c_int, P, POINTER(c_double), c_char_p, POINTER(c_double), E)
_proto(lib, "lv_ocp_create", c_int, c_char_p, POINTER(c_void_p), E)
_proto(lib, "lv_ocp_free", None, P)
_proto(lib, "lv_ocp_solve", c_int, P, POINTER(lv_ocp_settings), POINTER(lv_ocp_result), E)
_proto(lib, "lv_ocp_violation", c_int, P, c_size_t, c_char_p, c_size_t, POINTER(c_double), E)
_proto(lib, "lv_ocp_phase_times", c_int, P, c_size_t, POINTER(c_double), POINTER(c_double), E)
_proto(lib, "lv_ocp_write", c_int, P, c_char_p, c_uint, E)
_proto(lib, "lv_ocp_check_write", c_int, P, c_char_p, c_uint, E)
_proto(lib, "lv_mission_disp_count", c_size_t, P)
_proto(lib, "lv_mission_disp_info", None, P, c_size_t, POINTER(lv_disp_info))
_proto(lib, "lv_mission_disp_seed", c_int, P, POINTER(c_uint64))
_proto(lib, "lv_mission_disp_draw", None, P, c_uint64, c_uint64, POINTER(c_double))
_proto(lib, "lv_run_disperse", c_int, P, c_uint64, c_uint64, POINTER(c_double), E)


def text(b):
    """C string (bytes or None) -> str or None."""
    return None if b is None else b.decode("utf-8", "replace")


def name_arg(s, what="name"):
    """A name argument (a phase, final, parameter, model, method name) -> bytes for a
    const char *: TypeError unless a str, ValueError for an embedded NUL (C would see a
    shorter name)."""
    if isinstance(s, bytes):
        s = s.decode("utf-8")
    if not isinstance(s, str):
        raise TypeError(f"{what} must be a str, not {type(s).__name__} ({s!r})")
    if "\x00" in s:
        raise ValueError(f"{what} {s!r} contains a NUL character")
    return s.encode("utf-8")


def path_arg(s, what="path"):
    """A file or folder argument (str, bytes or os.PathLike) -> bytes: TypeError for
    anything else, ValueError for "" or an embedded NUL."""
    if isinstance(s, os.PathLike):
        s = os.fspath(s)
    if isinstance(s, bytes):
        b = s
    elif isinstance(s, str):
        b = os.fsencode(s)
    else:
        raise TypeError(f"{what} must be a str or path, not {type(s).__name__} ({s!r})")
    if b"\x00" in b:
        raise ValueError(f"{what} {s!r} contains a NUL character")
    if not b:
        raise ValueError(f"{what} is empty")
    return b


def real_arg(v, what="value"):
    """A number argument -> float: TypeError for a bool, a str or anything that is not a
    real number (numpy scalars are fine)."""
    if isinstance(v, (bool, np_bool_types())) or isinstance(v, (str, bytes)):
        raise TypeError(f"{what} must be a number, not {type(v).__name__} ({v!r})")
    try:
        return float(v.__float__()) if not isinstance(v, float) else v
    except (AttributeError, TypeError):
        raise TypeError(f"{what} must be a number, not {type(v).__name__} ({v!r})") from None


U64_MAX = 2**64 - 1  # seeds and run indices are uint64_t in C


def bool_arg(v, what="value"):
    """A flag argument -> bool: True/False (numpy's too) or 0/1; TypeError otherwise (a str, a
    list or NaN is no flag)."""
    if isinstance(v, (bool, np_bool_types())):
        return bool(v)
    if isinstance(v, int) and v in (0, 1):
        return bool(v)
    raise TypeError(f"{what} must be True or False, not {type(v).__name__} ({v!r})")


def int_arg(v, what="value", lo=None, hi=None):
    """A whole-number argument -> int: TypeError for a bool, a float (2.7), a str; ValueError
    below `lo` or above `hi`."""
    import operator
    if isinstance(v, (bool, np_bool_types())):
        raise TypeError(f"{what} must be an integer, not {type(v).__name__} ({v!r})")
    try:
        n = operator.index(v)
    except TypeError:
        raise TypeError(f"{what} must be an integer, not {type(v).__name__} ({v!r})") from None
    if lo is not None and n < lo:
        raise ValueError(f"{what} must be >= {lo}, got {n}")
    if hi is not None and n > hi:
        raise ValueError(f"{what} must be <= {hi}, got {n}")
    return n


def np_bool_types():
    try:
        import numpy
        return numpy.bool_
    except ImportError:  # pragma: no cover
        return bool


def enc(s, what="name"):
    """A name argument -> bytes (name_arg); None stays NULL (an optional argument)."""
    return None if s is None else name_arg(s, what)
_proto(lib, "lv_laws_count", c_size_t)
_proto(lib, "lv_laws_get", c_int, c_size_t, POINTER(lv_law_info), E)
_proto(lib, "lv_laws_common_keys", POINTER(lv_law_key), c_int, POINTER(c_size_t))
