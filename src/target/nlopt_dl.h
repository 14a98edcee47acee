/* nlopt_dl.h - internal: NLopt is loaded when first used (nlopt_dl.c defines the NLopt
 * functions lvsim calls and forwards them); include <nlopt.h> for the functions. */
#ifndef LV_TARGET_NLOPT_DL_H
#define LV_TARGET_NLOPT_DL_H

/* Why NLopt could not be loaded (an NLopt function then fails), or NULL when it is loaded.
 * Loads it if no NLopt function has yet. */
const char *lv_nlopt_error(void);

#endif
