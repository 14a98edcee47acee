/* yaml_tree.c - YAML text to an lv_ynode tree via libyaml's event API (YAML 1.1).
 * The tree is built iteratively (an explicit parent pointer, a depth limit), so hostile
 * input can neither recurse deeply nor expand aliases. */
#include "mission/yaml_tree.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

#include "core/status.h"

static int mark_int(size_t v)
{
    return v < (size_t)INT_MAX ? (int)v + 1 : INT_MAX;
}

void lv_yaml_free(lv_ynode *n)
{
    if (n == NULL)
        return;
    for (size_t i = 0; i < n->n; i++)
        lv_yaml_free(n->kids[i]); /* depth <= LV_YAML_MAX_DEPTH */
    free(n->kids);
    free(n->text);
    free(n);
}

int lv_yaml_is_null(const lv_ynode *n)
{
    static const char *const nulls[] = { "", "~", "null", "Null", "NULL" };
    if (n == NULL || n->kind != LV_YNODE_SCALAR || !n->plain)
        return 0;
    for (size_t i = 0; i < sizeof nulls / sizeof nulls[0]; i++)
        if (strcmp(n->text, nulls[i]) == 0)
            return 1;
    return 0;
}

static int add_kid(lv_ynode *parent, lv_ynode *kid)
{
    if (parent->n == parent->cap) {
        size_t cap = parent->cap ? 2 * parent->cap : 8;
        lv_ynode **k = realloc(parent->kids, cap * sizeof *k);
        if (k == NULL)
            return -1;
        parent->kids = k;
        parent->cap = cap;
    }
    parent->kids[parent->n++] = kid;
    kid->up = parent;
    return 0;
}

static lv_status syntax_error(const yaml_parser_t *p, const char *text, size_t len,
                              const char *file, lv_err *err)
{
    if (p->error == YAML_MEMORY_ERROR)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory while reading YAML", file);
    const char *problem = p->problem ? p->problem : "unknown error";
    if (p->error == YAML_READER_ERROR) { /* no mark: line and column (bytes) of the offset */
        size_t line = 0, col = 0;
        for (size_t i = 0; i < p->problem_offset && i < len; i++) {
            col++;
            if (text[i] == '\n') {
                line++;
                col = 0;
            }
        }
        return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: invalid YAML input: %s (byte %zu)", file,
                       mark_int(line), mark_int(col), problem, p->problem_offset);
    }
    if (p->context != NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: YAML syntax error: %s (%s at line %d, "
                       "column %d)", file, mark_int(p->problem_mark.line),
                       mark_int(p->problem_mark.column), problem, p->context,
                       mark_int(p->context_mark.line), mark_int(p->context_mark.column));
    return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: YAML syntax error: %s", file,
                   mark_int(p->problem_mark.line), mark_int(p->problem_mark.column), problem);
}

/* Anchors, aliases and tags: the tree would no longer be what the file shows. */
static lv_status check_node_event(const yaml_event_t *ev, const char *file, lv_err *err)
{
    const yaml_char_t *anchor = NULL, *tag = NULL;
    switch (ev->type) {
    case YAML_SCALAR_EVENT:
        anchor = ev->data.scalar.anchor;
        tag = ev->data.scalar.tag;
        break;
    case YAML_SEQUENCE_START_EVENT:
        anchor = ev->data.sequence_start.anchor;
        tag = ev->data.sequence_start.tag;
        break;
    case YAML_MAPPING_START_EVENT:
        anchor = ev->data.mapping_start.anchor;
        tag = ev->data.mapping_start.tag;
        break;
    default:
        return LV_OK;
    }
    const int line = mark_int(ev->start_mark.line), col = mark_int(ev->start_mark.column);
    if (anchor != NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: anchors (&%.40s) and aliases are not "
                       "supported in mission files", file, line, col, (const char *)anchor);
    if (tag != NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: tags (%.60s) are not supported in "
                       "mission files", file, line, col, (const char *)tag);
    return LV_OK;
}

static lv_ynode *new_node(const yaml_event_t *ev)
{
    lv_ynode *n = calloc(1, sizeof *n);
    if (n == NULL)
        return NULL;
    n->line = mark_int(ev->start_mark.line);
    n->col = mark_int(ev->start_mark.column);
    if (ev->type == YAML_SCALAR_EVENT) {
        n->kind = LV_YNODE_SCALAR;
        n->plain = ev->data.scalar.style == YAML_PLAIN_SCALAR_STYLE;
        n->len = ev->data.scalar.length;
        n->text = malloc(n->len + 1);
        if (n->text == NULL) {
            free(n);
            return NULL;
        }
        if (n->len > 0)
            memcpy(n->text, ev->data.scalar.value, n->len);
        n->text[n->len] = '\0';
    } else {
        n->kind = ev->type == YAML_MAPPING_START_EVENT ? LV_YNODE_MAP : LV_YNODE_SEQ;
    }
    return n;
}

lv_status lv_yaml_load(const char *text, size_t len, const char *file, lv_ynode **root,
                       lv_err *err)
{
    yaml_parser_t p;
    yaml_event_t ev;
    int have_event = 0, docs = 0, depth = 0, done = 0;
    lv_ynode *top = NULL, *cur = NULL;
    lv_status st = LV_OK;

    *root = NULL;
    if (!yaml_parser_initialize(&p))
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory while reading YAML", file);
    yaml_parser_set_input_string(&p, (const unsigned char *)text, len);

    while (!done) {
        if (!yaml_parser_parse(&p, &ev)) {
            st = syntax_error(&p, text, len, file, err);
            goto fail;
        }
        have_event = 1;
        const int line = mark_int(ev.start_mark.line), col = mark_int(ev.start_mark.column);
        switch (ev.type) {
        case YAML_STREAM_END_EVENT:
            done = 1;
            break;
        case YAML_DOCUMENT_START_EVENT:
            if (++docs > 1) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: a second YAML document; a mission "
                             "file holds exactly one", file, line, col);
                goto fail;
            }
            break;
        case YAML_ALIAS_EVENT:
            st = lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: aliases (*%.40s) and anchors are not "
                         "supported in mission files", file, line, col,
                         (const char *)ev.data.alias.anchor);
            goto fail;
        case YAML_SCALAR_EVENT:
        case YAML_SEQUENCE_START_EVENT:
        case YAML_MAPPING_START_EVENT: {
            st = check_node_event(&ev, file, err);
            if (st != LV_OK)
                goto fail;
            const int is_key = cur != NULL && cur->kind == LV_YNODE_MAP && cur->n % 2 == 0;
            if (is_key && ev.type != YAML_SCALAR_EVENT) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: a mapping key must be a plain "
                             "name, not a %s", file, line, col,
                             ev.type == YAML_MAPPING_START_EVENT ? "mapping" : "list");
                goto fail;
            }
            if (ev.type != YAML_SCALAR_EVENT && ++depth > LV_YAML_MAX_DEPTH) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: nested deeper than %d levels", file,
                             line, col, LV_YAML_MAX_DEPTH);
                goto fail;
            }
            lv_ynode *n = new_node(&ev);
            if (n != NULL && cur == NULL) {
                top = n;
            } else if (n == NULL || add_kid(cur, n) != 0) {
                lv_yaml_free(n);
                st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory while reading YAML", file);
                goto fail;
            }
            if (ev.type != YAML_SCALAR_EVENT)
                cur = n;
            break;
        }
        case YAML_SEQUENCE_END_EVENT:
        case YAML_MAPPING_END_EVENT:
            if (cur != NULL) { /* always: libyaml balances start and end events */
                cur = cur->up;
                depth--;
            }
            break;
        default: /* stream start, document end, no event */
            break;
        }
        yaml_event_delete(&ev);
        have_event = 0;
    }
    yaml_parser_delete(&p);
    if (top == NULL || lv_yaml_is_null(top)) {
        lv_yaml_free(top);
        return lv_fail(err, LV_ERR_INPUT, "%s:1:1: empty document: a mission file needs at "
                       "least 'mission', 'stages' and 'phases'", file);
    }
    *root = top;
    return LV_OK;

fail:
    if (have_event)
        yaml_event_delete(&ev);
    yaml_parser_delete(&p);
    lv_yaml_free(top);
    return st;
}
