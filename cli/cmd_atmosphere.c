/* cmd_atmosphere.c - `lvsim atmosphere ALT_M...`: T, p, rho, a, mu of an atmosphere model at
 * geometric altitudes (lv_atmo_eval_by_name), or of a profile file (lv_atmo_create_profile),
 * one line per altitude.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "common.h"

static int atmosphere_run(const cli_cmd *self, int argc, char **argv)
{
    const char *model = "us76", *profile = NULL;
    double blend = LV_ATMO_PROFILE_BLEND;
    double *alt = calloc((size_t)argc + 1, sizeof *alt);
    lv_atmo_state *out = calloc((size_t)argc + 1, sizeof *out);
    size_t n = 0;
    int rc = EXIT_OK;
    if (alt == NULL || out == NULL) {
        fprintf(stderr, "lvsim: out of memory\n");
        rc = EXIT_INTERNAL;
        goto done;
    }
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--model") == 0) {
            model = option_value(argc, argv, &i);
            if (model == NULL) {
                rc = usage_error(self, "missing value for option", a);
                goto done;
            }
        } else if (strcmp(a, "--profile") == 0) {
            profile = option_value(argc, argv, &i);
            if (profile == NULL) {
                rc = usage_error(self, "missing value for option", a);
                goto done;
            }
        } else if (strcmp(a, "--blend") == 0) {
            const char *b = option_value(argc, argv, &i);
            if (b == NULL || !parse_double(b, &blend)) {
                rc = usage_error(self, b == NULL ? "missing value for option"
                                                 : "--blend takes a band in m", a);
                goto done;
            }
        } else if (is_option(a)) {
            rc = usage_error(self, "unknown option", a);
            goto done;
        } else if (!parse_double(a, &alt[n++])) {
            fprintf(stderr, "lvsim atmosphere: '%s' is not an altitude in m\n", a);
            rc = EXIT_INPUT;
            goto done;
        }
    }
    if (n == 0) {
        rc = usage_error(self, "atmosphere needs at least one altitude in m", NULL);
        goto done;
    }
    lv_err err;
    lv_status st;
    if (profile != NULL) { /* a profile file: read once, then evaluated */
        lv_atmo *atm = NULL;
        st = lv_atmo_create_profile(profile, blend, &atm, &err);
        for (size_t i = 0; i < n && st == LV_OK; i++)
            st = lv_atmo_eval(atm, alt[i], &out[i], &err);
        lv_atmo_free(atm);
        model = profile;
    } else {
        st = lv_atmo_eval_by_name(model, alt, n, out, &err);
    }
    if (st != LV_OK) {
        rc = print_err("lvsim atmosphere", &err, exit_code_for_input(st));
        goto done;
    }
    printf("# %s: altitude [m]  T [K]  p [Pa]  rho [kg/m3]  a [m/s]  mu [Pa s]\n", model);
    for (size_t i = 0; i < n; i++)
        printf("%.9g %.9g %.9g %.9g %.9g %.9g\n", alt[i], out[i].T, out[i].p, out[i].rho,
               out[i].a, out[i].mu);
done:
    free(alt);
    free(out);
    return rc;
}

const cli_cmd cli_cmd_atmosphere = {
    "atmosphere",
    "T, p, rho, a, mu of an atmosphere model at geometric altitudes",
    "ALT_M... [--model us76|exp] [--profile FILE [--blend M]]",
    "After a '#' header line, one line per geometric altitude ALT_M [m]: altitude [m],\n"
    "temperature T [K], pressure p [Pa], density rho [kg/m3], speed of sound a [m/s] and\n"
    "dynamic viscosity mu [Pa s] (docs/atmosphere.md). Altitudes outside the model (-5 km\n"
    "to 1000 km) or non-numbers exit 2.\n"
    "\n"
    "options:\n"
    "  --model M               us76 (U.S. Standard Atmosphere 1976) or exp (exponential\n"
    "                          density, constant temperature) (default us76)\n"
    "  --profile FILE          a measured or forecast profile (profile CSV or University of\n"
    "                          Wyoming sounding text list), blended into US76 above its top\n"
    "                          (docs/atmosphere.md, \"Profiles\"); a bad file: its\n"
    "                          file:line:column, exit 2\n"
    "  --blend M               the blend band above the profile's top, m (default 10000)\n",
    atmosphere_run,
};
