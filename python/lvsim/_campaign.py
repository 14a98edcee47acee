"""_campaign.py - Monte Carlo dispersion campaigns (lv_campaign.h, in liblvsim_post) for
Python: N runs of a mission with the values its `dispersions:` draw, on C worker threads (the
GIL released), stored in an SQLite database that Python's sqlite3 reads; the statistics
written by lv_campaign_stats. Schema and statistics: docs/monte-carlo.md."""
import json
import os
import sqlite3
from ctypes import byref, c_int, pointer

from . import _lib
from ._lib import enc
from .errors import LvsimError, check


class Campaign:
    """A campaign database (`db_path`) and what the call that ran it reports: `total`,
    `done` (stored runs), `this_session`, `failed` (runs with a failed phase or a drawn
    input out of range), `elapsed` (s), `rate` (runs/s). Read it with runs(), phase() and
    stats()."""

    def __init__(self, db_path, progress=None):
        self.db_path = os.fspath(db_path)
        if progress is not None:
            for f, _ in _lib.lv_campaign_progress._fields_:
                setattr(self, f, getattr(progress, f))

    @classmethod
    def run(cls, mission, n_runs, db_path, *, seed=None, threads=1, resume=False,
            overwrite=False, keep_runs=0, keep_dir=None, method=None, tolerance=0.0,
            output_interval=0.0, progress=None):
        """Runs runs 0 .. n_runs-1 of `mission` (lv_campaign_run) into the SQLite database
        `db_path`: seed (None: the file's `seed:`, else 1, as `lvsim mc`), threads (C
        worker threads), resume (continue a database of the same campaign), overwrite
        (replace one), keep_runs/keep_dir (runs < keep_runs also write result files into
        keep_dir/run_<i>), method/tolerance/output_interval (every phase's; 0: only start
        and end rows, the fastest). progress(dict) is called about every 0.25 s from the
        calling thread (total, done, failed, rate, eta); returning True stops the campaign
        (CancelledError, the runs done are kept). Failed runs are outcomes, not errors;
        LvsimError for the campaign itself (an existing database without overwrite or
        resume, one of another campaign)."""
        post = _lib.post()
        o = _lib.lv_campaign_options()
        post.lv_campaign_options_default(byref(o))
        if n_runs <= 0:
            raise LvsimError(f"n_runs must be > 0, got {n_runs}", -2)
        if seed is None:
            seed = mission.seed if mission.seed is not None else 1
        o.n_runs, o.seed, o.threads = int(n_runs), int(seed), int(threads)
        keep = [enc(db_path), enc(keep_dir), enc(method)]
        o.db_path, o.keep_dir, o.method = keep
        o.resume, o.overwrite, o.keep_runs = int(bool(resume)), int(bool(overwrite)), int(keep_runs)
        o.tolerance, o.output_interval = float(tolerance), float(output_interval)
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
        err = _lib.lv_err()
        st = post.lv_campaign_run(mission._handle(), byref(o), byref(out), byref(err))
        if "exc" in state:
            raise state["exc"]
        check(st, err)
        return cls(db_path, out)

    def stats(self, outdir):
        """Writes the statistics into `outdir` (lv_campaign_stats: stats.json, stats.csv,
        ellipses.csv, outcomes.csv, sensitivity.csv, footprint.kml) and returns stats.json
        as a dict."""
        os.makedirs(outdir, exist_ok=True)
        err = _lib.lv_err()
        check(_lib.post().lv_campaign_stats(enc(self.db_path), enc(outdir), byref(err)), err)
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
        """The `runs` table: run, status ("ok", "failed", "input"), message, then each
        dispersed parameter's drawn value; a DataFrame (a dict of lists without pandas)."""
        return self._frame(*self._query("SELECT * FROM runs ORDER BY run"))

    def phase(self, name):
        """Phase `name`'s table: per run its state, end reason, t_end, error and every final
        value (NULL unless done); a DataFrame (a dict of lists without pandas)."""
        cols, rows = self._query("SELECT name, tbl FROM phases")
        tables = {n: t for n, t in rows}
        if name not in tables:
            raise LvsimError(f"campaign has no phase '{name}'; phases: {', '.join(tables)}", -5)
        tbl = tables[name].replace('"', '""')
        return self._frame(*self._query(f'SELECT * FROM "{tbl}" ORDER BY run'))
