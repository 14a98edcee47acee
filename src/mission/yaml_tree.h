/* yaml_tree.h - a YAML document as a small tree of scalars, mappings and lists, with the
 * line and column of every node, read with libyaml's event API (not exported).
 *
 * One document per stream; anchors, aliases and explicit tags are rejected, so the tree is
 * exactly what the file shows and its size is bounded by the input size.
 */
#ifndef LV_MISSION_YAML_TREE_H
#define LV_MISSION_YAML_TREE_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#define LV_YAML_MAX_DEPTH 64 /* nesting limit: deeper input is rejected, not recursed into */

typedef enum lv_ynode_kind { LV_YNODE_SCALAR, LV_YNODE_MAP, LV_YNODE_SEQ } lv_ynode_kind;

typedef struct lv_ynode {
    lv_ynode_kind kind;
    int line, col;          /* 1-based position of the node's first character */
    int plain;              /* scalar written without quotes (numbers must be plain) */
    char *text;             /* scalar: NUL-terminated copy (may contain NUL: see len) */
    size_t len;             /* scalar: bytes in text */
    struct lv_ynode **kids; /* map: key0, value0, key1, value1, ..; list: the items */
    size_t n;               /* entries in kids (a map holds 2 per pair) */
    size_t cap;
    struct lv_ynode *up;
} lv_ynode;

/* Parses `text` (len bytes, any encoding libyaml accepts) into *root. `file` only names
 * the input in messages "file:line:column: ...". LV_ERR_INPUT for syntax errors, an empty
 * stream, several documents, anchors, aliases, tags, non-scalar mapping keys or nesting
 * deeper than LV_YAML_MAX_DEPTH; LV_ERR_NOMEM. lv_yaml_free(*root) when done. */
lv_status lv_yaml_load(const char *text, size_t len, const char *file, lv_ynode **root,
                       lv_err *err);
void lv_yaml_free(lv_ynode *n); /* accepts NULL */

/* A plain "", "~" or "null" (any YAML 1.1 spelling): an empty value. */
int lv_yaml_is_null(const lv_ynode *n);

#endif
