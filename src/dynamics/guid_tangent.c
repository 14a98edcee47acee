/* guid_tangent.c - steering laws `linear_tangent` and `bilinear_tangent`: tan theta = (a +
 * b tau) / (c + d tau), tau = t - the phase's start, in `frame` (local or inertial), heading
 * `heading`, roll 0; linear tangent: c = 1, d = 0. The optimal steering of a constant-thrust
 * vacuum ascent over a flat Earth: Bryson & Ho, Applied Optimal Control, sec. 2.7 (the linear
 * tangent law); docs/guidance.md.
 */
#include "dynamics/guid_kit.h"

typedef struct tangent_par {
    double a, b, c, d;    /* -, 1/s, -, 1/s */
    double heading;       /* rad */
    int frame;            /* lv_att_frame: local or inertial */
    double cs_heading[2]; /* init: cos, sin of heading */
} tangent_par;

#define KEY_A                                                                                  \
    {.name = "a", .type = LV_KEY_NUMBER, .unit = "1", .lo = -HUGE_VAL, .hi = HUGE_VAL,          \
     .dflt = NAN, .offset = offsetof(tangent_par, a),                                          \
     .description = "numerator of tan theta at the phase's start"}
#define KEY_B                                                                                  \
    {.name = "b", .type = LV_KEY_NUMBER, .unit = "1/s", .lo = -HUGE_VAL, .hi = HUGE_VAL,       \
     .dflt = NAN, .offset = offsetof(tangent_par, b),                                          \
     .description = "rate of the numerator"}
#define KEY_HEADING_FRAME                                                                      \
    {.name = "heading", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_TURN_LO,             \
     .hi = LV_KR_TURN_HI, .dflt = NAN, .flags = LV_KEY_ANGLE,                                  \
     .offset = offsetof(tangent_par, heading), .description = "heading of the pitch plane"},   \
    {.name = "frame", .type = LV_KEY_CHOICE, .unit = "", .dflt = LV_FRAME_INERTIAL,             \
     .choices = lv_guid_frame_words, .offset = offsetof(tangent_par, frame),                   \
     .description = "the frame of the pitch: local or inertial (frozen at the phase's start)"}

static const lv_law_key linear_keys[] = {KEY_A, KEY_B, KEY_HEADING_FRAME};

/* c >= 0: the denominator c + d tau is not negative at the phase's start (theta within +-90
 * deg; c = 0 starts vertical) */
static const lv_law_key bilinear_keys[] = {
    KEY_A,
    KEY_B,
    {.name = "c", .type = LV_KEY_NUMBER, .unit = "1", .lo = 0.0, .hi = HUGE_VAL, .dflt = NAN,
     .offset = offsetof(tangent_par, c),
     .description = "denominator at the phase's start (0: vertical)"},
    {.name = "d", .type = LV_KEY_NUMBER, .unit = "1/s", .lo = -HUGE_VAL, .hi = HUGE_VAL,
     .dflt = NAN, .offset = offsetof(tangent_par, d),
     .description = "rate of the denominator"},
    KEY_HEADING_FRAME,
};

static lv_status check_frame(const tangent_par *p, lv_law_at *at, lv_err *err)
{
    if (p->frame != LV_FRAME_AERO)
        return LV_OK;
    at->key = "frame";
    at->node = LV_AT_VALUE;
    return lv_fail(err, LV_ERR_INPUT, "the pitch is measured in the local or the inertial frame");
}

static lv_status check_linear(const void *par, lv_law_at *at, lv_err *err)
{
    return check_frame(par, at, err);
}

static lv_status check_bilinear(const void *par, lv_law_at *at, lv_err *err)
{
    const tangent_par *p = par;
    lv_status st = check_frame(p, at, err);
    if (st == LV_OK && p->a == 0.0 && p->c == 0.0 && p->b == 0.0 && p->d == 0.0)
        return lv_fail(err, LV_ERR_INPUT, "a, b, c and d are all 0");
    return st;
}

static lv_status init_bilinear(lv_guid *g, lv_err *err)
{
    (void)err;
    tangent_par *p = LV_GUID_PAR_W(tangent_par, g);
    p->cs_heading[0] = cos(p->heading);
    p->cs_heading[1] = sin(p->heading);
    return LV_OK;
}

static lv_status init_linear(lv_guid *g, lv_err *err)
{
    tangent_par *p = LV_GUID_PAR_W(tangent_par, g);
    p->c = 1.0;
    p->d = 0.0;
    return init_bilinear(g, err);
}

static int attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                    const lv_flight_air *a, double fpa0, double chi0, int full,
                    lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    (void)fpa0, (void)err;
    const tangent_par *p = LV_GUID_PAR(tangent_par, g);
    const double tau = t - rt->t0;
    /* cos and sin of theta = atan2(a + b tau, c + d tau) without trigonometry */
    const double num = p->a + p->b * tau, den = p->c + p->d * tau;
    const double nn = sqrt(num * num + den * den);
    const double cs[3][2] = {{nn > 0.0 ? den / nn : 1.0, nn > 0.0 ? num / nn : 0.0},
                             {p->cs_heading[0], p->cs_heading[1]},
                             {1.0, 0.0}};
    lv_guid_euler_attitude(g, rt, k, a, (lv_att_frame)p->frame, cs, chi0, full, c, ax);
    return 0;
}

const lv_law lv_law_linear_tangent = {
    .name = "linear_tangent",
    .description = "tan theta = a + b tau in the local or inertial frame, heading `heading`",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NAMED,
    .keys = linear_keys,
    .n_keys = sizeof linear_keys / sizeof linear_keys[0],
    .par_size = sizeof(tangent_par),
    .check = check_linear,
    .init = init_linear,
    .attitude = attitude,
};

const lv_law lv_law_bilinear_tangent = {
    .name = "bilinear_tangent",
    .description = "tan theta = (a + b tau) / (c + d tau) in the local or inertial frame, "
                   "heading `heading`",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NAMED,
    .keys = bilinear_keys,
    .n_keys = sizeof bilinear_keys / sizeof bilinear_keys[0],
    .par_size = sizeof(tangent_par),
    .check = check_bilinear,
    .init = init_bilinear,
    .attitude = attitude,
};
