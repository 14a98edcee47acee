/* units.h - the unit constants for the library's own code (not exported): the public
 * lv_units.h is their one definition. */
#ifndef LV_CORE_UNITS_H
#define LV_CORE_UNITS_H

#include "lvsim/lv_units.h"

#endif
