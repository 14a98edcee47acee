/* sundials_dl.h - internal: SUNDIALS' CVODE and ARKODE libraries are loaded on first use
 * (integrate/cvode_dl.c, arkode_dl.c; io/dl_lib.h). Not exported. */
#ifndef LV_INTEGRATE_SUNDIALS_DL_H
#define LV_INTEGRATE_SUNDIALS_DL_H

/* NULL when the library is loaded (loading it now if no function has yet), else why it could
 * not be: the dynamic loader's message, or the function it lacks. Thread-safe. */
const char *lv_cvode_error(void);
const char *lv_arkode_error(void);

#endif
