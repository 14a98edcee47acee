/* flight_ends.c - the named ends of a flight model over the planet (flight_ends.h). */
#include "dynamics/flight_ends.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"

static const struct {
    const char *name, *description;
} end_info[] = {
    {"", ""},
    {"altitude", "Geodetic altitude crosses the configured value"},
    {"speed_rel", "Speed relative to the rotating planet crosses the configured value"},
    {"speed_inertial", "Inertial speed crosses the configured value"},
    {"apogee", "Radial velocity falls through zero"},
    {"impact", "Geodetic altitude falls through the configured ground level"},
};

lv_status lv_flight_ends_init(lv_flight_ends *fe, const char *model, const lv_dof3_end *ends,
                              size_t n, lv_err *err)
{
    if (n > 0 && ends == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: n_ends = %zu but ends is NULL", model, n);
    fe->events = calloc(n + 1, sizeof *fe->events);
    fe->names = calloc(n + 1, sizeof *fe->names);
    fe->ends = calloc(n + 1, sizeof *fe->ends);
    fe->off = calloc(n + 1, sizeof *fe->off);
    if (!fe->events || !fe->names || !fe->ends || !fe->off)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    snprintf(fe->names[0], LV_FLIGHT_END_NAME_MAX, "burnout");
    fe->events[0] = (lv_event_def){fe->names[0],
                                   "Propellant exhausted: m falls through the start mass minus "
                                   "the propellant",
                                   LV_DIR_FALLING, 0};
    for (size_t i = 0; i < n; i++) {
        const lv_dof3_end *e = &ends[i];
        if (e->kind < LV_DOF3_END_ALTITUDE || e->kind > LV_DOF3_END_IMPACT)
            return lv_fail(err, LV_ERR_INPUT, "%s: ends[%zu]: unknown kind %d", model, i,
                           (int)e->kind);
        const char *nm = e->name != NULL ? e->name : end_info[e->kind].name;
        if (nm[0] == '\0' || strlen(nm) >= LV_FLIGHT_END_NAME_MAX)
            return lv_fail(err, LV_ERR_INPUT, "%s: ends[%zu]: name '%s' is empty or longer "
                           "than %d characters", model, i, nm, LV_FLIGHT_END_NAME_MAX - 1);
        for (size_t j = 0; j <= i; j++)
            if (strcmp(fe->names[j], nm) == 0)
                return lv_fail(err, LV_ERR_INPUT, "%s: ends[%zu]: event name '%s' is used twice",
                               model, i, nm);
        if (!isfinite(e->value))
            return lv_fail(err, LV_ERR_INPUT, "%s: end '%s': value %g is not finite", model, nm,
                           e->value);
        if ((e->kind == LV_DOF3_END_SPEED_REL || e->kind == LV_DOF3_END_SPEED_INERTIAL) &&
            e->value < 0.0)
            return lv_fail(err, LV_ERR_INPUT, "%s: end '%s': speed %g m/s is negative", model,
                           nm, e->value);
        if (e->direction < LV_DIR_FALLING || e->direction > LV_DIR_RISING)
            return lv_fail(err, LV_ERR_INPUT, "%s: end '%s': direction %d", model, nm,
                           (int)e->direction);
        snprintf(fe->names[i + 1], LV_FLIGHT_END_NAME_MAX, "%s", nm);
        fe->ends[i] = *e;
        fe->ends[i].name = fe->names[i + 1];
        lv_dir dir = e->direction;
        if (e->kind == LV_DOF3_END_APOGEE || e->kind == LV_DOF3_END_IMPACT)
            dir = LV_DIR_FALLING;
        fe->events[i + 1] = (lv_event_def){fe->names[i + 1], end_info[e->kind].description,
                                           dir, e->stop != 0};
    }
    fe->n = n;
    return LV_OK;
}

void lv_flight_ends_clear(lv_flight_ends *fe)
{
    free(fe->events);
    free(fe->names);
    free(fe->ends);
    free(fe->off);
    memset(fe, 0, sizeof *fe);
}

int lv_flight_ends_start(lv_flight_ends *fe, double h0, char *why, size_t cap)
{
    for (size_t i = 0; i < fe->n; i++) {
        const lv_dof3_end *e = &fe->ends[i];
        if (e->kind == LV_DOF3_END_IMPACT && h0 < e->value - LV_FLIGHT_ENDS_BELOW_TOL) {
            snprintf(why, cap, "the start altitude h = %.9g m is below the level %g m of its "
                     "end '%s': the vehicle would start under the ground it is to hit, and "
                     "never cross it (start higher, or give the ground's level: {impact: %.6g})",
                     h0, e->value, e->name, h0);
            return 1;
        }
        fe->off[i] = e->kind == LV_DOF3_END_IMPACT && h0 <= e->value ? e->value - h0 + 1e-6
                                                                      : 0.0;
    }
    return 0;
}

void lv_flight_ends_eval(const lv_flight_ends *fe, const lv_flight_world *w, lv_flight_kin *kin,
                         const double r[3], const double v[3], double *g)
{
    int have_h = 0;
    for (size_t i = 0; i < fe->n; i++) {
        const lv_dof3_end *e = &fe->ends[i];
        double gi = 0.0;
        switch (e->kind) {
        case LV_DOF3_END_ALTITUDE:
        case LV_DOF3_END_IMPACT:
            if (!have_h) {
                lv_flight_geodetic(w, kin, 0, 0);
                have_h = 1;
            }
            gi = kin->h - e->value + fe->off[i];
            break;
        case LV_DOF3_END_SPEED_REL:
            gi = lv_v3_norm(kin->v_rel) - e->value;
            break;
        case LV_DOF3_END_SPEED_INERTIAL:
            gi = hypot(hypot(v[0], v[1]), v[2]) - e->value;
            break;
        case LV_DOF3_END_APOGEE: /* d|r|/dt = r.v / |r| (w x r is normal to r) */
            gi = (r[0] * v[0] + r[1] * v[1] + r[2] * v[2]) / hypot(hypot(r[0], r[1]), r[2]);
            break;
        }
        g[i] = gi;
    }
}
