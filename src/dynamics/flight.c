/* flight.c - the pieces of a flight model's right-hand side (flight.h): kinematics over the
 * rotating ellipsoid, flight condition, controls, axes, engines and aerodynamics, and the
 * translational equations of motion. Stevens, Lewis & Johnson, Aircraft Control and
 * Simulation, 3rd ed., sec. 1.6 (rotating frames) and 2.3 (wind and body axes). */
#include "dynamics/flight.h"

#include <math.h>
#include <stdlib.h>

#include "core/status.h"
#include "lvsim/lv_wind.h"

#define VERTICAL_TOL 1e-9 /* sin of the angle from the vertical below which chi is undefined */

void lv_flight_world_init(lv_flight_world *w)
{
    w->e2 = lv_planet_e2(&w->planet);
    w->b = lv_planet_b(&w->planet);
}

lv_status lv_flight_world_setup(lv_flight_world *w, const char *model, const lv_planet *planet,
                                const lv_gravity *gravity, const lv_atmo *atmo, lv_wind_fn wind,
                                void *wind_user, double **grav_ws, double *gm, lv_err *err)
{
    lv_status st = lv_planet_check(planet, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "%s", model);
    w->planet = *planet;
    lv_flight_world_init(w);
    if (gravity == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: no gravity model (gravity is NULL)", model);
    w->grav = gravity;
    if (gm != NULL) {
        lv_gravity_info gi;
        lv_gravity_info_get(gravity, &gi);
        *gm = gi.gm;
    }
    const size_t nws = lv_gravity_ws_size(gravity);
    *grav_ws = malloc((nws > 0 ? nws : 1) * sizeof **grav_ws);
    if (*grav_ws == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    if (atmo != NULL) {
        w->atmo_model = lv_atmo_model_of(atmo);
        w->atmo_par = lv_atmo_par(atmo);
    }
    w->wind = wind;
    w->wind_user = wind_user;
    w->wind_latlon = wind != NULL && wind != lv_wind_fn_table;
    return LV_OK;
}

/* ---- 1. kinematics ------------------------------------------------------------------ */

void lv_flight_to_ecef(const lv_flight_world *w, double t, const double r_eci[3],
                       const double v_eci[3], lv_flight_kin *k)
{
    const double th = w->planet.theta0 + w->planet.omega * t, om = w->planet.omega;
    const double c = cos(th), s = sin(th);
    const double rx = r_eci[0], ry = r_eci[1], rz = r_eci[2];
    const double vx = v_eci[0] + om * ry, vy = v_eci[1] - om * rx, vz = v_eci[2];
    k->c_th = c;
    k->s_th = s;
    k->r_ecef = lv_v3(c * rx + s * ry, -s * rx + c * ry, rz);
    k->v_rel = lv_v3(c * vx + s * vy, -s * vx + c * vy, vz);
}

void lv_flight_geodetic(const lv_flight_world *w, lv_flight_kin *k, int exact, int angles)
{
    const double a = w->planet.a, b = w->b, e2 = w->e2, ep2 = e2 / (1.0 - e2);
    const double x = k->r_ecef.x, y = k->r_ecef.y, z = k->r_ecef.z;
    const double wr = sqrt(x * x + y * y);
    const double co = wr > 0.0 ? x / wr : 1.0, so = wr > 0.0 ? y / wr : 0.0;
    const double hb = sqrt(b * wr * b * wr + a * z * a * z);
    double cl, sl;
    if (exact || !(hb > 0.0)) {
        const double r[3] = {x, y, z};
        lv_frames_ecef_to_geodetic(&w->planet, r, &k->lat, &k->lon, &k->h);
        cl = cos(k->lat);
        sl = sin(k->lat);
    } else {
        const double cb = b * wr / hb, sb = a * z / hb; /* parametric latitude */
        const double num = z + ep2 * b * sb * sb * sb, den = wr - e2 * a * cb * cb * cb;
        const double hy = sqrt(num * num + den * den);
        sl = num / hy;
        cl = den / hy;
        k->h = wr * cl + z * sl - a * sqrt(1.0 - e2 * sl * sl); /* along the normal */
        k->lat = angles ? atan2(sl, cl) : NAN;
        k->lon = angles ? atan2(y, x) : NAN;
    }
    k->n_ax = lv_v3(-sl * co, -sl * so, cl);
    k->e_ax = lv_v3(-so, co, 0.0);
    k->d_ax = lv_v3(-cl * co, -cl * so, -sl);
}

void lv_flight_kinematics(const lv_flight_world *w, double t, const double r_eci[3],
                          const double v_eci[3], int exact, lv_flight_kin *k)
{
    lv_flight_to_ecef(w, t, r_eci, v_eci, k);
    lv_flight_geodetic(w, k, exact, w->wind_latlon); /* a wind that reads lat, lon */
}

lv_vec3 lv_flight_from_ned(const lv_flight_kin *k, double n, double e, double d)
{
    return lv_v3_add(lv_v3_add(lv_v3_scale(k->n_ax, n), lv_v3_scale(k->e_ax, e)),
                     lv_v3_scale(k->d_ax, d));
}

/* ---- 2. flight condition -------------------------------------------------------------- */

int lv_flight_air_eval(const lv_flight_world *w, double t, const lv_flight_kin *k,
                       lv_flight_air *a, lv_err *err)
{
    /* atmosphere (above its range: vacuum with the top layer's speed of sound) */
    a->rho = a->p_amb = 0.0;
    a->a_sound = 1.0;
    a->w_ned[0] = a->w_ned[1] = a->w_ned[2] = 0.0;
    if (w->atmo_model != NULL) {
        if (isnan(k->h)) {
            if (err)
                lv_fail(err, LV_ERR_INPUT, "altitude is NaN at t = %.9g s", t);
            return 1;
        }
        /* Below the atmosphere's floor: its floor values, so that a trial step there can be
         * taken and the model's domain bound (lv_domain_def) is located instead. */
        const double ha = k->h < LV_ATMO_ALT_MIN   ? LV_ATMO_ALT_MIN
                          : k->h < LV_ATMO_ALT_MAX ? k->h
                                                   : LV_ATMO_ALT_MAX;
        lv_atmo_state as;
        if (w->atmo_model->eval(w->atmo_par, ha, &as, err) != LV_OK)
            return 1;
        a->a_sound = as.a;
        if (k->h <= LV_ATMO_ALT_MAX) {
            a->rho = as.rho;
            a->p_amb = as.p;
        }
    }

    /* air-relative velocity */
    a->v_air = k->v_rel;
    if (w->wind != NULL) {
        double *w_ned = a->w_ned;
        int rc = w->wind(t, k->h, k->lat, k->lon, w_ned, w->wind_user);
        if (rc != 0) {
            if (err)
                lv_fail(err, LV_ERR_INPUT, "wind function returned %d at t = %.9g s", rc, t);
            return rc;
        }
        a->v_air = lv_v3_sub(k->v_rel, lv_flight_from_ned(k, w_ned[0], w_ned[1], w_ned[2]));
    }
    a->v_air_n = lv_v3_norm(a->v_air);
    a->mach = a->v_air_n / a->a_sound;
    a->q = 0.5 * a->rho * a->v_air_n * a->v_air_n;
    return 0;
}

/* ---- 3. controls -------------------------------------------------------------------------- */

int lv_flight_controls_eval(const double *u0, const lv_flight_schedule *sch,
                            lv_table_cursor *cur, lv_flight_trig_cache *cache, double t,
                            lv_flight_controls *c, lv_err *err)
{
    for (int i = 0; i < LV_CTRL_N; i++)
        c->u[i] = u0[i];
    if (sch->table != NULL) {
        if (lv_table_eval1(sch->table, cur, t, sch->buf, err) != LV_OK) {
            if (err)
                lv_fail_prefix(err, LV_ERR_INPUT, "inputs");
            return 1;
        }
        for (int i = 0; i < LV_CTRL_N; i++)
            if (sch->k[i] >= 0)
                c->u[i] = sch->buf[sch->k[i]];
    }
    for (int i = 0; i < 3; i++) {
        if (c->u[i] != cache->ang[i]) {
            cache->ang[i] = c->u[i];
            cache->cs[i][0] = cos(c->u[i]);
            cache->cs[i][1] = sin(c->u[i]);
        }
        c->cs[i][0] = cache->cs[i][0];
        c->cs[i][1] = cache->cs[i][1];
    }
    return 0;
}

/* ---- 4. vehicle forces -------------------------------------------------------------------- */

lv_vec3 lv_flight_down_normal(const lv_flight_kin *k, lv_vec3 xw, double v_air_n, int from_start,
                              double chi0)
{
    const double dx = lv_v3_dot(k->d_ax, xw);
    const lv_vec3 z = lv_v3_sub(k->d_ax, lv_v3_scale(xw, dx));
    const double zn = lv_v3_norm(z); /* sin of the angle from the vertical */
    if (from_start ? zn > VERTICAL_TOL : v_air_n * zn >= LV_FLIGHT_V_GUARD)
        return lv_v3_scale(z, 1.0 / zn);
    /* the start heading, made normal to x_w: towards it going up, away from it going down */
    const lv_vec3 h = lv_v3_scale(lv_flight_from_ned(k, cos(chi0), sin(chi0), 0.0),
                                  dx <= 0.0 ? 1.0 : -1.0);
    const lv_vec3 hz = lv_v3_sub(h, lv_v3_scale(xw, lv_v3_dot(h, xw)));
    const double hn = lv_v3_norm(hz);
    /* hn < 0.5 only for an x_w within 30 deg of the horizontal at barely the guard speed,
     * where the vertical plane through x_w is well defined (zn > 0.5) */
    return hn >= 0.5 || !(zn > 0.0) ? lv_v3_scale(hz, 1.0 / hn) : lv_v3_scale(z, 1.0 / zn);
}

void lv_flight_axes_eval(const lv_flight_kin *k, const lv_flight_air *a,
                         const lv_flight_controls *c, double fpa0, double chi0,
                         lv_flight_axes *ax)
{
    const int from_start = !(a->v_air_n >= LV_FLIGHT_V_GUARD);
    if (!from_start) {
        ax->xw = lv_v3_scale(a->v_air, 1.0 / a->v_air_n);
    } else {
        const double cg = cos(fpa0), sg = sin(fpa0);
        ax->xw = lv_flight_from_ned(k, cg * cos(chi0), cg * sin(chi0), -sg);
    }
    const lv_vec3 z0 = lv_flight_down_normal(k, ax->xw, a->v_air_n, from_start, chi0);
    const lv_vec3 y0 = lv_v3_cross(z0, ax->xw);
    const double cm = c->cs[LV_CTRL_MU][0], sm = c->cs[LV_CTRL_MU][1];
    ax->yw = lv_v3_add(lv_v3_scale(y0, cm), lv_v3_scale(z0, sm));
    ax->zw = lv_v3_sub(lv_v3_scale(z0, cm), lv_v3_scale(y0, sm));

    /* C_body_wind = R2(alpha) R3(-beta) */
    const double ca = c->cs[LV_CTRL_ALPHA][0], sa = c->cs[LV_CTRL_ALPHA][1];
    const double cb = c->cs[LV_CTRL_BETA][0], sb = c->cs[LV_CTRL_BETA][1];
    ax->xb = lv_v3_add(lv_v3_scale(ax->xw, ca * cb),
                       lv_v3_sub(lv_v3_scale(ax->yw, -ca * sb), lv_v3_scale(ax->zw, sa)));
    ax->yb = lv_v3_add(lv_v3_scale(ax->xw, sb), lv_v3_scale(ax->yw, cb));
    ax->zb = lv_v3_add(lv_v3_scale(ax->xw, sa * cb),
                       lv_v3_add(lv_v3_scale(ax->yw, -sa * sb), lv_v3_scale(ax->zw, ca)));
}

int lv_flight_thrust(lv_engine *eng, size_t n_eng, int engines_on, double t,
                     const lv_flight_controls *c, const lv_flight_air *a, double *buf,
                     double *thrust, double *mdot, lv_err *err)
{
    *thrust = *mdot = 0.0;
    if (!engines_on)
        return 0;
    for (size_t i = 0; i < n_eng; i++) {
        double f, md;
        if (lv_engine_eval(&eng[i], t, c->u[LV_CTRL_THROTTLE], a->p_amb, buf, &f, &md, err) !=
            LV_OK)
            return 1;
        *thrust += f;
        *mdot += md;
    }
    return 0;
}

int lv_flight_aero(lv_aero *aero, const lv_flight_kin *k, const lv_flight_air *a,
                   const lv_flight_controls *c, const lv_flight_axes *ax, double coef[3],
                   lv_vec3 *f_aero, lv_err *err)
{
    coef[0] = coef[1] = coef[2] = 0.0;
    *f_aero = lv_v3(0.0, 0.0, 0.0);
    if (aero == NULL || !(a->q > 0.0)) /* only where there is air to push */
        return 0;
    if (lv_aero_coefs(aero, a->mach, c->u[LV_CTRL_ALPHA], c->u[LV_CTRL_BETA], k->h, coef, err) !=
        LV_OK)
        return 1;
    double fw[3];
    lv_aero_force_wind(aero, coef, a->q * aero->s_ref, c->cs[LV_CTRL_ALPHA][0],
                       c->cs[LV_CTRL_ALPHA][1], c->cs[LV_CTRL_BETA][0], c->cs[LV_CTRL_BETA][1],
                       fw);
    *f_aero = lv_v3_add(lv_v3_add(lv_v3_scale(ax->xw, fw[0]), lv_v3_scale(ax->yw, fw[1])),
                        lv_v3_scale(ax->zw, fw[2]));
    return 0;
}

/* ---- 5. equations of motion ---------------------------------------------------------------- */

lv_vec3 lv_flight_gravity(const lv_flight_world *w, double *ws, const lv_flight_kin *k)
{
    double r[3] = {k->r_ecef.x, k->r_ecef.y, k->r_ecef.z}, g[3];
    lv_gravity_eval(w->grav, ws, r, g, NULL);
    return lv_v3(g[0], g[1], g[2]);
}

lv_vec3 lv_flight_accel_eci_g(const lv_flight_kin *k, lv_vec3 g_ecef, lv_vec3 f, double m)
{
    const lv_vec3 a = lv_v3_add(g_ecef, lv_v3_scale(f, 1.0 / m));
    return lv_v3(k->c_th * a.x - k->s_th * a.y, k->s_th * a.x + k->c_th * a.y, a.z);
}

lv_vec3 lv_flight_accel_eci(const lv_flight_world *w, double *ws, const lv_flight_kin *k,
                            lv_vec3 f, double m, lv_vec3 *g_ecef)
{
    *g_ecef = lv_flight_gravity(w, ws, k);
    return lv_flight_accel_eci_g(k, *g_ecef, f, m);
}

lv_vec3 lv_flight_frame_accel(const lv_flight_world *w, const lv_flight_kin *k)
{
    const double om = w->planet.omega;
    /* -2 w x v_rel - w x (w x r) with w = (0, 0, om) */
    return lv_v3(2.0 * om * k->v_rel.y + om * om * k->r_ecef.x,
                 -2.0 * om * k->v_rel.x + om * om * k->r_ecef.y, 0.0);
}

double lv_flight_drho_dh(const lv_flight_world *w, double h, double rho)
{
    const double dh = 0.01; /* m: truncation dh / (2 H) ~ 1e-6, rounding ~ 1e-10 (relative) */
    if (w->atmo_model == NULL || h < LV_ATMO_ALT_MIN || h + dh > LV_ATMO_ALT_MAX)
        return 0.0;
    lv_atmo_state s1;
    if (w->atmo_model->eval(w->atmo_par, h + dh, &s1, NULL) != LV_OK)
        return 0.0;
    return (s1.rho - rho) / dh;
}
