/* parse_tree.c - the phase tree of a mission file: `from:` cycles, the order in which phases run
 * (parents before children, otherwise file order) and the checks between a child and its
 * parent (paper sec. 3.2: the sequential simulation with branches). */
#include "mission/mission.h"

#include <stdio.h>
#include <stdlib.h>

#include "mission/dispersion.h"
#include "mission/parse_int.h"
#include "mission/phase_type.h"

/* A `from` chain that comes back: "P2 -> P3 -> P2", from the first member in file order. */
lv_status lv_parse_check_cycles(const lv_pctx *c, const lv_ynode *const *from)
{
    const lv_mission_def *m = c->m;
    const size_t n = m->n_phases;
    size_t *seen = calloc(n, sizeof *seen); /* walk number + 1 that reached the phase */
    unsigned char *done = calloc(n, 1);
    lv_status st = LV_OK;
    if (seen == NULL || done == NULL) {
        st = lv_pk_nomem(c);
        goto fail;
    }
    for (size_t i = 0; i < n; i++) {
        long j = (long)i;
        while (j >= 0 && !done[j] && seen[j] != i + 1) {
            seen[j] = i + 1;
            j = m->phases[j].parent;
        }
        if (j >= 0 && !done[j]) { /* back on this walk: a cycle through j */
            size_t first = (size_t)j;
            for (long q = m->phases[j].parent; q != j; q = m->phases[q].parent)
                if ((size_t)q < first)
                    first = (size_t)q;
            char path[320];
            size_t used = (size_t)snprintf(path, sizeof path, "%s", m->phases[first].name);
            long q = (long)first;
            do {
                q = m->phases[q].parent;
                if (used < sizeof path)
                    used += (size_t)snprintf(path + used, sizeof path - used, " -> %s",
                                             m->phases[q].name);
            } while ((size_t)q != first);
            st = lv_pk_fail(c, from[first], "phase '%s': from: cycle %s (each phase starts from the "
                      "next); a root phase has no 'from'", m->phases[first].name, path);
            goto fail;
        }
        for (j = (long)i; j >= 0 && !done[j]; j = m->phases[j].parent)
            done[j] = 1;
    }
fail:
    free(seen);
    free(done);
    return st;
}

/* Parents before children; otherwise file order: repeatedly take the lowest file index
 * whose parent has been taken (a binary min-heap of ready phases). */
lv_status lv_parse_order_phases(const lv_pctx *c)
{
    lv_mission_def *m = c->m;
    const size_t n = m->n_phases;
    size_t *heap = malloc(n * sizeof *heap), *pos = malloc(n * sizeof *pos);
    size_t *kid_first = malloc(n * sizeof *kid_first), *kid_next = malloc(n * sizeof *kid_next);
    lv_phase_def *out = malloc(n * sizeof *out);
    size_t nh = 0, taken = 0;
    lv_status st = LV_OK;
    if (heap == NULL || pos == NULL || kid_first == NULL || kid_next == NULL || out == NULL) {
        st = lv_pk_nomem(c);
        goto fail;
    }
    for (size_t i = 0; i < n; i++)
        kid_first[i] = SIZE_MAX;
    for (size_t i = n; i-- > 0;) { /* children lists in file order */
        if (m->phases[i].parent >= 0) {
            const size_t p = (size_t)m->phases[i].parent;
            kid_next[i] = kid_first[p];
            kid_first[p] = i;
        }
    }
    for (size_t i = 0; i < n; i++) /* the roots, ascending: already a min-heap */
        if (m->phases[i].parent < 0)
            heap[nh++] = i;
    while (nh > 0) {
        const size_t top = heap[0];
        heap[0] = heap[--nh];
        for (size_t a = 0;;) { /* sift down */
            size_t b = 2 * a + 1;
            if (b >= nh)
                break;
            if (b + 1 < nh && heap[b + 1] < heap[b])
                b++;
            if (heap[a] <= heap[b])
                break;
            const size_t t = heap[a];
            heap[a] = heap[b];
            heap[b] = t;
            a = b;
        }
        pos[top] = taken++;
        for (size_t k = kid_first[top]; k != SIZE_MAX; k = kid_next[k]) {
            size_t a = nh++; /* sift up */
            heap[a] = k;
            while (a > 0 && heap[(a - 1) / 2] > heap[a]) {
                const size_t t = heap[a];
                heap[a] = heap[(a - 1) / 2];
                heap[(a - 1) / 2] = t;
                a = (a - 1) / 2;
            }
        }
    }
    /* taken == n: lv_parse_check_cycles() ran first, every phase reaches a root */
    for (size_t i = 0; i < n; i++) {
        out[pos[i]] = m->phases[i];
        const int p = m->phases[i].parent;
        out[pos[i]].parent = p >= 0 ? (int)pos[p] : -1;
        out[pos[i]].file_index = i;
    }
    free(m->phases);
    m->phases = out;
    out = NULL;
    for (size_t i = 0; i < m->n_slots; i++) /* the phases' slots follow them */
        if (m->slots[i].owner == LV_OWN_PHASE)
            m->slots[i].owner_index = pos[m->slots[i].owner_index];
fail:
    free(heap);
    free(pos);
    free(kid_first);
    free(kid_next);
    free(out);
    return st;
}

/* 1 if phase a is phase d or one of its ancestors. */
static int is_ancestor(const lv_mission_def *m, int a, int d)
{
    for (; d >= 0; d = m->phases[d].parent)
        if (d == a)
            return 1;
    return 0;
}

/* The child of `anc` on the way down to `d` (anc an ancestor of d, anc != d); anc = -1: the
 * root of d. */
static int child_towards(const lv_mission_def *m, int anc, int d)
{
    while (m->phases[d].parent != anc)
        d = m->phases[d].parent;
    return d;
}

static lv_src_loc slot_loc(const lv_mission_def *m, lv_slot s, lv_src_loc fallback)
{
    return s != LV_NO_SLOT && m->slots[s].loc.line > 0 ? m->slots[s].loc : fallback;
}

/* What the phase tree must satisfy to be flown (after ordering, parents first):
 *  - a child carries only stages its parent carries (a stage cannot appear from nowhere);
 *  - a stage flies in one branch at a time: two phases whose branches split at a phase X both
 *    carry it only if one of the two branches is marked `alternative: true` (abort cases);
 *  - a child's stop_time is after its parent's stop_time (the latest its parent can end:
 *    otherwise it may have nothing to run), and a child's start_time, if written, is its
 *    parent's end (known only when the parent ends at its stop_time, without end events). */
lv_status lv_parse_check_tree(const lv_pctx *c)
{
    const lv_mission_def *m = c->m;
    for (size_t k = 0; k < m->n_phases; k++) {
        const lv_phase_def *ph = &m->phases[k];
        if (ph->parent < 0)
            continue;
        const lv_phase_def *par = &m->phases[ph->parent];
        if (ph->type->check_parent != NULL) {
            const lv_status st = ph->type->check_parent(c, ph, par);
            if (st != LV_OK)
                return st;
        }
        for (size_t i = 0; i < ph->n_stages; i++) {
            int carried = 0;
            for (size_t j = 0; j < par->n_stages; j++)
                carried |= par->stages[j] == ph->stages[i];
            if (!carried)
                return lv_fail(c->err, LV_ERR_INPUT,
                               "%s:%d:%d: phase '%s': stages: '%s' is not carried by its parent "
                               "'%s' (stages: a child carries some of its parent's stages)",
                               m->path, ph->stage_locs[i].line, ph->stage_locs[i].column,
                               ph->name, m->stages[ph->stages[i]].name, par->name);
        }
        const double stop = lv_mission_def_value(m, ph->t_stop);
        const double pstop = lv_mission_def_value(m, par->t_stop);
        lv_src_loc at = slot_loc(m, ph->t_stop, ph->loc);
        if (!(stop > pstop))
            return lv_fail(c->err, LV_ERR_INPUT,
                           "%s:%d:%d: phase '%s': stop_time %g s is not after the stop_time %g "
                           "s of its parent '%s': it would have nothing to run when '%s' runs "
                           "to its limit",
                           m->path, at.line, at.column, ph->name, stop, pstop, par->name,
                           par->name);
        if (ph->t_start != LV_NO_SLOT) {
            const double t0 = lv_mission_def_value(m, ph->t_start);
            at = slot_loc(m, ph->t_start, ph->loc);
            if (par->n_ends > 0)
                return lv_fail(c->err, LV_ERR_INPUT,
                               "%s:%d:%d: phase '%s': start_time: a phase with `from` starts "
                               "when its parent '%s' ends, which an end event decides: remove "
                               "start_time",
                               m->path, at.line, at.column, ph->name, par->name);
            if (t0 != pstop)
                return lv_fail(c->err, LV_ERR_INPUT,
                               "%s:%d:%d: phase '%s': start_time %g s is not the end %g s of its "
                               "parent '%s' (a phase starts from its parent's final state: "
                               "remove start_time)",
                               m->path, at.line, at.column, ph->name, t0, pstop, par->name);
        }
    }
    /* an engine-out within its phase: `time` after the phase's start, before its stop_time.
     * The start is known when written (start_time), 0 for a root, its parent's stop_time for
     * a child of a parent without end events; otherwise it lies after the latest of those
     * up the tree, and an engine-out after the stop_time even from there never happens. (A
     * start known only at run time is checked there too: run.c.) */
    for (size_t k = 0; k < m->n_phases; k++) {
        const lv_phase_def *ph = &m->phases[k];
        if (ph->n_engine_out == 0)
            continue;
        int exact = 1;
        double t0 = 0.0;
        for (const lv_phase_def *q = ph; q != NULL;) {
            if (q->t_start != LV_NO_SLOT) {
                t0 = lv_mission_def_value(m, q->t_start);
                break;
            }
            if (q->parent < 0)
                break; /* a root starts at 0 */
            const lv_phase_def *par = &m->phases[q->parent];
            if (par->n_ends == 0) { /* the parent runs to its stop_time */
                t0 = lv_mission_def_value(m, par->t_stop);
                break;
            }
            exact = 0; /* after the parent's start, at least */
            q = par;
        }
        const double stop = lv_mission_def_value(m, ph->t_stop);
        for (size_t j = 0; j < ph->n_engine_out; j++) {
            const lv_engine_out_def *o = &ph->engine_out[j];
            const double dt = lv_mission_def_value(m, o->time);
            if (t0 + dt < stop)
                continue;
            const lv_src_loc at = slot_loc(m, o->time, o->loc);
            return lv_fail(c->err, LV_ERR_INPUT,
                           "%s:%d:%d: phase '%s', engine_out: time %g s after the phase's start "
                           "(%s t = %g s) is at or after its stop_time %g s: the engine-out "
                           "would never happen",
                           m->path, at.line, at.column, ph->name, dt,
                           exact ? "at" : "after", t0, stop);
        }
    }
    /* a stage in two branches at once */
    for (size_t a = 0; a < m->n_phases; a++)
        for (size_t b = a + 1; b < m->n_phases; b++) {
            const lv_phase_def *pa = &m->phases[a], *pb = &m->phases[b];
            if (is_ancestor(m, (int)a, (int)b))
                continue;
            for (size_t i = 0; i < pa->n_stages; i++)
                for (size_t j = 0; j < pb->n_stages; j++) {
                    if (pa->stages[i] != pb->stages[j])
                        continue;
                    int x = pa->parent; /* the phase where the two branches split (-1: roots) */
                    while (x >= 0 && !is_ancestor(m, x, (int)b))
                        x = m->phases[x].parent;
                    const lv_phase_def *ca = &m->phases[child_towards(m, x, (int)a)];
                    const lv_phase_def *cb = &m->phases[child_towards(m, x, (int)b)];
                    if (ca->alternative || cb->alternative)
                        continue;
                    return lv_fail(c->err, LV_ERR_INPUT,
                                   "%s:%d:%d: phase '%s': stages: '%s' also flies in phase '%s' "
                                   "(line %d) of another branch%s%s%s: a stage is in one place "
                                   "at a time; if the branches are alternatives (an abort "
                                   "case), mark one `alternative: true`",
                                   m->path, pb->stage_locs[j].line, pb->stage_locs[j].column,
                                   pb->name, m->stages[pb->stages[j]].name, pa->name,
                                   pa->loc.line, x >= 0 ? " (they split after '" : "",
                                   x >= 0 ? m->phases[x].name : "", x >= 0 ? "')" : "");
                }
        }
    return LV_OK;
}
