/* numparse.h - internal: decimal text to double as strtod() reads it, faster for the plain
 * numbers lvsim writes (fast_float through a small C++ shim, numparse.cc; strtod for anything
 * else). Used by the reader of a results folder. Not exported. */
#ifndef LV_IO_NUMPARSE_H
#define LV_IO_NUMPARSE_H

#ifdef __cplusplus
extern "C" {
#endif

/* strtod(s, end)'s value and end, for a field that ends at '\0', ',', a blank or a line end.
 * errno is left as it was for the fast path. Thread-safe. */
double lv_numparse_double(const char *s, char **end);

#ifdef __cplusplus
}
#endif
#endif
