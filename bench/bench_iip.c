/* bench_iip.c - the instantaneous impact point's cost per output row (issue 28: "the IIP
 * output cost per row"): nanoseconds per call of lv_iip_propagate (the outputs' method,
 * docs/models.md "Instantaneous impact point") and of the Kepler conic alone, for states along
 * examples/kourou-leo's ascent (times of flight 62 s to 1839 s) and in orbit (no impact: the
 * conic's verdict), under the J2 and the EGM2008 degree-8 field. Processor time, best of 5.
 * Prints a table; asserts nothing. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "dynamics/iip.h"
#include "lvsim/lv_planet.h"

static double now_s(void) { return (double)clock() / (double)CLOCKS_PER_SEC; }

static const struct { double t, r[3], v[3]; } states[] = {
#include "../tests/unit/iip_kourou_leo_states.h"
    /* in orbit: 1 s before kourou-leo's SECO (periapsis 86 km above a) */
    {475.4635130268806, {5179135.627199125, -4030177.6724785394, 579271.6955862509},
     {4761.530008964216, 6101.60284150845, -164.36695241637747}},
};

int main(void)
{
    const lv_planet earth = lv_planet_earth();
    const char *specs[] = {"j2", "sh:8"};
    printf("%-24s %-6s %10s %12s %12s\n", "state", "model", "tof [s]", "ns/propagate",
           "ns/conic");
    for (size_t s = 0; s < sizeof specs / sizeof specs[0]; s++) {
        lv_gravity_config cfg;
        lv_gravity *g = NULL;
        lv_err err;
        if (lv_gravity_parse_spec(specs[s], &cfg, &err) != LV_OK ||
            lv_gravity_create(&earth, &cfg, &g, &err) != LV_OK) {
            fprintf(stderr, "bench_iip: %s\n", err.msg);
            return 1;
        }
        double *ws = malloc((lv_gravity_ws_size(g) + 1) * sizeof *ws);
        lv_gravity_info info;
        lv_gravity_info_get(g, &info);
        for (size_t k = 0; k < sizeof states / sizeof states[0]; k++) {
            lv_iip iip;
            double sink = 0.0, best_p = 1e300, best_c = 1e300;
            lv_iip_propagate(&earth, g, ws, info.gm, states[k].t, states[k].r, states[k].v, &iip);
            const double tof = iip.tof;
            const long n = iip.valid ? 200 : 200000;
            for (int rep = 0; rep < 5; rep++) {
                double t0 = now_s();
                for (long i = 0; i < n; i++) {
                    lv_iip_propagate(&earth, g, ws, info.gm, states[k].t + 1e-9 * (double)i,
                                     states[k].r, states[k].v, &iip);
                    sink += iip.valid ? iip.lat : 1.0;
                }
                double dt = (now_s() - t0) / (double)n * 1e9;
                best_p = dt < best_p ? dt : best_p;
                t0 = now_s();
                for (long i = 0; i < 200000; i++) {
                    lv_iip_conic(&earth, info.gm, states[k].t + 1e-9 * (double)i, states[k].r,
                                 states[k].v, &iip);
                    sink += iip.valid ? iip.lat : 1.0;
                }
                dt = (now_s() - t0) / 200000.0 * 1e9;
                best_c = dt < best_c ? dt : best_c;
            }
            char what[32];
            snprintf(what, sizeof what, "kourou-leo t = %.0f s", states[k].t);
            printf("%-24s %-6s %10.1f %12.0f %12.0f\n", what, specs[s], tof, best_p, best_c);
            if (sink == 42.0)
                printf(" ");
        }
        free(ws);
        lv_gravity_free(g);
    }
    return 0;
}
