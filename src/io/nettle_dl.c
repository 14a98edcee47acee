/* nettle_dl.c - GNU Nettle's SHA-256, loaded the first time lvsim hashes a file it writes.
 *
 * Every results file is hashed as it is written (io/atomic.c) for its folder's manifest, but
 * `lvsim --version`, `check` and the commands that write nothing never hash: linking Nettle
 * cost each of them its loading and relocation, about 333,000 instructions (callgrind, an
 * empty program linked with libnettle: 461,965 against 128,522), more than lvsim's own start.
 * These forwarders (io/dl_lib.h) have Nettle's own signatures (nettle/sha2.h: sha256_init is
 * a macro for nettle_sha256_init) and open the library once per process at the first call.
 * Nettle's functions return nothing, so a caller asks lv_nettle_error() before it trusts a
 * digest: atomic.c then records none (the manifest reads the file), post/sha256.c and the FMU
 * exporter fail naming the reason. libnettle8 is on every Debian system (apt and GnuTLS need
 * it). Compiled into liblvsim and, hidden, into each library that carries io/atomic.c. */
#define _GNU_SOURCE

#include <nettle/sha2.h>

#include "io/dl_lib.h"
#include "io/nettle_dl.h"

#ifndef LV_NETTLE_SONAME
#define LV_NETTLE_SONAME "libnettle.so.8" /* set by cmake/lv_deps.cmake */
#endif

/* X(return type, name, parameters, arguments, value on failure); V(name, ...) for void */
#define NETTLE_FUNCS(X, V)                                                                    \
    V(nettle_sha256_init, (struct sha256_ctx * a), (a))                                      \
    V(nettle_sha256_update, (struct sha256_ctx * a, size_t b, const uint8_t *c), (a, b, c))  \
    V(nettle_sha256_digest, (struct sha256_ctx * a, size_t b, uint8_t *c), (a, b, c))

LV_DL_LIBRARY(LV_NETTLE_SONAME, NETTLE_FUNCS)

const char *lv_nettle_error(void) { return dl_error(); }
