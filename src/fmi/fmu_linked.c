/* fmu_linked.c - the FMU binary links SUNDIALS and Nettle statically (CMakeLists.txt,
 * lvsim_fmu): they are always there, so the questions liblvsim asks of its first-use loaders
 * (integrate/sundials_dl.h, io/nettle_dl.h) have the answer "loaded". liblvsim itself gets
 * these functions from integrate/cvode_dl.c, arkode_dl.c and io/nettle_dl.c instead. */
#include "integrate/sundials_dl.h"
#include "io/nettle_dl.h"

const char *lv_cvode_error(void) { return 0; }
const char *lv_arkode_error(void) { return 0; }
const char *lv_nettle_error(void) { return 0; }
