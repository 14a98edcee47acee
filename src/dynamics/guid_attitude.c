/* guid_attitude.c - steering law `attitude`: constant angles in `frame` (alpha, beta, mu in
 * the aerodynamic frame; pitch, heading, roll in the local or inertial one), or from `table`
 * over time, altitude, speed or Mach (axis named "time"/"t" [s, mission time],
 * "altitude"/"h" [m], "speed"/"v_rel" [m/s], "mach"), outputs named "alpha", "beta", "mu"
 * (aero) or "pitch", "heading", "roll" (local, inertial) in rad, and "throttle"; an angle the
 * table does not give keeps its constant. A time table's breakpoints are time events.
 * Frames: Stevens, Lewis & Johnson, Aircraft Control and Simulation, 3rd ed., sec. 1.3, 2.3
 * (docs/guidance.md).
 */
#include "core/table_unit.h"
#include "dynamics/guid_kit.h"

typedef struct attitude_par {
    int frame;                  /* lv_att_frame */
    double pitch, heading, roll; /* rad, local and inertial frames */
    double alpha, beta, mu;     /* rad, aerodynamic frame */
    const lv_table *table;      /* or NULL */
    /* init: */
    double angle[3];            /* the frame's three angles */
    lv_gaxis axis;              /* the table's axis */
    int k[4];                   /* the table's output of each angle and the throttle, -1: none */
} attitude_par;

#define LI ((1u << LV_FRAME_LOCAL) | (1u << LV_FRAME_INERTIAL))
#define AE (1u << LV_FRAME_AERO)
/* pitch (and alpha) within +-90 deg, sideslip +-180 deg, heading, roll and bank a turn either
 * way */
static const lv_law_key keys[] = {
    {.name = "frame", .type = LV_KEY_CHOICE, .unit = "", .dflt = LV_FRAME_LOCAL,
     .choices = lv_guid_frame_words, .offset = offsetof(attitude_par, frame),
     .description = "the frame of the angles: aero, local or inertial (frozen at the start)"},
    {.name = "pitch", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_LAT_LO,
     .hi = LV_KR_LAT_HI, .dflt = 0.0, .flags = LV_KEY_ANGLE, .frames = LI,
     .offset = offsetof(attitude_par, pitch), .description = "pitch theta (3-2-1)"},
    {.name = "heading", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_TURN_LO,
     .hi = LV_KR_TURN_HI, .dflt = 0.0, .flags = LV_KEY_ANGLE, .frames = LI,
     .offset = offsetof(attitude_par, heading), .description = "heading (yaw) psi"},
    {.name = "roll", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_TURN_LO,
     .hi = LV_KR_TURN_HI, .dflt = 0.0, .flags = LV_KEY_ANGLE, .frames = LI,
     .offset = offsetof(attitude_par, roll), .description = "roll phi"},
    {.name = "alpha", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_LAT_LO,
     .hi = LV_KR_LAT_HI, .dflt = 0.0, .flags = LV_KEY_ANGLE, .frames = AE,
     .offset = offsetof(attitude_par, alpha), .description = "angle of attack"},
    {.name = "beta", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_AERO_LO,
     .hi = LV_KR_AERO_HI, .dflt = 0.0, .flags = LV_KEY_ANGLE, .frames = AE,
     .offset = offsetof(attitude_par, beta), .description = "sideslip"},
    {.name = "mu", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_TURN_LO,
     .hi = LV_KR_TURN_HI, .dflt = 0.0, .flags = LV_KEY_ANGLE, .frames = AE,
     .offset = offsetof(attitude_par, mu), .description = "bank about the air-relative velocity"},
    {.name = "table", .type = LV_KEY_TABLE, .unit = "", .offset = offsetof(attitude_par, table),
     .description = "the angles (and throttle) over time, altitude, speed or mach"},
};

static int is_axis(const char *name, const char *a, const char *b)
{
    return strcmp(name, a) == 0 || (b != NULL && strcmp(name, b) == 0);
}

/* The table's axis and the output index of each angle of the frame and the throttle. */
static lv_status table_check(const lv_table *t, lv_att_frame frame, lv_gaxis *axis_out,
                             int k_out[4], lv_err *err)
{
    lv_status st = lv_guid_table_fits(t, err);
    if (st != LV_OK)
        return st;
    const char *ax = lv_table_n_dims(t) == 1 ? lv_table_axis_name(t, 0) : "";
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
    if ((st = lv_table_expect_unit(t, 1, 0, axis_si[axis], NULL, err)) != LV_OK)
        return st;
    static const char *const aero_out[3] = {"alpha", "beta", "mu"};
    static const char *const att_out[3] = {"pitch", "heading", "roll"};
    const char *const *names = frame == LV_FRAME_AERO ? aero_out : att_out;
    int any = 0;
    size_t idx;
    for (int i = 0; i < 4; i++) {
        k_out[i] = -1;
        if (lv_table_out_index(t, i < 3 ? names[i] : "throttle", &idx, NULL) == LV_OK) {
            if ((st = lv_table_expect_unit(t, 0, idx, i < 3 ? "rad" : "1", NULL, err)) != LV_OK)
                return st;
            k_out[i] = (int)idx;
            any = 1;
        }
    }
    if (!any)
        return lv_fail(err, LV_ERR_INPUT, "table '%s' has none of the "
                       "outputs %s, %s, %s, throttle (frame %s; its first output is '%s')",
                       lv_table_name(t), names[0], names[1], names[2],
                       frame == LV_FRAME_AERO ? "aero" : "local/inertial",
                       lv_table_out_name(t, 0));
    *axis_out = axis;
    return LV_OK;
}

static lv_status check(const void *par, lv_law_at *at, lv_err *err)
{
    const attitude_par *p = par;
    if (p->table == NULL)
        return LV_OK;
    lv_gaxis axis;
    int k[4];
    at->key = "table";
    at->node = LV_AT_VALUE;
    return table_check(p->table, (lv_att_frame)p->frame, &axis, k, err);
}

static lv_status init(lv_guid *g, lv_err *err)
{
    attitude_par *p = LV_GUID_PAR_W(attitude_par, g);
    const int aero = p->frame == LV_FRAME_AERO;
    p->angle[0] = aero ? p->alpha : p->pitch;
    p->angle[1] = aero ? p->beta : p->heading;
    p->angle[2] = aero ? p->mu : p->roll;
    for (int i = 0; i < 4; i++)
        p->k[i] = -1;
    p->axis = LV_GAXIS_TIME;
    return p->table != NULL ? table_check(p->table, (lv_att_frame)p->frame, &p->axis, p->k, err)
                            : LV_OK;
}

static int attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                    const lv_flight_air *a, double fpa0, double chi0, int full,
                    lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    const attitude_par *p = LV_GUID_PAR(attitude_par, g);
    double ang[3] = {p->angle[0], p->angle[1], p->angle[2]};
    if (p->table != NULL) {
        double x = t;
        switch (p->axis) {
        case LV_GAXIS_TIME: x = t; break;
        case LV_GAXIS_ALTITUDE: x = k->h; break;
        case LV_GAXIS_SPEED: x = lv_v3_norm(k->v_rel); break;
        case LV_GAXIS_MACH: x = a->mach; break;
        }
        if (lv_table_eval1(p->table, &rt->cur, x, rt->buf, err) != LV_OK) {
            if (err)
                lv_fail_prefix(err, LV_ERR_INPUT, "guidance 'attitude'");
            return 1;
        }
        for (int i = 0; i < 3; i++)
            if (p->k[i] >= 0)
                ang[i] = rt->buf[p->k[i]];
        if (p->k[3] >= 0)
            c->u[LV_CTRL_THROTTLE] = rt->buf[p->k[3]];
    }
    if (p->frame == LV_FRAME_AERO) {
        lv_guid_aero_angles(rt, k, a, ang, fpa0, chi0, c, ax);
        return 0;
    }
    lv_guid_trig3(rt, ang);
    lv_guid_euler_attitude(g, rt, k, a, (lv_att_frame)p->frame, (const double(*)[2])rt->cs, chi0,
                           full, c, ax);
    return 0;
}

static double next_time_event(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    (void)rt;
    const attitude_par *p = LV_GUID_PAR(attitude_par, g);
    return p->table != NULL && p->axis == LV_GAXIS_TIME ? lv_table_next_breakpoint(p->table, 0, t)
                                                        : INFINITY;
}

static const char *time_event_label(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    (void)rt;
    const attitude_par *p = LV_GUID_PAR(attitude_par, g);
    if (p->table == NULL || p->axis != LV_GAXIS_TIME)
        return NULL;
    size_t n = 0;
    const double *b = lv_table_breakpoints(p->table, 0, &n);
    for (size_t i = 0; b != NULL && i < n; i++)
        if (b[i] == t)
            return "guidance: attitude table breakpoint";
    return NULL;
}

static int reads_atmosphere(const lv_guid *g)
{
    const attitude_par *p = LV_GUID_PAR(attitude_par, g);
    return p->table != NULL && p->axis == LV_GAXIS_MACH;
}

static int gives_throttle(const void *par)
{
    const attitude_par *p = par;
    size_t k;
    return p->table != NULL && lv_table_out_index(p->table, "throttle", &k, NULL) == LV_OK;
}

/* The aero frame's angles rest on the air-relative velocity; the others on NED frames. */
static unsigned refs(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    (void)rt, (void)t;
    return LV_GUID_PAR(attitude_par, g)->frame == LV_FRAME_AERO ? LV_GREF_WIND : 0u;
}

const lv_law lv_law_attitude = {
    .name = "attitude",
    .description = "constant angles in a frame, or from a table over time, altitude, speed or "
                   "Mach",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NAMED,
    .keys = keys,
    .n_keys = sizeof keys / sizeof keys[0],
    .par_size = sizeof(attitude_par),
    .check = check,
    .init = init,
    .attitude = attitude,
    .next_time_event = next_time_event,
    .time_event_label = time_event_label,
    .reads_atmosphere = reads_atmosphere,
    .gives_throttle = gives_throttle,
    .refs = refs,
};
