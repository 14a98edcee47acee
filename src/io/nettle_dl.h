/* nettle_dl.h - internal: GNU Nettle (SHA-256) is loaded on first use (io/nettle_dl.c,
 * io/dl_lib.h). Not exported. */
#ifndef LV_IO_NETTLE_DL_H
#define LV_IO_NETTLE_DL_H

/* NULL when Nettle is loaded (loading it now if no function has yet), else why it could not
 * be: the dynamic loader's message, or the function it lacks. Thread-safe. */
const char *lv_nettle_error(void);

#endif
