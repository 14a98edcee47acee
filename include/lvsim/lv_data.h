/* lv_data.h - where lvsim finds its data files at run time: the gravity coefficients
 * (gravity/egm2008_n20.gfc) and the 3-D viewer (viewer/stage.sh, viewer/web/).
 *
 * Nothing is looked up by a path compiled in from the source tree. A name relative to the
 * data folder is searched in these folders, first match wins:
 *   1. `dir`, when the caller gives one;
 *   2. $LVSIM_DATA (one folder: an installation's share/lvsim, or a copy of it);
 *   3. next to the library that holds lvsim: <libdir>/../share/lvsim, and for a multiarch
 *      libdir (lib/<triplet>) also <libdir>/../../share/lvsim. When lvsim is linked
 *      statically into a program, <libdir> is the program's folder. The build tree has the
 *      same layout (build/lib, build/share/lvsim), so it works without installing;
 *   4. the install prefix's datadir chosen at configure time (<prefix>/share/lvsim).
 */
#ifndef LVSIM_LV_DATA_H
#define LVSIM_LV_DATA_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LV_DATA_ENV "LVSIM_DATA" /* environment variable naming a data folder */

/* Finds the data file `name` ("gravity/egm2008_n20.gfc": relative, not empty) and writes
 * its path (a folder above joined with `name`) to path[size]. `dir` may be NULL.
 * Reads the environment (getenv) and the file system; keeps nothing.
 * Not found: LV_ERR_NOTFOUND, the message lists every folder searched. Bad name or a path
 * longer than size - 1: LV_ERR_INPUT. */
LV_API lv_status lv_data_find(const char *dir, const char *name, char *path, size_t size,
                              lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
