/* plot_keys.c - the key figures of a run, per body, from its results folder (post/results.h:
 * summary.json, the phase CSVs, the body trajectories): final state, maximum dynamic
 * pressure with its time and altitude, maximum axial and normal load factor, the state at
 * each burnout and separation, the injection state and osculating orbit of a body that
 * reaches orbit (periapsis above 100 km, e < 1; e >= 1: escape) or the end of a suborbital
 * powered flight it coasts up from, and the impact or landing point with its distance from
 * the launch site and its load (left out of the load maxima), the heating, and the
 * instantaneous impact point at the end of each powered phase. A payload that never burns
 * and ends in orbit gets the injection of the last stage that carried it (carried_by).
 * Written to OUTDIR/key_figures.json (SI units) and shown by the report (plot_html.c).
 * Definitions: docs/visualization.md ("Key figures"); tests/python/check_key_figures.py
 * recomputes every number from the CSV files. */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "io/atomic.h"
#include "lvsim/lv_atmosphere.h"
#include "post/plot.h"
#include "post/json_print.h"

#define G0 9.80665            /* m/s^2, standard gravity: load factors in g0 */
#define R_MEAN 6371008.8      /* m, IUGG mean Earth radius: great-circle distances */
#define ORBIT_PERI_MIN 100e3  /* m: a body reaches orbit when its periapsis stays above */
#define LANDING_SPEED_MAX 10.0 /* m/s: a ground contact slower than this is a landing */

/* A phase CSV's columns the figures read; -1 when absent. */
typedef struct cols {
    long t, h, speed, v_in, fpa, fpa_in, q, rho, nax, nno, m, lat, lon, x, y, thrust, sma, ecc,
        inc, apo, peri, drag, dvx, dvy, vz;
} cols;

static long col(const lv_results_table *t, const char *a, const char *b)
{
    long k = lv_results_table_col(t, a);
    return k >= 0 || b == NULL ? k : lv_results_table_col(t, b);
}

static cols find_cols(const lv_results_table *t)
{
    cols c = {col(t, "time", NULL), col(t, "h", "z"), col(t, "v_rel", "speed"),
              col(t, "v_inertial", NULL), col(t, "fpa", NULL), col(t, "fpa_inertial", NULL),
              col(t, "q_dyn", NULL), col(t, "rho", NULL), col(t, "n_axial", NULL),
              col(t, "n_normal", NULL), col(t, "m", NULL), col(t, "lat", NULL),
              col(t, "lon", NULL), col(t, "x", NULL), col(t, "y", NULL), col(t, "thrust", NULL),
              col(t, "sma", NULL), col(t, "ecc", NULL), col(t, "inc", NULL),
              col(t, "apo_alt", NULL), col(t, "peri_alt", NULL), col(t, "drag", NULL),
              col(t, "der(vx)", NULL), col(t, "der(vy)", NULL), col(t, "vz", NULL)};
    return c;
}

static double at(const lv_results_table *t, size_t r, long c)
{
    return c >= 0 ? t->v[r * t->n_cols + (size_t)c] : NAN;
}

static void num(cJSON *o, const char *key, double v)
{
    if (isfinite(v))
        cJSON_AddNumberToObject(o, key, v);
    else
        cJSON_AddNullToObject(o, key);
}

/* The state at row r of a phase file: time, altitude, speeds, flight-path angles, vehicle
 * mass (the whole body that flies in the phase), position. */
static cJSON *state_json(const lv_results_table *t, const cols *c, size_t r, const char *phase)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "phase", phase);
    num(o, "t", at(t, r, c->t));
    num(o, "h", at(t, r, c->h));
    num(o, "speed", at(t, r, c->speed));
    if (c->v_in >= 0)
        num(o, "v_inertial", at(t, r, c->v_in));
    if (c->fpa >= 0)
        num(o, "fpa", at(t, r, c->fpa));
    num(o, "vehicle_mass", at(t, r, c->m));
    if (c->lat >= 0) {
        num(o, "lat", at(t, r, c->lat));
        num(o, "lon", at(t, r, c->lon));
    } else if (c->x >= 0) {
        num(o, "x", at(t, r, c->x));
        num(o, "y", at(t, r, c->y));
    }
    return o;
}

/* The axial load factor [g0] of row r: the sensed specific force (thrust + aerodynamic force,
 * over the mass) along the body axis, as the planet models' `n_axial` (docs/models.md). The
 * model's `n_axial` when it has one; otherwise the flat world's (flat6): its thrust acts
 * along +z, so the axis is +z. Without air (no `rho` column) the only force beside gravity is
 * the thrust: T / (m g0). With air the drag D acts along -v_air: its horizontal parts are the
 * horizontal accelerations (m der(vx), m der(vy): thrust and gravity are vertical), so its
 * vertical part is |D_z| = sqrt(drag^2 - (m der(vx))^2 - (m der(vy))^2), against the vertical
 * speed vz (the air's vertical speed, a wind's w_down, taken as smaller than |vz|), and
 * n = (T + D_z) / (m g0). NAN (not available, never 0) when a column is missing. */
static double axial_load(const lv_results_table *t, const cols *c, size_t r)
{
    if (c->nax >= 0)
        return at(t, r, c->nax);
    const double thrust = at(t, r, c->thrust), m = at(t, r, c->m);
    if (c->rho < 0)
        return thrust / (m * G0);
    if (c->drag < 0 || c->dvx < 0 || c->dvy < 0 || c->vz < 0)
        return NAN;
    const double d = at(t, r, c->drag), ax = m * at(t, r, c->dvx), ay = m * at(t, r, c->dvy);
    const double vz = at(t, r, c->vz);
    const double dz = sqrt(fmax(0.0, d * d - ax * ax - ay * ay));
    return (thrust + (vz > 0.0 ? -dz : vz < 0.0 ? dz : 0.0)) / (m * G0);
}

/* First row of t at time `time` (an event instant has two: the one before it), or the last
 * row before it; (size_t)-1 when none. */
static size_t row_at(const lv_results_table *t, long ct, double time)
{
    size_t best = (size_t)-1;
    for (size_t r = 0; r < t->n_rows; r++) {
        const double x = at(t, r, ct);
        if (x == time)
            return r;
        if (x < time)
            best = r;
    }
    return best;
}

/* Great-circle distance on the sphere of the IUGG mean radius (haversine). */
static double gc_distance(double lat1, double lon1, double lat2, double lon2)
{
    const double s1 = sin(0.5 * (lat2 - lat1)), s2 = sin(0.5 * (lon2 - lon1));
    const double a = s1 * s1 + cos(lat1) * cos(lat2) * s2 * s2;
    return 2.0 * R_MEAN * asin(fmin(1.0, sqrt(a)));
}

/* The bottom stage of a phase (the one that burns) is body b's? */
static int burns_in(const lv_results *res, size_t k, const char *body)
{
    const lv_results_phase *p = &res->phases[k];
    return p->n_stages > 0 && strcmp(p->stages[0], body) == 0;
}

/* The label summary.json's timeline gives the separation of `body` at the start of `phase`
 * ("separation of booster", "separation of fairing": what separated, so that a payload's two
 * separations read as two different ones), or NULL when the summary has no timeline. */
static const char *separation_label(const lv_results *res, const char *body, const char *phase,
                                    double t)
{
    const cJSON *b;
    cJSON_ArrayForEach(b, cJSON_GetObjectItemCaseSensitive(res->json, "bodies"))
    {
        const cJSON *nm = cJSON_GetObjectItemCaseSensitive(b, "name"), *e;
        if (!cJSON_IsString(nm) || strcmp(nm->valuestring, body) != 0)
            continue;
        cJSON_ArrayForEach(e, cJSON_GetObjectItemCaseSensitive(b, "timeline"))
        {
            const cJSON *k = cJSON_GetObjectItemCaseSensitive(e, "kind");
            const cJSON *p = cJSON_GetObjectItemCaseSensitive(e, "phase");
            const cJSON *et = cJSON_GetObjectItemCaseSensitive(e, "t");
            const cJSON *l = cJSON_GetObjectItemCaseSensitive(e, "label");
            if (cJSON_IsString(k) && strcmp(k->valuestring, "separation") == 0 &&
                cJSON_IsString(p) && strcmp(p->valuestring, phase) == 0 && cJSON_IsNumber(et) &&
                et->valuedouble == t && cJSON_IsString(l))
                return l->valuestring;
        }
    }
    return NULL;
}

static cJSON *body_keys(const lv_plot_data *d, size_t bi, int flat)
{
    const lv_results *res = d->res;
    const lv_plot_body *b = &d->bodies[bi];
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", b->name);
    cJSON *burn = cJSON_CreateArray(), *sep = cJSON_CreateArray();
    double q_max = -INFINITY, q_t = NAN, q_h = NAN;
    double na_max = NAN, na_t = NAN, /* NAN: none yet */
           nn_max = -INFINITY, nn_t = NAN;
    const lv_results_table *first_t = NULL, *last_t = NULL;
    size_t last_k = 0;
    cJSON *injection = NULL;
    /* the body's last powered instant (thrust > 0 in a phase where its stage burns): the end
     * of powered flight, whatever ended the burn (a burnout, an orbit end such as `sma`) */
    const lv_results_table *pow_t = NULL;
    size_t pow_r = 0;
    const char *pow_phase = NULL;
    size_t pow_k = 0;
    /* the last powered instant of any stage that carried it (a phase it flies in whose bottom
     * stage burns, thrust > 0): a body that never burns (a payload) is injected there */
    const lv_results_table *car_t = NULL;
    size_t car_r = 0, car_k = 0;
    for (size_t i = 0; i < b->n; i++) {
        const size_t k = b->phase[i];
        const lv_results_phase *ph = &res->phases[k];
        const lv_results_table *t = d->phases[k].csv;
        if (t == NULL || t->n_rows == 0)
            continue;
        if (first_t == NULL)
            first_t = t;
        last_t = t;
        last_k = k;
        const cols c = find_cols(t);
        /* a phase that ends on the ground: its last row is the touchdown or impact, whose load
         * (a landing law's last braking, a crash) is the ground contact's, not the flight's */
        const int grounded = ph->end_event != NULL && strcmp(ph->end_event, "impact") == 0;
        for (size_t r = 0; r < t->n_rows; r++) {
            /* q only where the atmosphere model is defined: rho > 0, h <= its top */
            const double q = at(t, r, c.q), rho = at(t, r, c.rho), h = at(t, r, c.h);
            if (isfinite(q) && rho > 0.0 && h <= LV_ATMO_ALT_MAX && q > q_max) {
                q_max = q;
                q_t = at(t, r, c.t);
                q_h = h;
            }
            /* axial: the sensed specific force along the body axis (axial_load), the largest
             * in magnitude with its sign (+ thrust along the axis, - drag on re-entry: a
             * booster's -13 g entry is the load, not its +4 g at burnout) */
            const int contact = grounded && r + 1 == t->n_rows;
            const double na = axial_load(t, &c, r);
            if (!contact && isfinite(na) && !(fabs(na) <= fabs(na_max))) {
                na_max = na;
                na_t = at(t, r, c.t);
            }
            const double nn = fabs(at(t, r, c.nno));
            if (!contact && isfinite(nn) && nn > nn_max) {
                nn_max = nn;
                nn_t = at(t, r, c.t);
            }
            if (c.thrust >= 0 && at(t, r, c.thrust) > 0.0 && burns_in(res, k, b->name)) {
                pow_t = t;
                pow_r = r;
                pow_phase = ph->name;
                pow_k = k;
            }
            if (c.thrust >= 0 && at(t, r, c.thrust) > 0.0) {
                car_t = t;
                car_r = r;
                car_k = k;
            }
        }
        /* separation: the phase starts with fewer stages than its parent */
        if (ph->parent >= 0 && ph->n_stages < res->phases[ph->parent].n_stages) {
            cJSON *s = state_json(t, &c, 0, ph->name);
            const char *label = separation_label(res, b->name, ph->name, at(t, 0, c.t));
            if (label != NULL)
                cJSON_AddStringToObject(s, "label", label);
            cJSON_AddItemToArray(sep, s);
        }
        /* burnout of the stage it burns */
        for (size_t e = 0; e < ph->n_events; e++) {
            const lv_results_event *ev = &ph->events[e];
            if (ev->name == NULL || strcmp(ev->name, "burnout") != 0 || ev->kind == NULL ||
                strcmp(ev->kind, "state") != 0 || !burns_in(res, k, b->name))
                continue;
            const size_t r = row_at(t, c.t, ev->t);
            if (r == (size_t)-1)
                continue;
            cJSON *s = state_json(t, &c, r, ph->name);
            cJSON_AddItemToArray(burn, s);
        }
    }
    /* a body that never burns gets the end of powered flight of the last stage that carried
     * it (the same row: the same orbit), but only where that is an orbit or an escape and the
     * body ends above ORBIT_PERI_MIN too (it ends in orbit; a fairing dropped on the way up
     * does not) */
    const char *carrier = NULL;
    if (pow_t == NULL && car_t != NULL && last_t != NULL) {
        const cols cl = find_cols(last_t), cc = find_cols(car_t);
        const double peri_end = at(last_t, last_t->n_rows - 1, cl.peri);
        const double peri_car = at(car_t, car_r, cc.peri);
        const lv_results_phase *cp = &res->phases[car_k];
        if (peri_end > ORBIT_PERI_MIN && peri_car > ORBIT_PERI_MIN && cp->n_stages > 0) {
            pow_t = car_t;
            pow_r = car_r;
            pow_phase = cp->name;
            pow_k = car_k;
            carrier = cp->stages[0];
        }
    }
    if (pow_t != NULL) { /* over a planet (osculating elements): the injection candidate */
        const cols c = find_cols(pow_t);
        if (c.sma >= 0) {
            injection = state_json(pow_t, &c, pow_r, pow_phase);
            num(injection, "fpa_inertial", at(pow_t, pow_r, c.fpa_in));
            cJSON *orb = cJSON_AddObjectToObject(injection, "orbit");
            num(orb, "sma", at(pow_t, pow_r, c.sma));
            num(orb, "ecc", at(pow_t, pow_r, c.ecc));
            num(orb, "inc", at(pow_t, pow_r, c.inc));
            num(orb, "apo_alt", at(pow_t, pow_r, c.apo));
            num(orb, "peri_alt", at(pow_t, pow_r, c.peri));
            if (carrier != NULL) /* the stage whose burn injected it */
                cJSON_AddStringToObject(injection, "carried_by", carrier);
        }
    }
    /* final state: the last row of its last phase, and the stage's own mass */
    if (last_t != NULL) {
        const cols c = find_cols(last_t);
        cJSON *f = state_json(last_t, &c, last_t->n_rows - 1, res->phases[last_k].name);
        const lv_results_table *tr = b->traj;
        const long cs = lv_results_table_col(tr, "stage_mass");
        if (tr != NULL && cs >= 0 && tr->n_rows > 0)
            num(f, "stage_mass", at(tr, tr->n_rows - 1, cs));
        const lv_results_phase *lp = &res->phases[last_k];
        cJSON_AddStringToObject(f, "end", lp->end_event ? lp->end_event
                                          : lp->end_reason ? lp->end_reason : "?");
        cJSON_AddItemToObject(o, "final", f);
    } else {
        cJSON_AddNullToObject(o, "final");
    }
    cJSON *mq = NULL;
    if (isfinite(q_max)) {
        mq = cJSON_CreateObject();
        num(mq, "value", q_max);
        num(mq, "t", q_t);
        num(mq, "h", q_h);
    }
    cJSON_AddItemToObject(o, "max_q", mq ? mq : cJSON_CreateNull());
    cJSON *na = NULL, *nn = NULL;
    if (isfinite(na_max)) {
        na = cJSON_CreateObject();
        num(na, "value", na_max);
        num(na, "t", na_t);
    }
    if (isfinite(nn_max)) {
        nn = cJSON_CreateObject();
        num(nn, "value", nn_max);
        num(nn, "t", nn_t);
    }
    cJSON_AddItemToObject(o, "max_n_axial", na ? na : cJSON_CreateNull());
    cJSON_AddItemToObject(o, "max_n_normal", nn ? nn : cJSON_CreateNull());
    cJSON_AddItemToObject(o, "burnouts", burn);
    cJSON_AddItemToObject(o, "separations", sep);
    /* injection: the end of powered flight, an orbit if its periapsis stays above 100 km; a
     * suborbital one only where the body coasts up from it (fpa_inertial > 0: its ballistic
     * apoapsis is ahead), not a landing burn's touchdown or a burn on the way down */
    if (injection != NULL) {
        const cJSON *orb = cJSON_GetObjectItemCaseSensitive(injection, "orbit");
        const cJSON *peri = cJSON_GetObjectItemCaseSensitive(orb, "peri_alt");
        const cJSON *ecc = cJSON_GetObjectItemCaseSensitive(orb, "ecc");
        const cJSON *fpa = cJSON_GetObjectItemCaseSensitive(injection, "fpa_inertial");
        const int above = cJSON_IsNumber(peri) && peri->valuedouble > ORBIT_PERI_MIN;
        const int bound = cJSON_IsNumber(ecc) && ecc->valuedouble < 1.0;
        const lv_results_phase *pp = &res->phases[pow_k];
        const int lands = pow_k == last_k && pp->end_event != NULL &&
                          strcmp(pp->end_event, "impact") == 0; /* burns to the ground */
        const int climbs = cJSON_IsNumber(fpa) && fpa->valuedouble > 0.0 && !lands;
        if (!above && !climbs) {
            cJSON_Delete(injection);
            injection = NULL;
        } else {
            cJSON_AddBoolToObject(injection, "reaches_orbit", above && bound);
            cJSON_AddStringToObject(injection, "trajectory", !above ? "suborbital"
                                                             : bound ? "orbit" : "escape");
        }
    }
    if (injection != NULL)
        cJSON_AddItemToObject(o, "injection", injection);
    else
        cJSON_AddNullToObject(o, "injection");
    /* ground contact: its last phase ended by an impact event */
    cJSON *gc = NULL;
    const lv_results_phase *lp = last_t ? &res->phases[last_k] : NULL;
    if (lp != NULL && lp->end_event != NULL && strcmp(lp->end_event, "impact") == 0 &&
        first_t != NULL) {
        const cols c0 = find_cols(first_t), c = find_cols(last_t);
        const size_t r = last_t->n_rows - 1;
        gc = cJSON_CreateObject();
        const double v = at(last_t, r, c.speed);
        cJSON_AddStringToObject(gc, "kind", v < LANDING_SPEED_MAX ? "landing" : "impact");
        cJSON_AddStringToObject(gc, "phase", lp->name);
        num(gc, "t", at(last_t, r, c.t));
        num(gc, "speed", v);
        /* the load of the contact row, left out of the flight's maxima */
        num(gc, "n_axial", axial_load(last_t, &c, r)); /* null: not available */
        if (c.nno >= 0)
            num(gc, "n_normal", fabs(at(last_t, r, c.nno)));
        double dist = NAN;
        if (!flat && c.lat >= 0 && c0.lat >= 0) {
            const double la = at(last_t, r, c.lat), lo = at(last_t, r, c.lon);
            num(gc, "lat", la);
            num(gc, "lon", lo);
            dist = gc_distance(at(first_t, 0, c0.lat), at(first_t, 0, c0.lon), la, lo);
        } else if (c.x >= 0 && c0.x >= 0) {
            const double x = at(last_t, r, c.x), y = at(last_t, r, c.y);
            num(gc, "x", x);
            num(gc, "y", y);
            dist = hypot(x - at(first_t, 0, c0.x), y - at(first_t, 0, c0.y));
        }
        num(gc, "distance", dist);
        /* the miss from the last phase's guidance target (its target_lat/lon; the phase's
         * start point when it names none): the target_distance output of the contact row */
        const long ctd = lv_results_table_col(last_t, "target_distance");
        if (ctd >= 0)
            num(gc, "target_distance", at(last_t, r, ctd));
    }
    cJSON_AddItemToObject(o, "ground_contact", gc ? gc : cJSON_CreateNull());
    return o;
}

/* summary.json's phases[k].handoff.absorbed, or NULL. */
static const cJSON *absorbed_of(const lv_results *res, size_t k)
{
    const cJSON *phs = cJSON_GetObjectItemCaseSensitive(res->json, "phases");
    const cJSON *pj = cJSON_GetArrayItem(phs, (int)k);
    return cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(pj, "handoff"),
                                            "absorbed");
}

/* A body's touchdown on a runway: the first phase with the body as its bottom stage that a
 * touchdown started (its hand-off absorbed a sink rate: a runway roll-out from a flight phase;
 * flown or crashed, so not only the body's flown phases). What the touchdown
 * was (summary.json's handoff.absorbed: the point from the threshold along the centre line,
 * sink rate, lateral offset and speed, ground speed, pitch, bank), whether it landed (the
 * roll-out flown) or crashed (beyond the landing gear's limits: the reason), and the roll-out:
 * its distance on the runway, the time from touchdown to the stop and where it stopped. NULL
 * when the body has no touchdown. docs/visualization.md, "Key figures". */
static cJSON *touchdown_json(const lv_plot_data *d, size_t bi)
{
    const lv_results *res = d->res;
    const lv_plot_body *b = &d->bodies[bi];
    for (size_t k = 0; k < res->n_phases; k++) {
        const lv_results_phase *ph = &res->phases[k];
        if (ph->n_stages == 0 || ph->stages[0] == NULL || strcmp(ph->stages[0], b->name) != 0)
            continue;
        const cJSON *ab = absorbed_of(res, k);
        const cJSON *sink = cJSON_GetObjectItemCaseSensitive(ab, "sink_rate");
        if (!cJSON_IsNumber(sink))
            continue;
        cJSON *o = cJSON_CreateObject();
        /* crashed at the touchdown (not flown), or by a crash end of the roll-out (flown:
         * off the runway's end) */
        const int crashed = ph->state != NULL && strcmp(ph->state, "crashed") == 0;
        cJSON_AddStringToObject(o, "status", crashed    ? "crashed"
                                             : ph->done ? "landed"
                                             : ph->state ? ph->state : "?");
        if ((crashed || !ph->done) && ph->error != NULL)
            cJSON_AddStringToObject(o, "reason", ph->error);
        cJSON_AddStringToObject(o, "phase", ph->name);
        num(o, "t", ph->t_start);
        static const char *const keys[] = {"distance", "sink_rate", "lateral", "lateral_speed",
                                           "ground_speed", "pitch", "bank"};
        for (size_t j = 0; j < sizeof keys / sizeof keys[0]; j++) {
            const cJSON *v = cJSON_GetObjectItemCaseSensitive(ab, keys[j]);
            num(o, strcmp(keys[j], "distance") == 0 ? "from_threshold" : keys[j],
                cJSON_IsNumber(v) ? v->valuedouble : NAN);
        }
        const lv_results_table *t = d->phases[k].csv;
        const long cs = t ? lv_results_table_col(t, "distance") : -1;
        const long cv = t ? lv_results_table_col(t, "speed") : -1;
        if (ph->done && t != NULL && t->n_rows > 0 && cs >= 0) {
            const size_t r = t->n_rows - 1;
            num(o, "rollout_distance", at(t, r, cs) - at(t, 0, cs));
            num(o, "stop_from_threshold", at(t, r, cs));
            num(o, "stop_speed", cv >= 0 ? at(t, r, cv) : NAN);
            num(o, "time_on_runway", ph->t_end - ph->t_start);
        }
        return o;
    }
    return NULL;
}

#define FM_JETTISON 1135.0 /* W/m^2: the free-molecular flux below which launchers jettison
                              their fairing (Ariane 5 User's Manual, issue 5, sec. 2.3.6) */

/* The aerothermal heating of body bi (docs/visualization.md, "Key figures"; docs/models.md,
 * "Aerothermal heating"): the largest stagnation-point heat flux (`heat_flux`, Sutton-Graves)
 * with its time, altitude and phase; the heat load, its time integral over the body's phases:
 * in a phase with the model's `heat_load` state (integrated with the trajectory) its change
 * over the phase (last row less first: a child starts from its parent's load, a phase after
 * one without the state from 0), else the trapezoidal rule on the phase file's rows (an event
 * instant's two rows add nothing);
 * and the first time the free-molecular flux falls below FM_JETTISON (linear between the two
 * rows around it). NULL: no phase has the columns. */
static cJSON *heating_json(const lv_plot_data *d, size_t bi)
{
    const lv_plot_body *b = &d->bodies[bi];
    double sg_max = -INFINITY, sg_t = NAN, sg_h = NAN, load = 0.0, fm_t = NAN, fm_h = NAN;
    const char *sg_phase = NULL, *fm_phase = NULL;
    int any = 0;
    for (size_t i = 0; i < b->n; i++) {
        const size_t k = b->phase[i];
        const lv_results_table *t = d->phases[k].csv;
        if (t == NULL || t->n_rows == 0)
            continue;
        const long ct = col(t, "time", NULL), ch = col(t, "h", NULL);
        const long csg = col(t, "heat_flux", NULL), cfm = col(t, "heat_flux_fm", NULL);
        if (csg < 0 || cfm < 0)
            continue;
        any = 1;
        const long cl = col(t, "heat_load", NULL);
        if (cl >= 0)
            load += at(t, t->n_rows - 1, cl) - at(t, 0, cl);
        for (size_t r = 0; r < t->n_rows; r++) {
            const double q = at(t, r, csg), tr = at(t, r, ct);
            if (q > sg_max) {
                sg_max = q;
                sg_t = tr;
                sg_h = at(t, r, ch);
                sg_phase = d->res->phases[k].name;
            }
            if (r == 0)
                continue;
            const double t0 = at(t, r - 1, ct), q0 = at(t, r - 1, csg);
            if (cl < 0)
                load += 0.5 * (tr - t0) * (q + q0);
            const double f0 = at(t, r - 1, cfm), f1 = at(t, r, cfm);
            if (isnan(fm_t) && f0 >= FM_JETTISON && f1 < FM_JETTISON) {
                const double w = (f0 - FM_JETTISON) / (f0 - f1);
                fm_t = t0 + w * (tr - t0);
                fm_h = at(t, r - 1, ch) + w * (at(t, r, ch) - at(t, r - 1, ch));
                fm_phase = d->res->phases[k].name;
            }
        }
    }
    if (!any)
        return NULL;
    cJSON *o = cJSON_CreateObject();
    cJSON *m = cJSON_AddObjectToObject(o, "max_heat_flux");
    num(m, "value", sg_max);
    num(m, "t", sg_t);
    num(m, "h", sg_h);
    if (sg_phase != NULL)
        cJSON_AddStringToObject(m, "phase", sg_phase);
    num(o, "heat_load", load);
    if (fm_phase != NULL) {
        m = cJSON_AddObjectToObject(o, "fm_below_1135");
        num(m, "t", fm_t);
        num(m, "h", fm_h);
        cJSON_AddStringToObject(m, "phase", fm_phase);
    } else {
        cJSON_AddNullToObject(o, "fm_below_1135");
    }
    return o;
}

/* The instantaneous impact point at the end of each powered phase of body bi (docs/
 * visualization.md, "Key figures"; docs/models.md, "Instantaneous impact point"): in every
 * phase whose bottom stage (the one that burns) is the body and whose file has the iip_*
 * columns, the last row with thrust > 0 (the cut-off, whatever ended the burn: a burnout, an
 * orbit end, the phase's end); its time, altitude, iip_lat, iip_lon, iip_tof, iip_range (null
 * with `impact` false where the drag-free path does not come down: in orbit). NULL: no phase
 * of the body has the columns. */
static cJSON *iip_json(const lv_plot_data *d, size_t bi)
{
    const lv_plot_body *b = &d->bodies[bi];
    static const char *const keys[4] = {"iip_lat", "iip_lon", "iip_tof", "iip_range"};
    cJSON *arr = NULL;
    for (size_t i = 0; i < b->n; i++) {
        const size_t k = b->phase[i];
        const lv_results_table *t = d->phases[k].csv;
        if (t == NULL || t->n_rows == 0)
            continue;
        long ci[4];
        int have = 1;
        for (int j = 0; j < 4; j++)
            have &= (ci[j] = col(t, keys[j], NULL)) >= 0;
        if (!have)
            continue;
        if (arr == NULL && (arr = cJSON_CreateArray()) == NULL)
            return NULL;
        const long cth = col(t, "thrust", NULL), ct = col(t, "time", NULL), ch = col(t, "h", NULL);
        if (cth < 0 || !burns_in(d->res, k, b->name))
            continue;
        size_t last = (size_t)-1;
        for (size_t r = 0; r < t->n_rows; r++)
            if (at(t, r, cth) > 0.0)
                last = r;
        if (last == (size_t)-1)
            continue;
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "phase", d->res->phases[k].name);
        num(o, "t", at(t, last, ct));
        num(o, "h", at(t, last, ch));
        cJSON_AddBoolToObject(o, "impact", isfinite(at(t, last, ci[0])));
        for (int j = 0; j < 4; j++)
            num(o, keys[j], at(t, last, ci[j]));
        cJSON_AddItemToArray(arr, o);
    }
    return arr;
}

lv_status lv_plot_keys(const lv_plot_data *d, cJSON **out, lv_err *err)
{
    *out = NULL;
    cJSON *doc = cJSON_CreateObject();
    if (doc == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    cJSON_AddStringToObject(doc, "mission", d->res->mission ? d->res->mission : "?");
    cJSON_AddStringToObject(doc, "world", d->flat ? "flat" : "planet");
    cJSON *bodies = cJSON_AddArrayToObject(doc, "bodies");
    for (size_t i = 0; i < d->n_bodies; i++)
    {
        cJSON *bk = body_keys(d, i, d->flat), *td = touchdown_json(d, i);
        cJSON_AddItemToObject(bk, "touchdown", td ? td : cJSON_CreateNull());
        cJSON *heat = heating_json(d, i);
        cJSON_AddItemToObject(bk, "heating", heat ? heat : cJSON_CreateNull());
        cJSON *iip = iip_json(d, i);
        cJSON_AddItemToObject(bk, "iip_cutoff", iip ? iip : cJSON_CreateNull());
        cJSON_AddItemToArray(bodies, bk);
    }
    char *text = lv_json_print(doc);
    if (text == NULL) {
        cJSON_Delete(doc);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    char path[4200];
    snprintf(path, sizeof path, "%s/key_figures.json", d->outdir);
    lv_atomic a;
    lv_status st = lv_atomic_open(&a, path, err);
    if (st == LV_OK) {
        fputs(text, a.fp);
        fputc('\n', a.fp);
        st = lv_atomic_commit(&a, err);
    }
    cJSON_free(text);
    if (st != LV_OK) {
        cJSON_Delete(doc);
        return st;
    }
    *out = doc;
    return LV_OK;
}
