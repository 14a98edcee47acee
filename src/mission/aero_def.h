/* aero_def.h - a phase's aerodynamic dataset as the mission file writes it (`aero:`), shared
 * by the phase-model types that fly one (not exported). Each coefficient is a constant (a
 * slot "<phase>.aero.<C>"), a table of its own (`CN: {file: cn.mat, var: cn}`), or an output
 * of the dataset's table (`table:`, outputs named as the coefficients); the reference area is
 * the slot "<phase>.aero.s_ref". Tables are loaded and checked (axes, outputs) when the file
 * is read. Format: docs/mission-format.md ("aero").
 */
#ifndef LV_MISSION_AERO_DEF_H
#define LV_MISSION_AERO_DEF_H

#include "lvsim/lv_vehicle.h"
#include "mission/parse_kit.h"

typedef struct lv_aero_def {
    int present;             /* the phase has `aero:` */
    int body_axes;           /* 0: CD, CL, CY (wind axes); 1: CA, CN, CY (body axes) */
    lv_slot s_ref;           /* m^2 */
    lv_slot coef[3];         /* constants; LV_NO_SLOT: from a table, or 0 */
    lv_table *tab[3];        /* a coefficient's own table (owned), or NULL */
    char *out[3];            /* the output it reads: of its own table, or of `table` (NULL: 0) */
    char *file[3], *var[3];  /* where its own table comes from */
    lv_table *table;         /* the dataset's table (owned), or NULL */
    char *table_file, *table_var;
} lv_aero_def;

/* Parses `aero:` (n may be NULL or empty: no dataset) of phase `phase`. drag_only: only CD
 * (or CA) is allowed, the others are refused as keys (a body without angle of attack).
 * The slots belong to c->owner. */
lv_status lv_aero_def_parse(const lv_pctx *c, const lv_ynode *n, const char *phase,
                            int drag_only, lv_aero_def *a);
void lv_aero_def_clear(lv_aero_def *a); /* accepts a zeroed one */

/* The dataset for a model, from a run's values (`vals`: one per slot); tables and output
 * names are borrowed from `a`. */
void lv_aero_def_config(const lv_aero_def *a, const double *vals, lv_aero_config *out);

#endif
