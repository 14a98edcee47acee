/* units.h - constants for unit conversion at the user interface (not exported).
 * Inside lvsim everything is SI and radians; degrees exist only in I/O code. */
#ifndef LV_CORE_UNITS_H
#define LV_CORE_UNITS_H

#define LV_PI 3.14159265358979323846
#define LV_DEG (LV_PI / 180.0) /* rad per degree: x_rad = x_deg * LV_DEG */

#endif
