/* plot_html.c - OUTDIR/index.html: the run at a glance (mission, phase table, events, bodies,
 * the figures, the result files, the 3D view). Every text that comes from the mission file is
 * HTML-escaped; every link is percent-encoded. Plain HTML, no script. */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "io/atomic.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_units.h"
#include "post/plot.h"

static void esc(FILE *f, const char *s)
{
    for (; s != NULL && *s; s++)
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&#39;", f); break;
        default: fputc(*s, f);
        }
}

/* A relative link: bytes outside the URL's unreserved set (and '/') as %XX. */
static void url(FILE *f, const char *s)
{
    for (; s != NULL && *s; s++) {
        const unsigned char c = (unsigned char)*s;
        if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
            strchr("-._~/", c) != NULL)
            fputc(c, f);
        else
            fprintf(f, "%%%02X", c);
    }
}

static void link_to(FILE *f, const char *href, const char *text)
{
    fputs("<a href=\"", f);
    url(f, href);
    fputs("\">", f);
    esc(f, text);
    fputs("</a>", f);
}

/* A number with `prec` decimals (sign > 0: always signed). */
static void td_num(FILE *f, double v, int prec, int sign)
{
    fputs("<td>", f);
    if (isfinite(v))
        fprintf(f, sign > 0 ? "%+.*f" : "%.*f", prec, v);
    else
        fputs("&ndash;", f);
    fputs("</td>", f);
}

/* A number in 4 significant digits (a drift: 4.8e-08 m or 100 m). */
static void td_g(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "<td>%.4g</td>", v);
    else
        fputs("<td>&ndash;</td>", f);
}

static void td_text(FILE *f, const char *s)
{
    fputs("<td class=\"l\">", f);
    if (s != NULL)
        esc(f, s);
    else
        fputs("&ndash;", f);
    fputs("</td>", f);
}

static const char style[] =
    "body{font-family:sans-serif;max-width:1150px;margin:1em auto;padding:0 1em;color:#222}\n"
    "table{border-collapse:collapse;font-size:.9em;margin:.5em 0}\n"
    "th,td{border:1px solid #ccc;padding:2px 6px;text-align:right;vertical-align:top}\n"
    "th{background:#eee}td.l,th.l{text-align:left}tr.bad td{color:#a00}\n"
    "figure{margin:1.5em 0}img{max-width:100%;border:1px solid #ddd}\n"
    "figcaption{font-size:.9em}code{background:#f4f4f4;padding:0 3px}\n";

static void phase_table(FILE *f, const lv_results *res)
{
    fputs("<h2 id=\"phases\">Phases</h2>\n<table>\n<tr><th>#</th><th>phase</th><th>from</th>"
          "<th>stages</th><th>model</th><th>t0 [s]</th><th>t1 [s]</th><th>end</th>"
          "<th>steps</th><th>RHS evals</th><th>state events</th><th>time events</th>"
          "<th>CPU [ms]</th><th>status</th></tr>\n",
          f);
    for (size_t k = 0; k < res->n_phases; k++) {
        const lv_results_phase *ph = &res->phases[k];
        fputs(ph->done ? "<tr>" : "<tr class=\"bad\">", f);
        td_num(f, ph->index > 0 ? (double)ph->index : NAN, 0, 0);
        td_text(f, ph->name);
        td_text(f, ph->from ? ph->from : "(parameters)");
        fputs("<td class=\"l\">", f);
        for (size_t i = 0; i < ph->n_stages; i++) {
            fputs(i == 0 ? "" : ", ", f);
            esc(f, ph->stages[i]);
        }
        fputs("</td>", f);
        td_text(f, ph->model);
        td_num(f, ph->t_start, 3, 0);
        td_num(f, ph->t_end, 3, 0);
        fputs("<td class=\"l\">", f);
        if (ph->end_reason != NULL || ph->end_event != NULL || isfinite(ph->end_value)) {
            esc(f, ph->end_reason);
            if (ph->end_event != NULL) {
                fputs(": ", f);
                esc(f, ph->end_event);
            }
            if (isfinite(ph->end_value))
                fprintf(f, " (%g)", ph->end_value);
            if (ph->end_label != NULL) { /* the user's name of the end: "MECO" */
                fputs(" &ndash; ", f);
                esc(f, ph->end_label);
            }
        } else {
            fputs("&ndash;", f);
        }
        fputs("</td>", f);
        td_num(f, ph->steps, 0, 0);
        td_num(f, ph->rhs_evals, 0, 0);
        td_num(f, ph->state_events, 0, 0);
        td_num(f, ph->time_events, 0, 0);
        td_num(f, 1e3 * ph->cpu_time, 2, 0);
        fputs("<td class=\"l\">", f);
        esc(f, ph->state ? ph->state : "?");
        if (ph->error != NULL) {
            fputs(": ", f);
            esc(f, ph->error);
        }
        fputs("</td></tr>\n", f);
    }
    fputs("</table>\n", f);
}

/* Each phase's drift from its reference (an optimiser's trajectory; summary.json's
 * `reference` block: docs/result-files.md); nothing when no phase has one. */
static void reference_table(FILE *f, const lv_results *res)
{
    int any = 0;
    for (size_t k = 0; k < res->n_phases; k++)
        any |= res->phases[k].ref.present;
    if (!any)
        return;
    fputs("<h2 id=\"reference\">Drift from the reference</h2>\n<p>Each phase with a "
          "<code>reference:</code> (an optimiser's trajectory) against it at the result rows "
          "within its range: 3-D position, velocity relative to the planet, mass "
          "(docs/optimal-control.md).</p>\n<table>\n<tr><th>phase</th><th>rows</th>"
          "<th>position, largest [m]</th><th>at t [s]</th><th>final [m]</th>"
          "<th>velocity, largest [m/s]</th><th>final [m/s]</th><th>mass, largest [kg]</th>"
          "<th>final [kg]</th></tr>\n", f);
    for (size_t k = 0; k < res->n_phases; k++) {
        const lv_results_phase *ph = &res->phases[k];
        if (!ph->ref.present)
            continue;
        const double v[5] = {ph->ref.pos_final, ph->ref.vel_max, ph->ref.vel_final,
                             ph->ref.mass_max, ph->ref.mass_final};
        fputs("<tr>", f);
        td_text(f, ph->name);
        td_num(f, ph->ref.rows, 0, 0);
        td_g(f, ph->ref.pos_max);
        td_num(f, ph->ref.pos_max_t, 3, 0);
        for (int i = 0; i < 5; i++)
            td_g(f, v[i]);
        fputs("</tr>\n", f);
    }
    fputs("</table>\n", f);
}

typedef struct event_ref {
    double t;
    size_t order; /* position in summary.json: ties keep it */
    const lv_results_phase *phase;
    const lv_results_event *event;
} event_ref;

static int by_time(const void *a, const void *b)
{
    const event_ref *x = a, *y = b;
    if (x->t != y->t)
        return x->t < y->t ? -1 : 1;
    return x->order < y->order ? -1 : x->order > y->order;
}

/* Every logged event of every phase, in time order. */
static void event_list(FILE *f, const lv_results *res)
{
    fputs("<h2 id=\"events\">Events</h2>\n", f);
    size_t n = 0;
    for (size_t k = 0; k < res->n_phases; k++)
        n += res->phases[k].n_events;
    event_ref *refs = calloc(n + 1, sizeof *refs);
    n = 0;
    for (size_t k = 0; k < res->n_phases; k++) {
        const lv_results_phase *ph = &res->phases[k];
        for (size_t j = 0; j < ph->n_events; j++) {
            const lv_results_event *ev = &ph->events[j];
            if (refs != NULL)
                refs[n] = (event_ref){isfinite(ev->t) ? ev->t : INFINITY, n, ph, ev};
            n++;
        }
    }
    if (refs != NULL)
        qsort(refs, n, sizeof *refs, by_time);
    if (n > 0)
        fputs("<table>\n<tr><th>t [s]</th><th>phase</th><th>kind</th><th>event</th>"
              "<th>direction</th></tr>\n",
              f);
    for (size_t i = 0; i < n && refs != NULL; i++) {
        fputs("<tr>", f);
        td_num(f, refs[i].t, 6, 0);
        td_text(f, refs[i].phase->name);
        td_text(f, refs[i].event->kind);
        td_text(f, refs[i].event->name);
        td_num(f, refs[i].event->direction, 0, 1);
        fputs("</tr>\n", f);
    }
    fputs(n ? "</table>\n" : "<p>No events were logged.</p>\n", f);
    free(refs);
}

static void body_list(FILE *f, const lv_results *res)
{
    fputs("<h2 id=\"bodies\">Bodies</h2>\n<ul>\n", f);
    for (size_t i = 0; i < res->n_bodies; i++) {
        const lv_results_body *b = &res->bodies[i];
        fputs("<li><b>", f);
        esc(f, b->name);
        fputs("</b>: ", f);
        for (size_t j = 0; j < b->n_phases; j++) {
            fputs(j == 0 ? "" : " &rarr; ", f);
            esc(f, res->phases[b->phases[j]].name);
        }
        if (b->trajectory != NULL) {
            fputs(" (", f);
            link_to(f, b->trajectory, b->trajectory);
            fputs(")", f);
        }
        fputs("</li>\n", f);
    }
    fputs("</ul>\n", f);
}

static void plot_section(FILE *f, const lv_plot_list *l)
{
    fputs("<h2 id=\"plots\">Plots</h2>\n<p>Every body is one curve across all the phases it "
          "flies in; dashed grey lines mark where phases start. Each figure is also an SVG "
          "file.</p>\n",
          f);
    char href[128];
    for (size_t i = 0; i < l->n_made; i++) {
        fputs("<figure>\n<img src=\"", f);
        snprintf(href, sizeof href, "plots/%s.png", l->made[i].stem);
        url(f, href);
        fputs("\" alt=\"", f);
        esc(f, l->made[i].title);
        fputs("\">\n<figcaption>", f);
        esc(f, l->made[i].title);
        fputs(" &mdash; ", f);
        link_to(f, href, "PNG");
        fputs(", ", f);
        snprintf(href, sizeof href, "plots/%s.svg", l->made[i].stem);
        link_to(f, href, "SVG");
        fputs("</figcaption>\n</figure>\n", f);
    }
    if (l->n_skipped > 0) {
        fputs("<h3>Skipped</h3>\n<ul>\n", f);
        for (size_t i = 0; i < l->n_skipped; i++) {
            fputs("<li><code>", f);
            esc(f, l->skipped[i].what);
            fputs("</code>: ", f);
            esc(f, l->skipped[i].why);
            fputs("</li>\n", f);
        }
        fputs("</ul>\n", f);
    }
    if (l->n_notes > 0) {
        fputs("<h3>Notes</h3>\n<ul>\n", f);
        for (size_t i = 0; i < l->n_notes; i++) {
            fputs("<li>", f);
            esc(f, l->notes[i]);
            fputs("</li>\n", f);
        }
        fputs("</ul>\n", f);
    }
}

static void file_list(FILE *f, const lv_results *res)
{
    fputs("<h2 id=\"files\">Result files</h2>\n<ul>\n<li>", f);
    link_to(f, "summary.json", "summary.json");
    fputs(": per phase times, end, events, statistics, hand-off, final state</li>\n<li>", f);
    link_to(f, "key_figures.json", "key_figures.json");
    fputs(": the key figures above, SI units</li>\n<li>", f);
    link_to(f, "manifest.json", "manifest.json");
    fputs(": every file of the folder with its size and SHA-256, the mission file's SHA-256, "
          "the lvsim version and the time (written by <code>lvsim run</code>)</li>\n",
          f);
    for (size_t i = 0; i < res->n_bodies; i++) {
        const lv_results_body *b = &res->bodies[i];
        if (b->trajectory == NULL)
            continue;
        fputs("<li>", f);
        link_to(f, b->trajectory, b->trajectory);
        fputs(": body ", f);
        esc(f, b->name);
        fputs(", all its phases</li>\n", f);
    }
    for (size_t k = 0; k < res->n_phases; k++) {
        const lv_results_phase *ph = &res->phases[k];
        int n = 0; /* its result files, one per format written: "a.mat, a.csv" */
        for (size_t i = 0; lv_result_format_info(i, NULL, NULL) != NULL; i++) {
            if (ph->files[i] == NULL)
                continue;
            if (n++ == 0) {
                fputs("<li>phase ", f);
                esc(f, ph->name);
                fputs(": ", f);
            } else {
                fputs(", ", f);
            }
            link_to(f, ph->files[i], ph->files[i]);
        }
        if (n > 0)
            fputs("</li>\n", f);
    }
    fputs("</ul>\n", f);
}


/* ---- key figures (plot_keys.c's document, SI) -------------------------------------------- */

static double jnum(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static const char *jstr(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(v) ? v->valuestring : NULL;
}

/* " name = value unit" when the value is known: value * scale with prec decimals. */
static void kv(FILE *f, const char *name, double v, double scale, int prec, const char *unit,
               int *first)
{
    if (!isfinite(v))
        return;
    fprintf(f, "%s%s %.*f%s%s", *first ? "" : ", ", name, prec, v * scale,
            LV_UNIT_ONE(unit) ? "" : " ", LV_UNIT_AFTER_NUMBER(unit));
    *first = 0;
}

/* A state: t, altitude, speeds, flight-path angle, mass, position. */
static void state_text(FILE *f, const cJSON *s, int flat)
{
    int first = 1;
    kv(f, "t", jnum(s, "t"), 1.0, 3, "s", &first);
    kv(f, flat ? "z" : "h", jnum(s, "h"), 1e-3, 3, "km", &first);
    kv(f, flat ? "speed" : "v_rel", jnum(s, "speed"), 1.0, 1, "m/s", &first);
    kv(f, "v_inertial", jnum(s, "v_inertial"), 1.0, 1, "m/s", &first);
    kv(f, "fpa", jnum(s, "fpa"), 1.0 / LV_DEG, 2, "deg", &first);
    kv(f, "fpa_inertial", jnum(s, "fpa_inertial"), 1.0 / LV_DEG, 2, "deg", &first);
    kv(f, "vehicle mass", jnum(s, "vehicle_mass"), 1.0, 1, "kg", &first);
    kv(f, "stage mass", jnum(s, "stage_mass"), 1.0, 1, "kg", &first);
    kv(f, "lat", jnum(s, "lat"), 1.0 / LV_DEG, 4, "deg", &first);
    kv(f, "lon", jnum(s, "lon"), 1.0 / LV_DEG, 4, "deg", &first);
    kv(f, "x", jnum(s, "x"), 1e-3, 3, "km", &first);
    kv(f, "y", jnum(s, "y"), 1e-3, 3, "km", &first);
    const char *ph = jstr(s, "phase");
    if (ph != NULL) {
        fputs(" (phase ", f);
        esc(f, ph);
        fputs(")", f);
    }
}

static void key_row(FILE *f, const char *what)
{
    fputs("<tr><td class=\"l\">", f);
    esc(f, what);
    fputs("</td><td class=\"l\">", f);
}

static void key_section(FILE *f, const cJSON *doc, int flat)
{
    fputs("<h2 id=\"keys\">Key figures</h2>\n<p>Per body, across every phase it flies in "
          "(also in <a href=\"key_figures.json\">key_figures.json</a>, SI units). Dynamic "
          "pressure only where the atmosphere model is defined (&rho; &gt; 0, h &le; 1000 km); "
          "load factors in g<sub>0</sub> = 9.80665 m/s&sup2; distances on the sphere of "
          "radius 6371.0088 km.</p>\n",
          f);
    const cJSON *bodies = cJSON_GetObjectItemCaseSensitive(doc, "bodies"), *b;
    cJSON_ArrayForEach(b, bodies)
    {
        fputs("<h3>", f);
        esc(f, jstr(b, "name"));
        fputs("</h3>\n<table>\n<tr><th class=\"l\">figure</th><th class=\"l\">value</th></tr>\n", f);
        const cJSON *fin = cJSON_GetObjectItemCaseSensitive(b, "final");
        if (cJSON_IsObject(fin)) {
            key_row(f, "final state");
            state_text(f, fin, flat);
            fputs("; ended by ", f);
            esc(f, jstr(fin, "end"));
            fputs("</td></tr>\n", f);
        }
        const cJSON *q = cJSON_GetObjectItemCaseSensitive(b, "max_q");
        key_row(f, "max dynamic pressure");
        if (cJSON_IsObject(q)) {
            int first = 1;
            kv(f, "q", jnum(q, "value"), 1e-3, 3, "kPa", &first);
            kv(f, "at t", jnum(q, "t"), 1.0, 3, "s", &first);
            kv(f, "h", jnum(q, "h"), 1e-3, 3, "km", &first);
        } else {
            fputs(flat ? "&ndash; (flat world: no atmosphere)" : "&ndash; (no atmosphere met)", f);
        }
        fputs("</td></tr>\n", f);
        const cJSON *heat = cJSON_GetObjectItemCaseSensitive(b, "heating");
        if (cJSON_IsObject(heat)) { /* a planet's flight models */
            const cJSON *hs = cJSON_GetObjectItemCaseSensitive(heat, "max_heat_flux");
            const cJSON *hf = cJSON_GetObjectItemCaseSensitive(heat, "fm_below_1135");
            int first = 1;
            key_row(f, "max stagnation-point heat flux (Sutton-Graves)");
            kv(f, "q", jnum(hs, "value"), 1e-3, 3, "kW/m&sup2;", &first);
            kv(f, "at t", jnum(hs, "t"), 1.0, 3, "s", &first);
            kv(f, "h", jnum(hs, "h"), 1e-3, 3, "km", &first);
            kv(f, "heat load", jnum(heat, "heat_load"), 1e-6, 3, "MJ/m&sup2;", &first);
            fputs("</td></tr>\n", f);
            if (cJSON_IsObject(hf)) {
                first = 1;
                key_row(f, "free-molecular heat flux below 1135 W/m\xc2\xb2"); /* key_row escapes: UTF-8 ² */
                kv(f, "at t", jnum(hf, "t"), 1.0, 3, "s", &first);
                kv(f, "h", jnum(hf, "h"), 1e-3, 3, "km", &first);
                fputs("</td></tr>\n", f);
            }
        }
        const cJSON *iips = cJSON_GetObjectItemCaseSensitive(b, "iip_cutoff"), *ip;
        cJSON_ArrayForEach(ip, iips) /* the planet's flight models: IIP at each cut-off */
        {
            char what[160];
            snprintf(what, sizeof what, "IIP at the end of powered flight in %s",
                     jstr(ip, "phase") ? jstr(ip, "phase") : "?");
            key_row(f, what);
            int first = 1;
            kv(f, "at t", jnum(ip, "t"), 1.0, 3, "s", &first);
            kv(f, "h", jnum(ip, "h"), 1e-3, 3, "km", &first);
            if (cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(ip, "impact"))) {
                kv(f, "impact lat", jnum(ip, "iip_lat"), 1.0 / LV_DEG, 4, "deg", &first);
                kv(f, "lon", jnum(ip, "iip_lon"), 1.0 / LV_DEG, 4, "deg", &first);
                kv(f, "time of flight", jnum(ip, "iip_tof"), 1.0, 1, "s", &first);
                kv(f, "range", jnum(ip, "iip_range"), 1e-3, 1, "km", &first);
            } else {
                fputs(", no impact (the drag-free path stays in orbit)", f);
            }
            fputs("</td></tr>\n", f);
        }
        static const char *const nk[2] = {"max_n_axial", "max_n_normal"};
        static const char *const nt[2] = {"max axial load factor in flight",
                                          "max normal load factor in flight"};
        for (int i = 0; i < 2; i++) {
            const cJSON *n = cJSON_GetObjectItemCaseSensitive(b, nk[i]);
            key_row(f, nt[i]);
            if (cJSON_IsObject(n)) {
                int first = 1;
                kv(f, "n", jnum(n, "value"), 1.0, 3, "g0", &first);
                kv(f, "at t", jnum(n, "t"), 1.0, 3, "s", &first);
            } else {
                fputs(i == 0      ? "not available"
                      : flat        ? "&ndash; (flat world: no lift or side force)"
                                    : "&ndash;",
                      f);
            }
            fputs("</td></tr>\n", f);
        }
        const cJSON *e;
        cJSON_ArrayForEach(e, cJSON_GetObjectItemCaseSensitive(b, "burnouts"))
        {
            key_row(f, "burnout (its engines cut off)");
            state_text(f, e, flat);
            fputs("</td></tr>\n", f);
        }
        cJSON_ArrayForEach(e, cJSON_GetObjectItemCaseSensitive(b, "separations"))
        {
            key_row(f, jstr(e, "label") ? jstr(e, "label") : "separation");
            state_text(f, e, flat);
            fputs("</td></tr>\n", f);
        }
        const cJSON *inj = cJSON_GetObjectItemCaseSensitive(b, "injection");
        if (cJSON_IsObject(inj)) {
            const char *traj = jstr(inj, "trajectory");
            const int orbit = traj && strcmp(traj, "orbit") == 0;
            const int escape = traj && strcmp(traj, "escape") == 0;
            key_row(f, orbit    ? "injection into orbit (end of powered flight)"
                       : escape ? "injection on an escape trajectory (end of powered flight)"
                                : "end of powered flight (suborbital)");
            state_text(f, inj, flat);
            const cJSON *o = cJSON_GetObjectItemCaseSensitive(inj, "orbit");
            int first = 1;
            if (orbit || escape) {
                fputs("; osculating orbit: ", f);
                kv(f, "a", jnum(o, "sma"), 1e-3, 1, "km", &first);
                kv(f, "e", jnum(o, "ecc"), 1.0, 5, "", &first);
                kv(f, "i", jnum(o, "inc"), 1.0 / LV_DEG, 3, "deg", &first);
                kv(f, "apoapsis altitude", jnum(o, "apo_alt"), 1e-3, 1, "km", &first);
                kv(f, "periapsis altitude", jnum(o, "peri_alt"), 1e-3, 1, "km", &first);
            } else { /* a suborbital arc: its elements say little; the apoapsis it coasts to */
                fputs("; ballistic ", f);
                kv(f, "apoapsis altitude", jnum(o, "apo_alt"), 1e-3, 1, "km", &first);
            }
            fputs("</td></tr>\n", f);
        }
        const cJSON *gc = cJSON_GetObjectItemCaseSensitive(b, "ground_contact");
        if (cJSON_IsObject(gc)) {
            const char *kind = jstr(gc, "kind");
            key_row(f, kind && strcmp(kind, "landing") == 0 ? "landing point" : "impact point");
            int first = 1;
            kv(f, "t", jnum(gc, "t"), 1.0, 3, "s", &first);
            kv(f, "lat", jnum(gc, "lat"), 1.0 / LV_DEG, 4, "deg", &first);
            kv(f, "lon", jnum(gc, "lon"), 1.0 / LV_DEG, 4, "deg", &first);
            kv(f, "x", jnum(gc, "x"), 1e-3, 3, "km", &first);
            kv(f, "y", jnum(gc, "y"), 1e-3, 3, "km", &first);
            kv(f, "distance from the launch site", jnum(gc, "distance"), 1e-3, 3, "km", &first);
            kv(f, "from the guidance target", jnum(gc, "target_distance"), 1.0, 1, "m", &first);
            kv(f, "speed", jnum(gc, "speed"), 1.0, 1, "m/s", &first);
            /* the contact row's load: not in the flight's maxima above */
            kv(f, "axial load factor at contact", jnum(gc, "n_axial"), 1.0, 3, "g0", &first);
            if (!isfinite(jnum(gc, "n_axial"))) /* null: the model gives no way to it */
                fputs(", axial load factor at contact not available", f);
            fputs("</td></tr>\n", f);
        }
        const cJSON *td = cJSON_GetObjectItemCaseSensitive(b, "touchdown");
        if (cJSON_IsObject(td)) { /* a runway touchdown: landed or crashed, and the roll-out */
            const char *status = jstr(td, "status");
            const int crashed = status != NULL && strcmp(status, "crashed") == 0;
            key_row(f, crashed ? "touchdown: CRASHED" : "touchdown");
            /* a roll-out flown to a crash end: it stopped nowhere, it left the runway */
            const int overran = crashed && isfinite(jnum(td, "rollout_distance"));
            int first = 1;
            kv(f, "t", jnum(td, "t"), 1.0, 3, "s", &first);
            kv(f, "from the threshold", jnum(td, "from_threshold"), 1.0, 0, "m", &first);
            kv(f, "sink rate", jnum(td, "sink_rate"), 1.0, 2, "m/s", &first);
            kv(f, "ground speed", jnum(td, "ground_speed"), 1.0, 1, "m/s", &first);
            kv(f, "lateral offset", jnum(td, "lateral"), 1.0, 1, "m", &first);
            kv(f, "lateral speed", jnum(td, "lateral_speed"), 1.0, 2, "m/s", &first);
            kv(f, "pitch", jnum(td, "pitch"), 1.0 / LV_DEG, 1, "deg", &first);
            kv(f, "bank", jnum(td, "bank"), 1.0 / LV_DEG, 1, "deg", &first);
            kv(f, "roll-out", jnum(td, "rollout_distance"), 1.0, 0, "m", &first);
            kv(f, overran ? "ran off the runway's end at" : "stopped from the threshold",
               jnum(td, "stop_from_threshold"), 1.0, 0, "m", &first);
            if (overran)
                kv(f, "at", jnum(td, "stop_speed"), 1.0, 1, "m/s", &first);
            kv(f, "time on the runway", jnum(td, "time_on_runway"), 1.0, 1, "s", &first);
            if (crashed && jstr(td, "reason") != NULL) {
                fputs("<br>", f);
                esc(f, jstr(td, "reason"));
            }
            fputs("</td></tr>\n", f);
        }
        fputs("</table>\n", f);
    }
}

/* ---- the bodies' timelines (summary.json bodies[].timeline, lv_run_timeline) ------------- */

/* Two bodies with the same events at the same times (a stack until it separates): one table. */
static int same_timeline(const cJSON *a, const cJSON *b)
{
    if (cJSON_GetArraySize(a) != cJSON_GetArraySize(b))
        return 0;
    for (const cJSON *x = a ? a->child : NULL, *y = b ? b->child : NULL; x && y;
         x = x->next, y = y->next) {
        const char *lx = jstr(x, "label"), *ly = jstr(y, "label");
        const char *px = jstr(x, "phase"), *py = jstr(y, "phase");
        if (!lx || !ly || !px || !py || strcmp(lx, ly) != 0 || strcmp(px, py) != 0 ||
            jnum(x, "t") != jnum(y, "t"))
            return 0;
    }
    return 1;
}

static void timeline_section(FILE *f, const lv_results *res)
{
    const cJSON *bodies = cJSON_GetObjectItemCaseSensitive(res->json, "bodies");
    const cJSON *b;
    int any = 0;
    cJSON_ArrayForEach(b, bodies) any |= cJSON_IsArray(cJSON_GetObjectItemCaseSensitive(b, "timeline"));
    if (!any)
        return;
    fputs("<h2 id=\"timeline\">Timeline</h2>\n<p>Per body, from <code>summary.json</code> "
          "(<code>bodies[].timeline</code>): lift-off, max-q, the end of every phase it flies in "
          "(by the name the mission file gives it, else by its end condition), burnouts and named "
          "events within a phase, and each separation it takes part in, once. Each value is that "
          "of a row of the phase's results file (none interpolated): an end its phase's last row, "
          "a separation the first row after it. Mach and q only where the atmosphere model is "
          "defined. Bodies with the same events share a table.</p>\n",
          f);
    int idx = 0;
    cJSON_ArrayForEach(b, bodies)
    {
        const cJSON *tl = cJSON_GetObjectItemCaseSensitive(b, "timeline");
        int dup = 0, j = 0;
        for (const cJSON *o = bodies->child; o != NULL && j < idx && !dup; o = o->next, j++)
            dup = cJSON_IsArray(cJSON_GetObjectItemCaseSensitive(o, "timeline")) &&
                  same_timeline(cJSON_GetObjectItemCaseSensitive(o, "timeline"), tl);
        idx++;
        if (!cJSON_IsArray(tl) || dup)
            continue;
        fputs("<h3>", f);
        esc(f, jstr(b, "name"));
        for (const cJSON *o = b->next; o != NULL; o = o->next)
            if (same_timeline(tl, cJSON_GetObjectItemCaseSensitive(o, "timeline"))) {
                fputs(", ", f);
                esc(f, jstr(o, "name"));
            }
        fputs("</h3>\n<table>\n<tr><th class=\"l\">event</th><th>t [s]</th><th>h [km]</th>"
              "<th>speed [m/s]</th><th>Mach</th><th>q [kPa]</th><th class=\"l\">phase</th>"
              "<th class=\"l\">condition</th></tr>\n",
              f);
        const cJSON *e;
        cJSON_ArrayForEach(e, tl)
        {
            fputs("<tr>", f);
            td_text(f, jstr(e, "label"));
            td_num(f, jnum(e, "t"), 3, 0);
            td_num(f, jnum(e, "h") * 1e-3, 3, 0);
            td_num(f, jnum(e, "speed"), 1, 0);
            td_num(f, jnum(e, "mach"), 2, 0);
            td_num(f, jnum(e, "q") * 1e-3, 3, 0);
            td_text(f, jstr(e, "phase"));
            td_text(f, jstr(e, "event"));
            fputs("</tr>\n", f);
        }
        fputs("</table>\n", f);
    }
}

lv_status lv_plot_html_write(const lv_plot_data *d, const lv_plot_list *l, const cJSON *keys,
                             lv_err *err)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/index.html", d->outdir);
    lv_atomic out;
    lv_status st = lv_atomic_open(&out, path, err);
    if (st != LV_OK)
        return st;
    FILE *f = out.fp;
    const lv_results *s = d->res;
    const char *name = s->mission ? s->mission : "mission";
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>", f);
    esc(f, name);
    fprintf(f, " &mdash; lvsim</title>\n<style>\n%s</style>\n</head>\n<body>\n<h1>", style);
    esc(f, name);
    fputs("</h1>\n<p>Mission file <code>", f);
    esc(f, s->file ? s->file : "?");
    fputs("</code>; epoch ", f);
    esc(f, s->epoch ? s->epoch : "?");
    /* summary.json "time": the leap seconds inside the mission (t counts them, as SI seconds)
     * and the note when ERFA's table cannot vouch for its dates */
    const cJSON *tm = cJSON_GetObjectItemCaseSensitive(s->json, "time"), *ls;
    cJSON_ArrayForEach(ls, cJSON_GetObjectItemCaseSensitive(tm, "leap_seconds"))
    {
        fputs(" (leap second ", f);
        esc(f, jstr(ls, "utc") ? jstr(ls, "utc") : "?");
        fprintf(f, " at t = %.3f s)", jnum(ls, "t"));
    }
    if (jstr(tm, "note") != NULL) {
        fputs(" (", f);
        esc(f, jstr(tm, "note"));
        fputc(')', f);
    }
    fputs("; world ", f);
    esc(f, s->world ? s->world : "?");
    fputs("; lvsim ", f);
    esc(f, s->lvsim ? s->lvsim : "?");
    fprintf(f, "; %zu phases, %zu bodies.</p>\n", d->n_phases, d->n_bodies);
    fputs("<p><a href=\"#keys\">Key figures</a> &middot; <a href=\"#timeline\">Timeline</a> "
          "&middot; <a href=\"#phases\">Phases</a> "
          "&middot; <a href=\"#events\">Events</a> &middot; <a href=\"#bodies\">Bodies</a> "
          "&middot; <a href=\"#plots\">Plots</a> &middot; <a href=\"#files\">Result files</a> "
          "&middot; <a href=\"#view\">3D view</a></p>\n",
          f);
    /* The viewer loads mission.czml and summary.json with fetch(), which browsers refuse on
     * file:// pages: it needs a server, which `lvsim view` is. */
    fputs("<p id=\"view\"><b><a href=\"viewer/index.html\">3D view</a></b>: run <code>lvsim "
          "view FOLDER</code> on this results folder; it serves the folder on http://127.0.0.1 "
          "and prints the viewer's address (this report is then at the same address, and the "
          "link works). Opened from disk (a <code>file://</code> address) the viewer cannot "
          "load its data: browsers do not let a page read files that way.</p>\n",
          f);
    if (keys != NULL)
        key_section(f, keys, d->flat);
    timeline_section(f, s);
    phase_table(f, s);
    reference_table(f, s);
    event_list(f, s);
    body_list(f, s);
    plot_section(f, l);
    file_list(f, s);
    fputs("</body>\n</html>\n", f);
    return lv_atomic_commit(&out, err);
}
