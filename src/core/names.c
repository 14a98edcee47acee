/* names.c - nearest-name suggestions by Levenshtein distance.
 * Written here rather than taken from a library: it is twenty lines and Debian
 * has no small C library for it. */
#include "core/names.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LV_NAME_CMP_MAX 255

size_t lv_edit_distance(const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    if (na > LV_NAME_CMP_MAX) na = LV_NAME_CMP_MAX;
    if (nb > LV_NAME_CMP_MAX) nb = LV_NAME_CMP_MAX;
    size_t row[LV_NAME_CMP_MAX + 1];
    for (size_t j = 0; j <= nb; j++)
        row[j] = j;
    for (size_t i = 1; i <= na; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= nb; j++) {
            size_t up = row[j];
            size_t cost = (a[i - 1] == b[j - 1]) ? 0 : 1;
            size_t best = diag + cost;
            if (row[j] + 1 < best) best = row[j] + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[nb];
}

void lv_suggest_init(lv_suggest *s, const char *query)
{
    memset(s, 0, sizeof *s);
    s->query = query;
}

void lv_suggest_add(lv_suggest *s, const char *candidate)
{
    size_t d = lv_edit_distance(s->query, candidate);
    /* A suggestion must be plausibly a typo: at most half the query's length away,
     * or the query is contained in the candidate ("mass" -> "body1.mass"). */
    size_t qlen = strlen(s->query);
    size_t limit = qlen / 2 + 1;
    if (d > limit && strstr(candidate, s->query) == NULL)
        return;
    size_t pos = s->n;
    while (pos > 0 && s->dist[pos - 1] > d)
        pos--;
    if (pos >= LV_SUGGEST_MAX)
        return;
    size_t last = s->n < LV_SUGGEST_MAX ? s->n : LV_SUGGEST_MAX - 1;
    for (size_t k = last; k > pos; k--) {
        s->best[k] = s->best[k - 1];
        s->dist[k] = s->dist[k - 1];
    }
    s->best[pos] = candidate;
    s->dist[pos] = d;
    if (s->n < LV_SUGGEST_MAX)
        s->n++;
}

void lv_suggest_text(const lv_suggest *s, char *buf, size_t cap)
{
    if (cap == 0)
        return;
    buf[0] = '\0';
    if (s->n == 0)
        return;
    size_t used = (size_t)snprintf(buf, cap, "; did you mean ");
    for (size_t k = 0; k < s->n && used < cap; k++) {
        const char *sep = k == 0 ? "" : (k + 1 == s->n ? " or " : ", ");
        used += (size_t)snprintf(buf + used, cap - used, "%s'%s'", sep, s->best[k]);
    }
    if (used < cap)
        snprintf(buf + used, cap - used, "?");
}

/* FNV-1a: the table only needs names spread over its slots. */
static size_t name_hash(const char *s)
{
    size_t h = (size_t)14695981039346656037u;
    for (const unsigned char *c = (const unsigned char *)s; *c != '\0'; c++)
        h = (h ^ *c) * (size_t)1099511628211u;
    return h;
}

size_t lv_names_duplicate(const char *const *names, size_t n)
{
    enum { STACK_SLOTS = 512 };
    size_t stack[STACK_SLOTS];
    size_t cap = 1;
    while (cap < 2 * n)
        cap *= 2;
    size_t *slot = cap <= STACK_SLOTS ? stack : malloc(cap * sizeof *slot);
    if (slot == NULL) { /* no memory for a table: compare every pair */
        for (size_t i = 1; i < n; i++)
            for (size_t j = 0; j < i; j++)
                if (strcmp(names[i], names[j]) == 0)
                    return i;
        return n;
    }
    for (size_t k = 0; k < cap; k++)
        slot[k] = (size_t)-1;
    size_t dup = n;
    for (size_t i = 0; i < n && dup == n; i++) {
        size_t k = name_hash(names[i]) & (cap - 1);
        while (slot[k] != (size_t)-1) { /* linear probing; the table is at most half full */
            if (strcmp(names[slot[k]], names[i]) == 0) {
                dup = i;
                break;
            }
            k = (k + 1) & (cap - 1);
        }
        slot[k] = i;
    }
    if (slot != stack)
        free(slot);
    return dup;
}

size_t lv_names_find(const char *const *names, size_t n, const char *name)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(names[i], name) == 0)
            return i;
    return (size_t)-1;
}
