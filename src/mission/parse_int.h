/* parse_int.h - the mission parser's own pieces, shared among its files (parse.c: the file
 * and its root keys; parse_env.c, parse_vehicle.c, parse_params.c, parse_phase.c,
 * parse_tree.c). Not for the phase-model types: they use parse_kit.h. Each function reads one
 * section of the file into c->m and returns LV_OK or LV_ERR_INPUT / LV_ERR_NOMEM with the
 * message, at file:line:column, in c->err.
 */
#ifndef LV_MISSION_PARSE_INT_H
#define LV_MISSION_PARSE_INT_H

#include "mission/parse_kit.h"

lv_status lv_parse_env(const lv_pctx *c, const lv_ynode *n);    /* environment: */
lv_status lv_parse_stages(const lv_pctx *c, const lv_ynode *n); /* stages: */
lv_status lv_parse_params(const lv_pctx *c, const lv_ynode *n); /* parameters: */
lv_status lv_parse_phases(const lv_pctx *c, const lv_ynode *n); /* phases: (and the tree) */
/* A phase's `engines:` and `engine_out:` (engine_run.c), once its stages are known. */
lv_status lv_parse_engine_run(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph);

/* The phase tree (parse_tree.c), once every phase is read. A `from` chain that comes back
 * ("P2 -> P3 -> P2", from the first member in file order); from[k]: phase k's `from` value
 * node, or NULL. */
lv_status lv_parse_check_cycles(const lv_pctx *c, const lv_ynode *const *from);
/* Parents before children; otherwise file order. */
lv_status lv_parse_order_phases(const lv_pctx *c);
/* The checks between children and parents (stages, models, times, names: parse_tree.c). */
lv_status lv_parse_check_tree(const lv_pctx *c);

/* Slot names unique across the file (every section registered its own). */
lv_status lv_pk_check_slot_names(const lv_pctx *c);

#endif
