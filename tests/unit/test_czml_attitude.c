/* test_czml_attitude.c - the CZML vehicle models' orientation (issue 26 item 2): runs
 * examples/two-stage-6dof into czml_att_out/, exports the CZML and checks, at every row of the
 * phase CSVs whose instant is a sample of the model's `orientation`, that the model's axes
 * turned by the CZML quaternion are the body's axes computed here from the result files
 * alone, by another route than the exporter's:
 *   - 6-DoF phase boost: body x and z from the quaternion columns q_w..q_z (body -> ECI,
 *     docs/result-files.md, `lvsim vars dof6`), turned to ECEF about the polar axis by
 *     omega t (docs/frames.md F1: theta0 = 0, omega = 7.292115e-5 rad/s, WGS-84 / NIMA
 *     TR8350.2 table 3.1); the exporter uses lv_frames_C_ecef_eci. Bound 1e-9 rad (issue).
 *   - 3-DoF phase upper-burn (above the wind table's zero-wind altitudes): the wind axes from
 *     the ground-relative velocity v_north, v_east, v_down and the bank mu_in, then the body
 *     axes by alpha_in, beta_in (docs/models.md, "Aerodynamic angles": C_body_wind =
 *     R2(alpha) R3(-beta), x_w along the air-relative velocity, z_w in the vertical plane,
 *     down); the exporter goes through the Euler outputs theta, psi, phi and NED.
 * The convention (docs/exports.md, "Vehicle models"): model +x = body x (nose), model +y =
 * -body y, model +z = -body z (Cesium: +z up, +x forward). Also the model packets present
 * (one per phase, the spent booster after staging) and their glTF data URI a GLB. */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "lvsim/lv_export.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_summary.h"

#define OMEGA 7.292115e-5 /* rad/s, WGS-84 (NIMA TR8350.2 table 3.1) */
#define OUT "czml_att_out"

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    fseek(f, 0, SEEK_END);
    const long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    if (s != NULL)
        s[fread(s, 1, (size_t)n, f)] = '\0';
    fclose(f);
    return s;
}

/* A numeric CSV (header "name [unit],..."): rows of n_cols doubles. */
typedef struct csv {
    char **names;
    size_t n_cols, n_rows;
    double *v;
} csv;

static int csv_read(const char *path, csv *c)
{
    memset(c, 0, sizeof *c);
    char *text = slurp(path);
    if (text == NULL)
        return -1;
    char *save = NULL;
    char *line = strtok_r(text, "\n", &save);
    for (char *p = line; p != NULL && *p;) { /* header */
        char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        char *name = malloc(len + 1);
        memcpy(name, p, len);
        name[len] = '\0';
        char *br = strstr(name, " [");
        if (br != NULL)
            *br = '\0';
        c->names = realloc(c->names, (c->n_cols + 1) * sizeof *c->names);
        c->names[c->n_cols++] = name;
        p = comma ? comma + 1 : NULL;
    }
    size_t cap = 0;
    while ((line = strtok_r(NULL, "\n", &save)) != NULL) {
        if (c->n_rows == cap) {
            cap = cap ? 2 * cap : 1024;
            c->v = realloc(c->v, cap * c->n_cols * sizeof *c->v);
        }
        char *p = line;
        for (size_t k = 0; k < c->n_cols; k++) {
            c->v[c->n_rows * c->n_cols + k] = strtod(p, &p);
            if (*p == ',')
                p++;
        }
        c->n_rows++;
    }
    free(text);
    return 0;
}

static long col(const csv *c, const char *name)
{
    for (size_t k = 0; k < c->n_cols; k++)
        if (strcmp(c->names[k], name) == 0)
            return (long)k;
    CHECK(!"column missing");
    fprintf(stderr, "  column '%s' missing\n", name);
    return 0;
}

static void csv_free(csv *c)
{
    for (size_t k = 0; k < c->n_cols; k++)
        free(c->names[k]);
    free(c->names);
    free(c->v);
}

/* v turned by the unit quaternion (w; x, y, z): v + 2w (q x v) + 2 q x (q x v). */
static void qrot(double w, double x, double y, double z, const double v[3], double out[3])
{
    const double t[3] = {2.0 * (y * v[2] - z * v[1]), 2.0 * (z * v[0] - x * v[2]),
                         2.0 * (x * v[1] - y * v[0])};
    out[0] = v[0] + w * t[0] + (y * t[2] - z * t[1]);
    out[1] = v[1] + w * t[1] + (z * t[0] - x * t[2]);
    out[2] = v[2] + w * t[2] + (x * t[1] - y * t[0]);
}

/* The angle between a and b (rad), by atan2 of |a x b| and a . b (accurate near 0). */
static double angle(const double a[3], const double b[3])
{
    const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]};
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                 a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

static const cJSON *packet(const cJSON *doc, const char *id)
{
    const cJSON *p;
    cJSON_ArrayForEach(p, doc) {
        const cJSON *i = cJSON_GetObjectItemCaseSensitive(p, "id");
        if (cJSON_IsString(i) && strcmp(i->valuestring, id) == 0)
            return p;
    }
    return NULL;
}

/* The orientation samples of packet id: [t, x, y, z, w] * n. */
static const cJSON *samples(const cJSON *doc, const char *id)
{
    const cJSON *o = cJSON_GetObjectItemCaseSensitive(packet(doc, id), "orientation");
    const cJSON *q = cJSON_GetObjectItemCaseSensitive(o, "unitQuaternion");
    CHECK(cJSON_IsArray(q) && cJSON_GetArraySize(q) % 5 == 0 && cJSON_GetArraySize(q) > 0);
    return q;
}

/* The CZML sample at time t: q[4] = x, y, z, w; 0 when none. */
static int sample_at(const cJSON *q, double t, double out[4])
{
    const int n = cJSON_GetArraySize(q) / 5;
    for (int i = 0; i < n; i++) {
        if (cJSON_GetArrayItem(q, 5 * i)->valuedouble != t)
            continue;
        for (int k = 0; k < 4; k++)
            out[k] = cJSON_GetArrayItem(q, 5 * i + 1 + k)->valuedouble;
        return 1;
    }
    return 0;
}

/* The model's +x and +z in ECEF from a CZML sample (x, y, z, w). */
static void model_axes(const double q[4], double mx[3], double mz[3])
{
    const double ex[3] = {1, 0, 0}, ez[3] = {0, 0, 1};
    qrot(q[3], q[0], q[1], q[2], ex, mx);
    qrot(q[3], q[0], q[1], q[2], ez, mz);
}

static void check_dof6(const cJSON *doc)
{
    csv c;
    CHECK(csv_read(OUT "/phase_2_boost.csv", &c) == 0);
    const cJSON *q = samples(doc, "model/boost");
    const long t_ = col(&c, "time"), w_ = col(&c, "q_w"), x_ = col(&c, "q_x"),
               y_ = col(&c, "q_y"), z_ = col(&c, "q_z");
    size_t n = 0;
    double worst_x = 0.0, worst_z = 0.0;
    for (size_t i = 0; i < c.n_rows; i++) {
        const double *v = c.v + i * c.n_cols;
        double s[4];
        if (!sample_at(q, v[t_], s))
            continue;
        const double nq = sqrt(v[w_] * v[w_] + v[x_] * v[x_] + v[y_] * v[y_] + v[z_] * v[z_]);
        const double ex[3] = {1, 0, 0}, ez[3] = {0, 0, 1};
        double bx[3], bz[3];
        qrot(v[w_] / nq, v[x_] / nq, v[y_] / nq, v[z_] / nq, ex, bx); /* ECI */
        qrot(v[w_] / nq, v[x_] / nq, v[y_] / nq, v[z_] / nq, ez, bz);
        const double th = OMEGA * v[t_], ct = cos(th), st = sin(th);
        const double bx_e[3] = {ct * bx[0] + st * bx[1], -st * bx[0] + ct * bx[1], bx[2]};
        const double up_e[3] = {-(ct * bz[0] + st * bz[1]), -(-st * bz[0] + ct * bz[1]), -bz[2]};
        double mx[3], mz[3];
        model_axes(s, mx, mz);
        worst_x = fmax(worst_x, angle(mx, bx_e));
        worst_z = fmax(worst_z, angle(mz, up_e));
        n++;
    }
    printf("dof6 boost: %zu rows, model x vs body x %.3g rad, model z vs -body z %.3g rad\n", n,
           worst_x, worst_z);
    CHECK(n >= 200); /* 146 s at 0.5 s */
    CHECK(worst_x < 1e-9);
    CHECK(worst_z < 1e-9);
    csv_free(&c);
}

static void check_dof3(const cJSON *doc)
{
    csv c;
    CHECK(csv_read(OUT "/phase_4_upper-burn.csv", &c) == 0);
    const cJSON *q = samples(doc, "model/upper-burn");
    const long t_ = col(&c, "time"), vn_ = col(&c, "v_north"), ve_ = col(&c, "v_east"),
               vd_ = col(&c, "v_down"), al_ = col(&c, "alpha_in"), be_ = col(&c, "beta_in"),
               mu_ = col(&c, "mu_in"), la_ = col(&c, "lat"), lo_ = col(&c, "lon"),
               h_ = col(&c, "h");
    size_t n = 0;
    double worst_x = 0.0, worst_z = 0.0, alpha_max = 0.0;
    for (size_t i = 0; i < c.n_rows; i++) {
        const double *v = c.v + i * c.n_cols;
        double s[4];
        if (!sample_at(q, v[t_], s) || v[h_] < 30e3) /* wind.csv: none from 30 km up */
            continue;
        const double sl = sin(v[la_]), cl = cos(v[la_]), so = sin(v[lo_]), co = cos(v[lo_]);
        const double N[3] = {-sl * co, -sl * so, cl}, E[3] = {-so, co, 0},
                     D[3] = {-cl * co, -cl * so, -sl};
        double xw[3], z0[3], y0[3];
        for (int k = 0; k < 3; k++)
            xw[k] = v[vn_] * N[k] + v[ve_] * E[k] + v[vd_] * D[k];
        const double nv = sqrt(xw[0] * xw[0] + xw[1] * xw[1] + xw[2] * xw[2]);
        const double dx = (D[0] * xw[0] + D[1] * xw[1] + D[2] * xw[2]) / nv;
        for (int k = 0; k < 3; k++) {
            xw[k] /= nv;
            z0[k] = D[k] - dx * xw[k];
        }
        const double nz = sqrt(z0[0] * z0[0] + z0[1] * z0[1] + z0[2] * z0[2]);
        for (int k = 0; k < 3; k++)
            z0[k] /= nz;
        y0[0] = z0[1] * xw[2] - z0[2] * xw[1];
        y0[1] = z0[2] * xw[0] - z0[0] * xw[2];
        y0[2] = z0[0] * xw[1] - z0[1] * xw[0];
        const double cm = cos(v[mu_]), sm = sin(v[mu_]), ca = cos(v[al_]), sa = sin(v[al_]),
                     cb = cos(v[be_]), sb = sin(v[be_]);
        double bx[3], up[3];
        for (int k = 0; k < 3; k++) {
            const double yw = cm * y0[k] + sm * z0[k], zw = cm * z0[k] - sm * y0[k];
            bx[k] = ca * cb * xw[k] - ca * sb * yw - sa * zw;
            up[k] = -(sa * cb * xw[k] - sa * sb * yw + ca * zw);
        }
        double mx[3], mz[3];
        model_axes(s, mx, mz);
        worst_x = fmax(worst_x, angle(mx, bx));
        worst_z = fmax(worst_z, angle(mz, up));
        alpha_max = fmax(alpha_max, fabs(v[al_]));
        n++;
    }
    printf("dof3 upper-burn: %zu rows (|alpha| up to %.3g rad), model x vs body x %.3g rad, "
           "model z vs -body z %.3g rad\n", n, alpha_max, worst_x, worst_z);
    CHECK(n >= 100);
    CHECK(alpha_max > 0.05); /* the steering holds the nose off the velocity: a real test */
    CHECK(worst_x < 1e-9);
    CHECK(worst_z < 1e-9);
    csv_free(&c);
}

int main(void)
{
    char path[1024];
    const char *root = getenv("LV_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/examples/two-stage-6dof/mission.yaml", root ? root : "..");
    lv_err err = {0};
    lv_mission *m = NULL;
    lv_run *r = NULL;
    CHECK_OK(lv_mission_load(path, &m, &err), &err);
    lv_run_options opt = {0};
    opt.outdir = OUT;
    opt.threads = 1;
    mkdir(OUT, 0777);
    if (m != NULL)
        CHECK_OK(lv_run_create(m, &r, &err), &err);
    if (r != NULL) {
        CHECK_OK(lv_run_execute(r, &opt, &err), &err);
        CHECK_OK(lv_run_write_summary(r, OUT, &err), &err);
    }
    lv_run_free(r);
    lv_mission_free(m);
    CHECK_OK(lv_export_run(OUT, LV_EXPORT_CZML, &err), &err);
    char *text = slurp(OUT "/mission.czml");
    CHECK(text != NULL);
    cJSON *doc = text != NULL ? cJSON_Parse(text) : NULL;
    CHECK(cJSON_IsArray(doc));
    if (cJSON_IsArray(doc)) {
        /* a model per phase and the booster left behind at staging */
        static const char *const ids[] = {"model/liftoff", "model/boost", "model/boost/spent",
                                          "model/coast", "model/upper-burn"};
        for (size_t i = 0; i < sizeof ids / sizeof *ids; i++) {
            const cJSON *p = packet(doc, ids[i]);
            CHECK(p != NULL);
            const cJSON *g = cJSON_GetObjectItemCaseSensitive(
                cJSON_GetObjectItemCaseSensitive(p, "model"), "gltf");
            /* "glTF" base64-encoded is "Z2xURg" (RFC 4648) */
            CHECK(cJSON_IsString(g) &&
                  strncmp(g->valuestring, "data:model/gltf-binary;base64,Z2xURg", 36) == 0);
        }
        check_dof6(doc);
        check_dof3(doc);
    }
    cJSON_Delete(doc);
    free(text);
    return check_report("test_czml_attitude");
}
