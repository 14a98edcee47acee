/* fuzz_tables.c - libFuzzer target: the bytes of a table file through every reader of table
 * files: lv_table_load (CSV, MAT), the atmosphere table (lv_atmo_create_table), the wind
 * table (lv_wind_create_table_opts), the profile readers (CSV or sounding text list:
 * lv_atmo_create_profile, lv_wind_create_profiles, when a CSV's variant is odd), an ICGEM gravity coefficient file (lv_gravity_create,
 * "sh"), and a small mission that names the file as an engine table, an aerodynamic dataset,
 * the environment's atmosphere or wind, a control or moment table (parsed and loaded as
 * lv_mission_load does: the per-use checks of axes and outputs). A table that loads is then
 * evaluated inside, on and outside its grid. Any input must give LV_OK or an error with a
 * terminated message, never a crash, a leak or a hang.
 *
 * Input: byte 0 = the reader (bits 0-2), MAT instead of CSV (bit 3), PCHIP (bit 4), the
 * extrapolation (bits 5-6: error, clamp, linear, left to the default); byte 1 = the variant
 * (the mission's use of the table; the gravity degree and order); for MAT, the variable's
 * name up to a newline; then the file's bytes, written to a private temporary folder.
 * Seeds: fuzz/corpus/tables (fuzz/make_seeds.sh). Build and run: `make fuzz`. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_util.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_wind.h"
#include "mission/mission.h"
#include "mission/mission_rt.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { R_TABLE, R_ATMO, R_WIND, R_GRAVITY, R_ENGINE, R_AERO, R_ENV, R_CONTROL };

static char dir[4200];      /* the private folder: one process, one folder */
static char path[4300];   /* its table file */

static void cleanup(void)
{
    static const char *const names[] = {"t.csv", "t.mat", "t.gfc"};
    char p[4300];
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, names[i]);
        unlink(p);
    }
    rmdir(dir);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    lv_fuzz_tempdir(dir, sizeof dir, "tables");
    atexit(cleanup);
    return 0;
}

/* A loaded table evaluated at every breakpoint, between them, outside and at NaN. */
static void probe_table(const lv_table *t)
{
    const size_t nd = lv_table_n_dims(t), no = lv_table_n_out(t);
    if (nd < 1 || nd > LV_TABLE_MAX_DIMS || no < 1)
        __builtin_trap();
    double *y = malloc(no * sizeof *y);
    double x[LV_TABLE_MAX_DIMS];
    lv_table_cursor cur = LV_TABLE_CURSOR_INIT;
    lv_err err;
    size_t n0;
    const double *b0 = lv_table_breakpoints(t, 0, &n0);
    for (size_t d = 0; d < nd; d++) {
        size_t n;
        x[d] = lv_table_breakpoints(t, d, &n)[0];
    }
    for (size_t i = 0; i < n0 && i < 64; i++) {
        x[0] = b0[i];
        lv_fuzz_check_status(lv_table_eval(t, &cur, x, y, &err), &err);
        if (i + 1 < n0) {
            x[0] = 0.5 * (b0[i] + b0[i + 1]);
            lv_fuzz_check_status(lv_table_eval(t, &cur, x, y, &err), &err);
        }
        (void)lv_table_next_breakpoint(t, 0, b0[i]);
    }
    const double outside[] = {b0[0] - 1.0, b0[n0 - 1] + 1.0, -INFINITY, NAN};
    for (size_t i = 0; i < 4; i++) {
        x[0] = outside[i];
        lv_fuzz_check_status(lv_table_eval(t, NULL, x, y, &err), &err);
    }
    const double scale = 2.0, bias = -1.0;
    double sc[8], bi[8];
    for (size_t k = 0; k < 8; k++)
        sc[k] = scale, bi[k] = bias;
    lv_table *a = NULL;
    if (no <= 8) {
        const lv_status st = lv_table_create_affine(t, sc, bi, &a, &err);
        lv_fuzz_check_status(st, &err);
        if (st == LV_OK) {
            x[0] = b0[0];
            lv_fuzz_check_status(lv_table_eval(a, NULL, x, y, &err), &err);
        }
        lv_table_free(a);
    }
    size_t k;
    lv_fuzz_check_status(lv_table_out_index(t, "thrust", &k, &err), &err);
    (void)lv_table_name(t);
    (void)lv_table_axis_name(t, nd);
    (void)lv_table_out_unit(t, no);
    free(y);
}

/* "{file: t.csv, var: V, interp: pchip, extrap: clamp}" */
static void table_ref(char *buf, size_t cap, int mat, const char *var, int pchip, int extrap)
{
    static const char *const ex[] = {"error", "clamp", "linear"};
    int n = snprintf(buf, cap, "{file: %s", mat ? "t.mat" : "t.csv");
    if (mat)
        n += snprintf(buf + n, cap - (size_t)n, ", var: '%s'", var);
    n += snprintf(buf + n, cap - (size_t)n, ", interp: %s", pchip ? "pchip" : "linear");
    if (extrap < 3)
        snprintf(buf + n, cap - (size_t)n, ", extrap: %s", ex[extrap]);
    snprintf(buf + strlen(buf), cap - strlen(buf), "}");
}

/* The mission that uses the table in the way `reader` and `variant` say. */
static void mission_text(char *buf, size_t cap, int reader, int variant, const char *ref,
                         int mat, const char *var)
{
    static const char head_flat[] =
        "mission: {name: f}\n"
        "stages: [{name: s, dry_mass: 100, propellant_mass: 50, engines: [{name: e, "
        "thrust_vac: 2000, isp_vac: 250}]}]\n";
    static const char head_planet[] =
        "mission: {name: f}\n"
        "environment: {world: planet, atmosphere: us76}\n"
        "parameters: {start_h: 1000, start_vel: 200, start_fpa_deg: 45, start_chi_deg: 90}\n"
        "stages: [{name: s, dry_mass: 100, propellant_mass: 50, engines: [{name: e, "
        "thrust_vac: 2000, isp_vac: 250}],\n"
        "  rigid_body: {inertia_full: {xx: 10, yy: 100, zz: 100}, inertia_empty: {xx: 5, "
        "yy: 50, zz: 50}, cg_full: {x: -2}, cg_empty: {x: -1.5}, engine_position: {x: -4}}}]\n";
    switch (reader) {
    case R_ENGINE:
        snprintf(buf, cap,
                 "mission: {name: f}\n"
                 "stages: [{name: s, dry_mass: 100, propellant_mass: 50, engines: [{name: e, "
                 "table: %s}]}]\n"
                 "phases: [{name: p, model: %s, stages: [s], stop_time: 10}]\n",
                 ref, variant & 1 ? "dof3" : "flat6");
        if (variant & 1) { /* dof3 flies over a planet */
            char tmp[1024];
            snprintf(tmp, sizeof tmp, "%s", buf);
            snprintf(buf, cap, "environment: {world: planet}\nparameters: {start_h: 1000}\n%s",
                     tmp);
        }
        break;
    case R_AERO:
        if (variant & 2) /* flat6: CD only, from its own table */
            snprintf(buf, cap,
                     "%senvironment: {world: flat, atmosphere: us76}\n"
                     "phases: [{name: p, model: flat6, stages: [s], stop_time: 10, "
                     "aero: {s_ref: 0.03, CD: %s}}]\n",
                     head_flat, ref);
        else
            snprintf(buf, cap,
                     "%sphases: [{name: p, model: dof3, stages: [s], stop_time: 5, "
                     "aero: {s_ref: 1, axes: %s, table: %s}}]\n",
                     head_planet, variant & 1 ? "body" : "wind", ref);
        break;
    case R_ENV: { /* the atmosphere or the wind from the table; a flat world or a planet */
        char env[256];
        if (variant & 1)
            snprintf(env, sizeof env, "atmosphere: {table: %s%s%s}",
                     mat ? "t.mat, var: '" : "t.csv", mat ? var : "", mat ? "'" : "");
        else
            snprintf(env, sizeof env, "atmosphere: us76, wind: %s", ref);
        if (variant & 2)
            snprintf(buf, cap,
                     "mission: {name: f}\n"
                     "environment: {world: planet, %s}\n"
                     "parameters: {start_h: 1000, start_vel: 200, start_fpa_deg: 45}\n"
                     "stages: [{name: s, dry_mass: 100, propellant_mass: 0}]\n"
                     "phases: [{name: p, model: dof3, stages: [s], stop_time: 5, "
                     "aero: {s_ref: 1, CD: 0.3}}]\n",
                     env);
        else
            snprintf(buf, cap,
                     "%senvironment: {world: flat, %s}\n"
                     "phases: [{name: p, model: flat6, stages: [s], stop_time: 10, "
                     "aero: {s_ref: 0.03, CD: 0.3}}]\n",
                     head_flat, env);
        break;
    }
    default: /* R_CONTROL: dof3 inputs, dof6 inputs or moments */
        switch (variant & 3) {
        case 0:
            snprintf(buf, cap,
                     "%sphases: [{name: p, model: dof3, stages: [s], stop_time: 5, "
                     "inputs: {table: %s}}]\n",
                     head_planet, ref);
            break;
        case 1:
            snprintf(buf, cap,
                     "%sphases: [{name: p, model: dof6, stages: [s], stop_time: 5, "
                     "inputs: {table: %s}}]\n",
                     head_planet, ref);
            break;
        default:
            snprintf(buf, cap,
                     "%sphases: [{name: p, model: dof6, stages: [s], stop_time: 5, "
                     "aero: {s_ref: 1, axes: body, CA: 0.3, CN: 0.1}, "
                     "moments: {b_ref: 1, c_ref: 1, table: %s}}]\n",
                     head_planet, ref);
            break;
        }
        break;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2)
        return 0;
    const int reader = data[0] & 7, mat = (data[0] >> 3) & 1, pchip = (data[0] >> 4) & 1,
              extrap = (data[0] >> 5) & 3, variant = data[1];
    data += 2;
    size -= 2;
    char var[40] = "";
    if (mat) { /* the variable's name: up to a newline, printable, quotable in YAML */
        size_t n = 0;
        while (n < size && n < sizeof var - 1 && data[n] != '\n') {
            if (data[n] < 0x21 || data[n] > 0x7e || data[n] == '\'')
                return 0;
            var[n] = (char)data[n];
            n++;
        }
        if (n == size || data[n] != '\n')
            return 0;
        var[n] = '\0';
        data += n + 1;
        size -= n + 1;
    }
    snprintf(path, sizeof path, "%s/%s", dir,
             reader == R_GRAVITY ? "t.gfc" : mat ? "t.mat" : "t.csv");
    FILE *fp = fopen(path, "wb");
    if (fp == NULL || fwrite(data, 1, size, fp) != size || fclose(fp) != 0)
        abort();
    const lv_table_opts opts = {pchip ? LV_INTERP_PCHIP : LV_INTERP_LINEAR,
                                extrap < 3 ? (lv_extrap)extrap : LV_EXTRAP_ERROR, 0};
    const char *v = mat ? var : NULL;
    lv_err err;
    lv_status st;
    switch (reader) {
    case R_TABLE: {
        lv_table *t = NULL;
        st = lv_table_load(path, v, &opts, &t, &err);
        lv_fuzz_check_status(st, &err);
        if ((st == LV_OK) != (t != NULL))
            __builtin_trap();
        if (t != NULL)
            probe_table(t);
        lv_table_free(t);
        break;
    }
    case R_ATMO: {
        lv_atmo *a = NULL;
        if (!mat && (variant & 1)) /* a profile, blended over 100 m to 25.5 km */
            st = lv_atmo_create_profile(path, 100.0 * (variant >> 1) + 100.0, &a, &err);
        else
            st = lv_atmo_create_table(path, v, &a, &err);
        lv_fuzz_check_status(st, &err);
        if (a != NULL) {
            lv_atmo_state s;
            const double h[] = {-1e3, 0.0, 1e4, 86e3, 1e6, NAN};
            for (size_t i = 0; i < sizeof h / sizeof h[0]; i++)
                lv_fuzz_check_status(lv_atmo_eval(a, h[i], &s, &err), &err);
        }
        lv_atmo_free(a);
        break;
    }
    case R_WIND: {
        lv_wind *w = NULL;
        if (!mat && (variant & 1)) { /* the file as 1 or 2 profiles, 60 s apart */
            const char *const paths[2] = {path, path};
            const double t[2] = {0.0, 60.0};
            st = lv_wind_create_profiles(paths, t, (variant & 2) ? 2 : 1,
                                         100.0 * (variant >> 2) + 100.0, &w, &err);
        } else {
            st = lv_wind_create_table_opts(path, v, &opts, &w, &err);
        }
        lv_fuzz_check_status(st, &err);
        if (w != NULL) {
            double lo, hi, vned[3];
            lv_wind_range(w, &lo, &hi);
            const double h[] = {lo, hi, 0.5 * (lo + hi), lo - 1.0, hi + 1.0, NAN};
            lv_table_cursor cur = LV_TABLE_CURSOR_INIT;
            for (size_t i = 0; i < sizeof h / sizeof h[0]; i++) {
                lv_fuzz_check_status(lv_wind_eval(w, &cur, h[i], vned, &err), &err);
                lv_fuzz_check_status(lv_wind_eval_at(w, &cur, 30.0, h[i], vned, &err), &err);
                lv_fuzz_check_status(lv_wind_eval_at(w, &cur, NAN, h[i], vned, &err), &err);
            }
            const double bias[3] = {1.0, -1.0, 0.5};
            lv_wind *a = NULL;
            lv_fuzz_check_status(lv_wind_create_affine(w, 1.5, bias, &a, &err), &err);
            lv_wind_free(a);
        }
        lv_wind_free(w);
        break;
    }
    case R_GRAVITY: {
        const lv_planet earth = lv_planet_earth();
        const int degree = variant & 31, order = (variant >> 5) == 7 ? LV_GRAVITY_ORDER_ZONAL
                                                                      : (variant >> 5);
        const lv_gravity_config cfg = {"sh", degree, order <= degree ? order : 0, path};
        lv_gravity *g = NULL;
        st = lv_gravity_create(&earth, &cfg, &g, &err);
        lv_fuzz_check_status(st, &err);
        if (g != NULL) {
            double *ws = calloc(lv_gravity_ws_size(g) + 1, sizeof *ws);
            const double r[3] = {7.0e6, 1.0e5, -2.0e5};
            double a[3], U;
            lv_gravity_eval(g, ws, r, a, &U);
            free(ws);
        }
        lv_gravity_free(g);
        break;
    }
    default: {
        char ref[160], text[4096];
        table_ref(ref, sizeof ref, mat, var, pchip, extrap);
        mission_text(text, sizeof text, reader, variant, ref, mat, var);
        lv_mission_def *m = NULL;
        st = lv_mission_def_parse(text, strlen(text), "fuzz.yaml", dir, &m, &err);
        lv_fuzz_check_status(st, &err);
        if ((st == LV_OK) != (m != NULL))
            __builtin_trap();
        if (m != NULL) {
            lv_mission *mission = NULL;
            st = lv_mission_from_def(m, &mission, &err);
            lv_fuzz_check_status(st, &err);
            if ((st == LV_OK) != (mission != NULL))
                __builtin_trap();
            lv_mission_free(mission);
        }
        break;
    }
    }
    unlink(path); /* nothing left behind should the process end without atexit (a crash) */
    return 0;
}
