/* numfmt.h - internal: doubles as the shortest decimal text that reads back to the same double
 * (round-trip exact, fewest significant digits), laid out as printf's %.17g lays it out:
 * plain decimal for decimal exponents -4..16, otherwise d.ddde+XX with at least two exponent
 * digits; "nan", "-nan", "inf", "-inf" and "-0" as C prints them. The digits come from
 * Dragonbox (Junekey Jeon's shortest round-trip algorithm, Debian's libdragonbox-dev) through
 * a small C++ shim (numfmt.cc); lvsim lays them out. About 30-50 ns per number where
 * snprintf("%.17g") takes about 1 us. Used by the CSV result sink and the body trajectories.
 * Not exported. */
#ifndef LV_IO_NUMFMT_H
#define LV_IO_NUMFMT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define LV_NUMFMT_MAX 32 /* bytes a number may need, with the terminating NUL */

/* Writes v into buf (at least LV_NUMFMT_MAX bytes), NUL-terminated; returns the length
 * without the NUL (at most 24). Allocates nothing; thread-safe. */
size_t lv_numfmt_double(double v, char *buf);

#ifdef __cplusplus
}
#endif
#endif
