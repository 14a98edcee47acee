/* test_heating.c - the aerothermal heating outputs of the flight models over a planet
 * (docs/models.md, "Aerothermal heating"):
 *   (a) dof3 and dof6 at 60 km and 6000 m/s over the WGS-84 Earth with US76: heat_flux by
 *       Sutton-Graves with the top stage's nose radius 0.5 m, against a hand calculation with
 *       the US76 density at 60 km (Table I of the 1976 standard: 3.0968e-4 kg/m^3) and
 *       k = 1.7415e-4 kg^0.5/m (Tauber, NASA TP-2914, 1989):
 *           q = 1.7415e-4 sqrt(3.0968e-4 / 0.5) 6000^3 = 936157 W/m^2,
 *       and heat_flux_fm = 3.0968e-4 6000^3 / 2 = 3.34454e7 W/m^2 (5 digits: the table's);
 *   (b) on Mars with an exponential atmosphere (rho = 0.02 exp(-h / 11100 m)): the planet's
 *       constant 1.9027e-4 and a 2 m nose at 30 km and 4000 m/s, 315258 W/m^2 by hand; a
 *       planet's own `sutton_graves_k` replaces it, and without `nose_radius` the nose is 1 m;
 *   (c) an end on the free-molecular flux (a fairing jettison, `{heat_flux_fm: 1135,
 *       direction: falling}`) stops where rho v^3 / 2 of the end row's own density and speed
 *       is 1135 W/m^2;
 *   (d) refusals at load with file:line:col: nose_radius 0, a negative or huge
 *       sutton_graves_k. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"
#include "mission_kit.h"

/* The value of column `name` in row `row` of phase k's rows. */
static double row_value(const lv_run *r, size_t k, const char *name, size_t row)
{
    lv_err err;
    size_t c = 0;
    const lv_result *res = lv_run_rows(r, k);
    CHECK(res != NULL);
    if (res == NULL)
        return NAN;
    CHECK_OK(lv_result_column(res, name, &c, &err), &err);
    if (row == (size_t)-1)
        row = lv_result_rows(res) - 1;
    return lv_result_value(res, row, c);
}

#define STAGES(nose)                                                                       \
    "stages:\n"                                                                             \
    "  - {name: booster, dry_mass: 5000, propellant_mass: 0}\n"                             \
    "  - {name: capsule, dry_mass: 1000, propellant_mass: 0" nose "}\n"

static const char *const dof6_body =
    ",\n     rigid_body: {inertia_full: {xx: 100, yy: 900, zz: 900},\n"
    "                  inertia_empty: {xx: 100, yy: 900, zz: 900}, cg_full: {x: -1},\n"
    "                  cg_empty: {x: -1}}";

static void earth_case(const char *model)
{
    char yaml[4096];
    const int six = strcmp(model, "dof6") == 0;
    snprintf(yaml, sizeof yaml,
             "mission: {name: heating, epoch: 2026-03-01T12:00:00Z}\n"
             "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
             "parameters: {start_lat_deg: 0, start_lon_deg: 0, start_h: 60000,\n"
             "             start_vel: 6000, start_fpa_deg: 0, start_chi_deg: 90}\n"
             "stages:\n"
             "  - {name: booster, dry_mass: 5000, propellant_mass: 0%s}\n"
             "  - {name: capsule, dry_mass: 1000, propellant_mass: 0, nose_radius: 0.5}\n"
             "phases:\n"
             "  - {name: glide, model: %s, stages: [booster, capsule], start_time: 0,\n"
             "     stop_time: 1%s}\n",
             six ? dof6_body : "", model, six ? "" : ", throttle: off");
    lv_mission *m = NULL;
    lv_run *r = run_text("test_heating_earth.yaml", yaml, &m);
    CHECK(r != NULL);
    if (r != NULL) {
        const double q = row_value(r, 0, "heat_flux", 0);
        const double qf = row_value(r, 0, "heat_flux_fm", 0);
        printf("%s at 60 km, 6000 m/s: heat_flux %.6g W/m2 (hand 936157), heat_flux_fm %.6g "
               "(hand 3.34454e7)\n", model, q, qf);
        CHECK_REL(q, 936157.0, 1e-4);
        CHECK_REL(qf, 3.344544e7, 1e-4);
    }
    lv_run_free(r);
    lv_mission_free(m);
}

static void mars_case(void)
{
    static const char *const head =
        "mission: {name: heating-mars, epoch: 2026-03-01T12:00:00Z}\n"
        "environment: {world: planet, planet: %s, gravity: j2,\n"
        "              atmosphere: {model: exp, rho0: 0.02, scale_height: 11100, "
        "temperature: 210}}\n"
        "parameters: {start_lat_deg: 10, start_lon_deg: 0, start_h: 30000,\n"
        "             start_vel: 4000, start_fpa_deg: 0, start_chi_deg: 90}\n"
        "stages:\n"
        "  - {name: lander, dry_mass: 1000, propellant_mass: 0%s}\n"
        "phases:\n"
        "  - {name: entry, model: dof3, stages: [lander], start_time: 0, stop_time: 1,\n"
        "     throttle: off}\n";
    const double rho = 0.02 * exp(-30000.0 / 11100.0), v3 = 4000.0 * 4000.0 * 4000.0;
    const struct {
        const char *planet, *nose;
        double want; /* W/m^2, by hand from the closed-form density */
    } cases[] = {
        {"mars", ", nose_radius: 2", 1.9027e-4 * sqrt(rho / 2.0) * v3}, /* 315258 */
        {"{name: ares, base: mars}", ", nose_radius: 2", 1.9027e-4 * sqrt(rho / 2.0) * v3},
        {"{name: ares, base: mars, sutton_graves_k: 1.0e-4}", "", 1.0e-4 * sqrt(rho) * v3},
        {"{name: ares, base: mars, sutton_graves_k: 0}", "", 0.0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char yaml[2048];
        snprintf(yaml, sizeof yaml, head, cases[i].planet, cases[i].nose);
        lv_mission *m = NULL;
        lv_run *r = run_text("test_heating_mars.yaml", yaml, &m);
        CHECK(r != NULL);
        if (r != NULL) {
            const double q = row_value(r, 0, "heat_flux", 0);
            printf("mars (%s%s): heat_flux %.9g W/m2, by hand %.9g\n", cases[i].planet,
                   cases[i].nose, q, cases[i].want);
            CHECK_CLOSE(q, cases[i].want, 1e-9 * cases[i].want);
        }
        lv_run_free(r);
        lv_mission_free(m);
    }
}

/* A capsule coasting up from 90 km at 2 km/s, 60 deg: the free-molecular flux falls through
 * 1135 W/m^2 (near 110 km); the end stops there. */
static void fm_end_case(void)
{
    const char *yaml =
        "mission: {name: heating-fm, epoch: 2026-03-01T12:00:00Z}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 90000,\n"
        "             start_vel: 2000, start_fpa_deg: 60, start_chi_deg: 90}\n" STAGES("")
        "phases:\n"
        "  - {name: climb, model: dof3, stages: [booster, capsule], start_time: 0,\n"
        "     stop_time: 200, throttle: off,\n"
        "     end: [{heat_flux_fm: 1135, direction: falling, name: fairing jettison}]}\n";
    lv_mission *m = NULL;
    lv_run *r = run_text("test_heating_fm.yaml", yaml, &m);
    CHECK(r != NULL);
    if (r != NULL) {
        const double rho = row_value(r, 0, "rho", (size_t)-1);
        const double v = row_value(r, 0, "v_rel", (size_t)-1);
        const double h = row_value(r, 0, "h", (size_t)-1);
        const double fm = 0.5 * rho * v * v * v;
        printf("fm end: h %.1f m, rho %.6g kg/m3, v %.3f m/s: rho v^3 / 2 = %.9g W/m2\n", h, rho,
               v, fm);
        CHECK_REL(fm, 1135.0, 1e-6);
        CHECK(h > 95000.0 && h < 130000.0);
    }
    lv_run_free(r);
    lv_mission_free(m);
}

static void refusals(void)
{
    static const struct {
        const char *planet, *stage_extra, *want;
    } bad[] = {
        {"earth", ", nose_radius: 0", ":7:"},
        {"{name: x, base: earth, sutton_graves_k: -1}", "", "sutton_graves_k"},
        {"{name: x, base: earth, sutton_graves_k: 2}", "", "sutton_graves_k"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char yaml[2048];
        snprintf(yaml, sizeof yaml,
                 "mission: {name: bad, epoch: 2026-03-01T12:00:00Z}\n"
                 "environment: {world: planet, planet: %s}\n"
                 "parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 90000,\n"
                 "             start_vel: 2000, start_fpa_deg: 60, start_chi_deg: 90}\n"
                 "stages:\n"
                 "  - {name: booster, dry_mass: 5000, propellant_mass: 0}\n"
                 "  - {name: capsule, dry_mass: 1000, propellant_mass: 0%s}\n"
                 "phases:\n"
                 "  - {name: climb, model: dof3, stages: [booster, capsule], stop_time: 10}\n",
                 bad[i].planet, bad[i].stage_extra);
        write_file("test_heating_bad.yaml", yaml);
        lv_mission *m = NULL;
        lv_err err;
        const lv_status st = lv_mission_load("test_heating_bad.yaml", &m, &err);
        printf("refused: %s\n", st != LV_OK ? err.msg : "(loaded)");
        CHECK(st == LV_ERR_INPUT);
        CHECK(st != LV_OK && strstr(err.msg, "test_heating_bad.yaml:") != NULL &&
              strstr(err.msg, bad[i].want) != NULL);
        lv_mission_free(m);
    }
}

int main(void)
{
    earth_case("dof3");
    earth_case("dof6");
    mars_case();
    fm_end_case();
    refusals();
    return check_report("test_heating");
}
