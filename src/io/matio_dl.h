/* matio_dl.h - internal: libmatio is loaded when first used (matio_dl.c defines the matio
 * functions lvsim calls and forwards them); include <matio.h> for the functions themselves.
 * Not exported. */
#ifndef LV_IO_MATIO_DL_H
#define LV_IO_MATIO_DL_H

/* Why libmatio could not be loaded (a MAT function then fails), or NULL when it is loaded.
 * Loads it if no MAT function has yet. */
const char *lv_matio_error(void);

#endif
