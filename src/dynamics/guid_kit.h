/* guid_kit.h - what a law's file is written with (not exported): the geometry every steering
 * law composes its attitude from (static inline, so that each law's attitude compiles into one
 * function as the hot path wants), its parameters' access and the key tables' ranges.
 *
 * Attitude frames: the body axes from 3-2-1 Euler angles relative to a NED frame,
 * C_body_ned = R1(phi) R2(theta) R3(psi) (Stevens, Lewis & Johnson, Aircraft Control and
 * Simulation, 3rd ed., eq. 1.3-20); the aerodynamic angles of the air-relative velocity in
 * body axes, alpha = atan2(w, u), beta = asin(v / V) (ibid. eq. 2.3-6).
 */
#ifndef LV_DYNAMICS_GUID_KIT_H
#define LV_DYNAMICS_GUID_KIT_H

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "core/status.h"
#include "dynamics/guidance.h"
#include "lvsim/lv_units.h"

#define LV_GUID_V_AIR_MIN 1e-6 /* m/s, as flight.c: below, no aerodynamic angles */

/* A law's parameters (struct T) in g->par / t->par. */
#define LV_GUID_PAR(T, g) ((const T *)(const void *)(g)->par.d)
#define LV_GUID_PAR_W(T, g) ((T *)(void *)(g)->par.d)

/* Ranges of the key tables (lo, hi; the mission file's angle kinds, docs/mission-format.md,
 * "Angle ranges"): .lo = LV_KR_LAT_LO etc. */
#define LV_KR_LAT_LO (-0.5 * LV_PI) /* [-90, 90] deg: latitudes, pitch, alpha */
#define LV_KR_LAT_HI (0.5 * LV_PI)
#define LV_KR_TURN_LO (-2.0 * LV_PI) /* [-360, 360] deg: longitudes, headings, roll, bank */
#define LV_KR_TURN_HI (2.0 * LV_PI)
#define LV_KR_AERO_LO (-LV_PI) /* [-180, 180] deg: sideslip */
#define LV_KR_AERO_HI LV_PI

/* cos, sin of the three angles, cached while they do not change. */
static inline void lv_guid_trig3(lv_guid_rt *rt, const double ang[3])
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
static inline void lv_guid_body_from_euler(const lv_vec3 f[3], const double cs[3][2],
                                           lv_flight_axes *ax)
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
static inline void lv_guid_wind_from_body(const lv_flight_kin *k, const lv_flight_air *a,
                                          double chi0, int full, const int need[2],
                                          lv_flight_controls *c, lv_flight_axes *ax)
{
    if (!(a->v_air_n > LV_GUID_V_AIR_MIN)) {
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
    const lv_vec3 z0 = lv_flight_down_normal(k, ax->xw, V, 0, chi0);
    const lv_vec3 y0 = lv_v3_cross(z0, ax->xw);
    const double cm = lv_v3_dot(ax->yw, y0), sm = lv_v3_dot(ax->yw, z0);
    c->u[LV_CTRL_MU] = atan2(sm, cm);
    const double mn = sqrt(cm * cm + sm * sm);
    c->cs[LV_CTRL_MU][0] = mn > 0.0 ? cm / mn : 1.0;
    c->cs[LV_CTRL_MU][1] = mn > 0.0 ? sm / mn : 0.0;
}

/* Aerodynamic angles given: the axes as lv_flight_axes_eval makes them. */
static inline void lv_guid_aero_angles(lv_guid_rt *rt, const lv_flight_kin *k,
                                       const lv_flight_air *a, const double ang[3], double fpa0,
                                       double chi0, lv_flight_controls *c, lv_flight_axes *ax)
{
    lv_guid_trig3(rt, ang);
    for (int i = 0; i < 3; i++) {
        c->u[i] = ang[i];
        c->cs[i][0] = rt->cs[i][0];
        c->cs[i][1] = rt->cs[i][1];
    }
    lv_flight_axes_eval(k, a, c, fpa0, chi0, ax);
}

/* The frame an attitude is measured in, ECEF components: local NED, or the frozen one. */
static inline void lv_guid_frame_axes(const lv_guid_rt *rt, const lv_flight_kin *k,
                                      lv_att_frame fr, lv_vec3 f[3])
{
    if (fr == LV_FRAME_INERTIAL) {
        for (int i = 0; i < 3; i++) /* ECI -> ECEF: R3(theta) */
            f[i] = lv_v3(k->c_th * rt->f0[i].x + k->s_th * rt->f0[i].y,
                         -k->s_th * rt->f0[i].x + k->c_th * rt->f0[i].y, rt->f0[i].z);
    } else {
        f[0] = k->n_ax, f[1] = k->e_ax, f[2] = k->d_ax;
    }
}

/* The body axes of Euler angles with cosines and sines cs relative to frame fr, and the
 * aerodynamic angles that result. */
static inline void lv_guid_euler_attitude(const lv_guid *g, const lv_guid_rt *rt,
                                          const lv_flight_kin *k, const lv_flight_air *a,
                                          lv_att_frame fr, const double cs[3][2], double chi0,
                                          int full, lv_flight_controls *c, lv_flight_axes *ax)
{
    lv_vec3 f[3];
    const int need[2] = {g->need_alpha, g->need_beta};
    lv_guid_frame_axes(rt, k, fr, f);
    lv_guid_body_from_euler(f, cs, ax);
    lv_guid_wind_from_body(k, a, chi0, full, need, c, ax);
}

/* Direction of the target over the local (geodetic) horizon: cos and sin of its bearing
 * (from north to east) without trigonometry, from the chord to the target point projected on
 * the horizontal plane (on a sphere: the great circle's initial direction); (1, 0) at the
 * target itself. */
static inline void lv_guid_bearing_cs(const lv_guid *g, const lv_flight_kin *k, double cs[2])
{
    const lv_vec3 d = lv_v3_sub(g->target_r, k->r_ecef);
    const double hn = lv_v3_dot(d, k->n_ax), he = lv_v3_dot(d, k->e_ax);
    const double n = sqrt(hn * hn + he * he);
    cs[0] = n > 1e-3 ? hn / n : 1.0; /* within 1 mm of the target's vertical: north */
    cs[1] = n > 1e-3 ? he / n : 0.0;
}

/* A law's table fits lv_guid_rt.buf: at most 16 outputs. */
static inline lv_status lv_guid_table_fits(const lv_table *t, lv_err *err)
{
    if (lv_table_n_out(t) > 16)
        return lv_fail(err, LV_ERR_INPUT, "table '%s' has %zu outputs (at most 16)",
                       lv_table_name(t), lv_table_n_out(t));
    return LV_OK;
}

/* The law's table at `offset` of its parameters. */
static inline const lv_table *lv_guid_table_at(const void *par, size_t offset)
{
    const lv_table *t;
    memcpy(&t, (const char *)par + offset, sizeof t);
    return t;
}

/* A throttle law's acceleration relative to the planet at throttle c: a0 + c a1 [m/s^2, ECEF],
 * slope = dT/dc = t_full + p_ae > 0. */
static inline void lv_guid_thr_accel(const lv_thr_in *in, double slope, lv_vec3 *a0,
                                     lv_vec3 *a1)
{
    *a0 = lv_v3_sub(in->a_nothrust, lv_v3_scale(in->xb, in->p_ae / in->mass));
    *a1 = lv_v3_scale(in->xb, slope / in->mass);
}

/* The attitude frames' words (the key "frame"). */
extern const char *const lv_guid_frame_words[];

#endif
