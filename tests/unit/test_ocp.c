/* test_ocp.c - the optimal-control C API (lv_ocp.h; docs/optimal-control.md) on the linear
 * tangent problem: over a flat world (a non-rotating sphere of radius 1e10 m, g0 at its
 * surface) a constant thrust acceleration a = 2 g0 steered to maximise the horizontal speed at
 * tf = 60 s with the altitude 10 km higher and zero vertical speed there. Bryson & Ho, Applied
 * Optimal Control (1975), sec. 2.7: tan(theta) = tan(theta0) - c t, whose states are closed
 * forms (the integrals of cos and sin of theta; as tests/unit/test_guidance.c), theta0 and c
 * from y(tf) = H, vy(tf) = 0 by Newton's method here. Checked:
 *   (a) the optimum's horizontal speed against the closed form (11 control nodes);
 *   (b) one thread and two give the same point bit for bit (each Jacobian column is one
 *       worker's, whatever the thread);
 *   (c) the written optimal mission loads and flies to the optimum's speed;
 *   (d) an unreachable altitude: not optimal, the violated final named (lv_ocp_violation);
 *   (e) a mission without the section is refused. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_ocp.h"
#include "mission_kit.h"

#define G0 9.80665
#define TF 60.0
#define DH 10000.0
#define V0 100.0
#define FPA0 (80.0 * 3.14159265358979323846 / 180.0)

/* (y - y0, vx, vy) at t under tan(theta) = xi0 - c t, thrust acceleration a, from (vx0, vy0) */
static void lt_state(double a, double xi0, double c, double t, double *y, double *vx, double *vy)
{
    const double vx0 = V0 * cos(FPA0), vy0 = V0 * sin(FPA0);
    const double xi = xi0 - c * t;
    const double s0 = sqrt(1.0 + xi0 * xi0), s1 = sqrt(1.0 + xi * xi);
    const double g0v = 0.5 * (xi0 * s0 + asinh(xi0)), g1 = 0.5 * (xi * s1 + asinh(xi));
    *vx = vx0 + a / c * (asinh(xi0) - asinh(xi));
    *vy = vy0 + a / c * (s0 - s1) - G0 * t;
    *y = vy0 * t + a / c * (s0 * t - (g0v - g1) / c) - 0.5 * G0 * t * t;
}

static double lt_reference(void)
{
    const double a = 2.0 * G0;
    double xi0 = 1.5, c = 0.03, y, vx, vy, y1, vy1, y2, vy2; /* near the root (Newton) */
    for (int it = 0; it < 60; it++) {
        const double h1 = 1e-7 * xi0, h2 = 1e-7 * c;
        lt_state(a, xi0, c, TF, &y, &vx, &vy);
        lt_state(a, xi0 + h1, c, TF, &y1, &vx, &vy1);
        lt_state(a, xi0, c + h2, TF, &y2, &vx, &vy2);
        const double J00 = (y1 - y) / h1, J01 = (y2 - y) / h2;
        const double J10 = (vy1 - vy) / h1, J11 = (vy2 - vy) / h2;
        const double f0 = y - DH, f1 = vy, det = J00 * J11 - J01 * J10;
        xi0 -= (J11 * f0 - J01 * f1) / det;
        c -= (J00 * f1 - J10 * f0) / det;
    }
    lt_state(a, xi0, c, TF, &y, &vx, &vy);
    CHECK_CLOSE(y, DH, 1e-6);
    CHECK_CLOSE(vy, 0.0, 1e-9);
    return vx;
}

static const char *mission(double h_final)
{
    static char text[2048];
    snprintf(text, sizeof text,
             "mission: {name: lt-ocp}\n" FLAT_WORLD
             "parameters: {start_h: 1000, start_vel: %g, start_fpa_deg: 80, start_chi_deg: 90}\n"
             "stages: [{name: s, dry_mass: 1000, propellant_mass: 100,\n"
             "          engines: [{thrust_vac: %.17g, isp_vac: 1.0e15}]}]\n"
             "phases:\n"
             "  - {name: climb, model: dof3, stages: [s], stop_time: %g, inputs: {alpha_deg: 0}}\n"
             "optimal_control:\n"
             "  phases: [{name: climb, nodes: 11,\n"
             "            controls: [{name: alpha_deg, min: -60, max: 60}]}]\n"
             "  constraints:\n"
             "    - {final: climb.h, equal: %.17g, tolerance: 0.01}\n"
             "    - {final: climb.v_down, equal: 0, tolerance: 1.0e-4}\n"
             "  cost: {maximize: climb.v_east}\n",
             V0, 2.0 * G0 * 1100.0, TF, 1000.0 + h_final);
    return text;
}

static void test_linear_tangent(void)
{
    const double vx_ref = lt_reference();
    lv_err err;
    write_file("ocp_lt.yaml", mission(DH));
    double cost[2] = {NAN, NAN};
    for (int threads = 1; threads <= 2; threads++) {
        lv_ocp *o = NULL;
        CHECK_OK(lv_ocp_create("ocp_lt.yaml", &o, &err), &err);
        if (o == NULL)
            return;
        lv_ocp_settings s = {.threads = threads};
        lv_ocp_result res;
        CHECK_OK(lv_ocp_solve(o, &s, &res, &err), &err);
        printf("%d thread(s): %s after %d iterations, vx(tf) %.9f m/s (closed form %.9f), "
               "%zu variables, %zu rows, %zu groups, %.2f s\n", threads, res.ipopt_text,
               res.iterations, res.cost, vx_ref, res.n_vars, res.n_cons, res.n_groups,
               res.wall);
        CHECK(res.outcome == LV_OCP_OPTIMAL);
        CHECK(res.n_violated == 0);
        /* 11 nodes: the control's discretisation, 0.018 m/s measured (21 nodes: 1.1e-3) */
        CHECK_CLOSE(res.cost, vx_ref, 0.03);
        cost[threads - 1] = res.cost;
        if (threads == 2) {
            CHECK_OK(lv_ocp_write(o, "ocp_lt_opt.yaml", LV_OUTPUT_REPLACE, &err), &err);
            lv_mission *m = NULL;
            lv_run *r = NULL;
            CHECK_OK(lv_mission_load("ocp_lt_opt.yaml", &m, &err), &err);
            if (m != NULL && lv_run_create(m, &r, &err) == LV_OK) {
                CHECK_OK(lv_run_execute(r, NULL, &err), &err);
                double ve = NAN;
                CHECK_OK(lv_run_final(r, 0, "v_east", &ve, &err), &err);
                printf("the written mission re-flown: v_east %.9f m/s\n", ve);
                CHECK_CLOSE(ve, res.cost, 1e-4);
            }
            lv_run_free(r);
            lv_mission_free(m);
        }
        lv_ocp_free(o);
    }
    CHECK(cost[0] == cost[1]);
}

static void test_unreachable(void)
{
    lv_err err;
    write_file("ocp_far.yaml", mission(200000.0));
    lv_ocp *o = NULL;
    CHECK_OK(lv_ocp_create("ocp_far.yaml", &o, &err), &err);
    if (o == NULL)
        return;
    CHECK_FAILS(lv_ocp_write(o, "ocp_far_opt.yaml", 0, &err), &err, LV_ERR_INPUT,
                "not been solved");
    lv_ocp_settings s = {.threads = 2, .max_iterations = 30};
    lv_ocp_result res;
    CHECK_OK(lv_ocp_solve(o, &s, &res, &err), &err);
    CHECK(res.outcome != LV_OCP_OPTIMAL);
    CHECK(res.n_violated > 0);
    int named = 0;
    for (size_t i = 0; i < res.n_violated; i++) {
        char text[512];
        double v;
        CHECK_OK(lv_ocp_violation(o, i, text, sizeof text, &v, &err), &err);
        named |= strstr(text, "final 'climb.h'") != NULL;
        if (i < 3)
            printf("violated: %s (%.3g)\n", text, v);
    }
    CHECK(named);
    CHECK_FAILS(lv_ocp_violation(o, res.n_violated, (char[8]){0}, 8, NULL, &err), &err,
                LV_ERR_INPUT, "violated");
    CHECK_FAILS(lv_ocp_write(o, "ocp_far_opt.yaml", 0, &err), &err, LV_ERR_INPUT,
                "did not end optimal");
    CHECK_FAILS(lv_ocp_check_write(o, "ocp_far.yaml", LV_OUTPUT_REPLACE, &err), &err,
                LV_ERR_INPUT, "");
    lv_ocp_free(o);
}

static void test_no_section(void)
{
    lv_err err;
    write_file("ocp_none.yaml", "mission: {name: none}\n" FLAT_WORLD
                                "stages: [{name: s, dry_mass: 1000, propellant_mass: 0}]\n"
                                "phases: [{name: c, model: dof3, stages: [s], stop_time: 1}]\n");
    lv_ocp *o = NULL;
    CHECK_FAILS(lv_ocp_create("ocp_none.yaml", &o, &err), &err, LV_ERR_INPUT,
                "no optimal_control");
    CHECK(o == NULL);
}

int main(void)
{
    test_linear_tangent();
    test_unreachable();
    test_no_section();
    return check_report("test_ocp");
}
