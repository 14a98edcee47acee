/* random.h - the generator behind lvsim's random streams (random.c; the public face is
 * lv_disp_uniform, lv_disp_norm_inv, lv_disp_stream in lv_dispersion.h). */
#ifndef LVSIM_CORE_RANDOM_H
#define LVSIM_CORE_RANDOM_H

#include <stdint.h>

/* Two independent u in (0, 1) from one Philox4x32-10 call: key (seed mod 2^32, seed / 2^32),
 * counter (run mod 2^32, run / 2^32, stream mod 2^32, stream / 2^32); u[0] from the output's
 * high 64 bits (what lv_disp_uniform returns), u[1] from its low 64 bits. Pure. */
void lv_rand_u01x2(uint64_t seed, uint64_t run, uint64_t stream, double u[2]);
/* The two standard normals of that call: the inverse normal CDF (lv_disp_norm_inv) of u[0] and
 * u[1]. The white noise of the turbulence and of the perturbation profiles. */
void lv_rand_normal2(uint64_t seed, uint64_t run, uint64_t stream, double z[2]);

#endif
