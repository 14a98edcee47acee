/* test_heat_load.c - the heat loads heat_load and heat_load_fm of the flight models over a
 * planet (docs/models.md, "Aerothermal heating"): the time integrals of heat_flux and
 * heat_flux_fm, integrated as quadrature states out of the error control.
 *   (a) closed form: a drag-free circular orbit (no aerodynamic data) at h = 100 km around a
 *       non-rotating sphere with point-mass gravity, through an exponential atmosphere
 *       rho = 1.225 exp(-h / 7000 m): altitude, speed V = sqrt(gm / (R + h)) and density are
 *       constant, so over T seconds
 *           heat_load    = k sqrt(rho / r_n) V^3 T      (Sutton-Graves, k = 1.7415e-4)
 *           heat_load_fm = rho V^3 T / 2,
 *       in dof3 and dof6; an end {heat_load: Q} stops at T = Q / q;
 *   (b) hand-off: the orbit flown as two phases, the child starting from its parent's final
 *       heat load, ends with the one phase's load;
 *   (c) an independent quadrature: a coast up through US76 (the density and the
 *       speed change along the arc), heat_load at its end against the composite Simpson rule
 *       over the phase's heat_flux rows every 0.05 s (written here, on the output column);
 *   (d) the targeting section accepts `final: PHASE.heat_load`. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"
#include "mission_kit.h"

#define R_SPHERE 6371000.0
#define GM 3.986004418e14
#define H_ORBIT 100000.0
#define K_SG 1.7415e-4

static const char *const dof6_body =
    ",\n     rigid_body: {inertia_full: {xx: 100, yy: 900, zz: 900},\n"
    "                  inertia_empty: {xx: 100, yy: 900, zz: 900}, cg_full: {x: -1},\n"
    "                  cg_empty: {x: -1}}";

static double final_of(const lv_run *r, size_t k, const char *name)
{
    double v = NAN;
    lv_err err;
    CHECK_OK(lv_run_final(r, k, name, &v, &err), &err);
    return v;
}

/* The orbit's mission: phases `phases` (text) of model `model`. */
static void orbit_yaml(char *buf, size_t cap, const char *model, const char *phases)
{
    const int six = strcmp(model, "dof6") == 0;
    snprintf(buf, cap,
             "mission: {name: heat-load, epoch: 2026-03-01T12:00:00Z}\n"
             "environment: {world: planet, gravity: pointmass,\n"
             "  planet: {name: sphere, radius: 6371000, gm: 3.986004418e14, rotation_rate: 0},\n"
             "  atmosphere: {model: exp, rho0: 1.225, scale_height: 7000, temperature: 200}}\n"
             "parameters: {start_lat_deg: 0, start_lon_deg: 0, start_h: 100000,\n"
             "             start_vel: %.17g, start_fpa_deg: 0, start_chi_deg: 90}\n"
             "stages:\n"
             "  - {name: capsule, dry_mass: 1000, propellant_mass: 0, nose_radius: 0.5%s}\n"
             "phases:\n%s",
             sqrt(GM / (R_SPHERE + H_ORBIT)), six ? dof6_body : "", phases);
}

static void orbit_case(const char *model)
{
    const double v = sqrt(GM / (R_SPHERE + H_ORBIT)), rho = 1.225 * exp(-H_ORBIT / 7000.0);
    const double q_sg = K_SG * sqrt(rho / 0.5) * v * v * v, q_fm = 0.5 * rho * v * v * v;
    char phases[1024], yaml[4096];
    /* (a) one phase of 600 s */
    snprintf(phases, sizeof phases,
             "  - {name: orbit, model: %s, stages: [capsule], start_time: 0, stop_time: 600%s}\n",
             model, strcmp(model, "dof3") == 0 ? ", throttle: off" : "");
    orbit_yaml(yaml, sizeof yaml, model, phases);
    lv_mission *m = NULL;
    lv_run *r = run_text("test_heat_load_orbit.yaml", yaml, &m);
    CHECK(r != NULL);
    double one = NAN;
    if (r != NULL) {
        one = final_of(r, 0, "heat_load");
        const double fm = final_of(r, 0, "heat_load_fm"), h = final_of(r, 0, "h");
        printf("%s orbit 600 s: h %.3f m, heat_load %.9g J/m2 (closed form %.9g), heat_load_fm "
               "%.9g (%.9g)\n", model, h, one, q_sg * 600.0, fm, q_fm * 600.0);
        CHECK_CLOSE(h, H_ORBIT, 0.01);
        CHECK_REL(one, q_sg * 600.0, 1e-7);
        CHECK_REL(fm, q_fm * 600.0, 1e-7);
    }
    lv_run_free(r);
    lv_mission_free(m);

    /* (b) 250 s, then a child to 600 s */
    snprintf(phases, sizeof phases,
             "  - {name: first, model: %s, stages: [capsule], start_time: 0, stop_time: 250%s}\n"
             "  - {name: second, model: %s, from: first, stages: [capsule], stop_time: 600%s}\n",
             model, strcmp(model, "dof3") == 0 ? ", throttle: off" : "", model,
             strcmp(model, "dof3") == 0 ? ", throttle: off" : "");
    orbit_yaml(yaml, sizeof yaml, model, phases);
    r = run_text("test_heat_load_orbit2.yaml", yaml, &m);
    CHECK(r != NULL);
    if (r != NULL) {
        const double first = final_of(r, 0, "heat_load"), second = final_of(r, 1, "heat_load");
        printf("%s two phases: heat_load %.9g at 250 s (closed form %.9g), %.9g at 600 s\n",
               model, first, q_sg * 250.0, second);
        CHECK_REL(first, q_sg * 250.0, 1e-7);
        CHECK_REL(second, q_sg * 600.0, 1e-7);
        CHECK_REL(second, one, 1e-7);
    }
    lv_run_free(r);
    lv_mission_free(m);

    /* an end on the heat load: Q = 3e7 J/m^2 is reached at T = Q / q */
    snprintf(phases, sizeof phases,
             "  - {name: orbit, model: %s, stages: [capsule], start_time: 0, stop_time: 2000%s,\n"
             "     end: [{heat_load: 3.0e7}]}\n",
             model, strcmp(model, "dof3") == 0 ? ", throttle: off" : "");
    orbit_yaml(yaml, sizeof yaml, model, phases);
    r = run_text("test_heat_load_end.yaml", yaml, &m);
    CHECK(r != NULL);
    if (r != NULL) {
        const double t = final_of(r, 0, "time");
        printf("%s end {heat_load: 3e7}: t %.9g s (closed form %.9g)\n", model, t, 3.0e7 / q_sg);
        CHECK_REL(t, 3.0e7 / q_sg, 1e-7);
        CHECK_REL(final_of(r, 0, "heat_load"), 3.0e7, 1e-9);
    }
    lv_run_free(r);
    lv_mission_free(m);
}

/* (c) a coast up through US76 from 50 km at 3 km/s, 40 deg, for 120 s, with drag (CD S =
 * 1 m^2): heat_load against Simpson's rule over the 2400 intervals of the heat_flux rows (its
 * error ~ dt^4: far below the tolerance checked). Measured 7e-7 (dop853, 24 steps at the
 * default tolerance 1e-9); the quadrature is as accurate as the steps the states need: without
 * drag the same coast takes 7 steps that do not see the air, and the load is 5e-4 off
 * (docs/models.md, "Heat load"). */
static void simpson_case(void)
{
    const char *yaml =
        "mission: {name: heat-load-arc, epoch: 2026-03-01T12:00:00Z}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 50000,\n"
        "             start_vel: 3000, start_fpa_deg: 40, start_chi_deg: 90}\n"
        "stages:\n"
        "  - {name: capsule, dry_mass: 1000, propellant_mass: 0, nose_radius: 0.3}\n"
        "phases:\n"
        "  - {name: arc, model: dof3, stages: [capsule], start_time: 0, stop_time: 120,\n"
        "     throttle: off, aero: {s_ref: 1, CD: 1}, integrator: {output_interval: 0.05}}\n";
    lv_mission *m = NULL;
    lv_run *r = run_text("test_heat_load_arc.yaml", yaml, &m);
    CHECK(r != NULL);
    if (r != NULL) {
        lv_err err;
        const lv_result *res = lv_run_rows(r, 0);
        size_t ct = 0, cq = 0, cf = 0;
        CHECK(res != NULL);
        if (res != NULL) {
            CHECK_OK(lv_result_column(res, "time", &ct, &err), &err);
            CHECK_OK(lv_result_column(res, "heat_flux", &cq, &err), &err);
            CHECK_OK(lv_result_column(res, "heat_flux_fm", &cf, &err), &err);
            const size_t n = lv_result_rows(res);
            CHECK(n == 2401);
            double s_sg = 0.0, s_fm = 0.0;
            const double dt = 0.05;
            for (size_t i = 0; n == 2401 && i < n; i++) {
                const double w = (i == 0 || i == n - 1) ? 1.0 : (i % 2 ? 4.0 : 2.0);
                CHECK_CLOSE(lv_result_value(res, i, ct), dt * (double)i, 1e-9);
                s_sg += w * lv_result_value(res, i, cq);
                s_fm += w * lv_result_value(res, i, cf);
            }
            s_sg *= dt / 3.0;
            s_fm *= dt / 3.0;
            const double load = final_of(r, 0, "heat_load"), fm = final_of(r, 0, "heat_load_fm");
            printf("arc 120 s: heat_load %.9g J/m2 (Simpson %.9g), heat_load_fm %.9g (%.9g), "
                   "h %.0f m\n", load, s_sg, fm, s_fm, final_of(r, 0, "h"));
            CHECK_REL(load, s_sg, 1e-5);
            CHECK_REL(fm, s_fm, 1e-5);
            CHECK(load > 1e5); /* the arc is heated: not a comparison of zeros */
        }
    }
    lv_run_free(r);
    lv_mission_free(m);
}

/* (d) targeting: a constraint on a phase's final heat load is a final like any state */
static void targeting_case(void)
{
    char phases[1024], yaml[4096];
    snprintf(phases, sizeof phases,
             "  - {name: orbit, model: dof3, stages: [capsule], start_time: 0, stop_time: 600,\n"
             "     throttle: off}\n"
             "targeting:\n"
             "  variables: [{name: orbit.stop_time, min: 100, max: 1000}]\n"
             "  constraints: [{final: orbit.heat_load, equal: 3.0e7, tolerance: 1000}]\n");
    orbit_yaml(yaml, sizeof yaml, "dof3", phases);
    write_file("test_heat_load_target.yaml", yaml);
    lv_mission *m = NULL;
    lv_err err;
    CHECK_OK(lv_mission_load("test_heat_load_target.yaml", &m, &err), &err);
    lv_mission_free(m);
}

int main(void)
{
    orbit_case("dof3");
    orbit_case("dof6");
    simpson_case();
    targeting_case();
    return check_report("test_heat_load");
}
