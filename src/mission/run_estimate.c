/* run_estimate.c - how much a phase will write, at most, before it runs: rows from its
 * output grid and its longest possible duration (its stop time, or a `time` end), bytes from
 * the rows and its columns; and the up-front half of lv_run_options.max_rows: a phase that
 * nothing but that duration can end is refused beyond the limit before anything runs, one
 * with other ends (burnout, altitude, ...) is left to the run, which stops it at the limit
 * (sim/simulate.c). Reads the plan and the run's values only. */
#include <math.h>
#include <stdio.h>

#include "core/status.h"
#include "lvsim/lv_mission.h"
#include "mission/mission_rt.h"

/* lv_simulate's grid without output_interval or number_of_intervals (sim/simulate.c). */
#define GRID_DEFAULT_INTERVALS 500
/* The largest row count worth suggesting as a limit (lvsim --max-rows takes up to 1e15). */
#define LIMIT_SUGGEST_MAX 1e15

/* Earliest time phase k can start: its start_time, or its parent's end when the parent is
 * done and up to date in this run, or its parent's earliest start (a phase ends after it
 * starts). *known: 1 when that is when it starts (the first two), 0 when it is only a lower
 * bound (a child before its parent ran). */
static double earliest_start(const lv_run *r, size_t k, int *known)
{
    const lv_mission_def *d = lv_run_mission(r)->def;
    const double *v = lv_run_vals(r);
    *known = 1;
    for (int depth = 0; depth <= (int)d->n_phases; depth++) {
        const lv_phase_def *ph = &d->phases[k];
        if (ph->t_start != LV_NO_SLOT)
            return v[ph->t_start];
        if (ph->parent < 0)
            return 0.0;
        const lv_phase_result *pr = lv_run_result(r, (size_t)ph->parent);
        if (pr->state == LV_PHASE_DONE && isfinite(pr->t_end) &&
            !lv_run_stale(r, (size_t)ph->parent))
            return pr->t_end;
        *known = 0;
        k = (size_t)ph->parent;
    }
    return 0.0;
}

lv_status lv_run_estimate_output(const lv_run *r, size_t k, double output_interval,
                                 lv_output_estimate *out, lv_err *err)
{
    const lv_mission *m = lv_run_mission(r);
    const lv_mission_def *d = m->def;
    if (k >= d->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "phase index %zu out of range", k);
    const lv_phase_def *ph = &d->phases[k];
    const lv_phase_plan *pl = &m->plan[k];
    const double *v = lv_run_vals(r);
    int known;
    const double t0 = earliest_start(r, k, &known), tf = v[ph->t_stop];
    double span = tf - t0;
    /* a `time` end is a bound as exact as the stop time; any other end fires when it fires;
     * a child whose parent has not run yet starts when the parent ends: its rows are known
     * then (lv_run_check_phase_output, as it is about to start) */
    int bounded = known;
    for (size_t i = 0; i < ph->n_ends; i++) {
        const lv_end_def *e = &ph->ends[i];
        if (e->kind == LV_END_TIME && e->value != LV_NO_SLOT)
            span = fmin(span, v[e->value]);
        else
            bounded = 0;
    }
    const double dt = output_interval > 0.0 ? output_interval : v[ph->output_interval];
    double intervals;
    if (!(span > 0.0))
        intervals = 1.0;
    else if (dt > 0.0)
        intervals = fmax(1.0, ceil(span / dt - 1e-9));
    else
        intervals = ph->intervals > 0 ? ph->intervals : GRID_DEFAULT_INTERVALS;
    out->duration = span > 0.0 ? span : 0.0;
    out->rows = intervals + 1.0;
    out->n_signals = pl->n_final + pl->n_states; /* time, states, outputs + derivatives */
    out->bytes_mat = out->rows * (double)out->n_signals * 8.0;
    out->bytes_csv = out->rows * (double)out->n_signals * 22.0;
    out->bounded = bounded;
    return LV_OK;
}

/* The smallest number of three significant digits >= n: a limit that allows n rows and
 * reads back as written ("1.24e+09" for 1233999999). */
static double round_up3(double n)
{
    if (n < 1e7)
        return ceil(n);
    const double q = pow(10.0, floor(log10(n)) - 2.0);
    double up = ceil(n / q) * q;
    char buf[32];
    snprintf(buf, sizeof buf, "%.3g", up);
    if (sscanf(buf, "%lf", &up) != 1 || up < n) /* the decimal rounding went below n */
        up += q;
    return up;
}

/* The latest time phase k (a child) can start when its parent has not run: its parent's
 * stop time (a phase ends by its stop time at the latest). */
static double latest_start(const lv_run *r, size_t k)
{
    const lv_mission_def *d = lv_run_mission(r)->def;
    const int par = d->phases[k].parent;
    return par >= 0 ? lv_run_vals(r)[d->phases[par].t_stop] : NAN;
}

/* The refusal of phase k, when only its stop time (or a `time` end) ends it and its grid has
 * more than max_rows rows: what lv_run_check_output says of it. A child whose parent has not
 * run is over the limit already when the rows from its parent's stop time (its latest start)
 * are. 0: within the limit (or not known now), 1: over it (*rows: the rows counted, *least:
 * 1 when they are the fewest it can write), -1: error. */
static int over_limit(const lv_run *r, size_t k, const lv_run_options *opt, double *rows,
                      int *least, lv_err *err)
{
    lv_output_estimate e;
    if (lv_run_estimate_output(r, k, opt->output_interval, &e, err) != LV_OK)
        return -1;
    *rows = e.rows;
    *least = 0;
    if (e.bounded)
        return e.rows > opt->max_rows;
    const lv_mission_def *d = lv_run_mission(r)->def;
    const lv_phase_def *ph = &d->phases[k];
    int known;
    earliest_start(r, k, &known);
    for (size_t i = 0; i < ph->n_ends; i++)
        if (ph->ends[i].kind != LV_END_TIME)
            return 0; /* other ends: held as it runs */
    if (known)
        return 0;
    /* the fewest rows: from the latest start to the stop time (or a time end) */
    const double *v = lv_run_vals(r);
    double tf = v[ph->t_stop];
    for (size_t i = 0; i < ph->n_ends; i++)
        if (ph->ends[i].value != LV_NO_SLOT)
            tf = fmin(tf, v[ph->ends[i].value]);
    const double dt = opt->output_interval > 0.0 ? opt->output_interval : v[ph->output_interval];
    const double span = tf - latest_start(r, k);
    if (!(dt > 0.0) || !(span > 0.0))
        return 0;
    *rows = floor(span / dt + 1e-9) + 1.0;
    *least = 1;
    return *rows > opt->max_rows;
}

/* The message for phase k over the limit; `also`: the other phases over it ("", or "; phases
 * 3 'P3' (2.81e+09 rows) ... are over it too"), `need`: the largest row count of them all. */
static lv_status refuse(const lv_run *r, size_t k, const lv_run_options *opt, const char *also,
                        double own, double need, int least, lv_err *err)
{
    const lv_mission_def *d = lv_run_mission(r)->def;
    lv_output_estimate e;
    lv_status st = lv_run_estimate_output(r, k, opt->output_interval, &e, err);
    if (st != LV_OK)
        return st;
    const lv_phase_def *ph = &d->phases[k];
    char rows[32], lim[32], mat[32], csv[32], grid[64], raise[160];
    lv_fmt_count(e.rows, rows, sizeof rows);
    lv_fmt_count(opt->max_rows, lim, sizeof lim);
    lv_fmt_bytes(e.bytes_mat, mat, sizeof mat);
    lv_fmt_bytes(e.bytes_csv, csv, sizeof csv);
    const double dt = opt->output_interval > 0.0 ? opt->output_interval
                                                 : lv_run_vals(r)[ph->output_interval];
    if (dt > 0.0)
        snprintf(grid, sizeof grid, ", a row every %.3g s", dt);
    else
        grid[0] = '\0';
    int time_end = 0;
    for (size_t i = 0; i < ph->n_ends; i++)
        time_end |= ph->ends[i].kind == LV_END_TIME;
    if (need <= LIMIT_SUGGEST_MAX) {
        char up[32];
        lv_fmt_count(round_up3(need), up, sizeof up);
        snprintf(raise, sizeof raise, ", or raise the limit to %s rows (max_rows; lvsim "
                 "--max-rows %s)", up, up);
    } else {
        raise[0] = '\0';
    }
    if (least) { /* a child before its parent ran: the fewest rows it can write */
        lv_fmt_count(own, rows, sizeof rows);
        return lv_fail(err, LV_ERR_INPUT,
                       "phase %zu '%s' would write at least %s rows (from its parent's stop "
                       "time to its own%s; %zu columns) - more than the limit of %s rows per "
                       "phase, and nothing but its %s ends it%s. Give it a larger output "
                       "interval, an earlier stop_time or an end event%s",
                       k + 1, ph->name, rows, grid, e.n_signals, lim,
                       time_end ? "stop_time or time end" : "stop_time", also, raise);
    }
    return lv_fail(err, LV_ERR_INPUT,
                   "phase %zu '%s' would write up to %s rows (%.6g s of mission time%s; "
                   "%zu columns: %s of .mat, %s of .csv, and as much memory) - more than "
                   "the limit of %s rows per phase, and nothing but its %s ends it%s. Give "
                   "it a larger output interval, an earlier stop_time or an end event%s",
                   k + 1, ph->name, rows, e.duration, grid, e.n_signals, mat, csv, lim,
                   time_end ? "stop_time or time end" : "stop_time", also, raise);
}

lv_status lv_run_check_output(const lv_run *r, const lv_run_options *opt, lv_err *err)
{
    if (opt == NULL || !(opt->max_rows > 0.0))
        return LV_OK;
    const lv_mission_def *d = lv_run_mission(r)->def;
    long first = -1;
    int first_least = 0;
    double need = 0.0, first_rows = 0.0;
    char list[192] = "";
    size_t n_also = 0, used = 0;
    for (size_t k = 0; k < d->n_phases; k++) {
        if (opt->want != NULL) { /* wanted, or an ancestor of a wanted phase */
            int needed = 0;
            for (size_t j = 0; j < d->n_phases && !needed; j++)
                for (int a = opt->want[j] ? (int)j : -1; a >= 0 && !needed;
                     a = d->phases[a].parent)
                    needed = (size_t)a == k;
            if (!needed)
                continue;
        }
        const lv_phase_result *res = lv_run_result(r, k);
        if (res->state == LV_PHASE_DONE && !lv_run_stale(r, k))
            continue; /* it will not run */
        double rows;
        int least;
        const int over = over_limit(r, k, opt, &rows, &least, err);
        if (over < 0)
            return LV_ERR_INPUT;
        if (!over)
            continue;
        need = fmax(need, rows);
        if (first < 0) {
            first = (long)k;
            first_least = least;
            first_rows = rows;
            continue;
        }
        char n[32];
        lv_fmt_count(rows, n, sizeof n);
        if (used < sizeof list)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%zu '%s' (%s rows)",
                                     n_also ? ", " : "", k + 1, d->phases[k].name, n);
        n_also++;
    }
    if (first < 0)
        return LV_OK;
    char also[224] = "";
    if (n_also > 0)
        snprintf(also, sizeof also, "; phase%s %s %s over it too", n_also > 1 ? "s" : "", list,
                 n_also > 1 ? "are" : "is");
    return refuse(r, (size_t)first, opt, also, first_rows, need, first_least, err);
}

lv_status lv_run_check_phase_output(const lv_run *r, size_t k, const lv_run_options *opt,
                                    lv_err *err)
{
    if (opt == NULL || !(opt->max_rows > 0.0))
        return LV_OK;
    double rows;
    int least;
    const int over = over_limit(r, k, opt, &rows, &least, err);
    if (over < 0)
        return LV_ERR_INPUT;
    return over ? refuse(r, k, opt, "", rows, rows, least, err) : LV_OK;
}
