/* test_examples_guidance.c - the guided-flight examples fly what their READMEs say (issue 12):
 *   examples/kourou-leo   a two-stage launch from Kourou into a low Earth orbit;
 *   examples/kourou-rtls  the same vehicle with its booster returning to the launch site.
 * The checks are requirement-level facts of the missions, not figures copied from a run:
 * every phase done and ended by the event it was built for, a closed orbit whose perigee
 * stays above 150 km for a whole revolution, the ascent's dynamic pressure and axial load
 * within the throttle law's limits (read from the run's parameters), no propellant book below
 * zero, the fairing's mass gone at the jettison, and the booster down on its pad slowly. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_mission.h"

#define DEG (M_PI / 180.0)

static double final(const lv_run *r, size_t k, const char *name)
{
    double v = NAN;
    lv_err err;
    CHECK_OK(lv_run_final(r, k, name, &v, &err), &err);
    return v;
}

static double param(const lv_run *r, const char *name)
{
    double v = NAN;
    lv_err err;
    CHECK_OK(lv_run_get(r, name, &v, &err), &err);
    return v;
}

static size_t phase(const lv_run *r, const char *name)
{
    size_t k = 0;
    lv_err err;
    CHECK_OK(lv_mission_phase_find(lv_run_mission(r), name, &k, &err), &err);
    return k;
}

/* Extremes of column `name` over phase k's rows whose altitude is above h_min (-INFINITY:
 * every row). */
static void col_range(const lv_run *r, size_t k, const char *name, double h_min, double *lo,
                      double *hi)
{
    const lv_result *res = lv_run_rows(r, k);
    size_t c, ch;
    *lo = INFINITY, *hi = -INFINITY;
    if (res == NULL || lv_result_column(res, name, &c, NULL) != LV_OK ||
        lv_result_column(res, "h", &ch, NULL) != LV_OK) {
        CHECK(0);
        return;
    }
    for (size_t i = 0; i < lv_result_rows(res); i++) {
        if (!(lv_result_value(res, i, ch) > h_min))
            continue;
        const double v = lv_result_value(res, i, c);
        *lo = v < *lo ? v : *lo;
        *hi = v > *hi ? v : *hi;
    }
}

static double first_row(const lv_run *r, size_t k, const char *name)
{
    const lv_result *res = lv_run_rows(r, k);
    size_t c;
    if (res == NULL || lv_result_rows(res) == 0 ||
        lv_result_column(res, name, &c, NULL) != LV_OK) {
        CHECK(0);
        return NAN;
    }
    return lv_result_value(res, 0, c);
}

/* Loads and runs examples/<name>/mission.yaml; NULL when it fails to load. */
static lv_run *run_example(const char *name, lv_mission **m)
{
    char path[1024];
    const char *root = getenv("LV_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/examples/%s/mission.yaml", root ? root : "..", name);
    lv_err err;
    lv_run *r = NULL;
    *m = NULL;
    CHECK_OK(lv_mission_load(path, m, &err), &err);
    if (*m == NULL)
        return NULL;
    CHECK_OK(lv_run_create(*m, &r, &err), &err);
    const lv_run_options opt = {.threads = 2};
    if (r != NULL)
        CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    return r;
}

/* Every phase done and ended by its first end event (the one it was built for: not a
 * fallback such as burnout or impact, nor its time limit). */
static void check_phases(const lv_run *r)
{
    const lv_mission *m = lv_run_mission(r);
    for (size_t k = 0; k < lv_mission_phase_count(m); k++) {
        const lv_phase_result *res = lv_run_result(r, k);
        const int ok = res->state == LV_PHASE_DONE && res->end_index == 0;
        if (!ok)
            fprintf(stderr, "  phase '%s': state %d, end %d (%s)\n", res->name, (int)res->state,
                    res->end_index, res->error);
        CHECK(ok);
    }
}

/* No phase's propellant book below zero: propellant_left in every row (the burning stage's,
 * to the integrator's rounding) and the stage book at every phase's end. */
static void check_propellant(const lv_run *r)
{
    const lv_mission *m = lv_run_mission(r);
    for (size_t k = 0; k < lv_mission_phase_count(m); k++) {
        double lo, hi;
        col_range(r, k, "propellant_left", -INFINITY, &lo, &hi);
        if (!(lo >= -1e-6))
            fprintf(stderr, "  phase '%s': propellant_left down to %g kg\n",
                    lv_mission_phase_name(m, k), lo);
        CHECK(lo >= -1e-6);
        const lv_phase_result *res = lv_run_result(r, k);
        for (size_t s = 0; s < lv_mission_stage_count(m); s++)
            CHECK(res->propellant_end[s] >= 0.0);
    }
}

/* The ascent's throttle law holds the dynamic pressure at most q_max (approached without
 * crossing, to the integrator's error) and the axial load at most g_limit (algebraic). */
static void check_ascent_limits(const lv_run *r)
{
    const size_t k = phase(r, "ascent");
    const double q_max = param(r, "ascent.throttle.q_max");
    const double g_limit = param(r, "ascent.throttle.g_limit");
    double lo, q_hi, n_hi;
    col_range(r, k, "q_dyn", -INFINITY, &lo, &q_hi);
    col_range(r, k, "n_axial", -INFINITY, &lo, &n_hi);
    printf("  ascent: max q %.1f Pa (limit %.0f), max axial load %.4f g (limit %.1f)\n", q_hi,
           q_max, n_hi, g_limit);
    CHECK(q_hi <= q_max * (1.0 + 1e-5));
    CHECK(q_hi >= 0.98 * q_max); /* the limit binds: the example shows it */
    CHECK(n_hi <= g_limit * (1.0 + 1e-9));
}

/* The upper stage: the fairing's mass gone at the jettison, and a closed low orbit that
 * keeps its perigee above 150 km through a whole revolution. */
static void check_upper_stage(const lv_run *r)
{
    const size_t k1 = phase(r, "upper-burn-1"), k2 = phase(r, "upper-burn-2");
    const size_t kc = phase(r, "orbit-coast");
    /* the stage book: the jettison takes exactly the fairing's dry mass off */
    CHECK_CLOSE(first_row(r, k2, "m"), final(r, k1, "m") - param(r, "fairing.dry_mass"), 1e-6);
    CHECK(final(r, k1, "h") >= 100000.0); /* above the air that would need the fairing */
    /* the orbit at the burn's end */
    const double peri = final(r, k2, "peri_alt"), apo = final(r, k2, "apo_alt");
    const double ecc = final(r, k2, "ecc"), inc = final(r, k2, "inc");
    printf("  orbit: %.1f x %.1f km, e %.5f, i %.3f deg; in it %.0f kg with %.0f kg of "
           "propellant left\n", peri / 1e3, apo / 1e3, ecc, inc / DEG, final(r, kc, "m"),
           final(r, kc, "propellant_left"));
    CHECK(peri >= 150000.0);
    CHECK(apo <= 2000000.0 && ecc < 0.01); /* a closed, near-circular low orbit */
    /* launched due east: the inclination is the site's latitude */
    CHECK(fabs(inc - param(r, "start_lat")) < 0.5 * DEG);
    /* one revolution: the altitude never below 150 km (J2 and drag act) */
    double h_lo, h_hi;
    col_range(r, kc, "h", -INFINITY, &h_lo, &h_hi);
    const double t_coast = lv_run_result(r, kc)->t_end - lv_run_result(r, kc)->t_start;
    const double period = 2.0 * M_PI * sqrt(pow(final(r, k2, "sma"), 3) / 3.986004418e14);
    printf("  coast: %.0f s (period %.0f s), altitude %.1f .. %.1f km\n", t_coast, period,
           h_lo / 1e3, h_hi / 1e3);
    CHECK(t_coast >= period);
    CHECK(h_lo >= 150000.0);
    CHECK(final(r, kc, "peri_alt") >= 150000.0);
    /* the payload is in orbit: nothing but the upper stage and the payload left */
    CHECK(final(r, kc, "m") >= param(r, "upper.dry_mass") + param(r, "payload.dry_mass"));
}

static void test_leo(void)
{
    lv_mission *m;
    printf("kourou-leo:\n");
    lv_run *r = run_example("kourou-leo", &m);
    if (r == NULL)
        return lv_mission_free(m);
    check_phases(r);
    check_propellant(r);
    check_ascent_limits(r);
    check_upper_stage(r);
    /* booster burnout is the staging */
    CHECK_CLOSE(final(r, phase(r, "ascent"), "propellant_left"), 0.0, 1e-6);
    lv_run_free(r);
    lv_mission_free(m);
}

static void test_rtls(void)
{
    lv_mission *m;
    printf("kourou-rtls:\n");
    lv_run *r = run_example("kourou-rtls", &m);
    if (r == NULL)
        return lv_mission_free(m);
    check_phases(r);
    check_propellant(r);
    check_ascent_limits(r);
    check_upper_stage(r);
    /* the booster stopped its ascent burn with its return's propellant */
    const size_t ka = phase(r, "ascent"), kl = phase(r, "landing");
    CHECK_CLOSE(final(r, ka, "propellant_left"), param(r, "ascent.end.propellant_left"), 1e-3);
    /* and it lands: on the ground, slowly, near the pad (the laws' default target is the
     * launch site), with propellant to spare */
    const double v_td = final(r, kl, "v_rel"), miss = final(r, kl, "target_distance");
    printf("  booster: touchdown at %.3f m/s, %.1f m from the pad, %.0f kg of propellant left\n",
           v_td, miss, final(r, kl, "propellant_left"));
    CHECK(fabs(final(r, kl, "h")) < 1e-3);
    CHECK(v_td < 3.0); /* the landing law aims at 2 m/s */
    CHECK(miss < 500.0);
    CHECK(final(r, kl, "propellant_left") > 0.0);
    /* the landing burn is flyable: down to the touchdown row itself the law never asks for
     * more thrust than the engines give (the constant-deceleration profile holds) */
    double lo, hi;
    col_range(r, kl, "throttle_in", -1.0, &lo, &hi);
    CHECK(hi < 1.0 && lo > 0.0);
    /* the booster's branch carries the booster alone: its mass is the stage's */
    CHECK_CLOSE(final(r, kl, "m"),
                param(r, "booster.dry_mass") + final(r, kl, "propellant_left"), 1e-6);
    lv_run_free(r);
    lv_mission_free(m);
}

int main(void)
{
    test_leo();
    test_rtls();
    return check_report("test_examples_guidance");
}
