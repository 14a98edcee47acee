/* test_profile.c - atmosphere and wind profiles from files (docs/atmosphere.md, "Profiles";
 * docs/wind.md, "Profiles"): a sounding text list and two CSV forecasts read back at their
 * levels, the missing one of T, p, rho by the ideal-gas law, the blend into US76 above the
 * top, the winds' taper, two profiles interpolated in time, a dispersed (scaled, biased)
 * profile wind, and bad files refused with file:line:column. Reference values are worked out
 * by hand from the files' text (the formulas are in the comments). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_wind.h"

#define R_AIR (8314.32 / 28.9644) /* J/(kg K), dry air: R* / M0 = 287.05307 */
#define R0 6356766.0              /* m, US76 eq. (18) */
#define KNOT (1852.0 / 3600.0)    /* m/s */

static char g_dir[1024];

static const char *data(const char *name)
{
    static char buf[4][1200];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", g_dir, name);
    return buf[k];
}

/* geometric altitude of geopotential height H, US76 eq. (18) inverted */
static double z_of(double H)
{
    return R0 * H / (R0 - H);
}

static void write_text(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (fp == NULL)
        return;
    fputs(text, fp);
    fclose(fp);
}

/* the sounding: its levels read back, the gas law, the surface, the blend into US76 */
static void test_sounding_atmosphere(void)
{
    lv_err err;
    lv_atmo *atm = NULL, *us = NULL;
    lv_atmo_state s, u0, u1;
    CHECK_OK(lv_atmo_create_profile(data("sounding.txt"), LV_ATMO_PROFILE_BLEND, &atm, &err),
             &err);
    CHECK_OK(lv_atmo_create("us76", &us, &err), &err);
    if (atm == NULL || us == NULL)
        goto done;
    /* 850 hPa, 1440 gpm, 15.0 C: z = 1440.32628 m; rho = 85000 / (287.05307 * 288.15)
     * = 1.0276331 kg/m^3 */
    CHECK_OK(lv_atmo_eval(atm, z_of(1440.0), &s, &err), &err);
    CHECK_CLOSE(z_of(1440.0), 1440.32628, 1e-5);
    CHECK_CLOSE(s.T, 288.15, 1e-12);
    CHECK_REL(s.p, 85000.0, 1e-14);
    CHECK_REL(s.rho, 1.0276331, 1e-7);
    CHECK_REL(s.rho, s.p / (R_AIR * s.T), 1e-14);
    /* 500 hPa, 5800 gpm, -8.5 C (the level after the wind-only row at 600 hPa) */
    CHECK_OK(lv_atmo_eval(atm, z_of(5800.0), &s, &err), &err);
    CHECK_CLOSE(s.T, 264.65, 1e-12);
    CHECK_REL(s.p, 50000.0, 1e-14);
    /* between 925 hPa (720 gpm, 19.5 C) and 850 hPa: T linear, p log-linear in altitude */
    const double za = z_of(720.0), zb = z_of(1440.0), zm = 0.25 * za + 0.75 * zb;
    CHECK_OK(lv_atmo_eval(atm, zm, &s, &err), &err);
    CHECK_CLOSE(s.T, 0.25 * 292.65 + 0.75 * 288.15, 1e-11);
    CHECK_REL(s.p, exp(0.25 * log(92500.0) + 0.75 * log(85000.0)), 1e-13);
    /* the lowest level is the surface row (998 hPa at the station's 60 m; the 1000 hPa row at
     * 45 m carries its height only and is skipped). Below it T is held (297.15 K) and p falls
     * off isothermally: at 0 gpm (z = 0), p = 99800 exp(g0 * 60 / (R 297.15)) = 99800 *
     * exp(588.399 / 85297.82) = 100490.8 Pa. Below -5 km: refused. */
    CHECK_OK(lv_atmo_eval(atm, z_of(60.0), &s, &err), &err);
    CHECK_REL(s.p, 99800.0, 1e-14);
    CHECK_OK(lv_atmo_eval(atm, 0.0, &s, &err), &err);
    CHECK_CLOSE(s.T, 297.15, 1e-12);
    CHECK_REL(s.p, 100490.8, 1e-6);
    CHECK_REL(s.rho, s.p / (R_AIR * s.T), 1e-13);
    CHECK(lv_atmo_eval(atm, -5001.0, &s, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "outside the valid range -5000 m to 1000000 m") != NULL);
    /* blend: top 20 hPa, 26500 gpm, -48.0 C = 225.15 K; US76 there (H = 26500 m') is
     * 216.65 + 0.001 (26500 - 20000) = 223.15 K, so dT = 2 K. Halfway through the 10 km band,
     * at z = z_top + 5000 m, H = r0 z / (r0 + z) = 31454.518 m': T = 216.65 + 0.001 (H - 20000)
     * + 2/2 = 229.104518 K; ln p and ln rho keep half their offsets at the top. */
    const double zt = z_of(26500.0), h = zt + 5000.0;
    CHECK_CLOSE(zt, 26610.9353, 1e-4);
    CHECK_OK(lv_atmo_eval(atm, h, &s, &err), &err);
    CHECK_CLOSE(s.T, 229.104518, 2e-6);
    CHECK_OK(lv_atmo_eval(us, zt, &u0, &err), &err);
    CHECK_OK(lv_atmo_eval(us, h, &u1, &err), &err);
    CHECK_CLOSE(u0.T, 223.15, 1e-9);
    const double p_top = 2000.0, rho_top = 2000.0 / (R_AIR * 225.15);
    CHECK_REL(s.p, u1.p * sqrt(p_top / u0.p), 1e-12);
    CHECK_REL(s.rho, u1.rho * sqrt(rho_top / u0.rho), 1e-12);
    /* continuous at the top; US76 itself from the band's end up */
    CHECK_OK(lv_atmo_eval(atm, zt, &s, &err), &err);
    CHECK_CLOSE(s.T, 225.15, 1e-12);
    CHECK_OK(lv_atmo_eval(atm, zt + 1e-6, &s, &err), &err);
    CHECK_CLOSE(s.T, 225.15, 1e-6);
    CHECK_REL(s.p, p_top, 1e-9);
    CHECK_OK(lv_atmo_eval(atm, zt + 10000.0, &s, &err), &err);
    CHECK_OK(lv_atmo_eval(us, zt + 10000.0, &u1, &err), &err);
    CHECK_CLOSE(s.T, u1.T, 1e-9);
    CHECK_REL(s.p, u1.p, 1e-14);
    CHECK_OK(lv_atmo_eval(atm, 300e3, &s, &err), &err);
    CHECK_OK(lv_atmo_eval(us, 300e3, &u1, &err), &err);
    CHECK(s.rho == u1.rho && s.T == u1.T);
done:
    lv_atmo_free(atm);
    lv_atmo_free(us);
}

/* the CSV forecasts: units converted, the missing quantity from p = rho R T */
static void test_csv_atmosphere(void)
{
    lv_err err;
    lv_atmo *a0 = NULL, *a1 = NULL;
    lv_atmo_state s;
    CHECK_OK(lv_atmo_create_profile(data("forecast_t0.csv"), 2000.0, &a0, &err), &err);
    CHECK_OK(lv_atmo_create_profile(data("forecast_t1.csv"), 2000.0, &a1, &err), &err);
    if (a0 == NULL || a1 == NULL)
        goto done;
    /* t0 at 1 km: 898 hPa, 293.5 K: rho = 89800 / (287.05307 * 293.5) = 1.0658744 kg/m^3 */
    CHECK_OK(lv_atmo_eval(a0, 1000.0, &s, &err), &err);
    CHECK_CLOSE(s.T, 293.5, 1e-12);
    CHECK_REL(s.p, 89800.0, 1e-14);
    CHECK_REL(s.rho, 1.0658744, 1e-7);
    /* t1 at 1000 m: 20.5 C, 1.06 kg/m^3: p = 1.06 * 287.05307 * 293.65 = 89350.72 Pa */
    CHECK_OK(lv_atmo_eval(a1, 1000.0, &s, &err), &err);
    CHECK_CLOSE(s.T, 293.65, 1e-12);
    CHECK_REL(s.rho, 1.06, 1e-14);
    CHECK_REL(s.p, 89350.72, 1e-7);
    /* a = (1.4 R* T / M0)^1/2 = (1.4 * 287.05307 * 293.65)^1/2 = 343.5264 m/s */
    CHECK_REL(s.a, 343.5264, 1e-6);
    CHECK(lv_atmo_eval(a1, NAN, &s, &err) == LV_ERR_INPUT);
done:
    lv_atmo_free(a0);
    lv_atmo_free(a1);
}

/* winds: the sounding's levels, the taper, two forecasts in time, a dispersed copy */
static void test_profile_winds(void)
{
    lv_err err;
    lv_wind *w = NULL, *w2 = NULL, *wd = NULL;
    double v[3];
    const char *one[1] = { data("sounding.txt") };
    const double t1[1] = { 0.0 };
    CHECK_OK(lv_wind_create_profiles(one, t1, 1, 10000.0, &w, &err), &err);
    if (w == NULL)
        return;
    CHECK(lv_wind_profile_count(w) == 1);
    /* 850 hPa: from 120 deg at 20 knot = 10.288889 m/s: the air moves towards 300 deg:
     * north = -V cos 120 = +5.144444, east = -V sin 120 = -8.910439 m/s */
    CHECK_OK(lv_wind_eval_at(w, NULL, 123.0, z_of(1440.0), v, &err), &err);
    CHECK_CLOSE(v[0], 5.144444444, 1e-8);
    CHECK_CLOSE(v[1], -8.910439154, 1e-8);
    CHECK(v[2] == 0.0);
    /* the wind-only row 600 hPa, 4310 gpm, 250 deg at 30 knot: north = -V cos 250, east =
     * -V sin 250 (V = 15.433333 m/s): 5.278511, 14.502589 */
    CHECK_OK(lv_wind_eval(w, NULL, z_of(4310.0), v, &err), &err);
    CHECK_CLOSE(v[0], 5.278511, 1e-6);
    CHECK_CLOSE(v[1], 14.502589, 1e-6);
    /* the temperature-only row 700 hPa (3080 gpm) is no wind level: between 1440 gpm
     * (5.144444, -8.910439) and 4310 gpm, linear in geometric altitude */
    const double za = z_of(1440.0), zb = z_of(4310.0), zc = z_of(3080.0);
    const double f = (zc - za) / (zb - za);
    CHECK_OK(lv_wind_eval(w, NULL, zc, v, &err), &err);
    CHECK_CLOSE(v[0], (1.0 - f) * 5.144444444 + f * 5.278511, 1e-6);
    /* below the surface row (60 gpm, 90 deg at 10 knot: east = -5.144444): held */
    CHECK_OK(lv_wind_eval(w, NULL, -100.0, v, &err), &err);
    CHECK_CLOSE(v[1], -10.0 * KNOT, 1e-12);
    CHECK_CLOSE(v[0], 0.0, 1e-12);
    /* the top (26500 gpm, 100 deg at 20 knot) tapers to 0 over 10 km: half at 5 km above */
    const double zt = z_of(26500.0);
    CHECK_OK(lv_wind_eval(w, NULL, zt + 5000.0, v, &err), &err);
    CHECK_CLOSE(v[1], 0.5 * -20.0 * KNOT * sin(100.0 * M_PI / 180.0), 1e-9);
    CHECK_OK(lv_wind_eval(w, NULL, zt + 10000.0, v, &err), &err);
    CHECK(v[0] == 0.0 && v[1] == 0.0);
    CHECK_OK(lv_wind_eval(w, NULL, 80e3, v, &err), &err);
    CHECK(v[0] == 0.0 && v[1] == 0.0);

    /* two forecasts, at t = 0 and t = 3600 s, blend 2 km. At t = 900 s the weights are 3/4
     * and 1/4. h = 1000 m: t0 (4, 8), t1 from 270 deg at 10 m/s = (0, 10): (3, 8.5).
     * h = 3000 m: t0 halfway between 1 km (4, 8) and 5 km (10, 20) = (7, 14); t1 halfway
     * between (0, 10) and 5 km, from 180 deg at 30 m/s = (30, 0): (15, 5); mixed (9, 11.75).
     * h = 6000 m, half through the taper: (5, 10) and (15, 0): (7.5, 7.5). */
    const char *two[2] = { data("forecast_t0.csv"), data("forecast_t1.csv") };
    const double t2[2] = { 0.0, 3600.0 };
    CHECK_OK(lv_wind_create_profiles(two, t2, 2, 2000.0, &w2, &err), &err);
    if (w2 == NULL)
        goto done;
    lv_table_cursor cur = LV_TABLE_CURSOR_INIT;
    CHECK_OK(lv_wind_eval_at(w2, &cur, 900.0, 1000.0, v, &err), &err);
    CHECK_CLOSE(v[0], 3.0, 1e-12);
    CHECK_CLOSE(v[1], 8.5, 1e-12);
    CHECK_OK(lv_wind_eval_at(w2, &cur, 900.0, 3000.0, v, &err), &err);
    CHECK_CLOSE(v[0], 9.0, 1e-12);
    CHECK_CLOSE(v[1], 11.75, 1e-12);
    CHECK_OK(lv_wind_eval_at(w2, &cur, 900.0, 6000.0, v, &err), &err);
    CHECK_CLOSE(v[0], 7.5, 1e-12);
    CHECK_CLOSE(v[1], 7.5, 1e-12);
    /* before the first and after the last profile: that profile */
    CHECK_OK(lv_wind_eval_at(w2, &cur, -50.0, 3000.0, v, &err), &err);
    CHECK_CLOSE(v[0], 7.0, 1e-12);
    CHECK_OK(lv_wind_eval_at(w2, &cur, 1e5, 3000.0, v, &err), &err);
    CHECK_CLOSE(v[0], 15.0, 1e-12);
    CHECK_CLOSE(v[1], 5.0, 1e-12);
    /* the 3-DoF hook passes the time through */
    lv_wind_user wu = LV_WIND_USER_INIT(w2);
    CHECK(lv_wind_fn_table(900.0, 3000.0, 0.1, 0.2, v, &wu) == 0);
    CHECK_CLOSE(v[1], 11.75, 1e-12);
    CHECK(lv_wind_fn_table(NAN, 3000.0, 0.1, 0.2, v, &wu) == 1);
    /* dispersions (lvsim mc's environment.wind.scale, .north.bias): 2 v + (1, 0) */
    const double bias[3] = { 1.0, 0.0, 5.0 };
    CHECK_OK(lv_wind_create_affine(w2, 2.0, bias, &wd, &err), &err);
    if (wd != NULL) {
        CHECK(lv_wind_profile_count(wd) == 2);
        CHECK_OK(lv_wind_eval_at(wd, NULL, 900.0, 3000.0, v, &err), &err);
        CHECK_CLOSE(v[0], 19.0, 1e-12);
        CHECK_CLOSE(v[1], 23.5, 1e-12);
        CHECK(v[2] == 0.0); /* no down component: its bias is ignored */
    }
    /* times out of order */
    const double tbad[2] = { 10.0, 10.0 };
    lv_wind *wb = NULL;
    CHECK(lv_wind_create_profiles(two, tbad, 2, 2000.0, &wb, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "increasing") != NULL);
done:
    lv_wind_free(w);
    lv_wind_free(w2);
    lv_wind_free(wd);
}

/* bad files: each refused with its file:line:column */
static void test_bad_files(void)
{
    static const struct {
        const char *name, *text, *where, *what;
        int wind; /* 1: load as a wind profile */
    } cases[] = {
        { "p_order.csv", "h [m], T [K], p [Pa]\n0, 288, 101325\n1000, 281, 89900\n900, 282, 90000\n",
          "p_order.csv:4:1:", "not greater than the previous", 0 },
        { "p_nan.csv", "h [m], T [K], p [Pa]\n0, 288, 101325\n1000, nan, 89900\n",
          "p_nan.csv:3:7:", "expected a finite number, found 'nan'", 0 },
        { "p_gap.csv", "h [m], T [K], p [Pa]\n0, 288, 101325\n1000, , 89900\n",
          "p_gap.csv:3:7:", "expected a finite number", 0 },
        { "p_one.csv", "# only T\nh [m], T [K]\n0, 288\n1000, 281\n",
          "p_one.csv:2:1:", "one of T, p, rho is not enough", 0 },
        { "p_unit.csv", "h [m], T [F], p [Pa]\n0, 59, 101325\n1000, 48, 89900\n",
          "p_unit.csv:1:8:", "column 'T' has unit 'F'", 0 },
        { "p_nounit.csv", "h [m], T, p [Pa]\n0, 288, 101325\n1000, 281, 89900\n",
          "p_nounit.csv:1:8:", "has no unit", 0 },
        { "p_col.csv", "h [m], T [K], p [Pa], rh [%]\n0, 288, 101325, 50\n1000, 281, 89900, 40\n",
          "p_col.csv:1:23:", "unknown column 'rh'", 0 },
        { "p_alt.csv", "alt [m], T [K], p [Pa]\n0, 288, 101325\n1000, 281, 89900\n",
          "p_alt.csv:1:1:", "'h [m]' (geometric) or 'gph [m]'", 0 },
        { "p_neg.csv", "h [m], T [K], p [Pa]\n0, 288, 101325\n1000, 281, -5\n",
          "p_neg.csv:3:12:", "p = -5 Pa must be positive", 0 },
        { "p_deep.csv", "h [km], T [K], p [Pa]\n-6, 288, 101325\n1, 281, 89900\n",
          "p_deep.csv:2:1:", "below the surface", 0 },
        { "w_half.csv", "h [m], speed [m/s]\n0, 3\n1000, 5\n",
          "w_half.csv:1:1:", "needs a direction column", 1 },
        { "w_none.csv", "h [m], T [K], p [Pa]\n0, 288, 101325\n1000, 281, 89900\n",
          "w_none.csv:", "has no wind", 1 },
        { "s_below.txt",
          "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV\n"
          "    hPa     m      C      C      %    g/kg    deg   knot     K      K      K \n"
          "-----------------------------------------------------------------------------\n"
          " 1000.0     45   24.5\n"
          "  998.0     60   24.0   20.0     78  15.20     90     10  297.3  337.7  300.1\n"
          "  925.0    720   19.5   16.0     80  12.60    100     16  299.2  333.1  301.5\n"
          "                          Station elevation: 60.0\n",
          "s_below.txt:4:8:", "below the surface (station elevation 60 m)", 0 },
        { "s_gap.txt",
          "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV\n"
          "    hPa     m      C      C      %    g/kg    deg   knot     K      K      K \n"
          "-----------------------------------------------------------------------------\n"
          "  998.0     60   24.0   20.0     78  15.20     90     10  297.3  337.7  300.1\n"
          "  925.0          19.5   16.0     80  12.60    100     16  299.2  333.1  301.5\n"
          "  850.0   1440   15.0   10.0     72   9.10    120     20  301.8  326.5  303.5\n",
          "s_gap.txt:5:8:", "HGHT is missing", 0 },
        { "s_order.txt",
          "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV\n"
          "    hPa     m      C      C      %    g/kg    deg   knot     K      K      K \n"
          "-----------------------------------------------------------------------------\n"
          "  998.0     60   24.0   20.0     78  15.20     90     10  297.3  337.7  300.1\n"
          "  925.0    720   19.5   16.0     80  12.60    100     16  299.2  333.1  301.5\n"
          "  850.0    700   15.0   10.0     72   9.10    120     20  301.8  326.5  303.5\n",
          "s_order.txt:6:8:", "not above the previous row's 720 m (line 5)", 0 },
        { "s_unit.txt",
          "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV\n"
          "    hPa     m      F      F      %    g/kg    deg   knot     K      K      K \n"
          "  998.0     60   75.2   68.0     78  15.20     90     10  297.3  337.7  300.1\n",
          "s_unit.txt:2:20:", "TEMP in 'F'; the text list gives it in 'C'", 0 },
        { "s_nan.txt",
          "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV\n"
          "    hPa     m      C      C      %    g/kg    deg   knot     K      K      K \n"
          "  998.0     60    NaN   20.0     78  15.20     90     10  297.3  337.7  300.1\n"
          "  925.0    720   19.5   16.0     80  12.60    100     16  299.2  333.1  301.5\n",
          "s_nan.txt:3:19:", "TEMP: expected a finite number, found 'NaN'", 0 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        lv_err err = { 0 };
        write_text(cases[i].name, cases[i].text);
        lv_status st;
        if (cases[i].wind) {
            lv_wind *w = NULL;
            const char *p[1] = { cases[i].name };
            const double t[1] = { 0.0 };
            st = lv_wind_create_profiles(p, t, 1, 1000.0, &w, &err);
            lv_wind_free(w);
        } else {
            lv_atmo *a = NULL;
            st = lv_atmo_create_profile(cases[i].name, 1000.0, &a, &err);
            lv_atmo_free(a);
        }
        CHECK(st == LV_ERR_INPUT);
        if (strncmp(err.msg, cases[i].where, strlen(cases[i].where)) != 0 ||
            strstr(err.msg, cases[i].what) == NULL) {
            fprintf(stderr, "case %s: want '%s' ... '%s', got: %s\n", cases[i].name,
                    cases[i].where, cases[i].what, err.msg);
            CHECK(0);
        }
        remove(cases[i].name);
    }
}

int main(void)
{
    const char *root = getenv("LV_SOURCE_DIR");
    snprintf(g_dir, sizeof g_dir, "%s/tests/data/profiles", root != NULL ? root : "..");
    test_sounding_atmosphere();
    test_csv_atmosphere();
    test_profile_winds();
    test_bad_files();
    return check_report("test_profile");
}
