/* parse_kit.h - the mission parser's tools, shared with the phase-model types that parse
 * their own phase keys (phase_type.h): typed values with "file:line:column: message" errors,
 * key checks with suggestions, table references, and slot registration (not exported).
 *
 * `what` names the object in messages ("phase 'P2', inputs"); `key` the offending key.
 * Every function returns LV_OK or LV_ERR_INPUT / LV_ERR_NOMEM with the message in c->err.
 */
#ifndef LV_MISSION_PARSE_KIT_H
#define LV_MISSION_PARSE_KIT_H

#include "core/status.h"
#include "lvsim/lv_table.h"
#include "mission/mission.h"
#include "mission/yaml_tree.h"

#define LV_NAME_MAX 64 /* stage, engine and phase names: [A-Za-z0-9_-], engines also '.' */
/* The mission's name and description are copied into every result file (summary.json, the
 * exports, the report, the manifest): bounded, in bytes of UTF-8 (docs/mission-format.md). */
#define LV_MISSION_NAME_MAX 256     /* one line: no control characters */
#define LV_DESCRIPTION_MAX 4096
#define LV_WHAT_MAX 160 /* "phase 'P2', inputs" */

typedef struct lv_pctx {
    const char *file;  /* the mission file, for messages */
    lv_err *err;
    lv_mission_def *m;
    lv_slot_owner owner; /* owner of the slots registered now */
    size_t owner_index;
} lv_pctx;

lv_status lv_pk_fail(const lv_pctx *c, const lv_ynode *at, const char *fmt, ...) LV_PRINTF(3, 4);
lv_status lv_pk_nomem(const lv_pctx *c);

const lv_ynode *lv_pk_get(const lv_ynode *map, const char *key); /* value of key, or NULL */
const lv_ynode *lv_pk_key(const lv_ynode *map, const char *key); /* the key node, or NULL */

/* `n` must be a mapping without duplicate keys; with `known` (NULL-terminated), only those. */
lv_status lv_pk_check_map(const lv_pctx *c, const lv_ynode *n, const char *what,
                          const char *const *known);
/* The value of a required key: present and not empty. */
lv_status lv_pk_need(const lv_pctx *c, const lv_ynode *map, const char *what, const char *key,
                     const lv_ynode **out);
/* A finite number written as a plain scalar. */
lv_status lv_pk_num(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                    double *out);
/* A non-empty string; *out borrows v. */
lv_status lv_pk_text(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                     const char **out);
/* One of `allowed` (NULL-terminated); *idx is its index. */
lv_status lv_pk_enum(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                     const char *const *allowed, size_t *idx);
/* A table given as `path` or {file, var, interp, extrap}: loaded into *tab; the resolved
 * path and .mat variable go to *file and *var (owned by the caller). */
lv_status lv_pk_table(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                      const char *what, lv_extrap extrap_default, char **file, char **var,
                      lv_table **tab);
/* The same, the mapping also taking `output: name` (the table output to use): *output is its
 * value node (a non-empty string), or NULL when not given. */
lv_status lv_pk_table_out(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                          const char *what, lv_extrap extrap_default, char **file, char **var,
                          const lv_ynode **output, lv_table **tab);
/* lv_pk_table for a trajectory (a reference): a CSV row repeating the previous row's time
 * replaces it (lv_table_opts.repeats_last: lvsim's own result rows, an event written before
 * and after). */
lv_status lv_pk_table_traj(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                           const char *what, lv_extrap extrap_default, char **file, char **var,
                           lv_table **tab);

/* The number at `v` (key `key` of `what`) registered as slot `name` with its unit and range,
 * owned by c->owner; out of range is an error at v naming the rule. `deg`: the value is in
 * degrees (converted to rad; the range applies to the radians). */
lv_status lv_pk_slot(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                     const char *name, const char *unit, lv_range range, int deg,
                     lv_slot *out);
/* A slot that the file does not write: its default value. */
lv_status lv_pk_slot_default(const lv_pctx *c, const char *name, const char *unit, double value,
                             lv_range range, lv_slot *out);

/* ---- the parser's smaller tools, for the types' own keys too --------------------------- */

char *lv_pk_strdup(const char *s); /* a malloc'ed copy, NULL: out of memory */
/* "a mapping", "a list", "nothing", "'text'" or "the string \"text\"" for messages (in buf). */
const char *lv_pk_describe(const lv_ynode *n, char *buf, size_t cap);
/* A random stream's seed: an integer 0 .. 2^64 - 1, written plainly. */
lv_status lv_pk_seed(const lv_pctx *c, const lv_ynode *v, const char *what, uint64_t *out);
/* A whole number >= min. */
lv_status lv_pk_int(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                    int min, int *out);
/* A non-empty string, copied into *out (owned by the caller). */
lv_status lv_pk_str(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                    char **out);
/* 1 when s is a name of at most LV_NAME_MAX characters [A-Za-z0-9_-] (and '.' with allow_dot). */
int lv_pk_valid_name(const char *s, int allow_dot);
/* A valid name (lv_pk_valid_name), copied into *out. */
lv_status lv_pk_name(const lv_pctx *c, const lv_ynode *v, const char *what, int allow_dot,
                     char **out);
/* An event's user name (`name:` of an end, an engine-out; docs/mission-format.md, "Named
 * events"): 1 to LV_EVENT_LABEL_MAX characters (UTF-8 counted as characters), printable (no
 * control characters), no leading or trailing space; copied into *out. */
#define LV_EVENT_LABEL_MAX 63
lv_status lv_pk_event_label(const lv_pctx *c, const lv_ynode *v, const char *what,
                            const char *key, char **out);
/* "stage 'stage1'" when the list item has a usable name, else "stage #2" (1-based k + 1). */
void lv_pk_label(const lv_ynode *item, const char *kind, size_t k, char *buf, size_t cap);
lv_src_loc lv_pk_loc(const lv_ynode *n); /* the node's line and column */
/* Copies `key` without a trailing "_deg" into buf; returns 1 if it had one. */
int lv_pk_strip_deg(const char *key, char *buf, size_t cap);

/* `rel` against the mission's directory (unless absolute), noted in the mission's list of the
 * files it reads (an FMU or any other package of the mission carries them). NULL: out of
 * memory. */
char *lv_pk_resolve_file(const lv_pctx *c, const char *rel);
/* {<file_key>: path, var: name} of a table read later by its model (atmosphere, wind). */
lv_status lv_pk_table_file(const lv_pctx *c, const lv_ynode *n, const char *what,
                           const char *file_key, char **file, char **var);
/* Only regular files: a device or a FIFO could block the parser forever. */
lv_status lv_pk_regular_file(const lv_pctx *c, const lv_ynode *at, const char *what,
                             const char *key, const char *path);

/* A constant throttle the file writes (slot `thr`; `key` names it: "inputs: throttle") within the range of every engine kind the phase's bottom stage runs, with the
 * file's values: refused at the value's file:line:column otherwise (a constant cannot follow a
 * saturation: docs/guidance.md, "Saturation"). A slot not written (LV_NO_SLOT, or defaulted)
 * passes. */
lv_status lv_pk_check_throttle(const lv_pctx *c, const lv_phase_def *ph, lv_slot thr,
                                  const char *key);

#endif
