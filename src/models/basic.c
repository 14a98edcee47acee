/* basic.c - reference models with closed-form solutions (see lv_models.h).
 * Equations: Tsiolkovsky ascent in uniform gravity, free fall, harmonic
 * oscillator, Kepler two-body problem. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "lvsim/lv_models.h"

/* ---- vertical ascent ----------------------------------------------------------- */

enum { P_ASC_THRUST, P_ASC_MDOT, P_ASC_G, P_ASC_M_FINAL, P_ASC_H0, P_ASC_V0, P_ASC_M0,
       P_ASC_STOP_APOGEE, P_ASC_N };

static const lv_var asc_states[LV_ASC_N] = {
    {"h", "m", "Altitude above the launch point", 0.0, 1e4},
    {"v", "m/s", "Vertical velocity, positive up", 0.0, 1e3},
    {"m", "kg", "Vehicle mass", 1000.0, 1e3},
};
static const lv_var asc_params[P_ASC_N] = {
    {"thrust", "N", "Thrust while the engine burns", 30000.0, 0},
    {"mdot", "kg/s", "Propellant mass flow while burning (> 0)", 10.0, 0},
    {"g", "m/s2", "Uniform gravity acceleration", 9.81, 0},
    {"m_final", "kg", "Mass at burnout (dry mass)", 400.0, 0},
    {"h0", "m", "Initial altitude", 0.0, 0},
    {"v0", "m/s", "Initial velocity", 0.0, 0},
    {"m0", "kg", "Initial mass", 1000.0, 0},
    {"stop_at_apogee", "1", "1: end the run at apogee; 0: continue to impact", 0.0, 0},
};
static const lv_var asc_outputs[] = {
    {"F", "N", "Thrust acting now", 0, 0},
    {"engine_on", "1", "1 while the engine burns", 0, 0},
};
static const lv_event_def asc_events[LV_ASC_EV_N] = {
    {"burnout", "Propellant exhausted: m falls through m_final", LV_DIR_FALLING, 0},
    {"apogee", "Vertical velocity falls through zero", LV_DIR_FALLING, 0},
    {"impact", "Altitude falls through zero", LV_DIR_FALLING, 0},
};

/* dh/dt = v; dv/dt = F/m - g; dm/dt = -mdot (engine on), as in the paper's
 * variable-mass point: dm = mdot. */
static int asc_rhs(double t, const double *x, const double *p, double *xdot, void *inst)
{
    (void)t;
    const lv_basic_inst *s = inst;
    const double m = x[LV_ASC_M];
    if (!(m > 0.0))
        return 1;
    const double F = s->engine_on ? p[P_ASC_THRUST] : 0.0;
    xdot[LV_ASC_H] = x[LV_ASC_V];
    xdot[LV_ASC_V] = F / m - p[P_ASC_G];
    xdot[LV_ASC_M] = s->engine_on ? -p[P_ASC_MDOT] : 0.0;
    return 0;
}

static const char *basic_why(const void *inst)
{
    return inst != NULL ? ((const lv_basic_inst *)inst)->why : NULL;
}

static int asc_start(const double *p, double *x, void *inst)
{
    lv_basic_inst *s = inst;
    s->why = NULL;
    if (!(p[P_ASC_M_FINAL] > 0.0) || !(p[P_ASC_MDOT] > 0.0) || !(p[P_ASC_THRUST] >= 0.0)) {
        s->why = "m_final and mdot must be > 0 and thrust >= 0";
        return 1;
    }
    x[LV_ASC_H] = p[P_ASC_H0];
    x[LV_ASC_V] = p[P_ASC_V0];
    x[LV_ASC_M] = p[P_ASC_M0];
    return 0;
}

static int asc_init(double t0, const double *x, const double *p, void *inst)
{
    (void)t0;
    lv_basic_inst *s = inst;
    s->why = NULL;
    if (!(x[LV_ASC_M] > 0.0)) {
        s->why = "the mass m must be > 0 kg";
        return 1;
    }
    s->engine_on = x[LV_ASC_M] > p[P_ASC_M_FINAL];
    return 0;
}

static int asc_g(double t, const double *x, const double *p, double *g, void *inst)
{
    (void)t;
    const lv_basic_inst *s = inst;
    /* Disarmed after burnout: a constant never crosses again. */
    g[LV_ASC_EV_BURNOUT] = s->engine_on ? x[LV_ASC_M] - p[P_ASC_M_FINAL] : 1.0;
    g[LV_ASC_EV_APOGEE] = x[LV_ASC_V];
    g[LV_ASC_EV_IMPACT] = x[LV_ASC_H];
    return 0;
}

static lv_event_action asc_event(double t, double *x, const double *p, const int *fired,
                                 void *inst)
{
    (void)t;
    (void)x;
    lv_basic_inst *s = inst;
    if (fired[LV_ASC_EV_IMPACT])
        return LV_EVENT_STOP;
    if (fired[LV_ASC_EV_APOGEE] && p[P_ASC_STOP_APOGEE] > 0.5)
        return LV_EVENT_STOP;
    if (fired[LV_ASC_EV_BURNOUT]) {
        s->engine_on = 0;
        return LV_EVENT_RESTART;
    }
    return LV_EVENT_CONTINUE;
}

/* The domain of both 1-D models: above the ground, where the impact is (h = 0). A start below
 * it is refused by lv_simulate with the value and the bound; the run never gets there, since
 * the impact (the same function) ends it first. */
static const lv_domain_def ground_domain[] = {
    {"h", "m", 0.0,
     "the body is under the ground, where its impact (h falls through 0) ends the run: start "
     "at h >= 0",
     0},
};

static int ground_q(double t, const double *x, const double *p, double *q, void *inst)
{
    (void)t;
    (void)p;
    (void)inst;
    q[0] = x[0]; /* h: state 0 of both */
    return 0;
}

static int asc_outputs_fn(double t, const double *x, const double *p, double *y, void *inst)
{
    (void)t;
    (void)x;
    const lv_basic_inst *s = inst;
    y[0] = s->engine_on ? p[P_ASC_THRUST] : 0.0;
    y[1] = s->engine_on;
    return 0;
}

const lv_model_def lv_model_vertical_ascent = {
    .name = "vertical_ascent",
    .description = "1-D rocket: constant thrust and mass flow to burnout in uniform gravity",
    .n_states = LV_ASC_N,
    .n_params = P_ASC_N,
    .n_outputs = 2,
    .n_events = LV_ASC_EV_N,
    .states = asc_states,
    .params = asc_params,
    .outputs = asc_outputs,
    .events = asc_events,
    .inst_size = sizeof(lv_basic_inst),
    .start = asc_start,
    .init = asc_init,
    .rhs = asc_rhs,
    .event_g = asc_g,
    .on_event = asc_event,
    .outputs_fn = asc_outputs_fn,
    .n_domain = 1,
    .domain = ground_domain,
    .domain_q = ground_q,
    .last_error = basic_why,
};

/* ---- free fall ------------------------------------------------------------------ */

enum { FF_H, FF_V, FF_N };
enum { P_FF_G, P_FF_H0, P_FF_V0, P_FF_N };

static const lv_var ff_states[FF_N] = {
    {"h", "m", "Height above ground", 100.0, 100.0},
    {"v", "m/s", "Vertical velocity, positive up", 0.0, 10.0},
};
static const lv_var ff_params[P_FF_N] = {
    {"g", "m/s2", "Uniform gravity acceleration", 9.81, 0},
    {"h0", "m", "Initial height", 100.0, 0},
    {"v0", "m/s", "Initial velocity", 0.0, 0},
};
static const lv_event_def ff_events[] = {
    {"impact", "Height falls through zero", LV_DIR_FALLING, 0},
};

static int ff_rhs(double t, const double *x, const double *p, double *xdot, void *inst)
{
    (void)t;
    (void)inst;
    xdot[FF_H] = x[FF_V];
    xdot[FF_V] = -p[P_FF_G];
    return 0;
}
static int ff_start(const double *p, double *x, void *inst)
{
    (void)inst;
    x[FF_H] = p[P_FF_H0];
    x[FF_V] = p[P_FF_V0];
    return 0;
}
static int ff_g(double t, const double *x, const double *p, double *g, void *inst)
{
    (void)t;
    (void)p;
    (void)inst;
    g[0] = x[FF_H];
    return 0;
}

const lv_model_def lv_model_free_fall = {
    .name = "free_fall",
    .description = "1-D free fall in uniform gravity to ground impact",
    .n_states = FF_N,
    .n_params = P_FF_N,
    .n_events = 1,
    .states = ff_states,
    .params = ff_params,
    .events = ff_events,
    .start = ff_start,
    .rhs = ff_rhs,
    .event_g = ff_g, /* no on_event: the first event ends the run */
    .n_domain = 1,
    .domain = ground_domain,
    .domain_q = ground_q,
};

/* ---- harmonic oscillator ----------------------------------------------------------- */

enum { OSC_X, OSC_V, OSC_N };
enum { P_OSC_OMEGA, P_OSC_X0, P_OSC_V0, P_OSC_N };

static const lv_var osc_states[OSC_N] = {
    {"x", "m", "Position", 1.0, 1.0},
    {"v", "m/s", "Velocity", 0.0, 1.0},
};
static const lv_var osc_params[P_OSC_N] = {
    {"omega", "rad/s", "Angular frequency", 1.0, 0},
    {"x0", "m", "Initial position", 1.0, 0},
    {"v0", "m/s", "Initial velocity", 0.0, 0},
};
static const lv_var osc_outputs[] = {
    {"energy", "m2/s2", "Specific energy (v^2 + omega^2 x^2)/2", 0, 0},
};

static int osc_rhs(double t, const double *x, const double *p, double *xdot, void *inst)
{
    (void)t;
    (void)inst;
    const double w = p[P_OSC_OMEGA];
    xdot[OSC_X] = x[OSC_V];
    xdot[OSC_V] = -w * w * x[OSC_X];
    return 0;
}
static int osc_start(const double *p, double *x, void *inst)
{
    (void)inst;
    x[OSC_X] = p[P_OSC_X0];
    x[OSC_V] = p[P_OSC_V0];
    return 0;
}
static int osc_out(double t, const double *x, const double *p, double *y, void *inst)
{
    (void)t;
    (void)inst;
    const double w = p[P_OSC_OMEGA];
    y[0] = 0.5 * (x[OSC_V] * x[OSC_V] + w * w * x[OSC_X] * x[OSC_X]);
    return 0;
}

const lv_model_def lv_model_oscillator = {
    .name = "oscillator",
    .description = "Harmonic oscillator x'' = -omega^2 x",
    .n_states = OSC_N,
    .n_params = P_OSC_N,
    .n_outputs = 1,
    .states = osc_states,
    .params = osc_params,
    .outputs = osc_outputs,
    .start = osc_start,
    .rhs = osc_rhs,
    .outputs_fn = osc_out,
};

/* ---- Kepler two-body problem ------------------------------------------------------- */

enum { P_KEP_MU, P_KEP_A, P_KEP_E, P_KEP_N };

static const lv_var kep_states[LV_KEP_N] = {
    {"rx", "m", "Position x, inertial", 0.0, 1e7}, {"ry", "m", "Position y, inertial", 0.0, 1e7},
    {"rz", "m", "Position z, inertial", 0.0, 1e7}, {"vx", "m/s", "Velocity x, inertial", 0.0, 1e4},
    {"vy", "m/s", "Velocity y, inertial", 0.0, 1e4}, {"vz", "m/s", "Velocity z, inertial", 0.0, 1e4},
};
static const lv_var kep_params[P_KEP_N] = {
    {"mu", "m3/s2", "Gravitational parameter", 3.986004418e14, 0},
    {"a", "m", "Semi-major axis of the start orbit", 7.0e6, 0},
    {"e", "1", "Eccentricity of the start orbit (start at periapsis, x-y plane)", 0.1, 0},
};
static const lv_var kep_outputs[] = {
    {"energy", "m2/s2", "Specific orbital energy v^2/2 - mu/r", 0, 0},
    {"h", "m2/s", "Specific angular momentum |r x v|", 0, 0},
    {"r", "m", "Radius", 0, 0},
};
static const lv_event_def kep_events[] = {
    {"periapsis", "Radial velocity r.v rises through zero", LV_DIR_RISING, 0},
};

static int kep_rhs(double t, const double *x, const double *p, double *xdot, void *inst)
{
    (void)t;
    (void)inst;
    const double rx = x[LV_KEP_RX], ry = x[LV_KEP_RY], rz = x[LV_KEP_RZ];
    const double r2 = rx * rx + ry * ry + rz * rz;
    if (!(r2 > 0.0))
        return 1;
    const double k = -p[P_KEP_MU] / (r2 * sqrt(r2));
    xdot[LV_KEP_RX] = x[LV_KEP_VX];
    xdot[LV_KEP_RY] = x[LV_KEP_VY];
    xdot[LV_KEP_RZ] = x[LV_KEP_VZ];
    xdot[LV_KEP_VX] = k * rx;
    xdot[LV_KEP_VY] = k * ry;
    xdot[LV_KEP_VZ] = k * rz;
    return 0;
}
/* Periapsis on +x, velocity along +y: r_p = a(1-e), v_p = sqrt(mu (1+e) / (a (1-e))). */
static int kep_start(const double *p, double *x, void *inst)
{
    lv_basic_inst *s = inst;
    const double mu = p[P_KEP_MU], a = p[P_KEP_A], e = p[P_KEP_E];
    s->why = !(a > 0.0)                  ? "the semi-major axis a must be > 0 m"
             : !(e >= 0.0 && e < 1.0)    ? "the eccentricity e must be >= 0 and < 1 (an ellipse)"
             : !(mu > 0.0)               ? "mu must be > 0 m^3/s^2"
                                         : NULL;
    if (s->why != NULL)
        return 1;
    memset(x, 0, LV_KEP_N * sizeof *x);
    x[LV_KEP_RX] = a * (1.0 - e);
    x[LV_KEP_VY] = sqrt(mu * (1.0 + e) / (a * (1.0 - e)));
    return 0;
}
static int kep_g(double t, const double *x, const double *p, double *g, void *inst)
{
    (void)t;
    (void)p;
    (void)inst;
    g[0] = x[LV_KEP_RX] * x[LV_KEP_VX] + x[LV_KEP_RY] * x[LV_KEP_VY] + x[LV_KEP_RZ] * x[LV_KEP_VZ];
    return 0;
}
static lv_event_action kep_event(double t, double *x, const double *p, const int *fired,
                                 void *inst)
{
    (void)t, (void)x, (void)p, (void)fired, (void)inst;
    return LV_EVENT_CONTINUE; /* count passages, change nothing */
}
static int kep_out(double t, const double *x, const double *p, double *y, void *inst)
{
    (void)t;
    (void)inst;
    const double rx = x[LV_KEP_RX], ry = x[LV_KEP_RY], rz = x[LV_KEP_RZ];
    const double vx = x[LV_KEP_VX], vy = x[LV_KEP_VY], vz = x[LV_KEP_VZ];
    const double r = sqrt(rx * rx + ry * ry + rz * rz);
    const double hx = ry * vz - rz * vy, hy = rz * vx - rx * vz, hz = rx * vy - ry * vx;
    y[0] = 0.5 * (vx * vx + vy * vy + vz * vz) - p[P_KEP_MU] / r;
    y[1] = sqrt(hx * hx + hy * hy + hz * hz);
    y[2] = r;
    return 0;
}

const lv_model_def lv_model_kepler = {
    .name = "kepler",
    .description = "Two-body orbit, point-mass gravity, inertial Cartesian coordinates",
    .n_states = LV_KEP_N,
    .n_params = P_KEP_N,
    .n_outputs = 3,
    .n_events = 1,
    .states = kep_states,
    .params = kep_params,
    .outputs = kep_outputs,
    .events = kep_events,
    .start = kep_start,
    .rhs = kep_rhs,
    .event_g = kep_g,
    .on_event = kep_event,
    .outputs_fn = kep_out,
    .inst_size = sizeof(lv_basic_inst),
    .last_error = basic_why,
};

/* ---- registry ----------------------------------------------------------------------- */

static const lv_model_def *const all_models[] = {&lv_model_vertical_ascent, &lv_model_free_fall,
                                                 &lv_model_oscillator, &lv_model_kepler, NULL};

const lv_model_def *const *lv_models_all(void) { return all_models; }

const lv_model_def *lv_models_find(const char *name)
{
    for (size_t i = 0; all_models[i] != NULL; i++)
        if (strcmp(all_models[i]->name, name) == 0)
            return all_models[i];
    return NULL;
}
