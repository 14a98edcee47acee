/* results.c - a results folder read back (results.h): summary.json with cJSON into plain
 * structures, and lvsim's CSV result files (docs/result-files.md; RFC 4180 quoting, as
 * io/result_csv.c and the body trajectories write them) into tables addressed by column name.
 * The one reader behind the exports, the figures and the report. */
#define _POSIX_C_SOURCE 200809L

#include "post/results.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/status.h"
#include "io/numparse.h"
#include "io/readfile.h"
#include "lvsim/lv_io.h"

/* ---------------------------------------------------------------- helpers -- */

static char *dup_str(const char *s)
{
    const size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d != NULL)
        memcpy(d, s, n);
    return d;
}

/* "dir/name" into a new string; NULL when out of memory. */
static char *join(const char *dir, const char *name)
{
    const size_t a = strlen(dir), b = strlen(name);
    char *s = malloc(a + b + 2);
    if (s != NULL) {
        memcpy(s, dir, a);
        s[a] = '/';
        memcpy(s + a + 1, name, b + 1);
    }
    return s;
}

/* A file named in summary.json is a bare name in OUTDIR: nothing that climbs out of it. */
static int bare_name(const char *s)
{
    return s[0] != '\0' && strchr(s, '/') == NULL && strcmp(s, ".") != 0 && strcmp(s, "..") != 0;
}


/* ---------------------------------------------------------------- summary -- */

static const char *json_str(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(v) ? v->valuestring : NULL;
}

static double json_num(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

int lv_results_phase_find(const lv_results *r, const char *name)
{
    for (size_t i = 0; name != NULL && i < r->n_phases; i++)
        if (r->phases[i].name != NULL && strcmp(r->phases[i].name, name) == 0)
            return (int)i;
    return -1;
}

static lv_status file_name(const lv_results *r, const char *what, const char *who,
                           const char *key, const char *name, lv_err *err)
{
    if (name == NULL || bare_name(name))
        return LV_OK;
    return lv_fail(err, LV_ERR_INPUT, "%s: %s '%s': %s '%.200s' is not a file name in the folder",
                   r->summary_path, what, who, key, name);
}

static lv_status read_phase(lv_results *r, const cJSON *pj, size_t i, lv_err *err)
{
    lv_results_phase *p = &r->phases[i];
    p->parent = -1;
    p->name = json_str(pj, "name");
    if (p->name == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: phases[%zu]: no 'name'", r->summary_path, i);
    const cJSON *ix = cJSON_GetObjectItemCaseSensitive(pj, "index");
    if (ix != NULL && !cJSON_IsNull(ix)) {
        if (!cJSON_IsNumber(ix) || !(ix->valuedouble >= 1.0 && ix->valuedouble <= 1e6))
            return lv_fail(err, LV_ERR_INPUT, "%s: phase '%s': index %g out of range (1 .. 10^6)",
                           r->summary_path, p->name, cJSON_IsNumber(ix) ? ix->valuedouble : NAN);
        p->index = (int)ix->valuedouble;
    }
    p->from = json_str(pj, "from");
    p->state = json_str(pj, "state");
    p->done = p->state != NULL && strcmp(p->state, "done") == 0;
    p->error = json_str(pj, "error");
    p->model = json_str(pj, "model");
    p->t_start = json_num(pj, "t_start");
    p->t_end = json_num(pj, "t_end");

    const cJSON *end = cJSON_GetObjectItemCaseSensitive(pj, "end");
    p->end_reason = json_str(end, "reason");
    p->end_event = json_str(end, "event");
    p->end_label = json_str(end, "label");
    /* a phase that ended by a crash end (a roll off the runway's end) was flown: its times,
     * events and rows are complete (a crash at the hand-off has no end event) */
    p->done |= p->state != NULL && strcmp(p->state, "crashed") == 0 && p->end_event != NULL;
    p->end_value = json_num(end, "value");

    const cJSON *stats = cJSON_GetObjectItemCaseSensitive(pj, "stats");
    p->steps = json_num(stats, "steps");
    p->rhs_evals = json_num(stats, "rhs_evals");
    p->state_events = json_num(stats, "state_events");
    p->time_events = json_num(stats, "time_events");
    p->cpu_time = json_num(stats, "cpu_time");

    const cJSON *files = cJSON_GetObjectItemCaseSensitive(pj, "files");
    const char *fmt;
    for (size_t k = 0; (fmt = lv_result_format_info(k, NULL, NULL)) != NULL; k++) {
        if (k >= LV_RESULTS_MAX_FORMATS) /* not reached: test_results.c */
            return lv_fail(err, LV_ERR_INPUT, "more result formats than LV_RESULTS_MAX_FORMATS");
        char key[16];
        snprintf(key, sizeof key, "files.%s", fmt);
        p->files[k] = json_str(files, fmt);
        lv_status st = file_name(r, "phase", p->name, key, p->files[k], err);
        if (st != LV_OK)
            return st;
        if (strcmp(fmt, "csv") == 0)
            p->csv = p->files[k];
    }
    /* the drift from its reference: the figures and the report read the block and its rows */
    const cJSON *ref = cJSON_GetObjectItemCaseSensitive(pj, "reference");
    if (cJSON_IsObject(ref)) {
        const cJSON *pos = cJSON_GetObjectItemCaseSensitive(ref, "position");
        const cJSON *vel = cJSON_GetObjectItemCaseSensitive(ref, "velocity");
        const cJSON *mas = cJSON_GetObjectItemCaseSensitive(ref, "mass");
        p->ref.present = 1;
        p->ref.rows = json_num(ref, "rows");
        p->ref.pos_max = json_num(pos, "max");
        p->ref.pos_max_t = json_num(pos, "t_max");
        p->ref.pos_final = json_num(pos, "final");
        p->ref.vel_max = json_num(vel, "max");
        p->ref.vel_final = json_num(vel, "final");
        p->ref.mass_max = json_num(mas, "max");
        p->ref.mass_final = json_num(mas, "final");
        p->ref.file = json_str(ref, "file");
        lv_status st = file_name(r, "phase", p->name, "reference.file", p->ref.file, err);
        if (st != LV_OK)
            return st;
    }

    const cJSON *ev = cJSON_GetObjectItemCaseSensitive(pj, "events");
    if (!cJSON_IsArray(ev))
        ev = NULL;
    const size_t ne = (size_t)cJSON_GetArraySize(ev);
    if (ne > 0 && (p->events = calloc(ne, sizeof *p->events)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    const cJSON *e;
    cJSON_ArrayForEach(e, ev)
    {
        lv_results_event *x = &p->events[p->n_events++];
        x->t = json_num(e, "t");
        x->name = json_str(e, "name");
        x->kind = json_str(e, "kind");
        x->label = json_str(e, "label");
        x->direction = json_num(e, "direction");
    }

    const cJSON *stages = cJSON_GetObjectItemCaseSensitive(pj, "stages");
    if (!cJSON_IsArray(stages))
        stages = NULL;
    const size_t ns = (size_t)cJSON_GetArraySize(stages);
    if (ns > 0 && (p->stages = calloc(ns, sizeof *p->stages)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    const cJSON *s;
    cJSON_ArrayForEach(s, stages)
    {
        if (cJSON_IsString(s))
            p->stages[p->n_stages++] = s->valuestring;
    }
    return LV_OK;
}

static lv_status read_body(lv_results *r, const cJSON *bj, size_t i, lv_err *err)
{
    lv_results_body *b = &r->bodies[i];
    const cJSON *pl = cJSON_GetObjectItemCaseSensitive(bj, "phases");
    b->name = json_str(bj, "name");
    if (b->name == NULL || !cJSON_IsArray(pl))
        return lv_fail(err, LV_ERR_INPUT, "%s: bodies[%zu]: no 'name' or no 'phases' array",
                       r->summary_path, i);
    b->trajectory = json_str(bj, "trajectory");
    lv_status st = file_name(r, "body", b->name, "trajectory", b->trajectory, err);
    if (st != LV_OK)
        return st;
    b->phases = calloc((size_t)cJSON_GetArraySize(pl) + 1, sizeof *b->phases);
    if (b->phases == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    const cJSON *pn;
    cJSON_ArrayForEach(pn, pl)
    {
        const int k = lv_results_phase_find(r, cJSON_IsString(pn) ? pn->valuestring : NULL);
        if (k < 0)
            return lv_fail(err, LV_ERR_INPUT, "%s: body '%s': phases[%zu] '%.100s' is not a "
                           "phase of the summary", r->summary_path, b->name, b->n_phases,
                           cJSON_IsString(pn) ? pn->valuestring : "?");
        b->phases[b->n_phases++] = (size_t)k;
    }
    return LV_OK;
}

void lv_results_free(lv_results *r)
{
    if (r == NULL)
        return;
    for (size_t i = 0; r->phases != NULL && i < r->n_phases; i++) {
        free(r->phases[i].events);
        free(r->phases[i].stages);
    }
    for (size_t i = 0; r->bodies != NULL && i < r->n_bodies; i++)
        free(r->bodies[i].phases);
    free(r->phases);
    free(r->bodies);
    cJSON_Delete(r->json);
    free(r->outdir);
    free(r->summary_path);
    free(r);
}

lv_status lv_results_open(const char *outdir, lv_results **out, lv_err *err)
{
    *out = NULL;
    if (outdir == NULL || outdir[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "results folder: no folder given");
    lv_results *r = calloc(1, sizeof *r);
    if (r == NULL || (r->outdir = dup_str(outdir)) == NULL ||
        (r->summary_path = join(outdir, "summary.json")) == NULL) {
        lv_results_free(r);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    const char *path = r->summary_path;
    char *text = NULL;
    size_t text_len;
    lv_status st = lv_read_file(path, LV_SUMMARY_FILE_MAX, NULL, &text, &text_len, err);
    if (st != LV_OK)
        goto fail;
    const char *stop = NULL;
    r->json = cJSON_ParseWithOpts(text, &stop, 0);
    if (r->json == NULL) {
        int line = 1;
        for (const char *c = text; stop != NULL && c < stop && *c; c++)
            line += *c == '\n';
        free(text);
        st = lv_fail(err, LV_ERR_INPUT, "%s:%d: malformed JSON", path, line);
        goto fail;
    }
    free(text);
    const cJSON *root = r->json;
    const cJSON *phases = cJSON_GetObjectItemCaseSensitive(root, "phases");
    const cJSON *bodies = cJSON_GetObjectItemCaseSensitive(root, "bodies");
    if (!cJSON_IsObject(root) || !cJSON_IsArray(phases) || !cJSON_IsArray(bodies)) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: not an lvsim summary: no 'phases' or 'bodies' array",
                     path);
        goto fail;
    }
    r->mission = json_str(root, "mission");
    r->file = json_str(root, "file");
    r->epoch = json_str(root, "epoch");
    r->world = json_str(root, "world");
    r->planet = json_str(root, "planet");
    r->lvsim = json_str(root, "lvsim");
    r->flat = r->world != NULL && strcmp(r->world, "flat") == 0;

    const size_t np = (size_t)cJSON_GetArraySize(phases);
    const size_t nb = (size_t)cJSON_GetArraySize(bodies);
    r->phases = calloc(np + 1, sizeof *r->phases);
    r->bodies = calloc(nb + 1, sizeof *r->bodies);
    if (r->phases == NULL || r->bodies == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    const cJSON *j;
    cJSON_ArrayForEach(j, phases)
    {
        if ((st = read_phase(r, j, r->n_phases++, err)) != LV_OK)
            goto fail;
    }
    for (size_t i = 0; i < r->n_phases; i++)
        r->phases[i].parent = lv_results_phase_find(r, r->phases[i].from);
    cJSON_ArrayForEach(j, bodies)
    {
        if ((st = read_body(r, j, r->n_bodies++, err)) != LV_OK)
            goto fail;
    }
    *out = r;
    return LV_OK;
fail:
    lv_results_free(r);
    return st;
}

int lv_results_exists(const lv_results *r, const char *file)
{
    char *path = join(r->outdir, file);
    struct stat sb;
    const int yes = path != NULL && stat(path, &sb) == 0;
    free(path);
    return yes;
}

/* -------------------------------------------------------------- CSV files -- */

void lv_results_table_free(lv_results_table *t)
{
    if (t == NULL)
        return;
    for (size_t c = 0; t->cols != NULL && c < t->n_cols; c++) {
        lv_results_column *col = &t->cols[c];
        free(col->name);
        free(col->unit);
        for (size_t i = 0; col->text != NULL && i < t->n_rows; i++)
            if (i == 0 || col->text[i] != col->text[i - 1])
                free(col->text[i]);
        free(col->text);
    }
    free(t->cols);
    free(t->v);
    free(t->line);
    free(t->path);
    free(t);
}

long lv_results_table_col(const lv_results_table *t, const char *name)
{
    for (size_t i = 0; t != NULL && i < t->n_cols; i++)
        if (strcmp(t->cols[i].name, name) == 0)
            return (long)i;
    return -1;
}

const char *lv_results_table_text(const lv_results_table *t, size_t row, size_t col)
{
    return t->cols[col].text != NULL ? t->cols[col].text[row] : NULL;
}

/* Splits one line in place into fields (RFC 4180: a quoted field may hold commas, and "" is a
 * quote). *fields grows as needed. Returns the field count; -1: an unterminated quote or text
 * after a closing quote; -2: out of memory. */
static long split_csv(char *s, char ***fields, size_t *cap)
{
    size_t n = 0;
    for (;;) {
        if (n == *cap) {
            const size_t nc = *cap ? 2 * *cap : 32;
            char **nf = realloc(*fields, nc * sizeof *nf);
            if (nf == NULL)
                return -2;
            *fields = nf;
            *cap = nc;
        }
        char *out = s;
        (*fields)[n++] = s;
        if (*s == '"') {
            char *in = s + 1;
            for (;;) {
                if (*in == '\0')
                    return -1;
                if (*in == '"' && in[1] == '"') {
                    *out++ = '"';
                    in += 2;
                } else if (*in == '"') {
                    in++;
                    break;
                } else {
                    *out++ = *in++;
                }
            }
            if (*in != ',' && *in != '\0')
                return -1;
            const char c = *in;
            *out = '\0';
            if (c == '\0')
                return (long)n;
            s = in + 1;
        } else {
            while (*s != ',' && *s != '\0')
                s++;
            if (*s == '\0')
                return (long)n;
            *s++ = '\0';
        }
    }
}

static char *dup_trim(const char *a, const char *b)
{
    while (a < b && (*a == ' ' || *a == '\t'))
        a++;
    while (b > a && (b[-1] == ' ' || b[-1] == '\t'))
        b--;
    char *s = malloc((size_t)(b - a) + 1);
    if (s != NULL) {
        memcpy(s, a, (size_t)(b - a));
        s[b - a] = '\0';
    }
    return s;
}

/* One header field "name [unit]" into its name and unit; 0 when out of memory. */
static int header_field(const char *f, lv_results_column *col)
{
    const char *end = f + strlen(f);
    const char *open = strrchr(f, '[');
    const char *close = open != NULL ? strchr(open, ']') : NULL;
    if (open != NULL && close != NULL) {
        col->name = dup_trim(f, open);
        col->unit = dup_trim(open + 1, close);
    } else {
        col->name = dup_trim(f, end);
        col->unit = dup_trim(end, end);
    }
    return col->name != NULL && col->unit != NULL;
}

static int listed(const char *const *list, const char *name)
{
    for (size_t i = 0; list != NULL && list[i] != NULL; i++)
        if (strcmp(list[i], name) == 0)
            return 1;
    return 0;
}

/* A number that fills its field (blanks around it allowed), else NAN; *ok tells which. */
static double number(const char *s, int *ok)
{
    char *stop;
    errno = 0;
    const double x = lv_numparse_double(s, &stop); /* strtod's value, faster (io/numparse.h) */
    const char *q = stop;
    while (*q == ' ' || *q == '\t')
        q++;
    *ok = stop != s && *q == '\0';
    return *ok ? x : NAN;
}

/* Frees the texts of the row being read (columns before `upto`): it is not in n_rows yet. */
static void drop_row_text(lv_results_table *t, size_t row, size_t upto)
{
    for (size_t c = 0; c < upto; c++) {
        char **tx = t->cols[c].text;
        if (tx != NULL && (row == 0 || tx[row] != tx[row - 1]))
            free(tx[row]);
    }
}

/* Room for one more row. */
static int grow_rows(lv_results_table *t, size_t *cap)
{
    if (t->n_rows < *cap)
        return 1;
    const size_t nc = *cap ? 2 * *cap : 1024;
    double *v = realloc(t->v, nc * t->n_cols * sizeof *v);
    if (v == NULL)
        return 0;
    t->v = v;
    size_t *line = realloc(t->line, nc * sizeof *line);
    if (line == NULL)
        return 0;
    t->line = line;
    for (size_t c = 0; c < t->n_cols; c++) {
        if (t->cols[c].text == NULL)
            continue;
        char **tx = realloc(t->cols[c].text, nc * sizeof *tx);
        if (tx == NULL)
            return 0;
        t->cols[c].text = tx;
    }
    *cap = nc;
    return 1;
}

lv_status lv_results_load(const lv_results *r, const char *file, const lv_results_csv_spec *spec,
                          lv_results_table **out, lv_err *err)
{
    *out = NULL;
    if (file == NULL || !bare_name(file))
        return lv_fail(err, LV_ERR_INPUT, "%s: '%.200s' is not a file name in the folder",
                       r->outdir, file != NULL ? file : "(null)");
    const char *const *text_cols = spec != NULL ? spec->text : NULL;
    const char *const *finite_cols = spec != NULL ? spec->finite : NULL;
    lv_results_table *t = calloc(1, sizeof *t);
    if (t == NULL || (t->path = join(r->outdir, file)) == NULL) {
        lv_results_table_free(t);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    const char *path = t->path;
    char reason[128];
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        lv_status st = lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", path,
                               lv_strerror(errno, reason, sizeof reason));
        lv_results_table_free(t);
        return st;
    }
    char *line = NULL, **fields = NULL;
    size_t cap = 0, fields_cap = 0, rows_cap = 0, lineno = 0;
    int *finite = NULL;
    lv_status st = LV_OK;
    while (getline(&line, &cap, f) >= 0) {
        lineno++;
        size_t len = strlen(line);
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            line[--len] = '\0';
        if (len == 0 || line[0] == '#')
            continue;
        const long n = split_csv(line, &fields, &fields_cap);
        if (n == -2)
            goto nomem;
        if (n < 0) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: unterminated quote", path, lineno);
            goto fail;
        }
        if (t->cols == NULL) { /* the header */
            t->header_line = lineno;
            t->cols = calloc((size_t)n, sizeof *t->cols);
            finite = calloc((size_t)n, sizeof *finite);
            if (t->cols == NULL || finite == NULL)
                goto nomem;
            for (long c = 0; c < n; c++) {
                t->n_cols++;
                if (!header_field(fields[c], &t->cols[c]))
                    goto nomem;
                finite[c] = listed(finite_cols, t->cols[c].name);
                if (listed(text_cols, t->cols[c].name) &&
                    (t->cols[c].text = malloc(sizeof *t->cols[c].text)) == NULL)
                    goto nomem;
            }
            continue;
        }
        if ((size_t)n != t->n_cols) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: %ld fields, the header has %zu", path, lineno,
                         n, t->n_cols);
            goto fail;
        }
        if (!grow_rows(t, &rows_cap))
            goto nomem;
        const size_t row = t->n_rows;
        double *v = t->v + row * t->n_cols;
        for (size_t c = 0; c < t->n_cols; c++) { /* numbers first: a bad one leaves no text */
            int ok;
            v[c] = t->cols[c].text != NULL ? NAN : number(fields[c], &ok);
            if (t->cols[c].text == NULL && finite[c] && !(ok && isfinite(v[c]))) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: column '%s': '%.40s' is not a finite "
                             "number", path, lineno, t->cols[c].name, fields[c]);
                goto fail;
            }
        }
        for (size_t c = 0; c < t->n_cols; c++) {
            char **tx = t->cols[c].text;
            if (tx == NULL)
                continue;
            if (row > 0 && strcmp(tx[row - 1], fields[c]) == 0)
                tx[row] = tx[row - 1];
            else if ((tx[row] = dup_str(fields[c])) == NULL) {
                drop_row_text(t, row, c);
                goto nomem;
            }
        }
        t->line[row] = lineno;
        t->n_rows++;
    }
    if (ferror(f)) {
        st = lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", path, LV_STRERROR(errno ? errno : EIO));
        goto fail;
    }
    if (t->cols == NULL) {
        st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: no header", path, lineno > 0 ? lineno : 1);
        goto fail;
    }
    t->n_lines = lineno;
    free(line);
    free(fields);
    free(finite);
    fclose(f);
    *out = t;
    return LV_OK;
nomem:
    st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
fail:
    free(line);
    free(fields);
    free(finite);
    fclose(f);
    lv_results_table_free(t);
    return st;
}
