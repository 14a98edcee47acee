/* json_print.h - internal: a cJSON document as text with exact numbers.
 *
 * cJSON 1.7.15's printer writes a number with 15 significant digits whenever they read back
 * within DBL_EPSILON (relative) of it, so it writes a different double for 8.5 % of
 * trajectory-like numbers (test_export: 847 of 9,983): a phase's end at t = 190.80430311868503 s came out as 190.804303118685, 3e-14 s
 * earlier than its result file's last row. lv_json_print lays the document out as
 * cJSON_Print does (indentation, key order, escapes) but writes every number as the shortest
 * decimal text that reads back to the same double (io/numfmt.h, Dragonbox: what the result
 * CSVs write), and NaN and the infinities as null (JSON has neither), as cJSON does.
 * Every JSON file lvsim writes goes through it: summary.json, manifest.json,
 * key_figures.json, a campaign's stats.json and the CLI's --json documents. (CZML, which is
 * streamed, writes its numbers with the same digits: export_czml.c.) */
#ifndef LV_POST_JSON_PRINT_H
#define LV_POST_JSON_PRINT_H

#include <cjson/cJSON.h>

/* The document as formatted text (free with cJSON_free), NULL when out of memory. The
 * document is the same afterwards: its numbers are turned into raw text for the printing
 * and back. Not thread-safe on one document (it is modified meanwhile); documents of other
 * threads are independent. */
char *lv_json_print(cJSON *doc);

#endif
