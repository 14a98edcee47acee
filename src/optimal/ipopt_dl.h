/* ipopt_dl.h - internal: IPOPT is loaded when first used (ipopt_dl.c defines the IPOPT
 * functions lvsim calls and forwards them); include <IpStdCInterface.h> for the functions. */
#ifndef LV_OPTIMAL_IPOPT_DL_H
#define LV_OPTIMAL_IPOPT_DL_H

/* Why IPOPT could not be loaded (an IPOPT function then fails), or NULL when it is loaded.
 * Loads it if no IPOPT function has yet. */
const char *lv_ipopt_error(void);

#endif
