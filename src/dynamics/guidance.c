/* guidance.c - steering and throttle laws (guidance.h, lv_guidance.h; docs/guidance.md).
 *
 * Attitude frames: the body axes from 3-2-1 Euler angles relative to a NED frame,
 * C_body_ned = R1(phi) R2(theta) R3(psi) (Stevens, Lewis & Johnson, Aircraft Control and
 * Simulation, 3rd ed., eq. 1.3-20); the aerodynamic angles of the air-relative velocity in
 * body axes, alpha = atan2(w, u), beta = asin(v / V) (ibid. eq. 2.3-6). Gravity turn and
 * tangent steering: Wiesel, Spaceflight Dynamics, 3rd ed., sec. 9; Bryson & Ho, Applied
 * Optimal Control, sec. 2.7 (linear tangent law). Throttle laws: docs/guidance.md.
 */
#include "dynamics/guidance.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/status.h"
#include "core/table_unit.h"
#include "core/units.h"

#define V_AIR_MIN 1e-6 /* m/s, as flight.c: below, no aerodynamic angles */

static const char *const law_names[] = {"inputs", "attitude", "gravity_turn", "tangent steering",
                                        "heading", "retrograde", "boostback"};

static int is_axis(const char *name, const char *a, const char *b)
{
    return strcmp(name, a) == 0 || (b != NULL && strcmp(name, b) == 0);
}

lv_status lv_guid_table_check(const lv_table *t, lv_steer_law law, lv_att_frame frame,
                             lv_guid *g, lv_err *err)
{
    if (lv_table_n_out(t) > 16)
        return lv_fail(err, LV_ERR_INPUT, "table '%s' has %zu outputs (at most 16)",
                       lv_table_name(t), lv_table_n_out(t));
    const char *ax = lv_table_n_dims(t) == 1 ? lv_table_axis_name(t, 0) : "";
    size_t idx;
    if (law == LV_STEER_HEADING) {
        if (!is_axis(ax, "mach", NULL))
            return lv_fail(err, LV_ERR_INPUT, "alpha table '%s' must have "
                           "one axis named 'mach' (it has %zu, the first '%s')", lv_table_name(t),
                           lv_table_n_dims(t), lv_table_axis_name(t, 0));
        if (lv_table_out_index(t, "alpha", &idx, NULL) != LV_OK)
            return lv_fail(err, LV_ERR_INPUT, "alpha table '%s' has no "
                           "output 'alpha' (its first is '%s')", lv_table_name(t),
                           lv_table_out_name(t, 0));
        lv_status st = lv_table_expect_unit(t, 1, 0, "1", NULL, err);
        if (st != LV_OK || (st = lv_table_expect_unit(t, 0, idx, "rad", NULL, err)) != LV_OK)
            return st;
        if (g != NULL)
            g->k[0] = (int)idx;
        return LV_OK;
    }
    lv_gaxis axis;
    if (is_axis(ax, "time", "t"))
        axis = LV_GAXIS_TIME;
    else if (is_axis(ax, "altitude", "h"))
        axis = LV_GAXIS_ALTITUDE;
    else if (is_axis(ax, "speed", "v_rel"))
        axis = LV_GAXIS_SPEED;
    else if (is_axis(ax, "mach", NULL))
        axis = LV_GAXIS_MACH;
    else
        return lv_fail(err, LV_ERR_INPUT, "table '%s' must have one axis "
                       "named time, altitude, speed or mach (it has %zu, the first '%s')",
                       lv_table_name(t), lv_table_n_dims(t), lv_table_axis_name(t, 0));
    static const char *const axis_si[] = {"s", "m", "m/s", "1"};
    lv_status ust = lv_table_expect_unit(t, 1, 0, axis_si[axis], NULL, err);
    if (ust != LV_OK)
        return ust;
    static const char *const aero_out[3] = {"alpha", "beta", "mu"};
    static const char *const att_out[3] = {"pitch", "heading", "roll"};
    const char *const *names = frame == LV_FRAME_AERO ? aero_out : att_out;
    int any = 0, k[4];
    for (int i = 0; i < 4; i++) {
        k[i] = -1;
        if (lv_table_out_index(t, i < 3 ? names[i] : "throttle", &idx, NULL) == LV_OK) {
            if ((ust = lv_table_expect_unit(t, 0, idx, i < 3 ? "rad" : "1", NULL, err)) != LV_OK)
                return ust;
            k[i] = (int)idx;
            any = 1;
        }
    }
    if (!any)
        return lv_fail(err, LV_ERR_INPUT, "table '%s' has none of the "
                       "outputs %s, %s, %s, throttle (frame %s; its first output is '%s')",
                       lv_table_name(t), names[0], names[1], names[2],
                       frame == LV_FRAME_AERO ? "aero" : "local/inertial",
                       lv_table_out_name(t, 0));
    if (g != NULL) {
        g->axis = axis;
        for (int i = 0; i < 4; i++)
            g->k[i] = k[i];
    }
    return LV_OK;
}

lv_status lv_guid_init(lv_guid *g, const lv_steering *s, const lv_planet *planet, int has_aero,
                       lv_err *err)
{
    memset(g, 0, sizeof *g);
    g->s = *s;
    for (int i = 0; i < 4; i++)
        g->k[i] = -1;
    if ((unsigned)s->law > LV_STEER_BOOSTBACK)
        return lv_fail(err, LV_ERR_INPUT, "guidance: unknown law %d", (int)s->law);
    const char *law = law_names[s->law];
    if ((unsigned)s->frame > LV_FRAME_INERTIAL)
        return lv_fail(err, LV_ERR_INPUT, "guidance '%s': unknown frame %d", law, (int)s->frame);
    for (int i = 0; i < 3; i++)
        if (!isfinite(s->angle[i]))
            return lv_fail(err, LV_ERR_INPUT, "guidance '%s': angle %d is not finite", law, i);
    if (!isfinite(s->heading) || !isfinite(s->pitch) || !isfinite(s->alpha) ||
        !isfinite(s->a) || !isfinite(s->b) || !isfinite(s->c) || !isfinite(s->d) ||
        !(fabs(s->target_lat) <= 0.5 * LV_PI) || !isfinite(s->target_lon))
        return lv_fail(err, LV_ERR_INPUT, "guidance '%s': a value is not finite (or the target "
                       "latitude is outside [-90, 90] deg)", law);
    switch (s->law) {
    case LV_STEER_GRAVITY_TURN:
        if (!(s->rise_time >= 0.0) || !(s->kick_time >= 0.0) || !isfinite(s->rise_time) ||
            !isfinite(s->kick_time))
            return lv_fail(err, LV_ERR_INPUT, "guidance 'gravity_turn': rise_time = %g s and "
                           "kick_time = %g s must be >= 0", s->rise_time, s->kick_time);
        if (!(s->kick >= 0.0 && s->kick <= 0.5 * LV_PI))
            return lv_fail(err, LV_ERR_INPUT, "guidance 'gravity_turn': kick = %g deg must be "
                           "in [0, 90] deg", s->kick / LV_DEG);
        if (s->kick > 0.0 && !(s->kick_time > 0.0))
            return lv_fail(err, LV_ERR_INPUT, "guidance 'gravity_turn': a kick of %g deg needs "
                           "a kick_time > 0", s->kick / LV_DEG);
        break;
    case LV_STEER_TANGENT:
        if (s->frame == LV_FRAME_AERO)
            return lv_fail(err, LV_ERR_INPUT, "guidance 'tangent steering': the pitch is measured in the "
                           "local or inertial frame, not the aerodynamic one");
        if (s->a == 0.0 && s->c == 0.0 && s->b == 0.0 && s->d == 0.0)
            return lv_fail(err, LV_ERR_INPUT, "guidance 'tangent steering': a, b, c and d are all 0");
        break;
    case LV_STEER_HEADING:
        if (!has_aero)
            return lv_fail(err, LV_ERR_INPUT, "guidance 'heading' banks the lift vector: the "
                           "phase needs an aerodynamic dataset (aero:)");
        if (!(s->bank_max > 0.0 && s->bank_max <= 0.5 * LV_PI))
            return lv_fail(err, LV_ERR_INPUT, "guidance 'heading': bank_max = %g deg must be in "
                           "(0, 90] deg", s->bank_max / LV_DEG);
        if (!(s->gain > 0.0) || !isfinite(s->gain))
            return lv_fail(err, LV_ERR_INPUT, "guidance 'heading': gain = %g must be > 0",
                           s->gain);
        if (!(s->n_max >= 0.0) || !isfinite(s->n_max))
            return lv_fail(err, LV_ERR_INPUT, "guidance 'heading': n_max = %g must be >= 0 "
                           "(0: no limit)", s->n_max);
        if (!(s->q_max >= 0.0) || !isfinite(s->q_max))
            return lv_fail(err, LV_ERR_INPUT, "guidance 'heading': q_max = %g Pa must be >= 0 "
                           "(0: none)", s->q_max);
        if (s->q_max > 0.0 && !(s->n_max > 0.0))
            return lv_fail(err, LV_ERR_INPUT, "guidance 'heading': q_max = %g Pa releases the "
                           "load-factor limit: it needs n_max > 0", s->q_max);
        break;
    default:
        break;
    }
    lv_status st = LV_OK;
    if (s->law == LV_STEER_ATTITUDE && s->table != NULL)
        st = lv_guid_table_check(s->table, s->law, s->frame, g, err);
    if (s->law == LV_STEER_HEADING && s->alpha_table != NULL)
        st = lv_guid_table_check(s->alpha_table, s->law, s->frame, g, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "guidance '%s'", law);
    g->need_alpha = g->need_beta = 1; /* lv_dof3 narrows them down */
    g->cs_heading[0] = cos(s->heading);
    g->cs_heading[1] = sin(s->heading);
    g->cs_pitch[0] = cos(s->pitch);
    g->cs_pitch[1] = sin(s->pitch);
    double r[3];
    lv_frames_geodetic_to_ecef(planet, s->target_lat, s->target_lon, 0.0, r);
    g->target_r = lv_v3(r[0], r[1], r[2]);
    g->target = lv_v3_unit(g->target_r);
    return LV_OK;
}

void lv_guid_start(const lv_guid *g, lv_guid_rt *rt, double t0, const lv_flight_kin *k)
{
    (void)g;
    rt->t0 = t0;
    rt->cur = (lv_table_cursor)LV_TABLE_CURSOR_INIT;
    rt->alpha_cur = (lv_table_cursor)LV_TABLE_CURSOR_INIT;
    for (int i = 0; i < 3; i++)
        rt->ang[i] = NAN;
    /* ECEF -> ECI: R3(theta)^T with theta the angle k->c_th, k->s_th stand for */
    const lv_vec3 ax[3] = {k->n_ax, k->e_ax, k->d_ax};
    for (int i = 0; i < 3; i++)
        rt->f0[i] = lv_v3(k->c_th * ax[i].x - k->s_th * ax[i].y,
                          k->s_th * ax[i].x + k->c_th * ax[i].y, ax[i].z);
}

double lv_guid_next_time_event(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    const lv_steering *s = &g->s;
    if (s->law == LV_STEER_GRAVITY_TURN) {
        const double t1 = rt->t0 + s->rise_time, t2 = t1 + s->kick_time;
        if (t1 > t)
            return t1;
        if (t2 > t)
            return t2;
        return INFINITY;
    }
    if (s->law == LV_STEER_ATTITUDE && s->table != NULL && g->axis == LV_GAXIS_TIME)
        return lv_table_next_breakpoint(s->table, 0, t);
    return INFINITY;
}

const char *lv_guid_time_event_label(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    const lv_steering *s = &g->s;
    if (s->law == LV_STEER_GRAVITY_TURN) {
        const double t1 = rt->t0 + s->rise_time;
        if (t == t1 && s->kick_time > 0.0)
            return "guidance: end of the vertical rise, start of the kick";
        if (t == t1 + s->kick_time)
            return s->kick_time > 0.0 ? "guidance: end of the kick, zero angle of attack"
                                      : "guidance: end of the vertical rise, zero angle of "
                                        "attack";
    }
    if (s->law == LV_STEER_ATTITUDE && s->table != NULL && g->axis == LV_GAXIS_TIME) {
        size_t n = 0;
        const double *b = lv_table_breakpoints(s->table, 0, &n);
        for (size_t i = 0; b != NULL && i < n; i++)
            if (b[i] == t)
                return "guidance: attitude table breakpoint";
    }
    return NULL;
}

/* cos, sin of the three angles, cached while they do not change. */
static void trig3(lv_guid_rt *rt, const double ang[3])
{
    for (int i = 0; i < 3; i++)
        if (ang[i] != rt->ang[i]) {
            rt->ang[i] = ang[i];
            rt->cs[i][0] = cos(ang[i]);
            rt->cs[i][1] = sin(ang[i]);
        }
}

/* Body axes from pitch, heading, roll (cosines and sines) relative to the frame (N, E, D):
 * the rows of C_body_ned = R1(phi) R2(theta) R3(psi). */
static void body_from_euler(const lv_vec3 f[3], const double cs[3][2], lv_flight_axes *ax)
{
    const double ct = cs[0][0], st = cs[0][1], cp = cs[1][0], sp = cs[1][1];
    const double cr = cs[2][0], sr = cs[2][1];
    const lv_vec3 hor = lv_v3_add(lv_v3_scale(f[0], cp), lv_v3_scale(f[1], sp));
    const lv_vec3 y0 = lv_v3_sub(lv_v3_scale(f[1], cp), lv_v3_scale(f[0], sp));
    const lv_vec3 z0 = lv_v3_add(lv_v3_scale(hor, st), lv_v3_scale(f[2], ct));
    ax->xb = lv_v3_sub(lv_v3_scale(hor, ct), lv_v3_scale(f[2], st));
    ax->yb = lv_v3_add(lv_v3_scale(y0, cr), lv_v3_scale(z0, sr));
    ax->zb = lv_v3_sub(lv_v3_scale(z0, cr), lv_v3_scale(y0, sr));
}

/* The aerodynamic angles of the air-relative velocity in the body axes ax->xb.., and the
 * wind axes they give: x_w = C_wind_body^T e_x (Stevens & Lewis eq. 2.3-2); bank mu about
 * x_w from the vertical plane through it (lv_flight_axes_eval's convention). Without
 * air-relative speed: all 0, wind axes = body axes. */
static void wind_from_body(const lv_flight_kin *k, const lv_flight_air *a, double chi0,
                           int full, const int need[2], lv_flight_controls *c,
                           lv_flight_axes *ax)
{
    if (!(a->v_air_n > V_AIR_MIN)) {
        ax->xw = ax->xb, ax->yw = ax->yb, ax->zw = ax->zb;
        for (int i = 0; i < 3; i++) {
            c->u[i] = 0.0;
            c->cs[i][0] = 1.0, c->cs[i][1] = 0.0;
        }
        return;
    }
    const double u = lv_v3_dot(a->v_air, ax->xb), v = lv_v3_dot(a->v_air, ax->yb);
    const double w = lv_v3_dot(a->v_air, ax->zb);
    const double uw = sqrt(u * u + w * w), V = a->v_air_n;
    const double ca = uw > 0.0 ? u / uw : 1.0, sa = uw > 0.0 ? w / uw : 0.0;
    const double sb = v / V, cb = uw / V;
    c->u[LV_CTRL_ALPHA] = full || need[0] ? atan2(w, u) : NAN;
    c->u[LV_CTRL_BETA] = full || need[1] ? asin(sb > 1.0 ? 1.0 : sb < -1.0 ? -1.0 : sb) : NAN;
    c->cs[LV_CTRL_ALPHA][0] = ca, c->cs[LV_CTRL_ALPHA][1] = sa;
    c->cs[LV_CTRL_BETA][0] = cb, c->cs[LV_CTRL_BETA][1] = sb;
    ax->xw = lv_v3_scale(a->v_air, 1.0 / V);
    ax->yw = lv_v3_add(lv_v3_scale(ax->xb, -ca * sb),
                       lv_v3_sub(lv_v3_scale(ax->yb, cb), lv_v3_scale(ax->zb, sa * sb)));
    ax->zw = lv_v3_add(lv_v3_scale(ax->xb, -sa), lv_v3_scale(ax->zb, ca));
    if (!full) { /* the force needs the wind axes, alpha and beta; mu is an output only */
        c->u[LV_CTRL_MU] = NAN;
        c->cs[LV_CTRL_MU][0] = NAN, c->cs[LV_CTRL_MU][1] = NAN;
        return;
    }
    /* mu: y_w = y0 cos mu + z0 sin mu, with z0 the downward direction normal to x_w in the
     * vertical plane and y0 = z0 x x_w */
    const double dx = lv_v3_dot(k->d_ax, ax->xw);
    lv_vec3 z0 = lv_v3_sub(k->d_ax, lv_v3_scale(ax->xw, dx));
    const double zn = lv_v3_norm(z0);
    if (zn > 1e-9)
        z0 = lv_v3_scale(z0, 1.0 / zn);
    else
        z0 = lv_v3_scale(lv_flight_from_ned(k, cos(chi0), sin(chi0), 0.0), -dx);
    const lv_vec3 y0 = lv_v3_cross(z0, ax->xw);
    const double cm = lv_v3_dot(ax->yw, y0), sm = lv_v3_dot(ax->yw, z0);
    c->u[LV_CTRL_MU] = atan2(sm, cm);
    const double mn = sqrt(cm * cm + sm * sm);
    c->cs[LV_CTRL_MU][0] = mn > 0.0 ? cm / mn : 1.0;
    c->cs[LV_CTRL_MU][1] = mn > 0.0 ? sm / mn : 0.0;
}

/* Aerodynamic angles given: the axes as lv_flight_axes_eval makes them. */
static void aero_angles(lv_guid_rt *rt, const lv_flight_kin *k, const lv_flight_air *a,
                        const double ang[3], double fpa0, double chi0, lv_flight_controls *c,
                        lv_flight_axes *ax)
{
    trig3(rt, ang);
    for (int i = 0; i < 3; i++) {
        c->u[i] = ang[i];
        c->cs[i][0] = rt->cs[i][0];
        c->cs[i][1] = rt->cs[i][1];
    }
    lv_flight_axes_eval(k, a, c, fpa0, chi0, ax);
}

/* The frame an attitude is measured in, ECEF components: local NED, or the frozen one. */
static void frame_axes(const lv_guid_rt *rt, const lv_flight_kin *k, lv_att_frame fr,
                       lv_vec3 f[3])
{
    if (fr == LV_FRAME_INERTIAL) {
        for (int i = 0; i < 3; i++) /* ECI -> ECEF: R3(theta) */
            f[i] = lv_v3(k->c_th * rt->f0[i].x + k->s_th * rt->f0[i].y,
                         -k->s_th * rt->f0[i].x + k->c_th * rt->f0[i].y, rt->f0[i].z);
    } else {
        f[0] = k->n_ax, f[1] = k->e_ax, f[2] = k->d_ax;
    }
}

/* Direction of the target over the local (geodetic) horizon: cos and sin of its bearing
 * (from north to east) without trigonometry, from the chord to the target point projected on
 * the horizontal plane (on a sphere: the great circle's initial direction); (1, 0) at the
 * target itself. */
static void bearing_cs(const lv_guid *g, const lv_flight_kin *k, double cs[2])
{
    const lv_vec3 d = lv_v3_sub(g->target_r, k->r_ecef);
    const double hn = lv_v3_dot(d, k->n_ax), he = lv_v3_dot(d, k->e_ax);
    const double n = sqrt(hn * hn + he * he);
    cs[0] = n > 1e-3 ? hn / n : 1.0; /* within 1 mm of the target's vertical: north */
    cs[1] = n > 1e-3 ? he / n : 0.0;
}

int lv_guid_attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                     const lv_flight_air *a, double throttle, double fpa0, double chi0, int full,
                     lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    const lv_steering *s = &g->s;
    const double tau = t - rt->t0;
    const int need[2] = {g->need_alpha, g->need_beta};
    c->u[LV_CTRL_THROTTLE] = throttle;
    lv_vec3 f[3];
    switch (s->law) {
    case LV_STEER_INPUTS: /* not a law of this module: the constants as aerodynamic angles */
        aero_angles(rt, k, a, s->angle, fpa0, chi0, c, ax);
        return 0;
    case LV_STEER_ATTITUDE: {
        double ang[3] = {s->angle[0], s->angle[1], s->angle[2]};
        if (s->table != NULL) {
            double x = t;
            switch (g->axis) {
            case LV_GAXIS_TIME: x = t; break;
            case LV_GAXIS_ALTITUDE: x = k->h; break;
            case LV_GAXIS_SPEED: x = lv_v3_norm(k->v_rel); break;
            case LV_GAXIS_MACH: x = a->mach; break;
            }
            if (lv_table_eval1(s->table, &rt->cur, x, rt->buf, err) != LV_OK) {
                if (err)
                    lv_fail_prefix(err, LV_ERR_INPUT, "guidance 'attitude'");
                return 1;
            }
            for (int i = 0; i < 3; i++)
                if (g->k[i] >= 0)
                    ang[i] = rt->buf[g->k[i]];
            if (g->k[3] >= 0)
                c->u[LV_CTRL_THROTTLE] = rt->buf[g->k[3]];
        }
        if (s->frame == LV_FRAME_AERO) {
            aero_angles(rt, k, a, ang, fpa0, chi0, c, ax);
            return 0;
        }
        trig3(rt, ang);
        frame_axes(rt, k, s->frame, f);
        body_from_euler(f, (const double(*)[2])rt->cs, ax);
        wind_from_body(k, a, chi0, full, need, c, ax);
        return 0;
    }
    case LV_STEER_GRAVITY_TURN: {
        if (tau >= s->rise_time + s->kick_time) { /* zero angle of attack; at rest (no
                                                      velocity to follow yet): straight up */
            static const double zero[3] = {0.0, 0.0, 0.0};
            aero_angles(rt, k, a, zero, 0.5 * LV_PI, s->heading, c, ax);
            return 0;
        }
        double pitch = 0.5 * LV_PI;
        if (tau > s->rise_time)
            pitch -= s->kick * (tau - s->rise_time) / s->kick_time;
        const double ang[3] = {pitch, s->heading, 0.0};
        trig3(rt, ang);
        frame_axes(rt, k, LV_FRAME_LOCAL, f);
        body_from_euler(f, (const double(*)[2])rt->cs, ax);
        wind_from_body(k, a, chi0, full, need, c, ax);
        return 0;
    }
    case LV_STEER_TANGENT: {
        /* cos and sin of theta = atan2(a + b tau, c + d tau) without trigonometry */
        const double num = s->a + s->b * tau, den = s->c + s->d * tau;
        const double nn = sqrt(num * num + den * den);
        const double cs[3][2] = {{nn > 0.0 ? den / nn : 1.0, nn > 0.0 ? num / nn : 0.0},
                                 {g->cs_heading[0], g->cs_heading[1]},
                                 {1.0, 0.0}};
        frame_axes(rt, k, s->frame, f);
        body_from_euler(f, cs, ax);
        wind_from_body(k, a, chi0, full, need, c, ax);
        return 0;
    }
    case LV_STEER_HEADING: {
        double alpha = s->alpha;
        if (s->alpha_table != NULL) {
            if (lv_table_eval1(s->alpha_table, &rt->alpha_cur, a->mach, rt->buf, err) != LV_OK) {
                if (err)
                    lv_fail_prefix(err, LV_ERR_INPUT, "guidance 'heading'");
                return 1;
            }
            alpha = rt->buf[g->k[0]];
        }
        /* the heading error from the two directions' cross and dot products */
        double b[2];
        bearing_cs(g, k, b);
        const double vn = lv_v3_dot(a->v_air, k->n_ax), ve = lv_v3_dot(a->v_air, k->e_ax);
        double mu = s->gain * atan2(vn * b[1] - ve * b[0], vn * b[0] + ve * b[1]);
        mu = mu > s->bank_max ? s->bank_max : mu < -s->bank_max ? -s->bank_max : mu;
        const double ang[3] = {alpha, 0.0, mu};
        aero_angles(rt, k, a, ang, fpa0, chi0, c, ax);
        return 0;
    }
    case LV_STEER_RETROGRADE: {
        static const double back[3] = {LV_PI, 0.0, 0.0};
        aero_angles(rt, k, a, back, fpa0, chi0, c, ax);
        return 0;
    }
    case LV_STEER_BOOSTBACK: {
        double b[2];
        bearing_cs(g, k, b);
        const double cs[3][2] = {{g->cs_pitch[0], g->cs_pitch[1]}, {b[0], b[1]}, {1.0, 0.0}};
        frame_axes(rt, k, LV_FRAME_LOCAL, f);
        body_from_euler(f, cs, ax);
        wind_from_body(k, a, chi0, full, need, c, ax);
        return 0;
    }
    }
    return 1;
}

double lv_guid_alpha_limited(const lv_guid *g, double alpha, double lift, double mass, double q)
{
    if (g->s.law != LV_STEER_HEADING || !(g->s.n_max > 0.0) || !(mass > 0.0))
        return alpha;
    return lv_guid_heading_alpha(alpha, fabs(lift) / (mass * LV_G0), g->s.n_max, q,
                                 g->s.q_max);
}

double lv_guid_heading_alpha(double alpha, double n, double n_max, double q, double q_max)
{
    if (!(n_max > 0.0) || !(n > 0.0))
        return alpha;
    /* soft saturation: alpha / (1 + (n / n_max)^8)^(1/8) */
    const double x = n / n_max, x2 = x * x, x4 = x2 * x2;
    const double f = sqrt(sqrt(sqrt(1.0 + x4 * x4)));
    const double a_n = alpha / f;
    if (!(q_max > 0.0))
        return a_n;
    /* the limit yields between q_max / 2 and q_max: smoothstep s(t) = 3 t^2 - 2 t^3 */
    double t = 2.0 * q / q_max - 1.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    const double s = t * t * (3.0 - 2.0 * t);
    return a_n + s * (alpha - a_n);
}

double lv_guid_throttle(const lv_throttle_cfg *t, double c_nom, const lv_thr_in *in,
                        const lv_flight_air *a)
{
    const double slope = in->t_full + in->p_ae; /* dT/dc, N */
    if (!(slope > 0.0))
        return c_nom;
    /* acceleration relative to the planet at throttle c: a0 + c a1 */
    const lv_vec3 a0 = lv_v3_sub(in->a_nothrust, lv_v3_scale(in->xb, in->p_ae / in->mass));
    const lv_vec3 a1 = lv_v3_scale(in->xb, slope / in->mass);
    if (t->law == LV_THROTTLE_LANDING) {
        /* constant deceleration from here to the landing point: v^2 - v_td^2 = 2 a dh */
        const double dh = in->h - t->land_altitude;
        const double vd = in->v_down > 0.0 ? in->v_down : 0.0;
        const double vt = t->land_speed;
        /* at or below the landing altitude the landing is over (the phase's impact end is
         * there): no vertical acceleration, so that the touchdown row shows no spike */
        const double a_req = dh > 0.0 ? (vd * vd - vt * vt) / (2.0 * dh) : 0.0;
        const double up1 = lv_v3_dot(in->up, a1);
        if (!(up1 > 0.0))
            return in->c_max;
        return (a_req - lv_v3_dot(in->up, a0)) / up1;
    }
    double c = c_nom;
    if (t->g_limit > 0.0) { /* (T(c) + F_aero . x_b) / m <= n g0 */
        const double cg = (t->g_limit * LV_G0 * in->mass - lv_v3_dot(in->f_aero, in->xb) +
                           in->p_ae) / slope;
        if (cg < c)
            c = cg;
    }
    if (t->q_max > 0.0 && a->v_air_n > V_AIR_MIN && a->rho > 0.0) {
        /* q' = rho' h' V^2 / 2 + rho V V' with V' = x_w . (a0 + c a1) <= k (q_max - q) */
        const lv_vec3 xw = lv_v3_scale(a->v_air, 1.0 / a->v_air_n);
        const double V = a->v_air_n;
        const double A = 0.5 * in->drho_dh * in->h_dot * V * V + a->rho * V * lv_v3_dot(xw, a0);
        const double B = a->rho * V * lv_v3_dot(xw, a1);
        if (B > 0.0) {
            const double cq = (t->q_gain * (t->q_max - a->q) - A) / B;
            if (cq < c)
                c = cq;
        }
    }
    return c;
}

void lv_guid_target(const lv_guid *g, const lv_flight_kin *k, double radius, double g_up,
                    double *distance, double *bearing, double *overshoot)
{
    double b[2];
    bearing_cs(g, k, b);
    *bearing = atan2(b[1], b[0]);
    if (*bearing < 0.0) /* [0, 2 pi), as the headings */
        *bearing += 2.0 * LV_PI;
    /* from the point on the ellipsoid below the vehicle (along its geodetic vertical), so that
     * a vehicle above the target is at distance 0 */
    const lv_vec3 foot = lv_v3_unit(lv_v3_add(k->r_ecef, lv_v3_scale(k->d_ax, k->h)));
    *distance =
        radius * atan2(lv_v3_norm(lv_v3_cross(foot, g->target)), lv_v3_dot(foot, g->target));
    /* vacuum ballistic flight over flat ground: t_fall from h' = v_up - g t, h(t_f) = 0 */
    const double v_up = -lv_v3_dot(k->v_rel, k->d_ax);
    const double hh = k->h > 0.0 ? k->h : 0.0;
    const double gg = g_up > 0.0 ? g_up : LV_G0;
    const double t_fall = (v_up + sqrt(v_up * v_up + 2.0 * gg * hh)) / gg;
    const double v_toward = lv_v3_dot(k->v_rel, lv_flight_from_ned(k, b[0], b[1], 0.0));
    *overshoot = v_toward * (t_fall > 0.0 ? t_fall : 0.0) - *distance;
}

void lv_guid_euler_local(const lv_flight_kin *k, const lv_flight_axes *ax, double *theta,
                         double *psi, double *phi)
{
    /* rows of C_body_ned: the body axes in NED components */
    const double x_n = lv_v3_dot(ax->xb, k->n_ax), x_e = lv_v3_dot(ax->xb, k->e_ax);
    const double x_d = lv_v3_dot(ax->xb, k->d_ax);
    const double y_d = lv_v3_dot(ax->yb, k->d_ax), z_d = lv_v3_dot(ax->zb, k->d_ax);
    *theta = -asin(x_d > 1.0 ? 1.0 : x_d < -1.0 ? -1.0 : x_d);
    if (x_n * x_n + x_e * x_e > 1e-18) {
        *psi = atan2(x_e, x_n);
        *phi = atan2(y_d, z_d);
    } else { /* body x vertical (gimbal lock): psi and phi are one rotation; phi = 0, so that
                body y = (-sin psi, cos psi, 0) gives psi */
        *psi = atan2(-lv_v3_dot(ax->yb, k->n_ax), lv_v3_dot(ax->yb, k->e_ax));
        *phi = 0.0;
    }
    if (*psi < 0.0) /* [0, 2 pi), as the headings */
        *psi += 2.0 * LV_PI;
}

int lv_guid_reads_atmosphere(const lv_guid *g)
{
    return (g->s.law == LV_STEER_ATTITUDE && g->axis == LV_GAXIS_MACH) ||
           g->s.law == LV_STEER_HEADING;
}

/* ---- a flight model's time events -------------------------------------------------------- */

double lv_flight_next_time_event(const lv_table *inputs, const lv_engine *eng, size_t n_eng,
                                 const lv_guid *g, const lv_guid_rt *rt, double t)
{
    double tn = inputs != NULL ? lv_table_next_breakpoint(inputs, 0, t) : INFINITY;
    for (size_t i = 0; i < n_eng; i++)
        if (eng[i].table != NULL)
            tn = fmin(tn, lv_table_next_breakpoint(eng[i].table, 0, t));
    return g != NULL ? fmin(tn, lv_guid_next_time_event(g, rt, t)) : tn;
}

/* 1 if table `tab` has a breakpoint at exactly t on its first axis (time). */
static int breakpoint_at(const lv_table *tab, double t)
{
    size_t n = 0;
    const double *b = tab != NULL ? lv_table_breakpoints(tab, 0, &n) : NULL;
    for (size_t i = 0; b != NULL && i < n; i++)
        if (b[i] == t)
            return 1;
    return 0;
}

const char *lv_flight_time_event_label(const lv_table *inputs, const lv_engine *eng,
                                       size_t n_eng, const lv_guid *g, const lv_guid_rt *rt,
                                       double t, char *buf, size_t cap)
{
    size_t len = 0;
    buf[0] = '\0';
    if (breakpoint_at(inputs, t))
        len += (size_t)snprintf(buf, cap, "inputs table '%.40s' breakpoint", lv_table_name(inputs));
    const char *gl = g != NULL ? lv_guid_time_event_label(g, rt, t) : NULL;
    if (gl != NULL && len < cap)
        len += (size_t)snprintf(buf + len, cap - len, "%s%s", len ? "; " : "", gl);
    for (size_t i = 0; i < n_eng && len < cap; i++)
        if (breakpoint_at(eng[i].table, t))
            len += (size_t)snprintf(buf + len, cap - len, "%sengine '%.24s' table breakpoint",
                                    len ? "; " : "", eng[i].name);
    if (len > 0 && len < cap)
        snprintf(buf + len, cap - len, " t = %.9g s", t);
    return buf;
}
