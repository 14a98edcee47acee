/* test_vehicle.c - engines and aerodynamic sets (src/vehicle): Isp definition, nozzle
 * exit-pressure loss, throttle limits, thrust tables, coefficient tables and the
 * wind/body force rotation; bad configurations with their messages. Every expected
 * value is derived in the comment next to it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_vehicle.h"
#include "vehicle/vehicle.h"

#define P_SL 101325.0 /* Pa, US76 sea-level pressure */

/* ---- (1) constant engine: Isp definition and exit-pressure loss -------------------- */
/* mdot = F_vac / (Isp g0) (Sutton & Biblarz, eq. 2-5); F = c F_vac - p A_exit (eq. 2-14):
 * at sea level the loss is exactly p_SL A_exit, in vacuum there is none. */
static void test_engine_constant(void)
{
    lv_err err;
    lv_engine_config c;
    lv_engine_config_default(&c);
    c.name = "merlin";
    c.thrust_vac = 914e3;
    c.isp_vac = 311.0;
    c.exit_area = 1.2;
    lv_engine e;
    CHECK_OK(lv_engine_init(&e, &c, 0, &err), &err);
    double f, md, buf[1];
    CHECK_OK(lv_engine_eval(&e, 0.0, 1.0, 0.0, buf, &f, &md, &err), &err);
    CHECK(f == 914e3);
    CHECK(md == 914e3 / (311.0 * LV_G0)); /* exactly the Isp definition */
    double f_sl, md_sl;
    CHECK_OK(lv_engine_eval(&e, 0.0, 1.0, P_SL, buf, &f_sl, &md_sl, &err), &err);
    CHECK(f_sl == 914e3 - P_SL * 1.2);
    CHECK_CLOSE(f - f_sl, P_SL * 1.2, 1e-9);
    CHECK(md_sl == md); /* the mass flow does not depend on the back pressure */

    /* throttle: thrust and mass flow scale with c; commanded values outside the limits
     * are clamped (here [0, 1]) */
    CHECK_OK(lv_engine_eval(&e, 0.0, 0.5, 0.0, buf, &f, &md, &err), &err);
    CHECK(f == 0.5 * 914e3);
    CHECK(md == 0.5 * (914e3 / (311.0 * LV_G0)));
    CHECK_OK(lv_engine_eval(&e, 0.0, 1.7, 0.0, buf, &f, &md, &err), &err);
    CHECK(f == 914e3);
    /* over-expanded at idle: 0.001 * 914e3 - P_SL 1.2 < 0, floored at zero thrust */
    CHECK_OK(lv_engine_eval(&e, 0.0, 0.001, P_SL, buf, &f, &md, &err), &err);
    CHECK(f == 0.0);

    /* mass flow given directly: it wins over Isp */
    c.mdot = 250.0;
    CHECK_OK(lv_engine_init(&e, &c, 0, &err), &err);
    CHECK_OK(lv_engine_eval(&e, 0.0, 1.0, 0.0, buf, &f, &md, &err), &err);
    CHECK(md == 250.0);
}

/* ---- (2) thrust table over time ---------------------------------------------------- */
/* Linear interpolation between breakpoints (0, 100 kN, 40 kg/s), (10, 120 kN, 44 kg/s),
 * (20, 60 kN, 20 kg/s): at t = 15 s, F = 90 kN, mdot = 32 kg/s; without an "mdot"
 * column the Isp gives mdot = F/(Isp g0). */
static void test_engine_table(void)
{
    lv_err err;
    const double t[] = {0.0, 10.0, 20.0};
    const double y[] = {100e3, 40.0, 120e3, 44.0, 60e3, 20.0};
    const char *outs[] = {"thrust", "mdot"};
    lv_table_spec s = {.n_dims = 1, .n = {3}, .x = {t}, .n_out = 2, .y = y,
                       .extrap = LV_EXTRAP_CLAMP, .name = "thrust_curve",
                       .axis_name = {"time"}, .out_name = outs};
    lv_table *tab = NULL;
    CHECK_OK(lv_table_create(&s, &tab, &err), &err);
    lv_engine_config c;
    lv_engine_config_default(&c);
    c.table = tab;
    c.exit_area = 0.5;
    lv_engine e;
    CHECK_OK(lv_engine_init(&e, &c, 3, &err), &err);
    CHECK(strcmp(e.name, "engine3") == 0);
    double f, md, buf[2];
    CHECK_OK(lv_engine_eval(&e, 15.0, 1.0, 1000.0, buf, &f, &md, &err), &err);
    CHECK_CLOSE(f, 90e3 - 1000.0 * 0.5, 1e-9);
    CHECK_CLOSE(md, 32.0, 1e-12);

    /* thrust only + Isp */
    const char *outs1[] = {"thrust"};
    const double y1[] = {100e3, 120e3, 60e3};
    lv_table_spec s1 = s;
    s1.n_out = 1;
    s1.y = y1;
    s1.out_name = outs1;
    lv_table *tab1 = NULL;
    CHECK_OK(lv_table_create(&s1, &tab1, &err), &err);
    c.table = tab1;
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT, "has no output 'mdot'");
    c.isp_vac = 300.0;
    CHECK_OK(lv_engine_init(&e, &c, 0, &err), &err);
    CHECK_OK(lv_engine_eval(&e, 15.0, 1.0, 0.0, buf, &f, &md, &err), &err);
    CHECK_CLOSE(md, 90e3 * (1.0 / (300.0 * LV_G0)), 1e-12);

    /* a table over Mach is not a thrust curve */
    lv_table_spec s2 = s;
    s2.axis_name[0] = "mach";
    lv_table *tab2 = NULL;
    CHECK_OK(lv_table_create(&s2, &tab2, &err), &err);
    c.table = tab2;
    c.name = "vinci";
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT,
                "engine 'vinci': table 'thrust_curve' must have exactly one axis named 'time'");
    /* and a table without "thrust" */
    const char *outs3[] = {"F", "mdot"};
    lv_table_spec s3 = s;
    s3.out_name = outs3;
    lv_table *tab3 = NULL;
    CHECK_OK(lv_table_create(&s3, &tab3, &err), &err);
    c.table = tab3;
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_NOTFOUND, "needs an output 'thrust'");
    lv_table_free(tab);
    lv_table_free(tab1);
    lv_table_free(tab2);
    lv_table_free(tab3);
}

static void test_engine_errors(void)
{
    lv_err err;
    lv_engine e;
    lv_engine_config c;
    lv_engine_config_default(&c);
    c.name = "e1";
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT, "thrust_vac = 0 N");
    c.thrust_vac = 1e5;
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT, "give isp_vac (s) or mdot");
    c.isp_vac = -3.0;
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT, "isp_vac = -3 s");
    c.isp_vac = 300.0;
    c.throttle_min = 0.8;
    c.throttle_max = 0.6;
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT,
                "engine 'e1': throttle limits [0.8, 0.6] invalid");
    /* issue 27 (L5): the range ends at LV_THROTTLE_MAX = 2 (twice the rated thrust), finite */
    c.throttle_min = 0.0;
    c.throttle_max = 1e9;
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT,
                "engine 'e1': throttle limits [0, 1e+09] invalid (need 0 <= min <= max, 0 < max "
                "<= 2");
    c.throttle_max = INFINITY;
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT, "throttle limits [0, inf]");
    c.throttle_max = nextafter(LV_THROTTLE_MAX, 3.0);
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT, "throttle limits");
    c.throttle_max = LV_THROTTLE_MAX;
    CHECK_OK(lv_engine_init(&e, &c, 0, &err), &err);
    c.throttle_max = 1.0;
    c.exit_area = -1.0;
    CHECK_FAILS(lv_engine_init(&e, &c, 0, &err), &err, LV_ERR_INPUT, "exit_area = -1");
}

/* ---- (3) aerodynamics ---------------------------------------------------------------- */
/* A bilinear CD(mach, alpha) = 0.2 + 0.1 mach + 2 alpha and CL = 3 alpha are reproduced
 * exactly by linear interpolation: at mach 1.5, alpha 0.05: CD = 0.45, CL = 0.15. */
static lv_table *make_aero_table(const char *ax0, const char *ax1)
{
    static const double mach[] = {0.0, 1.0, 2.0, 4.0};
    static const double alpha[] = {-0.1, 0.0, 0.1};
    double y[4 * 3 * 2];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 3; j++) {
            y[(i * 3 + j) * 2] = 0.2 + 0.1 * mach[i] + 2.0 * alpha[j];
            y[(i * 3 + j) * 2 + 1] = 3.0 * alpha[j];
        }
    const char *outs[] = {"CD", "CL"};
    lv_table_spec s = {.n_dims = 2, .n = {4, 3}, .x = {mach, alpha}, .n_out = 2, .y = y,
                       .name = "aero_ascent", .axis_name = {ax0, ax1}, .out_name = outs};
    lv_table *t = NULL;
    lv_err err;
    CHECK_OK(lv_table_create(&s, &t, &err), &err);
    return t;
}

static void test_aero_wind(void)
{
    lv_err err;
    lv_table *t = make_aero_table("mach", "alpha");
    lv_aero_config c;
    lv_aero_config_default(&c);
    c.s_ref = 4.0;
    c.coef[0].table = t;
    c.coef[1].table = t;
    c.coef[2].value = -0.01;
    lv_aero a;
    CHECK_OK(lv_aero_init(&a, &c, &err), &err);
    CHECK(a.n_tab == 1); /* one table, evaluated once for CD and CL */
    double coef[3];
    CHECK_OK(lv_aero_coefs(&a, 1.5, 0.05, 0.0, 1e4, coef, &err), &err);
    CHECK_CLOSE(coef[0], 0.45, 1e-15);
    CHECK_CLOSE(coef[1], 0.15, 1e-15);
    CHECK(coef[2] == -0.01);
    /* F_w = q S (-CD, CY, -CL) */
    const double qs = 20e3 * 4.0;
    double fw[3];
    lv_aero_force_wind(&a, coef, qs, cos(0.05), sin(0.05), 1.0, 0.0, fw);
    CHECK_CLOSE(fw[0], -qs * 0.45, 1e-9);
    CHECK_CLOSE(fw[1], -qs * 0.01, 1e-9);
    CHECK_CLOSE(fw[2], -qs * 0.15, 1e-9);
    /* out of the table under LV_EXTRAP_ERROR: the table's message, prefixed */
    CHECK_FAILS(lv_aero_coefs(&a, 5.0, 0.0, 0.0, 0.0, coef, &err), &err, LV_ERR_INPUT,
                "aerodynamics");
    lv_aero_clear(&a);
    lv_table_free(t);
}

/* Body axes: drag and lift from axial and normal coefficients (Anderson, Fundamentals of
 * Aerodynamics, 6th ed., eqs. 1.1-1.2): D = qS (CA cos a + CN sin a) cos b ..., here with
 * beta = 0: D = qS (CA cos a + CN sin a), L = qS (CN cos a - CA sin a). */
static void test_aero_body(void)
{
    lv_err err;
    lv_aero_config c;
    lv_aero_config_default(&c);
    c.axes = LV_AERO_BODY;
    c.s_ref = 2.0;
    c.coef[0].value = 0.3; /* CA */
    c.coef[1].value = 0.8; /* CN */
    lv_aero a;
    CHECK_OK(lv_aero_init(&a, &c, &err), &err);
    double coef[3], fw[3];
    CHECK_OK(lv_aero_coefs(&a, 2.0, 0.1, 0.0, 0.0, coef, &err), &err);
    const double al = 0.1, qs = 5e4 * 2.0;
    lv_aero_force_wind(&a, coef, qs, cos(al), sin(al), 1.0, 0.0, fw);
    CHECK_CLOSE(-fw[0], qs * (0.3 * cos(al) + 0.8 * sin(al)), 1e-8);
    CHECK_CLOSE(-fw[2], qs * (0.8 * cos(al) - 0.3 * sin(al)), 1e-8);
    CHECK_CLOSE(fw[1], 0.0, 1e-9);
    /* sideslip only, CY = 0: the axial force splits into drag and side force:
     * f_w = CA along -x_b = -(cb, -sb, 0) qS CA */
    c.coef[1].value = 0.0;
    CHECK_OK(lv_aero_init(&a, &c, &err), &err);
    CHECK_OK(lv_aero_coefs(&a, 2.0, 0.0, 0.2, 0.0, coef, &err), &err);
    lv_aero_force_wind(&a, coef, qs, 1.0, 0.0, cos(0.2), sin(0.2), fw);
    CHECK_CLOSE(fw[0], -qs * 0.3 * cos(0.2), 1e-9);
    CHECK_CLOSE(fw[1], qs * 0.3 * sin(0.2), 1e-9);
    CHECK_CLOSE(fw[2], 0.0, 1e-9);
}

static void test_aero_errors(void)
{
    lv_err err;
    lv_aero a;
    lv_aero_config c;
    lv_aero_config_default(&c);
    c.s_ref = 0.0;
    CHECK_FAILS(lv_aero_init(&a, &c, &err), &err, LV_ERR_INPUT, "s_ref = 0 m^2");
    c.s_ref = 1.0;
    lv_table *bad = make_aero_table("mach", "aoa");
    c.coef[0].table = bad;
    CHECK_FAILS(lv_aero_init(&a, &c, &err), &err, LV_ERR_INPUT,
                "aerodynamics CD: table 'aero_ascent': axis 1 is named 'aoa'");
    lv_table *t = make_aero_table("mach", "alpha");
    c.coef[0].table = t;
    c.coef[2].table = t; /* two outputs, no "CY" among them */
    CHECK_FAILS(lv_aero_init(&a, &c, &err), &err, LV_ERR_NOTFOUND, "aerodynamics CY");
    c.coef[2].table = NULL;
    c.coef[0].output = "cd";
    CHECK_FAILS(lv_aero_init(&a, &c, &err), &err, LV_ERR_NOTFOUND, "'cd'");
    lv_table *dup = make_aero_table("mach", "mach");
    c.coef[0].table = dup;
    c.coef[0].output = NULL;
    CHECK_FAILS(lv_aero_init(&a, &c, &err), &err, LV_ERR_INPUT, "axis 'mach' appears twice");
    lv_table_free(bad);
    lv_table_free(t);
    lv_table_free(dup);
}

int main(void)
{
    test_engine_constant();
    test_engine_table();
    test_engine_errors();
    test_aero_wind();
    test_aero_body();
    test_aero_errors();
    return check_report("test_vehicle");
}
