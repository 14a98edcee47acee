/* flight_model.c - what the flight models over the planet share (flight_model.h): mass and
 * domain set-up, the start from geodetic values, the instance's start, and the callbacks of
 * the burnout and the named ends, the domain and the time events. */
#include "dynamics/flight_model.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/table_unit.h"
#include "core/units.h"
#include "dynamics/iip.h"

/* ---- construction ------------------------------------------------------------------------ */

lv_status lv_flight_check_mass(const char *model, double m0, double propellant, lv_err *err)
{
    if (!isfinite(m0) || !(m0 > 0.0))
        return lv_fail(err, LV_ERR_INPUT, "%s: start mass m0 = %g kg (must be > 0)", model, m0);
    if (!isfinite(propellant) || propellant < 0.0 || !(propellant < m0))
        return lv_fail(err, LV_ERR_INPUT, "%s: propellant = %g kg (must be >= 0 and less than "
                       "the start mass m0 = %g kg)", model, propellant, m0);
    return LV_OK;
}

lv_status lv_flight_check_heating(const char *model, double nose_radius, double k_sg, lv_err *err)
{
    if (!isfinite(nose_radius) || !(nose_radius > 0.0))
        return lv_fail(err, LV_ERR_INPUT, "%s: nose_radius = %g m (must be > 0)", model,
                       nose_radius);
    if (!isfinite(k_sg) || !(k_sg >= 0.0))
        return lv_fail(err, LV_ERR_INPUT, "%s: k_sutton_graves = %g kg^0.5/m (must be >= 0)",
                       model, k_sg);
    return LV_OK;
}

void lv_flight_iip(const lv_flight_world *w, double *grav_ws, double gm, double t,
                   const double r_eci[3], const double v_eci[3], const double r_ecef[3],
                   double y[4])
{
    lv_iip iip;
    lv_iip_propagate(&w->planet, w->grav, grav_ws, gm, t, r_eci, v_eci, &iip);
    y[0] = iip.lat;
    y[1] = iip.lon;
    y[2] = iip.tof;
    y[3] = iip.valid ? lv_iip_range(w->planet.a, r_ecef, iip.r_ecef) : NAN;
}

void lv_flight_iip_if(const unsigned char *need, size_t i0, const lv_flight_world *w,
                      double *grav_ws, double gm, double t, const double r_eci[3],
                      const double v_eci[3], const double r_ecef[3], double y[4])
{
    if (need == NULL || need[i0] || need[i0 + 1] || need[i0 + 2] || need[i0 + 3]) {
        lv_flight_iip(w, grav_ws, gm, t, r_eci, v_eci, r_ecef, y);
        return;
    }
    for (int c = 0; c < 4; c++)
        y[c] = NAN;
}

lv_status lv_flight_engines_init(const char *model, const lv_engine_config *engines, size_t n,
                                 lv_engine **eng, size_t *n_eng, double **eng_buf, lv_err *err)
{
    if (n == 0)
        return LV_OK;
    if (engines == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: n_engines = %zu but engines is NULL", model, n);
    if ((*eng = calloc(n, sizeof **eng)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    size_t nbuf = 1;
    for (size_t i = 0; i < n; i++) {
        lv_status st = lv_engine_init(&(*eng)[i], &engines[i], i, err);
        if (st != LV_OK)
            return st;
        *n_eng = i + 1;
        if ((*eng)[i].n_out > nbuf)
            nbuf = (*eng)[i].n_out;
    }
    if ((*eng_buf = malloc(nbuf * sizeof **eng_buf)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    return LV_OK;
}

static const char *const why_speed =
    "the engines thrust along an attitude that follows the air-relative velocity (the aero "
    "frame: the inputs' alpha, beta, mu; the prograde, retrograde or heading law; the gravity "
    "turn after its kick), which has no direction at zero speed: the thrust would flip from "
    "step to step. End the burn before (e.g. {speed: 10, direction: falling}) or steer it in "
    "the local frame (guidance: {law: attitude, frame: local})";
static const char *const why_vertical =
    "the velocity turned vertical while a force normal to it acts (lift; thrust at an angle of "
    "attack or sideslip) or a 6-DoF attitude is commanded about it, and the bank's reference, "
    "the vertical plane through it, is undefined in vertical flight: the force would flip from "
    "step to step. Fly through the vertical in the local frame (guidance: {law: attitude, "
    "frame: local}) or with alpha = beta = 0 and no lift";
static const char *const why_vertical_6dof =
    "the 6-DoF attitude is commanded about the air-relative velocity while the engines thrust "
    "or a force normal to that velocity acts (lift, the aerodynamic force at an angle of "
    "attack), and its roll reference, the vertical plane through that velocity, is undefined at "
    "rest and in vertical flight: the commanded roll would follow the velocity's drift (the "
    "Earth's rotation, the wind) and flip. Start the phase after the pitch-over (a dof3 lift-off "
    "phase first, as examples/two-stage-6dof) or steer it in the local frame (guidance: {law: "
    "attitude, frame: local})";
void lv_flight_domain_init(lv_domain_def dom[3], lv_flight_core *core, int has_atmo)
{
    dom[0] = (lv_domain_def){
        "h", "m", has_atmo ? LV_ATMO_ALT_MIN : -20e3,
        has_atmo ? "the vehicle is under the ground (below the floor of the atmosphere model); "
                   "an `impact` end ends the phase on the ground"
                 : "the vehicle is under the ground (20 km below the ellipsoid); an `impact` "
                   "end ends the phase on the ground",
        0};
    core->dom[0] = LV_FGUARD_H;
    core->ground_h = NAN;
    for (size_t i = 0; core->fe != NULL && i < core->fe->n; i++)
        if (core->fe->ends[i].kind == LV_DOF3_END_IMPACT &&
            !(core->fe->ends[i].value <= core->ground_h))
            core->ground_h = core->fe->ends[i].value;
    size_t n = 1;
    const unsigned refs = core->law != NULL ? lv_guid_refs(core->law, NULL, 0.0) : 0u;
    if (refs & LV_GREF_WIND) {
        dom[n] = (lv_domain_def){"v_air", "m/s", LV_FLIGHT_V_GUARD, why_speed, 1};
        core->dom[n++] = LV_FGUARD_SPEED;
        /* a 6-DoF attitude about the wind has no roll reference in a start at rest or
         * vertical: such a start is refused; a point mass may start there (a launch) */
        dom[n] = (lv_domain_def){"v_air_horizontal", "m/s", LV_FLIGHT_V_GUARD,
                                 core->rolls ? why_vertical_6dof : why_vertical, !core->rolls};
        core->dom[n++] = LV_FGUARD_VERTICAL;
    }
    core->n_dom = n;
}

void lv_flight_def_callbacks(lv_model_def *def, const lv_flight_core *core, lv_flight_rt *rt,
                             const lv_domain_def *domain)
{
    def->n_events = 1 + core->fe->n;
    def->events = core->fe->events;
    def->event_g = lv_flight_event_g;
    def->on_event = lv_flight_on_event;
    def->next_time_event = lv_flight_next_time_event_cb;
    def->on_time_event = lv_flight_on_time_event_cb;
    def->time_event_name = lv_flight_time_event_name_cb;
    def->n_domain = core->n_dom;
    def->domain = domain;
    def->domain_q = lv_flight_domain_q;
    def->describe = lv_flight_describe;
    def->last_error = lv_flight_last_error_cb;
    rt->core = core;
}

static int is_time_axis(const char *name)
{
    return strcmp(name, "time") == 0 || strcmp(name, "t") == 0;
}

lv_status lv_flight_check_inputs_table(const char *model, const lv_table *tab, lv_err *err)
{
    if (lv_table_n_dims(tab) != 1 || !is_time_axis(lv_table_axis_name(tab, 0)))
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: input table '%s' must have exactly one axis named 'time' (has %zu, "
                       "the first named '%s')",
                       model, lv_table_name(tab), lv_table_n_dims(tab),
                       lv_table_axis_name(tab, 0));
    char what[64];
    snprintf(what, sizeof what, "%s: inputs", model);
    return lv_table_expect_unit(tab, 1, 0, "s", what, err);
}

/* ---- an instance ------------------------------------------------------------------------- */

int lv_flight_fail(lv_flight_rt *rt, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(rt->msg, sizeof rt->msg, fmt, ap);
    va_end(ap);
    return -1;
}

int lv_flight_check_start(lv_flight_rt *rt, double lat, double vel, double prop)
{
    if (!(fabs(lat) <= 0.5 * LV_PI))
        return lv_flight_fail(rt, "start_lat = %g rad is outside [-pi/2, pi/2]", lat);
    if (!(vel >= 0.0))
        return lv_flight_fail(rt, "start_vel = %g m/s is negative", vel);
    if (!(prop >= 0.0))
        return lv_flight_fail(rt, "propellant = %g kg is negative", prop);
    return 0;
}

int lv_flight_check_throttle(lv_flight_rt *rt, double c)
{
    const lv_flight_core *k = rt->core;
    for (size_t i = 0; i < k->n_eng; i++)
        if (!(c >= k->eng[i].thr_min && c <= k->eng[i].thr_max))
            return lv_flight_fail(rt, "throttle = %g is outside the limits [%g, %g] of engine "
                                  "'%s'", c, k->eng[i].thr_min, k->eng[i].thr_max,
                                  k->eng[i].name);
    return 0;
}

void lv_flight_start_state(const lv_planet *pl, double lat, double lon, double h, double vel,
                           double fpa, double chi, double t0, double *r, double *v)
{
    double r_ecef[3], v_ned[3], C[3][3], v_ecef[3];
    lv_frames_geodetic_to_ecef(pl, lat, lon, h, r_ecef);
    lv_frames_ned_from_fpa(vel, fpa, chi, v_ned);
    lv_frames_C_ned_ecef(lat, lon, C);
    for (int i = 0; i < 3; i++) /* v_ecef = C_ned_ecef^T v_ned */
        v_ecef[i] = C[0][i] * v_ned[0] + C[1][i] * v_ned[1] + C[2][i] * v_ned[2];
    lv_frames_ecef_to_eci(pl, t0, r_ecef, v_ecef, r, v);
}

const lv_event_def lv_flight_sat_events[LV_FLIGHT_SAT_N] = {
    {"throttle_min", "The commanded throttle (a throttle law's, a table's) asks for less than "
     "the engines' minimum throttle (-1: from here the engines give n T_min; +1: back within "
     "range)", LV_DIR_BOTH, 0},
    {"throttle_max", "The commanded throttle (a throttle law's, a table's) asks for more than "
     "the engines' maximum throttle (-1: from here the engines give n T_max; +1: back within "
     "range)", LV_DIR_BOTH, 0},
};

lv_event_def *lv_flight_add_sat_events(lv_model_def *def, lv_flight_core *core)
{
    lv_event_def *ev = malloc((def->n_events + LV_FLIGHT_SAT_N) * sizeof *ev);
    if (ev == NULL)
        return NULL;
    memcpy(ev, def->events, def->n_events * sizeof *ev);
    memcpy(ev + def->n_events, lv_flight_sat_events, sizeof lv_flight_sat_events);
    def->events = ev;
    def->n_events += LV_FLIGHT_SAT_N;
    core->sat_events = 1;
    return ev;
}

int lv_flight_sat_begin(int rc, int watch, const lv_flight_rt *rt, const lv_engine *eng, size_t n,
                        double *g)
{
    g[LV_FLIGHT_SAT_MIN] = g[LV_FLIGHT_SAT_MAX] = 1.0;
    if (rc != 0 || !watch || !rt->engines_on)
        return 0;
    for (size_t i = 0; i < n; i++)
        if (!eng[i].out)
            return 1;
    return 0;
}

void lv_flight_sat_g(double c, double c_min, double c_max, double *g)
{
    g[LV_FLIGHT_SAT_MIN] = c - c_min + 1e-9;
    g[LV_FLIGHT_SAT_MAX] = c_max + 1e-9 - c;
}

void lv_flight_start_geodetic(const lv_flight_world *w, double t0, const double *r,
                              const double *v, double g[6])
{
    lv_flight_kin k;
    lv_flight_kinematics(w, t0, r, v, 1, &k);
    g[0] = k.lat;
    g[1] = k.lon;
    g[2] = k.h;
    g[3] = lv_v3_norm(k.v_rel);
    const double ned[3] = {lv_v3_dot(k.v_rel, k.n_ax), lv_v3_dot(k.v_rel, k.e_ax),
                           lv_v3_dot(k.v_rel, k.d_ax)};
    lv_frames_fpa_from_ned(ned, NULL, &g[4], &g[5]);
}

int lv_flight_book(lv_flight_rt *rt, double m, double prop, int engines)
{
    if (!(m > 0.0))
        return lv_flight_fail(rt, "start mass m = %g kg is not positive", m);
    if (!(prop < m))
        return lv_flight_fail(rt, "the propellant %g kg is not less than the start mass %g kg",
                              prop, m);
    rt->m_burnout = m - prop;
    rt->burned_out = 0;
    rt->engines_on = engines && prop > 0.0;
    return 0;
}

int lv_flight_origin(lv_flight_rt *rt, double t, const double r_eci[3], const double v_eci[3],
                     const char *what, lv_flight_kin *kin)
{
    const lv_flight_core *k = rt->core;
    lv_flight_to_ecef(k->world, t, r_eci, v_eci, kin);
    const double rn = lv_v3_norm(kin->r_ecef);
    if (!(rn > 0.0))
        return lv_flight_fail(rt, "%s is the planet's centre (|r| = %g m)", what, rn);
    lv_flight_geodetic(k->world, kin, 0, 0);
    rt->r0_unit[0] = kin->r_ecef.x / rn;
    rt->r0_unit[1] = kin->r_ecef.y / rn;
    rt->r0_unit[2] = kin->r_ecef.z / rn;
    return 0;
}

int lv_flight_start(lv_flight_rt *rt, double t0, const double *x, lv_flight_kin *kin)
{
    rt->thrust_last = -1.0; /* not known before the first right-hand side */
    const lv_flight_core *k = rt->core;
    if (lv_flight_origin(rt, t0, x + k->i_r, x + k->i_v, "start position", kin) != 0)
        return -1;
    /* A vehicle that starts on its impact level (a launch from the ground) and sinks (thrust
     * below its weight) has no crossing from above to find: its impact is 1 micrometre below
     * where it starts; one that starts below it is refused. */
    char why[320];
    if (lv_flight_ends_start(k->fe, kin->h, why, sizeof why) != 0)
        return lv_flight_fail(rt, "%s", why);
    for (size_t i = 0; i < k->n_eng; i++)
        lv_engine_start(&k->eng[i], t0);
    return 0;
}

/* ---- the callbacks ----------------------------------------------------------------------- */

int lv_flight_event_g(double t, const double *x, const double *p, double *g, void *inst)
{
    (void)p;
    const lv_flight_rt *rt = inst;
    const lv_flight_core *k = rt->core;
    /* burnout: disarmed (a constant) once the engines are off */
    g[0] = rt->engines_on ? x[k->i_m] - rt->m_burnout : 1.0;
    if (k->fe->n == 0)
        return 0;
    lv_flight_kin kin;
    lv_flight_to_ecef(k->world, t, x + k->i_r, x + k->i_v, &kin);
    lv_flight_ends_eval(k->fe, k->world, &kin, x + k->i_r, x + k->i_v, g + 1);
    return 0;
}

lv_event_action lv_flight_on_event(double t, double *x, const double *p, const int *fired,
                                   void *inst)
{
    (void)t, (void)x, (void)p;
    lv_flight_rt *rt = inst;
    const lv_flight_core *k = rt->core;
    lv_event_action act = LV_EVENT_CONTINUE;
    if (fired[0]) { /* propellant gone: engines off, a new initial value problem */
        rt->engines_on = 0;
        rt->burned_out = 1;
        act = k->stop_at_burnout ? LV_EVENT_STOP : LV_EVENT_RESTART;
    }
    for (size_t i = 0; i < k->fe->n; i++)
        if (fired[1 + i] && k->fe->ends[i].stop)
            act = LV_EVENT_STOP;
    /* the throttle's clamp is a kink of the thrust: a new initial value problem */
    const int *fs = fired + 1 + k->fe->n;
    if (k->sat_events && (fs[LV_FLIGHT_SAT_MIN] || fs[LV_FLIGHT_SAT_MAX]) &&
        act < LV_EVENT_RESTART)
        act = LV_EVENT_RESTART;
    return act;
}

/* The model's domain (lv_flight_domain_init): the geodetic altitude, then the guards, each
 * LV_DOMAIN_OFF where it does not apply at (t, x). Which apply: the law's references at t
 * (a function of t) and the latest right-hand side's forces (they change where the mode or
 * the law's angles change). */
int lv_flight_domain_q(double t, const double *x, const double *p, double *q, void *inst)
{
    (void)p;
    const lv_flight_rt *rt = inst;
    const lv_flight_core *k = rt->core;
    const lv_flight_world *w = k->world;
    lv_flight_kin kin;
    lv_flight_to_ecef(w, t, x + k->i_r, x + k->i_v, &kin);
    lv_flight_geodetic(w, &kin, 0, w->wind != NULL && k->n_dom > 1);
    q[0] = kin.h;
    if (k->n_dom == 1)
        return 0;
    /* a landing (within the zone, not rising): the impact's to end; a launch from the
     * ground climbs out of the zone and keeps its guards */
    if (kin.h < k->ground_h + LV_FLIGHT_GROUND_ZONE && lv_v3_dot(kin.v_rel, kin.d_ax) >= 0.0) {
        for (size_t i = 1; i < k->n_dom; i++)
            q[i] = LV_DOMAIN_OFF;
        return 0;
    }
    const unsigned refs = lv_guid_refs(k->law, &rt->guid, t);
    /* before the first right-hand side (the start check) the engines' mode tells */
    const int thrusts = rt->thrust_last > 0.0 || (rt->thrust_last < 0.0 && rt->engines_on);
    lv_vec3 v_air = kin.v_rel;
    if ((refs & LV_GREF_WIND) && w->wind != NULL) {
        double w_ned[3] = {0.0, 0.0, 0.0};
        if (w->wind(t, kin.h, kin.lat, kin.lon, w_ned, w->wind_user) == 0)
            v_air = lv_v3_sub(kin.v_rel, lv_flight_from_ned(&kin, w_ned[0], w_ned[1], w_ned[2]));
    }
    for (size_t i = 1; i < k->n_dom; i++) {
        double qi = LV_DOMAIN_OFF;
        switch ((lv_flight_guard)k->dom[i]) {
        case LV_FGUARD_SPEED:
            if ((refs & LV_GREF_WIND) && thrusts)
                qi = lv_v3_norm(v_air);
            break;
        case LV_FGUARD_VERTICAL:
            if ((refs & LV_GREF_WIND) && (rt->normal_last || (k->rolls && thrusts))) {
                const double vd = lv_v3_dot(v_air, kin.d_ax);
                qi = lv_v3_norm(lv_v3_sub(v_air, lv_v3_scale(kin.d_ax, vd)));
            }
            break;
        case LV_FGUARD_H:
            break;
        }
        q[i] = qi;
    }
    return 0;
}

void lv_flight_note_forces(lv_flight_rt *rt, double thrust, lv_vec3 f, lv_vec3 xw, double mass)
{
    rt->thrust_last = thrust;
    if (rt->core->n_dom == 1) /* no guard reads it: the right-hand side's hot path */
        return;
    const double fn = lv_v3_norm(f);
    const double normal = lv_v3_norm(lv_v3_sub(f, lv_v3_scale(xw, lv_v3_dot(f, xw))));
    /* relative 1e-9: thrust along -x_w at alpha = 180 deg leaves sin(pi) = 1.2e-16 */
    rt->normal_last = normal > 1e-9 * fn && normal > LV_FLIGHT_NORMAL_MIN * mass;
}

void lv_flight_describe(double t, const double *x, const double *p, char *buf, size_t cap,
                        void *inst)
{
    (void)p;
    const lv_flight_rt *rt = inst;
    const lv_flight_core *k = rt->core;
    lv_flight_kin kin;
    lv_flight_to_ecef(k->world, t, x + k->i_r, x + k->i_v, &kin);
    lv_flight_geodetic(k->world, &kin, 1, 1);
    const double vn = lv_v3_dot(kin.v_rel, kin.n_ax), ve = lv_v3_dot(kin.v_rel, kin.e_ax);
    const double vd = lv_v3_dot(kin.v_rel, kin.d_ax), vh = hypot(vn, ve);
    const double fpa = atan2(-vd, vh) / LV_DEG;
    double chi = atan2(ve, vn) / LV_DEG;
    if (chi < 0.0)
        chi += 360.0;
    snprintf(buf, cap, "h = %.9g m, lat %.6f deg, lon %.6f deg, v_rel = %.6g m/s, fpa = %.4f "
             "deg, heading %.2f deg, m = %.9g kg", kin.h, kin.lat / LV_DEG, kin.lon / LV_DEG,
             lv_v3_norm(kin.v_rel), fpa, chi, x[k->i_m]);
}

double lv_flight_next_time_event_cb(double t, const double *p, void *inst)
{
    (void)p;
    const lv_flight_rt *rt = inst;
    const lv_flight_core *k = rt->core;
    return lv_flight_next_time_event(k->inputs, k->eng, k->n_eng, k->guid, &rt->guid, t);
}

lv_event_action lv_flight_on_time_event_cb(double t, double *x, const double *p, void *inst)
{
    (void)x, (void)p;
    const lv_flight_rt *rt = inst;
    const lv_flight_core *k = rt->core;
    for (size_t i = 0; i < k->n_eng; i++)
        lv_engine_out_event(&k->eng[i], t);
    /* a table breakpoint is a kink, an engine-out a jump: both a new initial value problem */
    return LV_EVENT_RESTART;
}

/* The time events at t by their source: the inputs table's, the steering law's or an engine
 * table's breakpoint. */
const char *lv_flight_time_event_name_cb(double t, const double *p, void *inst)
{
    (void)p;
    lv_flight_rt *rt = inst;
    const lv_flight_core *k = rt->core;
    return lv_flight_time_event_label(k->inputs, k->eng, k->n_eng, k->guid, &rt->guid, t,
                                      rt->tev, sizeof rt->tev);
}

/* Why the last callback failed (a table out of range, the atmosphere, a bad parameter). */
const char *lv_flight_last_error_cb(const void *inst)
{
    const lv_flight_rt *rt = inst;
    return rt != NULL && rt->msg[0] != '\0' ? rt->msg : NULL;
}
