/* numparse.h - internal: decimal text to double as strtod() reads it, faster for the plain
 * numbers lvsim writes (fast_float through a small C++ shim, numparse.cc; strtod for anything
 * else). Used by the reader of a results folder. Not exported. */
#ifndef LV_IO_NUMPARSE_H
#define LV_IO_NUMPARSE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* strtod(s, end)'s value and end, for a field that ends at '\0', ',', a blank or a line end.
 * errno is left as it was for the fast path. Thread-safe. */
double lv_numparse_double(const char *s, char **end);

/* The field s[0..len) as one finite number, as `strtod` of the field alone reads it: 0 and *v
 * set when strtod would consume the whole field without ERANGE and give a finite value; -1
 * otherwise (*v untouched). Plain decimals take fast_float's path; anything else (a '+', hex,
 * a zero or subnormal result, whose ERANGE only strtod reports) strtod's on a copy. Fields
 * longer than 63 bytes are refused. For the input tables (io/table_load.c, env/gravity_sh.c).
 * Thread-safe. */
int lv_numparse_field(const char *s, size_t len, double *v);

#ifdef __cplusplus
}
#endif
#endif
