/* cmd_gravity.c - `lvsim gravity LAT_DEG LON_DEG ALT_M`: a gravity model's acceleration in
 * the local NED frame at a geodetic point (lv_gravity_at_geodetic).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

static int gravity_run(const cli_cmd *self, int argc, char **argv)
{
    const char *spec = "sh", *planet_name = "earth";
    int effective = 0;
    double v[3];
    int npos = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--model") == 0 || strcmp(a, "--planet") == 0) {
            const char *val = option_value(argc, argv, &i);
            if (val == NULL)
                return usage_error(self, "missing value for option", a);
            if (a[2] == 'm')
                spec = val;
            else
                planet_name = val;
        } else if (strcmp(a, "--effective") == 0) {
            effective = 1;
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (npos < 3 && parse_double(a, &v[npos])) {
            npos++;
        } else {
            fprintf(stderr, "lvsim gravity: unexpected argument '%s' (expected LAT_DEG LON_DEG "
                            "ALT_M as numbers)\n", a);
            return EXIT_INPUT;
        }
    }
    if (npos != 3)
        return usage_error(self, "gravity needs LAT_DEG LON_DEG ALT_M", NULL);
    const double lat_deg = v[0], lon_deg = v[1], alt_m = v[2];
    if (fabs(lat_deg) > 90.0 || fabs(lon_deg) > 360.0) {
        fprintf(stderr, "lvsim gravity: latitude %g deg must be within [-90, 90] and longitude "
                        "%g deg within [-360, 360]\n", lat_deg, lon_deg);
        return EXIT_INPUT;
    }
    lv_err err;
    lv_planet planet;
    lv_gravity_config cfg;
    lv_gravity *g = NULL;
    lv_gravity_local loc;
    lv_status st = lv_planet_by_name(planet_name, &planet, &err);
    if (st == LV_OK && !(alt_m > -0.5 * planet.a)) {
        fprintf(stderr, "lvsim gravity: altitude %g m is below half the planet's radius\n", alt_m);
        return EXIT_INPUT;
    }
    if (st == LV_OK)
        st = lv_gravity_parse_spec(spec, &cfg, &err);
    if (st == LV_OK)
        st = lv_gravity_create(&planet, &cfg, &g, &err);
    const double deg = LV_DEG; /* user interface: degrees */
    if (st == LV_OK)
        st = lv_gravity_at_geodetic(g, &planet, lat_deg * deg, lon_deg * deg, alt_m, &loc, &err);
    lv_gravity_free(g);
    if (st != LV_OK)
        return print_err("lvsim gravity", &err, exit_code_for_input(st));
    const double *gv = effective ? loc.g_eff_ned : loc.g_ned;
    printf("# %s, model %s, planet %s, lat %g deg, lon %g deg, alt %g m\n",
           effective ? "gravity (gravitation + centrifugal)" : "gravitation",
           spec, planet.name, lat_deg, lon_deg, alt_m);
    printf("# g_north [m/s2]  g_east [m/s2]  g_down [m/s2]  |g| [m/s2]\n");
    printf("%.10g %.10g %.10g %.10g\n", gv[0], gv[1], gv[2],
           sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]));
    return EXIT_OK;
}

const cli_cmd cli_cmd_gravity = {
    "gravity",
    "a gravity model's acceleration in NED at a geodetic point",
    "LAT_DEG LON_DEG ALT_M [--model SPEC] [--planet NAME] [--effective]",
    "After two '#' header lines, one line: the gravitational acceleration in the local NED\n"
    "frame at geodetic latitude LAT_DEG [deg, -90..90], longitude LON_DEG [deg, -360..360]\n"
    "and altitude ALT_M [m] above the reference ellipsoid: g_north, g_east, g_down and |g|\n"
    "[m/s2] (docs/gravity.md).\n"
    "\n"
    "options:\n"
    "  --model SPEC            pointmass | j2 | zonal (J2-J4) | sh (spherical harmonics,\n"
    "                          EGM2008 to degree 20) | sh:N | sh:NxM (default sh)\n"
    "  --planet NAME           earth (WGS-84) | moon | mars (default earth)\n"
    "  --effective             add the centrifugal acceleration of the rotating planet\n"
    "\n"
    "'sh' reads gravity/egm2008_n20.gfc: $LVSIM_DATA, else share/lvsim next to the library,\n"
    "else the install prefix.\n",
    gravity_run,
};
