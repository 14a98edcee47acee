/* zip_dl.h - internal: libzip is loaded when first used (zip_dl.c defines the libzip
 * functions lvsim calls and forwards them); include <zip.h> for the functions themselves. */
#ifndef LV_FMI_ZIP_DL_H
#define LV_FMI_ZIP_DL_H

/* Why libzip could not be loaded (a zip function then fails), or NULL when it is loaded.
 * Loads it if no zip function has yet. */
const char *lv_zip_error(void);

#endif
