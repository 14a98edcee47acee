/* bench_gravity.c - nanoseconds per gravity evaluation (acceleration and
 * potential) for each model: point mass, J2, zonal J2-J4, and spherical
 * harmonics (EGM2008 file) to degree/order 2, 8 and 20. Prints a table. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "lvsim/lv_planet.h"

/* Processor time of this process: other jobs on a shared machine inflate wall
 * time, not this. */
static double now_s(void) { return (double)clock() / (double)CLOCKS_PER_SEC; }

int main(void)
{
    const char *specs[] = {"pointmass", "j2", "zonal", "sh:2", "sh:8", "sh:20"};
    const lv_planet earth = lv_planet_earth();
    printf("%-10s %8s %10s %12s\n", "model", "degree", "ws_doubles", "ns/eval");
    for (size_t s = 0; s < sizeof specs / sizeof specs[0]; s++) {
        lv_gravity_config cfg;
        lv_gravity *g = NULL;
        lv_err err;
        if (lv_gravity_parse_spec(specs[s], &cfg, &err) != LV_OK ||
            lv_gravity_create(&earth, &cfg, &g, &err) != LV_OK) {
            fprintf(stderr, "bench_gravity: %s\n", err.msg);
            return 1;
        }
        const size_t nws = lv_gravity_ws_size(g);
        double *ws = malloc((nws + 1) * sizeof *ws);
        lv_gravity_info info;
        lv_gravity_info_get(g, &info);
        const long n_eval = 4000000L / ((long)info.degree + 1) / ((long)info.degree + 1) + 20000;
        double sink = 0.0, best = 1e300;
        for (int rep = 0; rep < 5; rep++) {
            const double t0 = now_s();
            for (long i = 0; i < n_eval; i++) {
                /* a point moving over the globe, so nothing is hoisted out */
                const double r[3] = {6.7e6 - 1e-3 * (double)i, 1e6 + 2.0 * (double)(i & 1023),
                                     2e6 - 3.0 * (double)(i & 4095)};
                double a[3], u;
                lv_gravity_eval(g, ws, r, a, &u);
                sink += a[0] + a[1] + a[2] + 1e-9 * u;
            }
            const double dt = (now_s() - t0) / (double)n_eval * 1e9;
            if (dt < best) best = dt;
        }
        printf("%-10s %8d %10zu %12.1f\n", specs[s], info.degree, nws, best);
        if (sink == 42.0) printf(" ");
        free(ws);
        lv_gravity_free(g);
    }
    return 0;
}
