/* names.h - nearest-name suggestions for "unknown name" errors (not exported). */
#ifndef LV_CORE_NAMES_H
#define LV_CORE_NAMES_H

#include <stddef.h>

/* Levenshtein edit distance, case-sensitive; strings longer than 255 bytes are
 * compared on their first 255 bytes. */
size_t lv_edit_distance(const char *a, const char *b);

/* Collects candidates and keeps the `LV_SUGGEST_MAX` nearest to `query`. */
#define LV_SUGGEST_MAX 3
typedef struct lv_suggest {
    const char *query;
    const char *best[LV_SUGGEST_MAX];
    size_t dist[LV_SUGGEST_MAX];
    size_t n;
} lv_suggest;

void lv_suggest_init(lv_suggest *s, const char *query);
void lv_suggest_add(lv_suggest *s, const char *candidate);
/* Writes "; did you mean 'a', 'b' or 'c'?" (or "" when nothing is close) into buf. */
void lv_suggest_text(const lv_suggest *s, char *buf, size_t cap);

/* Finds a name given twice among names[0..n-1] (none NULL) with a hash table: O(n), where
 * comparing every pair costs O(n^2) string comparisons (a 3-DoF model's 60 names: 1,770).
 * Returns the index of the second occurrence of the first repeated name found, or n. Uses a
 * table on the stack for n <= 256, else allocates one; n (every name unique) also when that
 * allocation fails after falling back to pairs. */
size_t lv_names_duplicate(const char *const *names, size_t n);

/* The index of `name` among names[0..n-1] (a linear search: hand-offs look up a few names
 * once per phase), or (size_t)-1. */
size_t lv_names_find(const char *const *names, size_t n, const char *name);

#endif
