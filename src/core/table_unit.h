/* table_unit.h - a table column's unit against the one lvsim reads it in, and a derivative's
 * unit (not exported).
 * lvsim converts no units: a table column is read in SI ("rad", "m", "s", "N", "kg/s", "1");
 * a unit written in the file ("pitch [deg]") must be that one, or the table is refused,
 * naming the column, its unit and the one expected. No unit at all is accepted (SI read). */
#ifndef LV_CORE_TABLE_UNIT_H
#define LV_CORE_TABLE_UNIT_H

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"

/* 1 if `given` ("" when the file gives none) is `si`: the same text, an accepted spelling
 * ("kg/m3" and "kg/m^3", "m/s2" and "m/s^2"), or dimensionless as "1", "-" or "". */
int lv_unit_matches(const char *given, const char *si);

/* Axis `k` (is_axis) or output `k` of table t read in `si`: LV_OK, or LV_ERR_INPUT
 * "<what>: table 'T': column 'pitch' is in [deg]; lvsim reads it in rad (write [rad] or no
 * unit; no units are converted)". */
lv_status lv_table_expect_unit(const lv_table *t, int is_axis, size_t k, const char *si,
                               const char *what, lv_err *err);

/* lv_unit_per_second (a derivative's unit) is in lvsim/lv_units.h: the CLI uses it too. */
#include "lvsim/lv_units.h"

#endif
