/* json_print.c - lv_json_print (json_print.h): cJSON's layout, exact numbers.
 *
 * Written around cJSON rather than as a printer of its own: the numbers of the document are
 * turned into raw nodes holding their exact text (cJSON_Raw, which cJSON_Print copies as it
 * is), the document printed, and the nodes turned back. */
#include "post/json_print.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/numfmt.h"

typedef struct num_list {
    cJSON **item;
    size_t n, cap;
} num_list;

/* Every number node under (and including) it, depth first. 0, or -1 when out of memory. */
static int collect(cJSON *it, num_list *l)
{
    for (; it != NULL; it = it->next) {
        if ((it->type & 0xFF) == cJSON_Number) {
            if (l->n == l->cap) {
                const size_t cap = l->cap ? 2 * l->cap : 64;
                cJSON **grown = realloc(l->item, cap * sizeof *grown);
                if (grown == NULL)
                    return -1;
                l->item = grown;
                l->cap = cap;
            }
            l->item[l->n++] = it;
        } else if (it->child != NULL && collect(it->child, l) != 0) {
            return -1;
        }
    }
    return 0;
}

/* The first k collected nodes back to numbers (their valuedouble was never touched). */
static void restore(num_list *l, size_t k)
{
    for (size_t i = 0; i < k; i++) {
        cJSON *it = l->item[i];
        free(it->valuestring); /* malloc'd below; cJSON's hooks are the defaults in lvsim */
        it->valuestring = NULL;
        it->type = (it->type & ~0xFF) | cJSON_Number;
    }
}

char *lv_json_print(cJSON *doc)
{
    if (doc == NULL)
        return NULL;
    num_list l = {NULL, 0, 0};
    /* the document itself, then its children (collect walks siblings: not doc's) */
    cJSON *const next = doc->next;
    doc->next = NULL;
    const int rc = collect(doc, &l);
    doc->next = next;
    if (rc != 0) {
        free(l.item);
        return NULL;
    }
    size_t k = 0;
    for (; k < l.n; k++) {
        cJSON *it = l.item[k];
        char buf[LV_NUMFMT_MAX];
        const double v = it->valuedouble;
        if (isfinite(v))
            lv_numfmt_double(v, buf);
        else
            memcpy(buf, "null", 5);
        char *text = malloc(strlen(buf) + 1);
        if (text == NULL)
            break;
        memcpy(text, buf, strlen(buf) + 1);
        it->valuestring = text;
        it->type = (it->type & ~0xFF) | cJSON_Raw;
    }
    char *out = k == l.n ? cJSON_Print(doc) : NULL;
    restore(&l, k);
    free(l.item);
    return out;
}
