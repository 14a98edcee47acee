/* ocp_write.c - the optimal mission (lv_ocp_write): the mission file's YAML tree re-emitted in
 * block style with each optimised phase flying its control nodes (a table over mission time:
 * its inputs table, or its attitude law's), its stop_time the optimal end, no other ends, and the NLP's trajectory as its
 * reference, so that `lvsim run` re-flies it and reports the drift. Comments of the original
 * are not kept (the tree holds none): the file says where it came from in its header. Relative
 * file paths are rewritten when the file goes to another folder. */
#define _XOPEN_SOURCE 700 /* realpath */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/status.h"
#include "io/atomic.h"
#include "io/numfmt.h"
#include "io/readfile.h"
#include "mission/phase_type.h"
#include "mission/yaml_tree.h"
#include "optimal/ocp_int.h"
#include "target/target_int.h"

/* The reference's rows: every REF_DT seconds of a segment, at least REF_MIN and at most REF_MAX
 * per segment, and its events. The drift interpolates v and m linearly between them (v'' h^2 /
 * 8): at 10 rows per segment Goddard's burn read 0.04 kg, and at 50 rows a 88 s segment of
 * dof3-branch's upper stage 1.7 m/s near its burnout, where the re-flight was 1e-5 m/s off. */
#define REF_DT 0.1
#define REF_MIN 50
#define REF_MAX 5000

/* ---- the tree --------------------------------------------------------------------------- */

static lv_ynode *scalar(const char *text, int plain)
{
    lv_ynode *n = calloc(1, sizeof *n);
    if (n == NULL || (n->text = strdup(text)) == NULL) {
        free(n);
        return NULL;
    }
    n->kind = LV_YNODE_SCALAR;
    n->len = strlen(text);
    n->plain = plain;
    return n;
}

static lv_ynode *container(lv_ynode_kind kind)
{
    lv_ynode *n = calloc(1, sizeof *n);
    if (n != NULL)
        n->kind = kind;
    return n;
}

static int add_kid(lv_ynode *n, lv_ynode *kid)
{
    if (kid == NULL)
        return 0;
    if (n->n == n->cap) {
        const size_t cap = n->cap ? 2 * n->cap : 8;
        lv_ynode **k = realloc(n->kids, cap * sizeof *k);
        if (k == NULL) {
            lv_yaml_free(kid);
            return 0;
        }
        n->kids = k;
        n->cap = cap;
    }
    kid->up = n;
    n->kids[n->n++] = kid;
    return 1;
}

static int add_pair(lv_ynode *map, const char *key, lv_ynode *value)
{
    lv_ynode *k = scalar(key, 1);
    if (k == NULL || value == NULL) {
        lv_yaml_free(k);
        lv_yaml_free(value);
        return 0;
    }
    if (!add_kid(map, k)) {
        lv_yaml_free(value);
        return 0;
    }
    return add_kid(map, value);
}

static lv_ynode *map_get(const lv_ynode *map, const char *key)
{
    if (map == NULL || map->kind != LV_YNODE_MAP)
        return NULL;
    for (size_t i = 0; i + 1 < map->n; i += 2)
        if (strcmp(map->kids[i]->text, key) == 0)
            return map->kids[i + 1];
    return NULL;
}

static void map_drop(lv_ynode *map, const char *key)
{
    for (size_t i = 0; i + 1 < map->n; i += 2)
        if (strcmp(map->kids[i]->text, key) == 0) {
            lv_yaml_free(map->kids[i]);
            lv_yaml_free(map->kids[i + 1]);
            memmove(map->kids + i, map->kids + i + 2, (map->n - i - 2) * sizeof *map->kids);
            map->n -= 2;
            return;
        }
}

static int set_number(lv_ynode *n, double v)
{
    char buf[LV_NUMFMT_MAX];
    lv_numfmt_double(v, buf);
    char *t = strdup(buf);
    if (t == NULL)
        return 0;
    free(n->text);
    n->text = t;
    n->len = strlen(t);
    n->plain = 1;
    return 1;
}

/* ---- emitting ------------------------------------------------------------------------------- */

static int plain_ok(const char *s)
{
    if (*s == '\0')
        return 0;
    for (const char *q = s; *q != '\0'; q++)
        if (!((*q >= 'a' && *q <= 'z') || (*q >= 'A' && *q <= 'Z') || (*q >= '0' && *q <= '9') ||
              *q == '.' || *q == '/' || *q == '_' || *q == '-' || *q == '+'))
            return 0;
    return 1;
}

/* A scalar: as it is when it cannot be taken for anything else (numbers, names, paths), else
 * double-quoted (a text with blanks, commas or colons reads the same; numbers stay plain). */
static void emit_scalar(FILE *fp, const lv_ynode *n)
{
    if (plain_ok(n->text) || (n->plain && strcmp(n->text, "~") == 0)) {
        fputs(n->text, fp);
        return;
    }
    fputc('"', fp);
    for (size_t i = 0; i < n->len; i++) {
        const unsigned char ch = (unsigned char)n->text[i];
        if (ch == '"' || ch == '\\')
            fprintf(fp, "\\%c", ch);
        else if (ch < 0x20)
            fprintf(fp, "\\x%02x", ch);
        else
            fputc(ch, fp);
    }
    fputc('"', fp);
}

static void emit_flow(FILE *fp, const lv_ynode *n)
{
    if (n->kind == LV_YNODE_SCALAR) {
        emit_scalar(fp, n);
        return;
    }
    const int map = n->kind == LV_YNODE_MAP;
    fputc(map ? '{' : '[', fp);
    for (size_t i = 0; i < n->n; i += map ? 2 : 1) {
        if (i > 0)
            fputs(", ", fp);
        emit_flow(fp, n->kids[i]);
        if (map) {
            fputs(": ", fp);
            emit_flow(fp, n->kids[i + 1]);
        }
    }
    fputc(map ? '}' : ']', fp);
}

/* a node written on one line: a scalar, an empty container, a list of scalars or lists, a
 * mapping of scalars */
static int is_flat(const lv_ynode *n)
{
    if (n->kind == LV_YNODE_SCALAR || n->n == 0)
        return 1;
    for (size_t i = 0; i < n->n; i++)
        if (n->kids[i]->kind == LV_YNODE_MAP ||
            (n->kind == LV_YNODE_MAP && n->kids[i]->kind != LV_YNODE_SCALAR))
            return 0;
    return n->n <= 16;
}

static void emit_block(FILE *fp, const lv_ynode *n, int indent, int inline_first);

static void emit_value(FILE *fp, const lv_ynode *v, int indent)
{
    if (is_flat(v)) {
        fputc(' ', fp);
        emit_flow(fp, v);
        fputc('\n', fp);
        return;
    }
    fputc('\n', fp);
    emit_block(fp, v, indent + 2, 0);
}

static void emit_block(FILE *fp, const lv_ynode *n, int indent, int inline_first)
{
    if (n->kind == LV_YNODE_MAP) {
        for (size_t i = 0; i + 1 < n->n; i += 2) {
            if (i > 0 || !inline_first)
                fprintf(fp, "%*s", indent, "");
            emit_scalar(fp, n->kids[i]);
            fputc(':', fp);
            emit_value(fp, n->kids[i + 1], indent);
        }
        return;
    }
    for (size_t i = 0; i < n->n; i++) {
        const lv_ynode *it = n->kids[i];
        fprintf(fp, "%*s- ", indent, "");
        if (it->kind == LV_YNODE_MAP && it->n > 0 && !is_flat(it)) {
            emit_block(fp, it, indent + 2, 1);
        } else {
            emit_flow(fp, it);
            fputc('\n', fp);
        }
    }
}

/* ---- relative paths ------------------------------------------------------------------------ */

typedef struct repath {
    const char *mdir, *odir;
    lv_status st;
} repath;

static void walk_paths(repath *w, lv_ynode *n, const char *key)
{
    if (w->st != LV_OK || n == NULL)
        return;
    if (n->kind != LV_YNODE_SCALAR) {
        const int map = n->kind == LV_YNODE_MAP;
        for (size_t i = map ? 1 : 0; i < n->n; i += map ? 2 : 1)
            walk_paths(w, n->kids[i], map ? n->kids[i - 1]->text : key);
        return;
    }
    int nomem = 0;
    char *rel = lv_tw_rebase(w->mdir, w->odir, key, n->text, n->len, &nomem);
    if (rel == NULL) {
        if (nomem)
            w->st = LV_ERR_NOMEM;
        return; /* not a file: a model's name, a number */
    }
    free(n->text);
    n->text = rel;
    n->len = strlen(rel);
    n->plain = 0;
}

/* ---- the files ----------------------------------------------------------------------------- */

#define HEADER "# lvsim optimize:"

/* 1 when the file at path begins with the header lvsim optimize writes */
static int mission_is_ours(const char *path)
{
    FILE *fp = fopen(path, "r");
    if (fp == NULL)
        return 0;
    char line[64] = "";
    const int ours = fgets(line, sizeof line, fp) != NULL &&
                     strncmp(line, HEADER, strlen(HEADER)) == 0;
    fclose(fp);
    return ours;
}

/* path may be written: not an input (lv_output_check), and an existing file only when it is
 * one lvsim optimize wrote (its first line) or with LV_OUTPUT_REPLACE */
static lv_status may_write(const lv_mission *m, const char *path, unsigned flags, lv_err *err)
{
    lv_status st = lv_output_check(path, m, LV_OUTPUT_REPLACE, err);
    if (st != LV_OK || (flags & LV_OUTPUT_REPLACE))
        return st;
    struct stat sb;
    if (stat(path, &sb) != 0 || mission_is_ours(path))
        return LV_OK;
    return lv_fail(err, LV_ERR_INPUT, "%s exists and lvsim optimize did not write it: choose "
                   "another name, or --force", path);
}

static lv_status write_controls(lv_ocp *o, const oc_ph *p, const double *z, double t0, double D,
                                const char *path, lv_err *err)
{
    lv_atomic a = {0};
    lv_status st = lv_atomic_open(&a, path, err);
    if (st != LV_OK)
        return st;
    const lv_phase_def *ph = &o->w[0].m->def->phases[p->k];
    fprintf(a.fp, "time [s]");
    for (size_t c = 0; c < p->nu; c++)
        fprintf(a.fp, ",%s [%s]", ph->type->controls[p->def->ctrl[c].input],
                p->def->ctrl[c].deg ? "rad" : "1");
    fputc('\n', a.fp);
    char buf[LV_NUMFMT_MAX];
    for (size_t i = 0; i < p->nn; i++) {
        const double t = i + 1 == p->nn ? t0 + D : t0 + D * (double)i / (double)(p->nn - 1);
        lv_numfmt_double(t, buf);
        fputs(buf, a.fp);
        for (size_t c = 0; c < p->nu; c++) {
            const size_t v = p->iu + i * p->nu + c;
            lv_numfmt_double(z[v] * o->sx[v], buf);
            fprintf(a.fp, ",%s", buf);
        }
        fputc('\n', a.fp);
    }
    return lv_atomic_commit(&a, err);
}

/* The NLP's trajectory of phase p (the run of worker 0 is at z): each segment flown again from
 * its start state: rows every REF_DT (REF_MIN to REF_MAX per segment), its events, the end. */
static lv_status write_reference(lv_ocp *o, const oc_ph *p, const double *z, double t0,
                                 double D, const char *path, lv_err *err)
{
    static const char *const cols[] = {"h", "lat", "lon", "v_rel", "fpa", "heading", "m"};
    static const char *const head =
        "time [s],h [m],lat [rad],lon [rad],v [m/s],fpa [rad],heading [rad],m [kg]\n";
    oc_worker *w = &o->w[0];
    lv_phase_call *c;
    lv_status st = lv_run_prepare(w->r, p->k, &c, err);
    if (st != LV_OK)
        return st;
    const lv_model_def *def = lv_phase_call_model(c);
    double m_bo = NAN, x0[32];
    if (st == LV_OK)
        st = oc_phase_start(p, def, lv_phase_call_inst(c), lv_phase_call_settings(c), x0, &m_bo,
                            err);
    lv_atomic a = {0};
    if (st == LV_OK)
        st = lv_atomic_open(&a, path, err);
    if (st != LV_OK) {
        lv_phase_call_free(c);
        return st;
    }
    fputs(head, a.fp);
    const char *names[160];
    double values[160], xa[32];
    char buf[LV_NUMFMT_MAX];
    const double h = D / (double)p->ns;
    double t_last = -INFINITY;
    for (size_t j = 0; j < p->ns && st == LV_OK; j++) {
        const double ta = t0 + h * (double)j;
        const double tb = j + 1 == p->ns ? t0 + D : t0 + h * (double)(j + 1);
        for (size_t i = 0; i < p->nx; i++)
            xa[i] = z[p->ix + j * p->nx + i] * o->sx[p->ix + j * p->nx + i];
        lv_sim_settings s;
        /* the segment as the NLP flies it (ocp.c), its rows in memory: REF_DT apart
         * intervals and the two rows of each event (a kink: the burnout) */
        oc_segment_settings(o, lv_phase_call_settings(c), p, x0, t0, xa,
                            oc_segment_propellant(o, w, p, j, xa, m_bo), ta, tb, names, values,
                            &s);
        lv_result *rows = NULL;
        lv_sink mem;
        if ((st = lv_sink_memory_create(&rows, &mem, err)) != LV_OK)
            break;
        s.n_sinks = 1;
        s.sinks = &mem;
        s.number_of_intervals = (int)fmin(REF_MAX, fmax(REF_MIN, ceil((tb - ta) / REF_DT)));
        st = lv_simulate(def, lv_phase_call_inst(c), &s, NULL, NULL, err);
        size_t col[8];
        for (int i = 0; i < 8 && st == LV_OK; i++)
            st = lv_result_column(rows, i == 0 ? "time" : cols[i - 1], &col[i], err);
        /* the segment's end is the next one's first row (its node): written once; a grid row
         * that rounds onto or past the end goes with it, so the times only rise */
        const size_t nr = lv_result_rows(rows);
        const double t_cut = j + 1 == p->ns ? INFINITY : tb - 1e-12 * fmax(1.0, fabs(tb));
        for (size_t r = 0; r < nr && st == LV_OK; r++) {
            const double tr = lv_result_value(rows, r, col[0]);
            if (tr >= t_cut || tr < t_last)
                continue;
            t_last = tr;
            for (int i = 0; i < 8; i++) {
                lv_numfmt_double(lv_result_value(rows, r, col[i]), buf);
                fprintf(a.fp, i ? ",%s" : "%s", buf);
            }
            fputc('\n', a.fp);
        }
        lv_sink_destroy(&mem);
        lv_result_free(rows);
    }
    lv_phase_call_free(c);
    if (st != LV_OK) {
        lv_atomic_abort(&a);
        return st;
    }
    return lv_atomic_commit(&a, err);
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* The names lv_ocp_write writes: path's stem and csv[2 p], csv[2 p + 1] per optimised phase
 * (room for 2 np); each checked as lv_ocp_check_write says. */
static lv_status output_names(const lv_ocp *o, const char *path, unsigned flags,
                              char (*csv)[LV_ATOMIC_PATH_MAX + 80], lv_err *err)
{
    const oc_worker *w = &o->w[0];
    const lv_mission_def *d = w->m->def;
    const size_t pl = strlen(path);
    const int yml = pl > 4 && strcmp(path + pl - 4, ".yml") == 0;
    if (!yml && !(pl > 5 && strcmp(path + pl - 5, ".yaml") == 0))
        return lv_fail(err, LV_ERR_INPUT, "%s: the optimal mission is a .yaml (or .yml) file",
                       path);
    if (pl >= LV_ATOMIC_PATH_MAX)
        return lv_fail(err, LV_ERR_INPUT, "%.80s...: the path is too long", path);
    char stem[LV_ATOMIC_PATH_MAX];
    snprintf(stem, sizeof stem, "%.*s", (int)(pl - (yml ? 4 : 5)), path);
    lv_status st = may_write(w->m, path, flags, err);
    for (size_t p = 0; p < o->np && st == LV_OK; p++) {
        const char *pn = d->phases[o->ph[p].k].name;
        snprintf(csv[2 * p], sizeof csv[0], "%s_%s_controls.csv", stem, pn);
        snprintf(csv[2 * p + 1], sizeof csv[0], "%s_%s_reference.csv", stem, pn);
        for (int i = 0; i < 2 && st == LV_OK; i++) {
            /* never an input; an existing table only when the mission beside it is ours (the
             * two were written together) or with LV_OUTPUT_REPLACE */
            st = lv_output_check(csv[2 * p + i], w->m, LV_OUTPUT_REPLACE, err);
            struct stat sb;
            if (st == LV_OK && !(flags & LV_OUTPUT_REPLACE) && stat(csv[2 * p + i], &sb) == 0 &&
                !mission_is_ours(path))
                st = lv_fail(err, LV_ERR_INPUT, "%s exists and lvsim optimize did not write it "
                             "(its mission %s is not one it wrote): choose another name, or "
                             "--force", csv[2 * p + i], path);
        }
    }
    return st;
}

lv_status lv_ocp_check_write(const lv_ocp *o, const char *path, unsigned flags, lv_err *err)
{
    char (*csv)[LV_ATOMIC_PATH_MAX + 80] = calloc(2 * o->np + 1, sizeof *csv);
    if (csv == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    const lv_status st = output_names(o, path, flags, csv, err);
    free(csv);
    return st;
}

lv_status lv_ocp_write(lv_ocp *o, const char *path, unsigned flags, lv_err *err)
{
    oc_worker *w = &o->w[0];
    const lv_mission_def *d = w->m->def;
    char *text = NULL, *mdir = NULL, *odir = NULL;
    size_t len = 0;
    lv_ynode *root = NULL;
    lv_atomic a = {0};
    lv_status st = LV_OK;
    if (!o->solved || o->res.outcome != LV_OCP_OPTIMAL)
        return lv_fail(err, LV_ERR_INPUT, "no optimum to write: %s", !o->solved
                       ? "the problem has not been solved (lv_ocp_solve)"
                       : "the last solve did not end optimal");
    /* the point returned, flown on worker 0 (the files below read its run) */
    if (memcmp(o->z_base, o->z_best, o->n * sizeof *o->z_base) != 0 || !o->base_ok) {
        memcpy(o->z_base, o->z_best, o->n * sizeof *o->z_base);
        o->base_ok = oc_evaluate_base(o);
    }
    if (!o->base_ok)
        return lv_fail(err, LV_ERR_SOLVER, "the point to write does not fly: %s", w->why);
    char (*csv)[LV_ATOMIC_PATH_MAX + 80] = calloc(2 * o->np + 1, sizeof *csv);
    if (csv == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    if ((st = output_names(o, path, flags, csv, err)) != LV_OK)
        goto done;
    if ((st = lv_read_file(d->path, LV_MISSION_FILE_MAX, "the mission file", &text, &len, err)) !=
            LV_OK ||
        (st = lv_yaml_load(text, len, d->path, &root, err)) != LV_OK)
        goto done;
    mdir = realpath(d->dir, NULL);
    odir = lv_tw_dir_real(path);
    if (mdir == NULL || odir == NULL) {
        st = lv_fail(err, LV_ERR_IO, "%s: cannot resolve its folder", mdir == NULL ? d->dir : path);
        goto done;
    }
    if (strcmp(mdir, odir) != 0) {
        repath rp = {mdir, odir, LV_OK};
        walk_paths(&rp, root, NULL);
        if ((st = rp.st) != LV_OK) {
            st = lv_fail(err, st, "out of memory");
            goto done;
        }
    }
    /* the optimised phases */
    lv_ynode *phases = map_get(root, "phases");
    int ok = phases != NULL;
    for (size_t p = 0; p < o->np && ok && st == LV_OK; p++) {
        const oc_ph *op = &o->ph[p];
        const lv_phase_def *ph = &d->phases[op->k];
        const double t0 = oc_phase_t0(o, w, op->k);
        const double D = op->iD >= 0 ? o->z_base[op->iD] * o->sx[op->iD] : op->D;
        if ((st = write_controls(o, op, o->z_base, t0, D, csv[2 * p], err)) != LV_OK ||
            (st = write_reference(o, op, o->z_base, t0, D, csv[2 * p + 1], err)) != LV_OK)
            break;
        lv_ynode *pm = NULL;
        for (size_t i = 0; i < phases->n && pm == NULL; i++) {
            lv_ynode *nm = map_get(phases->kids[i], "name");
            if (nm != NULL && strcmp(nm->text, ph->name) == 0)
                pm = phases->kids[i];
        }
        lv_ynode *stop = map_get(pm, "stop_time");
        ok = pm != NULL && stop != NULL && set_number(stop, t0 + D);
        if (!ok)
            break;
        map_drop(pm, "end");
        map_drop(pm, "end_name"); /* it names the ends: none left */
        map_drop(pm, "reference");
        ok = add_pair(pm, "reference", scalar(base_name(csv[2 * p + 1]), 0));
        const char *key = ph->type->controls_key ? ph->type->controls_key(ph) : "inputs";
        if (ok && strcmp(key, "guidance") == 0) {
            /* the steering law's table, its other keys kept (a mapping: parse_phase.c) */
            lv_ynode *gd = map_get(pm, "guidance");
            ok = gd != NULL && gd->kind == LV_YNODE_MAP;
            if (ok) {
                map_drop(gd, "table");
                ok = add_pair(gd, "table", scalar(base_name(csv[2 * p]), 0));
            }
            /* a throttle control: the law's table gives it, so not the inputs' constant too */
            lv_ynode *in = map_get(pm, "inputs");
            for (size_t c = 0; ok && in != NULL && in->kind == LV_YNODE_MAP && c < op->nu; c++)
                if (strcmp(ph->type->controls[op->def->ctrl[c].input], "throttle") == 0) {
                    map_drop(in, "throttle");
                    if (in->n == 0)
                        map_drop(pm, "inputs");
                    break; /* in may be freed */
                }
            continue;
        }
        /* the inputs: the table, and the constants of the inputs not optimised */
        lv_ynode *in = container(LV_YNODE_MAP), *old = map_get(pm, "inputs");
        ok = in != NULL && add_pair(in, "table", scalar(base_name(csv[2 * p]), 0)) &&
             add_pair(in, "over", scalar("time", 1));
        for (size_t i = 0; ok && old != NULL && old->kind == LV_YNODE_MAP && i + 1 < old->n;
             i += 2) {
            const char *k = old->kids[i]->text;
            int drop = strcmp(k, "table") == 0 || strcmp(k, "var") == 0 ||
                       strcmp(k, "over") == 0 || strcmp(k, "duration") == 0;
            for (size_t c = 0; c < op->nu && !drop; c++) {
                const char *cn = ph->type->controls[op->def->ctrl[c].input];
                const size_t cl = strlen(cn);
                drop = strncmp(k, cn, cl) == 0 && (k[cl] == '\0' || strcmp(k + cl, "_deg") == 0);
            }
            if (!drop) {
                lv_ynode *v = scalar(old->kids[i + 1]->text, old->kids[i + 1]->plain);
                ok = add_pair(in, k, v);
            }
        }
        if (!ok) {
            lv_yaml_free(in);
            break;
        }
        map_drop(pm, "inputs");
        ok = add_pair(pm, "inputs", in);
    }
    /* the section: a warm start from here (each control's start is the phase's table; the
     * duration starts at the optimum) */
    lv_ynode *oc = map_get(map_get(root, "optimal_control"), "phases");
    for (size_t i = 0; ok && st == LV_OK && oc != NULL && i < oc->n; i++) {
        lv_ynode *pi = oc->kids[i], *cl = map_get(pi, "controls"), *dn = map_get(pi, "duration");
        for (size_t c = 0; cl != NULL && cl->kind == LV_YNODE_SEQ && c < cl->n; c++)
            if (cl->kids[c]->kind == LV_YNODE_MAP)
                map_drop(cl->kids[c], "start");
        const lv_ynode *nm = map_get(pi, "name");
        for (size_t p = 0; dn != NULL && dn->kind == LV_YNODE_MAP && nm != NULL && p < o->np;
             p++)
            if (o->ph[p].iD >= 0 && strcmp(d->phases[o->ph[p].k].name, nm->text) == 0) {
                const double D = o->z_base[o->ph[p].iD] * o->sx[o->ph[p].iD];
                lv_ynode *sv = map_get(dn, "start");
                ok = sv != NULL ? set_number(sv, D) : add_pair(dn, "start", scalar("0", 1)) &&
                                                          set_number(map_get(dn, "start"), D);
            }
    }
    if (st != LV_OK)
        goto done;
    if (!ok) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: cannot edit the mission's tree", d->path);
        goto done;
    }
    if ((st = lv_atomic_open(&a, path, err)) != LV_OK)
        goto done;
    fprintf(a.fp, HEADER " the optimal mission of %s (IPOPT: %s after %d iterations)\n",
            base_name(d->path), o->res.ipopt_text, o->res.iterations);
    fprintf(a.fp, "# Each optimised phase flies its control nodes (a table over mission time: "
                  "its inputs\n# table or its attitude law's) to its optimal stop_time; its "
                  "reference is the\n# optimiser's trajectory: `lvsim run` reports the drift. "
                  "Comments of the original\n# are not kept.\n");
    emit_block(a.fp, root, 0, 0);
    st = lv_atomic_commit(&a, err);
done:
    free(csv);
    free(text);
    free(mdir);
    free(odir);
    lv_yaml_free(root);
    return st;
}
