"""_campaign.py - Monte Carlo dispersion campaigns (lv_campaign.h, in liblvsim_post) for
Python: N runs of a mission with the values its `dispersions:` draw, on C worker threads (the
GIL released), stored in an SQLite database that Python's sqlite3 reads; the statistics
written by lv_campaign_stats. Schema and statistics: docs/monte-carlo.md."""
import json
import math
import os
import sqlite3
from ctypes import byref, c_char_p, c_int, c_void_p, pointer

from . import _lib
from ._lib import enc, int_arg, path_arg, real_arg, U64_MAX
from .errors import InputError, LvsimError, OutputLimitError, check


class Campaign:
    """A campaign database (`db_path`) and what the call that ran it reports: `total`,
    `done` (stored runs), `this_session`, `failed` (runs with a failed phase or a drawn
    input out of range), `impacts` (runs where no phase failed but one fell to the ground: it
    ended by an `impact` end that is not its first written end; an outcome, not a failure),
    `crashed` (runs where no phase failed but a touchdown was beyond the landing gear's limits),
    `elapsed` (s), `rate` (runs/s). Read it with runs(), phase() and stats()."""

    def __init__(self, db_path, progress=None):
        """An existing campaign database `db_path` (lvsim mc, Campaign.run): its counts are
        read from it (`total` the runs asked for, `done` those stored, `failed`, `impacts`, `crashed`; the timing
        attributes `this_session`, `elapsed`, `rate`, `eta` are those of the call that ran it,
        0 when opened here)."""
        self.db_path = os.fspath(db_path)
        if progress is not None:
            for f, _ in _lib.lv_campaign_progress._fields_:
                setattr(self, f, getattr(progress, f))
            return
        if not os.path.isfile(self.db_path):
            raise LvsimError(f"{self.db_path}: no such campaign database", _lib.LV_ERR_NOTFOUND)
        try:
            _, meta = self._query("SELECT key, value FROM campaign WHERE key = 'n_runs'")
            _, counts = self._query("SELECT COUNT(*), COALESCE(SUM(status NOT IN ('ok', 'impact', 'crashed')), 0),"
                                    " COALESCE(SUM(status = 'impact'), 0), COALESCE(SUM(status = 'crashed'), 0)"
                                    " FROM runs")
        except sqlite3.DatabaseError as e:
            raise LvsimError(f"{self.db_path}: not a campaign database ({e})", _lib.LV_ERR_INPUT) from None
        self.done, self.failed, self.impacts, self.crashed = (int(c) for c in counts[0])
        self.total = int(meta[0][1]) if meta else self.done
        self.this_session, self.elapsed, self.rate, self.eta = 0, 0.0, 0.0, 0.0

    @classmethod
    def run(cls, mission, n_runs, db_path, *, seed=None, threads=1, resume=False,
            overwrite=False, keep_runs=0, keep_dir=None, method=None, tolerance=None,
            output_interval="ends", progress=None, max_rows=1e6):
        """Runs runs 0 .. n_runs-1 of `mission` (lv_campaign_run) into the SQLite database
        `db_path`: seed (None: the file's `seed:`, else 1, as `lvsim mc`), threads (C
        worker threads), resume (continue a database of the same campaign), overwrite
        (replace one), keep_runs/keep_dir (runs < keep_runs also write result files into
        keep_dir/run_<i>), method/tolerance (every phase's; None: each phase's own),
        output_interval ("ends": only start and end rows, the fastest, the default; a
        number > 0: every phase's grid in s) - the same meanings as Run.execute's, so
        run.disperse(seed, i); run.execute(output_interval=..., method=..., tolerance=...)
        reproduces run i bit for bit. progress(dict) is called about every 0.25 s from the
        calling thread (total, done, failed, impacts, crashed, rate, eta); returning True stops the campaign
        within an integrator step of every running run (CancelledError; the runs done are
        kept, a run cut short is not stored: resume=True runs it). max_rows (default 1e6, as
        `lvsim mc --max-rows`; None: no limit): the output rows a phase of a run may compute
        (Run.execute's): a phase only its stop time ends beyond it is refused before
        anything runs (OutputLimitError), one with end events that reaches it fails in that
        run. A campaign whose database would not fit the free disk space is refused before
        anything runs (InputError, the sizes named). Failed runs are outcomes, not errors;
        LvsimError for the campaign itself (an existing database without overwrite or
        resume, one of another campaign); TypeError/ValueError for bad arguments."""
        from ._simulate import METHODS
        post = _lib.post()
        o = _lib.lv_campaign_options()
        post.lv_campaign_options_default(byref(o))
        n_runs = int_arg(n_runs, "n_runs")
        if n_runs <= 0:
            raise InputError(f"n_runs must be > 0, got {n_runs}")
        if seed is None:
            seed = mission.seed if mission.seed is not None else 1
        seed = int_arg(seed, "seed", 0, U64_MAX)
        threads = int_arg(threads, "threads", 0, 1024)
        keep_runs = int_arg(keep_runs, "keep_runs", 0)
        if method is not None:
            if not isinstance(method, str):
                raise TypeError(f"method must be a str, not {type(method).__name__}")
            if method not in METHODS:
                raise InputError(f"unknown method {method!r}; methods: {', '.join(METHODS)}")
        if tolerance is None:
            tol = 0.0
        else:
            tol = real_arg(tolerance, "tolerance")
            if not _lib.LV_TOLERANCE_MIN <= tol <= _lib.LV_TOLERANCE_MAX:
                raise InputError(f"tolerance must be from {_lib.LV_TOLERANCE_MIN:g} to "
                                 f"{_lib.LV_TOLERANCE_MAX:g}, got {tolerance!r}")
        if isinstance(output_interval, str) and output_interval == "ends":
            oi = 0.0  # lv_campaign_options: 0 is start and end rows only
        elif output_interval is None or isinstance(output_interval, str):
            raise InputError(f"output_interval {output_interval!r}: 'ends' (start and end rows "
                             "only) or a number of seconds > 0")
        else:
            oi = real_arg(output_interval, "output_interval")
            if not (oi > 0.0 and math.isfinite(oi)):
                raise InputError(f"output_interval must be > 0 s and finite, or 'ends', got "
                                 f"{output_interval!r}")
        o.n_runs, o.seed, o.threads = n_runs, seed, threads
        keep = [path_arg(db_path, "db_path"),
                None if keep_dir is None else path_arg(keep_dir, "keep_dir"), enc(method)]
        o.db_path, o.keep_dir, o.method = keep
        o.resume, o.overwrite, o.keep_runs = int(bool(resume)), int(bool(overwrite)), keep_runs
        o.tolerance, o.output_interval = tol, oi
        if max_rows is not None:
            max_rows = real_arg(max_rows, "max_rows")
            if not max_rows >= 1:
                raise InputError(f"max_rows must be >= 1 (or None: no limit), got {max_rows!r}")
            o.max_rows = max_rows
        err = _lib.lv_err()
        # the bounds before anything runs: the rows of a run (lv_run_check_output, as
        # lv_campaign_open holds them) and the database against the free disk space
        if o.max_rows > 0.0:
            r = c_void_p()
            check(_lib.lib.lv_run_create(mission._handle(), byref(r), byref(err)), err)
            try:
                ro = _lib.lv_run_options()
                ro.max_rows = o.max_rows
                for ro.output_interval in ((oi if oi > 0.0 else 1e300),) + \
                        ((oi,) if keep_runs > 0 else ()):
                    if _lib.lib.lv_run_check_output(r, byref(ro), byref(err)) != _lib.LV_OK:
                        raise OutputLimitError(err.msg.decode("utf-8", "replace"), _lib.LV_ERR_INPUT)
            finally:
                _lib.lib.lv_run_free(r)
        if post.lv_campaign_check_size(mission._handle(), byref(o), 0, None,
                                       byref(err)) != _lib.LV_OK:
            raise InputError(err.msg.decode("utf-8", "replace").replace("(-n)", "(n_runs)"),
                             -2)
        stop = c_int(0)
        o.stop = pointer(stop)
        state = {}
        if progress is not None:
            def _p(p, user):
                if "exc" in state:
                    return
                q = p.contents
                try:
                    if progress({f: getattr(q, f) for f, _ in _lib.lv_campaign_progress._fields_}):
                        stop.value = 1
                except BaseException as exc:  # stop; raised after the campaign
                    state["exc"] = exc
                    stop.value = 1
            cb = _lib.CAMPAIGN_PROGRESS_FN(_p)
            o.progress = cb
        out = _lib.lv_campaign_progress()
        st = post.lv_campaign_run(mission._handle(), byref(o), byref(out), byref(err))
        if "exc" in state:
            raise state["exc"]
        if st != _lib.LV_OK:  # the C messages name the CLI's flags: name the arguments
            msg = err.msg.decode("utf-8", "replace")
            msg = msg.replace("--resume", "resume=True").replace("--force", "overwrite=True")
            err.msg = msg.encode()[:_lib.LV_ERR_MSG_MAX - 1]
        check(st, err)
        return cls(db_path, out)

    def stats(self, outdir):
        """Writes the statistics into `outdir` (lv_campaign_stats: stats.json, stats.csv,
        ellipses.csv, outcomes.csv, sensitivity.csv, footprint.kml) and returns stats.json
        as a dict."""
        b = path_arg(outdir, "outdir")
        post = _lib.post()
        err = _lib.lv_err()
        # outdir as `lvsim mc -o` treats its folder (lv_outdir.h): new, empty or lvsim's;
        # written in a replica that replaces it, a user's file never replaced
        od = c_void_p()
        no_live = (c_char_p * 1)()
        check(post.lv_outdir_open_live(b, None, 0, no_live, byref(od), byref(err)), err)
        try:
            check(post.lv_outdir_stage(od, byref(err)), err)
            stage = post.lv_outdir_path(od)
            check(post.lv_campaign_stats(path_arg(self.db_path), stage, byref(err)), err)
            rec = _lib.lv_outdir_record()
            rec.command, rec.status = b"python stats", b"ok"
            check(post.lv_outdir_commit(od, byref(rec), byref(err)), err)
        finally:
            post.lv_outdir_free(od)
        with open(os.path.join(outdir, "stats.json"), encoding="utf-8") as f:
            return json.load(f)

    def _query(self, sql):
        con = sqlite3.connect(f"file:{self.db_path}?mode=ro", uri=True)
        try:
            cur = con.execute(sql)
            cols = [d[0] for d in cur.description]
            return cols, cur.fetchall()
        finally:
            con.close()

    def _frame(self, cols, rows):
        try:
            import pandas  # optional; imported on first use
        except ImportError:
            return {c: [r[i] for r in rows] for i, c in enumerate(cols)}
        return pandas.DataFrame(rows, columns=cols)

    def runs(self):
        """The `runs` table: run, status ("ok", "impact", "failed", "input"), message, then each
        dispersed parameter's drawn value; a DataFrame (a dict of lists without pandas)."""
        return self._frame(*self._query("SELECT * FROM runs ORDER BY run"))

    def phase(self, name):
        """Phase `name`'s table: per run its state ("done", "impact": ended on the ground by an
        `impact` end that is not its first written end, "failed", "skipped"), end reason, t_end,
        error and every final value (NULL unless done or impact); a DataFrame (a dict of lists
        without pandas)."""
        cols, rows = self._query("SELECT name, tbl FROM phases")
        tables = {n: t for n, t in rows}
        if name not in tables:
            raise LvsimError(f"campaign has no phase '{name}'; phases: {', '.join(tables)}", _lib.LV_ERR_NOTFOUND)
        tbl = tables[name].replace('"', '""')
        return self._frame(*self._query(f'SELECT * FROM "{tbl}" ORDER BY run'))
