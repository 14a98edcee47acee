/* parse.c - mission files (YAML) to lv_mission_def. Keys, types, units, names, references,
 * tables and the phase tree are validated before anything runs; every error reads
 * "file:line:column: message". Format: docs/mission-format.md. The shared parameter set is
 * the paper's userPar (sec. 2.1), the phase tree its sequential simulation (sec. 3).
 *
 * This file reads the file and its root keys; each section has its own file: parse_env.c
 * (environment), parse_vehicle.c (stages), parse_params.c (parameters), parse_phase.c
 * (phases), parse_tree.c (the phase tree), with the tools of parse_kit.c that the phase
 * types use too (parse_kit.h). */
#include "mission/mission.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/utc.h"
#include "io/readfile.h"
#include "mission/dispersion.h"
#include "mission/parse_int.h"
#include "mission/phase_type.h"
#include "mission/reference.h"
#include "mission/ocp_def.h"
#include "mission/targeting_def.h"


/* ---- the file ------------------------------------------------------------------------- */

/* NULL when `s` is a UTC instant written "YYYY-MM-DDThh:mm:ss[.f...]Z" that exists in the
 * proleptic Gregorian calendar and in UTC; otherwise why not. A second 60 exists only in a leap
 * second, 23:59:60 of a day that ended with one (ERFA's table of them, core/utc.h): mission
 * time counts SI seconds from the epoch, and the exports place the epoch and every later
 * instant with the same table. */
static const char *epoch_check(const char *s)
{
    static const char *const form = "an ISO 8601 UTC time like 2026-03-01T12:00:00Z expected";
    /* the fixed part: digits at these positions, separators at the others */
    static const char tmpl[] = "dddd-dd-ddTdd:dd:dd";
    for (size_t i = 0; i < sizeof tmpl - 1; i++) {
        const char ch = s[i];
        if (tmpl[i] == 'd' ? !(ch >= '0' && ch <= '9') : ch != tmpl[i])
            return form;
    }
    const char *p = s + sizeof tmpl - 1;
    if (*p == '.') { /* a fraction of a second: one digit or more */
        const char *q = ++p;
        while (*p >= '0' && *p <= '9')
            p++;
        if (p == q)
            return form;
    }
    if (p[0] != 'Z')
        return "the time must end with Z (UTC), without a zone offset";
    if (p[1] != '\0')
        return "text after the Z";
    int v[6];
    static const int at[6] = {0, 5, 8, 11, 14, 17}, len[6] = {4, 2, 2, 2, 2, 2};
    for (int k = 0; k < 6; k++) {
        v[k] = 0;
        for (int i = 0; i < len[k]; i++)
            v[k] = 10 * v[k] + (s[at[k] + i] - '0');
    }
    const int y = v[0], mo = v[1], d = v[2];
    static const int mdays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const int leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
    if (mo < 1 || mo > 12)
        return "the month must be 01 to 12";
    if (d < 1 || d > mdays[mo - 1] + (mo == 2 && leap))
        return "no such day in that month";
    if (v[3] > 23)
        return "the hour must be 00 to 23";
    if (v[4] > 59)
        return "the minute must be 00 to 59";
    if (v[5] > 60)
        return "the second must be 00 to 59 (60 only in a leap second)";
    lv_tai tai;
    if (v[5] == 60 && lv_utc_parse(s, &tai) == LV_UTC_NO_LEAP)
        return "no leap second here: a second 60 exists only as 23:59:60 at the end of a day "
               "that had one (IERS Bulletin C, e.g. 2016-12-31T23:59:60Z)";
    return NULL;
}

/* The mission's `key` (a scalar) holds at most `max` bytes and, with `line`, no control
 * character: what every result file copies stays bounded and one line (an OEM header, a CSV
 * title). */
static lv_status text_bounded(const lv_pctx *c, const lv_ynode *v, const char *key, size_t max,
                              int line)
{
    if (v->kind != LV_YNODE_SCALAR)
        return LV_OK; /* lv_pk_text says what it is */
    if (v->len > max)
        return lv_pk_fail(c, v, "mission: %s of %zu bytes: at most %zu (it is copied into every "
                          "result file)", key, v->len, max);
    for (size_t i = 0; line && i < v->len; i++) {
        const unsigned char ch = (unsigned char)v->text[i];
        const unsigned char n1 = i + 1 < v->len ? (unsigned char)v->text[i + 1] : 0;
        const unsigned char n2 = i + 2 < v->len ? (unsigned char)v->text[i + 2] : 0;
        if (ch < 0x20 || ch == 0x7f)
            return lv_pk_fail(c, v, "mission: %s: one line of text without control characters "
                              "(byte %zu is 0x%02x)", key, i + 1, ch);
        /* UTF-8 of the C1 controls U+0080..U+009F (NEL U+0085 is a YAML line break; CSI
         * U+009B a terminal escape) and of the line and paragraph separators U+2028, U+2029 */
        if ((ch == 0xc2 && n1 >= 0x80 && n1 <= 0x9f) ||
            (ch == 0xe2 && n1 == 0x80 && (n2 == 0xa8 || n2 == 0xa9)))
            return lv_pk_fail(c, v, "mission: %s: one line of text without control characters "
                              "(bytes %zu.. are U+%04X)", key, i + 1,
                              ch == 0xc2 ? (unsigned)n1 : 0x2000u + (n2 - 0x80u));
    }
    return LV_OK;
}

static lv_status parse_root(const lv_pctx *c, const lv_ynode *root)
{
    static const char *const keys[] = { "mission", "environment", "parameters", "stages",
                                        "phases", "dispersions", "targeting",
                                        "optimal_control", NULL };
    static const char *const mkeys[] = { "name", "description", "epoch", NULL };
    lv_mission_def *m = c->m;
    const lv_ynode *v, *info;
    char buf[64];
    lv_status st;

    if (root->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, root, "the top level must be a mapping with 'mission', 'stages' and "
                    "'phases', found %s", lv_pk_describe(root, buf, sizeof buf));
    if ((st = lv_pk_check_map(c, root, "top level", keys)) != LV_OK ||
        (st = lv_pk_need(c, root, "top level", "mission", &info)) != LV_OK ||
        (st = lv_pk_check_map(c, info, "mission", mkeys)) != LV_OK ||
        (st = lv_pk_need(c, info, "mission", "name", &v)) != LV_OK ||
        (st = text_bounded(c, v, "name", LV_MISSION_NAME_MAX, 1)) != LV_OK ||
        (st = lv_pk_str(c, v, "mission", "name", &m->name)) != LV_OK)
        return st;
    if (strspn(m->name, " ") == strlen(m->name)) /* it names the results, the FMU, the exports */
        return lv_pk_fail(c, v, "mission: name: at least one character that is not a blank");
    if ((v = lv_pk_get(info, "epoch")) != NULL) {
        const char *ep;
        if ((st = lv_pk_text(c, v, "mission", "epoch", &ep)) != LV_OK)
            return st;
        /* ISO 8601 UTC, as CZML and CCSDS OEM want it: 2026-03-01T12:00:00Z */
        const char *why = epoch_check(ep);
        if (why != NULL)
            return lv_pk_fail(c, v, "mission: epoch: '%.40s': %s", ep, why);
        if ((m->epoch = lv_pk_strdup(ep)) == NULL)
            return lv_pk_nomem(c);
    }
    if ((v = lv_pk_get(info, "description")) != NULL && !lv_yaml_is_null(v) &&
        ((st = text_bounded(c, v, "description", LV_DESCRIPTION_MAX, 0)) != LV_OK ||
         (st = lv_pk_str(c, v, "mission", "description", &m->description)) != LV_OK))
        return st;
    if ((st = lv_parse_env(c, lv_pk_get(root, "environment"))) != LV_OK ||
        (st = lv_parse_params(c, lv_pk_get(root, "parameters"))) != LV_OK)
        return st;
    if ((st = lv_pk_need(c, root, "top level", "stages", &v)) != LV_OK ||
        (st = lv_parse_stages(c, v)) != LV_OK)
        return st;
    if ((st = lv_pk_need(c, root, "top level", "phases", &v)) != LV_OK ||
        (st = lv_parse_phases(c, v)) != LV_OK ||
        (st = lv_targeting_def_parse(c, lv_pk_get(root, "targeting"))) != LV_OK ||
        (st = lv_ocp_def_parse(c, lv_pk_get(root, "optimal_control"))) != LV_OK)
        return st;
    /* after everything else: it names the parameters the other sections register */
    if ((st = lv_disp_def_parse(c, lv_pk_get(root, "dispersions"))) != LV_OK)
        return st;
    return lv_pk_check_slot_names(c);
}

lv_status lv_mission_def_parse(const char *text, size_t len, const char *name, const char *dir,
                               lv_mission_def **out, lv_err *err)
{
    lv_ynode *root = NULL;
    lv_status st;

    if (out == NULL || (text == NULL && len > 0))
        return lv_fail(err, LV_ERR_INPUT, "lv_mission_def_parse: NULL argument");
    *out = NULL;
    lv_mission_def *m = calloc(1, sizeof *m);
    if (m == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", name ? name : "mission");
    m->path = lv_pk_strdup(name != NULL ? name : "<mission>");
    m->dir = lv_pk_strdup(dir != NULL ? dir : ".");
    if (m->path == NULL || m->dir == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", name ? name : "mission");
        goto fail;
    }
    const lv_pctx c = { m->path, err, m, LV_OWN_ENV, 0 };
    if ((st = lv_yaml_load(text != NULL ? text : "", len, m->path, &root, err)) != LV_OK ||
        (st = parse_root(&c, root)) != LV_OK)
        goto fail;
    lv_yaml_free(root);
    *out = m;
    return LV_OK;
fail:
    lv_yaml_free(root);
    lv_mission_def_free(m);
    return st;
}

lv_status lv_mission_def_load(const char *path, lv_mission_def **out, lv_err *err)
{
    char *text = NULL, *dir = NULL;
    size_t len = 0;
    lv_status st;

    if (out == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_mission_def_load: NULL argument");
    *out = NULL;
    if ((st = lv_read_file(path, LV_MISSION_FILE_MAX, "the mission file", &text, &len, err)) !=
        LV_OK)
        return st;
    const char *slash = strrchr(path, '/');
    const size_t nd = slash == NULL ? 1 : (slash == path ? 1 : (size_t)(slash - path));
    if ((dir = malloc(nd + 1)) == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
        goto fail;
    }
    memcpy(dir, slash == NULL ? "." : path, nd);
    dir[nd] = '\0';
    st = lv_mission_def_parse(text, len, path, dir, out, err);
fail:
    free(text);
    free(dir);
    return st;
}

void lv_mission_def_free(lv_mission_def *m)
{
    if (m == NULL)
        return;
    free(m->name);
    free(m->description);
    free(m->epoch);
    free(m->env.atmo_file);
    free(m->env.atmo_var);
    free(m->env.wind_file);
    free(m->env.wind_var);
    for (size_t i = 0; i < m->env.n_wind_prof; i++)
        free(m->env.wind_prof_file[i]);
    free(m->env.wind_prof_file);
    free(m->env.wind_prof_t);
    free(m->path);
    free(m->dir);
    for (size_t i = 0; i < m->n_files; i++)
        free(m->files[i]);
    free(m->files);
    free(m->env.planet);
    free(m->env.pdef.zonal);
    free(m->env.pdef.coef_file);
    free(m->env.gravity);
    free(m->env.atmosphere);
    for (size_t i = 0; i < m->n_params; i++)
        free(m->param_names[i]);
    free(m->param_names);
    free(m->param_values);
    for (size_t i = 0; i < m->n_slots; i++) {
        free(m->slots[i].name);
        free(m->slots[i].unit);
    }
    free(m->slots);
    for (size_t i = 0; i < m->n_stages; i++) {
        lv_stage_def *s = &m->stages[i];
        for (size_t k = 0; k < s->n_engines; k++) {
            free(s->engines[k].name);
            free(s->engines[k].table_file);
            free(s->engines[k].table_var);
            lv_table_free(s->engines[k].table);
        }
        free(s->engines);
        free(s->name);
    }
    free(m->stages);
    for (size_t i = 0; i < m->n_phases; i++) {
        lv_phase_def *ph = &m->phases[i];
        free(ph->name);
        if (ph->type != NULL && ph->type->cfg_free != NULL)
            ph->type->cfg_free(ph->type_cfg);
        free(ph->params);
        free(ph->stages);
        free(ph->stage_locs);
        for (size_t j = 0; j < ph->n_ends; j++) {
            free(ph->ends[j].var);
            free(ph->ends[j].label);
        }
        free(ph->ends);
        free(ph->end_name);
        free(ph->separation_label);
        free(ph->method);
        for (size_t k = 0; k < ph->n_set; k++)
            free(ph->set_names[k]);
        free(ph->set_names);
        free(ph->set_values);
        free(ph->set_locs);
        free(ph->set_deg);
        free(ph->engines_run);
        for (size_t j = 0; j < ph->n_engine_out; j++)
            free(ph->engine_out[j].label);
        free(ph->engine_out);
        free(ph->iip_at);
        lv_reference_free(ph->reference);
    }
    free(m->phases);
    lv_targeting_def_free(m->targeting);
    lv_ocp_def_free(m->ocp);
    lv_disp_def_free(m->disp);
    free(m);
}

double lv_mission_def_param(const lv_mission_def *m, const char *name, double fallback)
{
    if (m == NULL || name == NULL)
        return fallback;
    for (size_t i = 0; i < m->n_params; i++)
        if (strcmp(m->param_names[i], name) == 0)
            return m->slots[m->param_values[i]].value;
    return fallback;
}

double lv_mission_def_value(const lv_mission_def *m, lv_slot s)
{
    return s < m->n_slots ? m->slots[s].value : NAN;
}

lv_slot lv_mission_def_slot(const lv_mission_def *m, const char *name)
{
    for (size_t i = 0; i < m->n_slots; i++)
        if (strcmp(m->slots[i].name, name) == 0)
            return i;
    return LV_NO_SLOT;
}

