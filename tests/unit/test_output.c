/* test_output.c - what output costs (docs/integration.md, "Output cost"): the statistics split
 * the RHS evaluations into those of the steps and those of the output between steps
 * (rhs_evals = rhs_evals_steps + rhs_evals_output); dopri5's dense output costs at most one
 * RHS per step however many output times the step holds, CVODE's and the fixed-step methods'
 * none; a run without a sink evaluates no row (row_evals counts the final values only); and
 * the dense output keeps its accuracy (oscillator against cos/sin at 20,000 output times).
 * Set-up: a model's names are checked for repeats by hashing (lv_names_duplicate), with the
 * same verdicts as comparing every pair. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "core/names.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_models.h"
#include "lvsim/lv_sim.h"

static const char *const methods[] = {"dassl", "cvode-adams", "dopri5", "rk4", "euler", "dp5",
                                       "dop853", "auto"};

/* The oscillator x'' = -w^2 x over 10 periods with `intervals` output intervals; with a
 * memory sink when `rows` is not NULL. Returns the largest |x - cos(w t)| over the rows. */
static double oscillator(const char *method, int intervals, int with_sink, lv_sim_report *rep)
{
    const double w = 2.0, T = 2.0 * M_PI / w;
    lv_sim_settings s;
    lv_sim_settings_default(&s);
    s.result_file = NULL;
    s.method = method;
    s.stop_time = 10.0 * T;
    s.number_of_intervals = intervals;
    s.tolerance = 1e-9;
    s.fixed_step = T / 400.0;
    const char *in[] = {"omega"};
    const double iv[] = {w};
    s.n_initial = 1;
    s.initial_names = in;
    s.initial_values = iv;
    const char *fin[] = {"x"};
    double x_end;
    s.n_final = 1;
    s.final_names = fin;
    lv_result *res = NULL;
    lv_sink mem = {0};
    lv_err err;
    if (with_sink) {
        CHECK_OK(lv_sink_memory_create(&res, &mem, &err), &err);
        s.n_sinks = 1;
        s.sinks = &mem;
    }
    CHECK_OK(lv_simulate(&lv_model_oscillator, NULL, &s, &x_end, rep, &err), &err);
    double worst = 0.0;
    if (res != NULL) {
        size_t ct, cx;
        CHECK_OK(lv_result_column(res, "time", &ct, &err), &err);
        CHECK_OK(lv_result_column(res, "x", &cx, &err), &err);
        CHECK(lv_result_rows(res) == (size_t)intervals + 1);
        for (size_t i = 0; i < lv_result_rows(res); i++) {
            const double t = lv_result_value(res, i, ct);
            worst = fmax(worst, fabs(lv_result_value(res, i, cx) - cos(w * t)));
        }
    }
    lv_sink_destroy(&mem);
    lv_result_free(res);
    return worst;
}

static void test_split(void)
{
    for (size_t k = 0; k < sizeof methods / sizeof methods[0]; k++) {
        lv_sim_report few, many;
        const double e_few = oscillator(methods[k], 10, 1, &few);
        const double e_many = oscillator(methods[k], 20000, 1, &many);
        for (int j = 0; j < 2; j++) {
            const lv_sim_stats *st = j == 0 ? &few.stats : &many.stats;
            CHECK(st->rhs_evals == st->rhs_evals_steps + st->rhs_evals_output);
            CHECK(st->rhs_evals_steps >= st->steps);
            if (strcmp(methods[k], "dopri5") == 0)
                CHECK(st->rhs_evals_output <= st->steps); /* once per step at most */
            else if (strcmp(methods[k], "dop853") == 0 || strcmp(methods[k], "auto") == 0)
                CHECK(st->rhs_evals_output <= 3 * st->steps); /* 3 extra stages per step */
            else
                CHECK(st->rhs_evals_output == 0); /* CVODE, rk4 (cubic), euler: free */
        }
        /* 2,000 output times per step or so change nothing in the cost of the steps */
        CHECK(many.stats.output_rows == 20001 && many.stats.row_evals == 20001 + 1);
        printf("%-12s steps %5ld/%5ld  rhs on steps %6ld/%6ld  on output %5ld/%5ld  "
               "(10 / 20000 output intervals)  max |x - cos| %.2e / %.2e\n",
               methods[k], few.stats.steps, many.stats.steps, few.stats.rhs_evals_steps,
               many.stats.rhs_evals_steps, few.stats.rhs_evals_output,
               many.stats.rhs_evals_output, e_few, e_many);
        if (strcmp(methods[k], "dopri5") == 0 || strcmp(methods[k], "dp5") == 0 ||
            strcmp(methods[k], "dop853") == 0) {
            /* the dense output is as accurate as the steps (degree-4 Hermite): the error at
             * 20,000 output times stays within a few times the one at the 11 grid points */
            CHECK(e_many < 1e-7 && e_many < 10.0 * e_few + 1e-9);
        }
        lv_sim_report_clear(&few);
        lv_sim_report_clear(&many);
    }
}

/* No sink: the rows are counted, not evaluated; only the final values are. The final value
 * is the same as with a sink. lvsim's own methods do not even stop at the output times
 * (sim/simulate.c, grid_skipped): the same steps, no right-hand side for the dense output
 * (dop853's three extra stages); the SUNDIALS methods stop there and interpolate as with a
 * sink. */
static void test_no_consumer(void)
{
    for (size_t k = 0; k < sizeof methods / sizeof methods[0]; k++) {
        lv_sim_report with, without;
        oscillator(methods[k], 1000, 1, &with);
        oscillator(methods[k], 1000, 0, &without);
        CHECK(without.stats.output_rows == with.stats.output_rows);
        CHECK(with.stats.row_evals == 1001 + 1);
        CHECK(without.stats.row_evals == 1); /* the final value */
        const int own = strcmp(methods[k], "dp5") == 0 || strcmp(methods[k], "dop853") == 0 ||
                        strcmp(methods[k], "auto") == 0;
        CHECK(without.stats.steps == with.stats.steps &&
              without.stats.rhs_evals_steps == with.stats.rhs_evals_steps);
        if (own)
            CHECK(without.stats.rhs_evals_output == 0);
        else
            CHECK(without.stats.rhs_evals == with.stats.rhs_evals);
        lv_sim_report_clear(&with);
        lv_sim_report_clear(&without);
    }
}

/* lv_names_duplicate against the pairwise check, on the stack table and on a heap one. */
static void test_duplicates(void)
{
    static char text[600][12];
    const char *names[600];
    for (size_t i = 0; i < 600; i++) {
        snprintf(text[i], sizeof text[i], "v%zu", i * 7);
        names[i] = text[i];
    }
    for (size_t n = 0; n <= 600; n += 50) {
        CHECK(lv_names_duplicate(names, n) == n); /* all distinct */
        if (n < 2)
            continue;
        names[n - 1] = names[n / 3]; /* one repeat, the last name */
        CHECK(lv_names_duplicate(names, n) == n - 1);
        names[n - 1] = text[n - 1];
    }
    /* a model whose output has a state's name fails validation, naming it */
    lv_model_def d = lv_model_vertical_ascent;
    lv_var outs[8];
    memcpy(outs, d.outputs, d.n_outputs * sizeof *outs);
    outs[d.n_outputs - 1].name = d.states[0].name;
    d.outputs = outs;
    lv_err err;
    CHECK_FAILS(lv_model_validate(&d, &err), &err, LV_ERR_INPUT, "is used twice");
    CHECK(strstr(err.msg, d.states[0].name) != NULL);
    CHECK_OK(lv_model_validate(&lv_model_vertical_ascent, &err), &err);
}

int main(void)
{
    test_duplicates();
    test_split();
    test_no_consumer();
    return check_report("test_output");
}
