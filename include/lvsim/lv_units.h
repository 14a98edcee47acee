/* lv_units.h - the constants lvsim converts and computes with, defined once.
 *
 * Inside lvsim everything is SI and radians; degrees exist only at the interface (mission
 * files, command line, result summaries), converted with LV_DEG. */
#ifndef LVSIM_LV_UNITS_H
#define LVSIM_LV_UNITS_H

#define LV_PI 3.14159265358979323846 /* pi */
#define LV_DEG (LV_PI / 180.0)       /* rad per degree: x_rad = x_deg * LV_DEG */
/* Standard acceleration of gravity, m/s^2 (3rd CGPM, 1901; exact): the g0 of the specific
 * impulse (mdot = F / (Isp g0)), of load factors, and of the US Standard Atmosphere 1976. */
#define LV_G0 9.80665

#endif
