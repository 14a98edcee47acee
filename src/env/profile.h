/* profile.h - a measured or forecast atmosphere profile read from a file (internal, not
 * exported): the profile CSV layout or the University of Wyoming sounding text list
 * (TEXT:LIST), as levels over geometric altitude with T, p, rho and the wind's north and east
 * components, in SI units. Layouts, unit conversions and the checks: docs/atmosphere.md,
 * "Profiles". Used by the "profile" atmosphere (atmosphere_profile.c) and the profile wind
 * (wind.c). */
#ifndef LV_ENV_PROFILE_H
#define LV_ENV_PROFILE_H

#include <stddef.h>

#include "core/status.h"

/* Specific gas constant of dry air, J/(kg K): R* / M0 with the US76 constants
 * (8314.32 / 28.9644 = 287.0531...), for p = rho R T. */
#define LV_PROFILE_R_AIR (8314.32 / 28.9644)
/* Effective Earth radius of US76 eq. (18), m: geometric z = r0 H / (r0 - H) from the
 * geopotential height H. */
#define LV_PROFILE_R0 6356766.0

typedef struct lv_profile {
    size_t n_t;              /* thermodynamic levels (0: the file has none) */
    double *z_t;             /* m, geometric altitude, strictly increasing */
    double *T, *p, *rho;     /* K, Pa, kg/m^3 */
    size_t n_w;              /* wind levels (0: the file has no wind) */
    double *z_w;             /* m, geometric altitude, strictly increasing */
    double *north, *east;    /* m/s, the air's velocity (towards), NED components */
    char src[256];           /* the file, for messages */
} lv_profile;

/* Reads `path`: the Wyoming text list when a line starts with the column names PRES HGHT,
 * else the profile CSV. Errors (LV_ERR_INPUT unless noted) carry path:line:column: a missing
 * or unknown column or unit, a value that is not a finite number (NaN, an empty cell), a
 * missing PRES or HGHT in a sounding row, altitudes not strictly increasing, a non-positive
 * T, p or rho, a level below the surface (a sounding's station elevation; -5 km for a CSV);
 * LV_ERR_IO when unreadable. lv_profile_clear(out) in every case. */
lv_status lv_profile_load(const char *path, lv_profile *out, lv_err *err);
void lv_profile_clear(lv_profile *p);

#endif
