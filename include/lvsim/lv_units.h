/* lv_units.h - the constants lvsim converts and computes with, defined once.
 *
 * Inside lvsim everything is SI and radians; degrees exist only at the interface (mission
 * files, command line, result summaries), converted with LV_DEG. */
#ifndef LVSIM_LV_UNITS_H
#define LVSIM_LV_UNITS_H

#include <stdio.h>
#include <string.h>

#define LV_PI 3.14159265358979323846 /* pi */
#define LV_DEG (LV_PI / 180.0)       /* rad per degree: x_rad = x_deg * LV_DEG */
/* Standard acceleration of gravity, m/s^2 (3rd CGPM, 1901; exact): the g0 of the specific
 * impulse (mdot = F / (Isp g0)), of load factors, and of the US Standard Atmosphere 1976. */
#define LV_G0 9.80665
/* Sutton-Graves constants k of the stagnation-point heat flux q = k sqrt(rho / r_n) V^3, in
 * kg^0.5/m (W/m^2 with rho in kg/m^3, r_n in m, V in m/s): Earth's air and Mars' CO2-N2
 * atmosphere (Tauber, NASA TP-2914, 1989, after Sutton & Graves, NASA TR R-376, 1971). */
#define LV_SUTTON_GRAVES_EARTH 1.7415e-4
#define LV_SUTTON_GRAVES_MARS 1.9027e-4

/* Units are SI strings; a dimensionless quantity's unit is "1" (as Modelica's unit="1" and
 * the SI Brochure, 9th ed., sec. 2.3.3, write it): the unit of every model variable, law key
 * and run parameter, shown "1" by `lvsim vars`, `params` and `laws` and "[1]" in the result
 * files' CSV headers and .mat descriptions (docs/result-files.md, "Units"). "" (a model of
 * one's own) means the same and is written "1". LV_UNIT_ONE(u): 1 when u is dimensionless. */
#define LV_UNIT_DIMENSIONLESS "1"
#define LV_UNIT_ONE(u) ((u) == 0 || (u)[0] == '\0' || ((u)[0] == '1' && (u)[1] == '\0'))
/* The unit as written after a number in text ("3 m/s", "0.5"): nothing for "1". */
#define LV_UNIT_AFTER_NUMBER(u) (LV_UNIT_ONE(u) ? "" : (u))

/* The unit of a time derivative of a quantity in `unit`, as every file and command names it
 * (docs/result-files.md, "Units"; the Modelica unit grammar): "m" -> "m/s", "m/s" -> "m/s2",
 * "m/s2" -> "m/s3", "rad.s" -> "rad", "s" -> "1", "1" or "" -> "1/s", "J" -> "W" and
 * "J/..." -> "W/..." (a heat load's "J/m2" -> "W/m2", J/s = W). Into buf[cap]; returns
 * buf. The one rule of lv_simulate, missions, the FMU export and `lvsim vars` (inline: the
 * post-processing library, which has none of the core's symbols, uses it too). */
static inline const char *lv_unit_per_second(const char *unit, char *buf, size_t cap)
{
    const size_t len = strlen(unit);
    if (LV_UNIT_ONE(unit))
        snprintf(buf, cap, "1/s");
    else if (strcmp(unit, "s") == 0)
        snprintf(buf, cap, "1");
    else if (unit[0] == 'J' && (unit[1] == '\0' || unit[1] == '/'))
        snprintf(buf, cap, "W%s", unit + 1);
    else if (len >= 3 && strcmp(unit + len - 2, ".s") == 0)
        snprintf(buf, cap, "%.*s", (int)(len - 2), unit);
    else if (len >= 2 && strcmp(unit + len - 2, "/s") == 0)
        snprintf(buf, cap, "%s2", unit);
    else if (len >= 3 && unit[len - 3] == '/' && unit[len - 2] == 's' && unit[len - 1] >= '2' &&
             unit[len - 1] < '9')
        snprintf(buf, cap, "%.*s%c", (int)(len - 1), unit, unit[len - 1] + 1);
    else
        snprintf(buf, cap, "%s/s", unit);
    return buf;
}

#endif
