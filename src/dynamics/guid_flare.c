/* guid_flare.c - steering law `flare`: the exponential flare of an unpowered (or constant-
 * thrust) glide landing onto a runway, 3-DoF phases. Equations: docs/guidance.md, "The flare
 * law".
 *
 * The runway: its threshold r0 (geodetic runway_lat, runway_lon, runway_elevation), the plane
 * through r0 normal to the ellipsoid's upward normal n there, its centre line u = cos psi N0 +
 * sin psi E0 (psi = runway_heading) and the lateral axis w = u x n (right of the centre line).
 * The height above the runway plane and its rate, relative to the rotating planet,
 *
 *     h = (r - r0) . n,   h' = v_rel . n        (n fixed in the planet: h'' = a_rel . n)
 *
 * Vertical: the exponential flare (Blakelock, Automatic Control of Aircraft and Missiles, 2nd
 * ed., Wiley 1991, sec. 5.6 "Automatic flare control"; Stevens, Lewis & Johnson, Aircraft
 * Control and Simulation, 3rd ed., sec. 4.8): the path h' = -(h + h_a) / tau, whose solution
 * h(t) = (h0 + h_a) exp(-t / tau) - h_a reaches the runway with the sink rate h_a / tau; so
 * h_a = sink_rate tau. With tau = 0 (the default) the path is the one tangent to the entry:
 * tau = h0 / (s0 - sink_rate) from the start height h0 and sink rate s0 = -h'0, and the flare
 * starts without a jump in the commanded vertical acceleration. The law commands
 *
 *     e = h' + (h + h_a) / tau,   h''_cmd = -h' / tau - k e        (k = path_gain)
 *
 * so that e' = -k e along the flight (e = 0 on the path: h'' = -h' / tau, the path's own
 * curvature); the 3-DoF model finds the angle of attack in [alpha_min, alpha_max] whose
 * forces give h''_cmd (guidance.h, lv_guid_accel_cmd). Within the alpha range and from an
 * entry on the path, the height follows h(t) above to the integrator's tolerance.
 *
 * Lateral: the bank turns the air-relative course toward a point `lookahead` metres down the
 * centre line from the vehicle's own station: course_cmd = psi - atan(y / lookahead) with y =
 * (r - r0) . w; mu = clamp(gain (course_cmd - course), +-bank_max).
 */
#include "dynamics/guid_kit.h"
#include "env/planet.h"

typedef struct flare_par {
    double lat, lon, elevation, heading; /* the runway: rad, rad, m, rad */
    double sink_rate;            /* m/s at touchdown, > 0 */
    double tau;                  /* s; 0: tangent to the entry */
    double path_gain;            /* 1/s */
    double alpha_min, alpha_max; /* rad */
    double bank_max;             /* rad */
    double lookahead;            /* m */
    double gain;                 /* rad/rad */
    /* init: the runway's frame, ECEF */
    double r0[3], n[3], u[3], w[3];
} flare_par;

enum { S0_TAU, S0_HA }; /* rt->s0: the flare's time constant [s] and offset h_a [m] */

static const lv_law_key keys[] = {
    {.name = "runway_lat", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_LAT_LO,
     .hi = LV_KR_LAT_HI, .dflt = NAN, .flags = LV_KEY_ANGLE, .offset = offsetof(flare_par, lat),
     .description = "geodetic latitude of the runway's threshold"},
    {.name = "runway_lon", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_TURN_LO,
     .hi = LV_KR_TURN_HI, .dflt = NAN, .flags = LV_KEY_ANGLE, .offset = offsetof(flare_par, lon),
     .description = "longitude of the runway's threshold"},
    {.name = "runway_elevation", .type = LV_KEY_NUMBER, .unit = "m", .lo = -1000.0,
     .hi = 10000.0, .dflt = 0.0, .offset = offsetof(flare_par, elevation),
     .description = "height of the threshold above the ellipsoid"},
    {.name = "runway_heading", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_TURN_LO,
     .hi = LV_KR_TURN_HI, .dflt = NAN, .flags = LV_KEY_ANGLE,
     .offset = offsetof(flare_par, heading),
     .description = "direction of landing along the centre line, from north to east"},
    {.name = "sink_rate", .type = LV_KEY_NUMBER, .unit = "m/s", .lo = 0.0, .hi = 10.0,
     .lo_open = 1, .dflt = 0.6, .offset = offsetof(flare_par, sink_rate),
     .description = "sink rate the path reaches the runway with (0.6 m/s: 2 ft/s)"},
    {.name = "tau", .type = LV_KEY_NUMBER, .unit = "s", .lo = 0.0, .hi = 1000.0, .dflt = 0.0,
     .offset = offsetof(flare_par, tau),
     .description = "time constant of the exponential path; 0: the path tangent to the entry"},
    {.name = "path_gain", .type = LV_KEY_NUMBER, .unit = "1/s", .lo = 0.0, .hi = 100.0,
     .lo_open = 1, .dflt = 1.0, .offset = offsetof(flare_par, path_gain),
     .description = "rate at which a departure from the path decays"},
    {.name = "alpha_min", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_LAT_LO,
     .hi = LV_KR_LAT_HI, .dflt = -5.0 * LV_DEG, .flags = LV_KEY_ANGLE,
     .offset = offsetof(flare_par, alpha_min),
     .description = "smallest angle of attack the flare may command"},
    {.name = "alpha_max", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_LAT_LO,
     .hi = LV_KR_LAT_HI, .dflt = 20.0 * LV_DEG, .flags = LV_KEY_ANGLE,
     .offset = offsetof(flare_par, alpha_max),
     .description = "largest angle of attack the flare may command (stall is not modelled)"},
    {.name = "bank_max", .type = LV_KEY_NUMBER, .unit = "rad", .lo = 0.0, .hi = 0.5 * LV_PI,
     .lo_open = 1, .dflt = 10.0 * LV_DEG, .flags = LV_KEY_ANGLE,
     .offset = offsetof(flare_par, bank_max), .description = "largest bank angle"},
    {.name = "lookahead", .type = LV_KEY_NUMBER, .unit = "m", .lo = 0.0, .hi = 1e5,
     .lo_open = 1, .dflt = 1000.0, .offset = offsetof(flare_par, lookahead),
     .description = "distance down the centre line the course aims at"},
    {.name = "gain", .type = LV_KEY_NUMBER, .unit = "1", .lo = 0.0, .hi = 100.0, .lo_open = 1,
     .dflt = 1.0, .offset = offsetof(flare_par, gain),
     .description = "bank per course error (rad/rad)"},
};

static lv_status check(const void *par, lv_law_at *at, lv_err *err)
{
    const flare_par *p = par;
    at->node = LV_AT_VALUE;
    at->key = "alpha_max";
    if (!(p->alpha_max > p->alpha_min))
        return lv_fail(err, LV_ERR_INPUT, "alpha_max %.6g deg must be above alpha_min %.6g deg",
                       p->alpha_max / LV_DEG, p->alpha_min / LV_DEG);
    return LV_OK;
}

static void put(double d[3], lv_vec3 v) { d[0] = v.x, d[1] = v.y, d[2] = v.z; }
static lv_vec3 get(const double d[3]) { return lv_v3(d[0], d[1], d[2]); }

static lv_status init(lv_guid *g, lv_err *err)
{
    (void)err;
    flare_par *p = LV_GUID_PAR_W(flare_par, g);
    const double cl = cos(p->lat), sl = sin(p->lat), co = cos(p->lon), so = sin(p->lon);
    const lv_vec3 north = lv_v3(-sl * co, -sl * so, cl), east = lv_v3(-so, co, 0.0);
    const lv_vec3 up = lv_v3(cl * co, cl * so, sl); /* the geodetic normal */
    const lv_vec3 u = lv_v3_add(lv_v3_scale(north, cos(p->heading)),
                                lv_v3_scale(east, sin(p->heading)));
    put(p->r0, lv_frames_geodetic_to_ecef_v(&g->planet, p->lat, p->lon, p->elevation));
    put(p->n, up);
    put(p->u, u);
    put(p->w, lv_v3_cross(u, up));
    return LV_OK;
}

/* Height above the runway plane and its rate [m, m/s]. */
static void height(const flare_par *p, const lv_flight_kin *k, double *h, double *h_dot)
{
    const lv_vec3 n = get(p->n);
    *h = lv_v3_dot(lv_v3_sub(k->r_ecef, get(p->r0)), n);
    *h_dot = lv_v3_dot(k->v_rel, n);
}

static int start(const lv_guid *g, lv_guid_rt *rt, const lv_flight_kin *k, char *msg,
                 size_t cap)
{
    const flare_par *p = LV_GUID_PAR(flare_par, g);
    double h, h_dot;
    height(p, k, &h, &h_dot);
    double tau = p->tau;
    if (!(tau > 0.0)) {
        if (!(h > 0.0) || !(-h_dot > p->sink_rate)) {
            snprintf(msg, cap, "guidance 'flare': the flare starts %.4g m above the runway "
                     "plane, sinking at %.4g m/s: the path tangent to the entry needs a start "
                     "above the runway sinking faster than sink_rate %.4g m/s (or give tau)",
                     h, -h_dot, p->sink_rate);
            return 1;
        }
        tau = h / (-h_dot - p->sink_rate);
    }
    rt->s0[S0_TAU] = tau;
    rt->s0[S0_HA] = p->sink_rate * tau;
    return 0;
}

static int attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                    const lv_flight_air *a, double fpa0, double chi0, int full,
                    lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    (void)t, (void)full, (void)err;
    const flare_par *p = LV_GUID_PAR(flare_par, g);
    /* the course: toward the centre line's point `lookahead` ahead; the course error from
     * the cross and dot products of the two horizontal directions (as the heading law) */
    const lv_vec3 u = get(p->u), w = get(p->w);
    const double y = lv_v3_dot(lv_v3_sub(k->r_ecef, get(p->r0)), w);
    const double toward = -atan(y / p->lookahead);
    const double ct = cos(toward), st = sin(toward);
    const lv_vec3 aim = lv_v3_add(lv_v3_scale(u, ct), lv_v3_scale(w, st));
    const double an = lv_v3_dot(aim, k->n_ax), ae = lv_v3_dot(aim, k->e_ax);
    const double vn = lv_v3_dot(a->v_air, k->n_ax), ve = lv_v3_dot(a->v_air, k->e_ax);
    double mu = p->gain * atan2(vn * ae - ve * an, vn * an + ve * ae);
    mu = mu > p->bank_max ? p->bank_max : mu < -p->bank_max ? -p->bank_max : mu;
    /* alpha: the model solves for it (accel_command); the middle of the range until then */
    const double ang[3] = {0.5 * (p->alpha_min + p->alpha_max), 0.0, mu};
    lv_guid_aero_angles(rt, k, a, ang, fpa0, chi0, c, ax);
    return 0;
}

static void accel_command(const lv_guid *g, const lv_guid_rt *rt, double t,
                          const lv_flight_kin *k, lv_guid_accel_cmd *cmd)
{
    (void)t;
    const flare_par *p = LV_GUID_PAR(flare_par, g);
    double h, h_dot;
    height(p, k, &h, &h_dot);
    const double tau = rt->s0[S0_TAU], e = h_dot + (h + rt->s0[S0_HA]) / tau;
    cmd->dir = get(p->n);
    cmd->accel = -h_dot / tau - p->path_gain * e;
    cmd->alpha_lo = p->alpha_min;
    cmd->alpha_hi = p->alpha_max;
}

/* alpha and the bank about the air-relative velocity */
static unsigned refs(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    (void)g, (void)rt, (void)t;
    return LV_GREF_WIND;
}

const lv_law lv_law_flare = {
    .name = "flare",
    .description = "exponential flare onto a runway: the angle of attack that keeps the "
                   "height on h' = -(h + h_a) / tau, the bank that holds the centre line",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NAMED,
    .keys = keys,
    .n_keys = sizeof keys / sizeof keys[0],
    .par_size = sizeof(flare_par),
    .needs_aero = "flares with the lift",
    .dof3_only = "its angle of attack is solved from the point mass's forces; a 6-DoF body "
                 "flies the attitude its controller reaches",
    .check = check,
    .init = init,
    .start = start,
    .attitude = attitude,
    .accel_command = accel_command,
    .refs = refs,
};
