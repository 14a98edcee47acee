/* lv_export.h - trajectory exports of a finished run: CZML (Cesium), KML 2.2 (Google Earth)
 * and CCSDS OEM 2.0 (KVN) ephemerides.
 *
 * Post-processing only: the exports read a results folder (summary.json and the merged
 * body_<stage>.csv files the runner writes) and never rerun anything; the mission file is not
 * needed. What each file holds, frames, units and the rules: docs/exports.md.
 */
#ifndef LVSIM_LV_EXPORT_H
#define LVSIM_LV_EXPORT_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The flag of export i of lv_export_format_info() is 1u << i: */
#define LV_EXPORT_CZML 1u /* OUTDIR/mission.czml */
#define LV_EXPORT_KML 2u  /* OUTDIR/mission.kml */
#define LV_EXPORT_OEM 4u  /* OUTDIR/<stage>.oem per body with an orbital portion (Earth only) */
#define LV_EXPORT_ALL (~0u) /* every registered export */

/* The registered exports, by position i = 0, 1, ... (flag 1u << i): its name ("czml": the
 * word of `lvsim export --format`, `lvsim run --outputs` and lv_export_item.format), and, when
 * the pointers are not NULL, the files it writes in OUTDIR ("mission.czml", "<stage>.oem") and
 * a one-line description. NULL when i is past the last export. Strings are static. */
LV_API const char *lv_export_format_info(size_t i, const char **files, const char **description);

/* Reads OUTDIR/summary.json and the body CSVs it lists, then writes the formats selected by
 * `formats` (an OR of LV_EXPORT_* flags; LV_EXPORT_ALL: every one) into OUTDIR. Each file is written under
 * "<name>.tmp" and renamed when complete. OEM files are written only for planet-world
 * missions over the Earth and only for bodies that have rows above 100 km; a flat-world
 * mission gets none (not an error). Times are the epoch plus SI seconds, written as UTC with
 * its leap seconds (ERFA): 23:59:60.ffffff inside one (CZML, OEM), 23:59:59.999999 in KML,
 * whose xsd:dateTime has no second 60 (docs/exports.md, "Times").
 * Errors: LV_ERR_IO when a file cannot be read or written (names the path and the system's
 * reason); LV_ERR_INPUT for a malformed summary.json ("path:line: ...") or body CSV
 * ("path:line: ..."), a summary and CSV that disagree, an epoch that is no UTC instant
 * (23:59:60 of a day without a leap second) or times past the year 9999; LV_ERR_NOMEM. */
LV_API lv_status lv_export_run(const char *outdir, unsigned formats, lv_err *err);

/* What an export request did: one item per file written, and one per requested format or
 * body that got no file, saying why ("oem: flat world: no orbit to describe"); and an item
 * "utc" without a file when the written UTC times lie past ERFA's leap-second table (or
 * before 1960), saying how far they can be off. */
typedef struct lv_export_item {
    char format[8];  /* "czml", "kml", "oem"; "utc" for the note on the times */
    char file[256];  /* the file written in OUTDIR ("mission.czml"), or "" */
    char note[256];  /* why nothing was written, or what the file leaves out; "" */
} lv_export_item;
typedef struct lv_export_report {
    size_t n;
    lv_export_item *items;
} lv_export_report;

/* lv_export_run, and what it wrote or not into *rep (zeroed first; rep may be NULL; free
 * with lv_export_report_clear, also after a failure). */
LV_API lv_status lv_export_run_report(const char *outdir, unsigned formats, lv_export_report *rep,
                                      lv_err *err);
LV_API void lv_export_report_clear(lv_export_report *rep);

#ifdef __cplusplus
}
#endif
#endif
