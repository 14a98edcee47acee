/* sha256.c - SHA-256 (FIPS 180-4) of a file, for the results folder's manifest.
 *
 * The digest comes from GNU Nettle (Debian's nettle-dev; libnettle8 is on every Debian
 * system, as GnuTLS and apt depend on it): a small, audited implementation with a plain
 * init/update/digest API and no global state, rather than a hash of our own. SHA-256
 * because it is what `sha256sum` (coreutils) and Python's hashlib check, so anyone can
 * verify a manifest without lvsim. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <nettle/sha2.h>
#include <stdio.h>
#include <string.h>

#include "core/status.h"
#include "io/nettle_dl.h"
#include "lvsim/lv_outdir.h"

lv_status lv_sha256_file(const char *path, char hex[65], unsigned long long *bytes, lv_err *err)
{
    char text[128];
    hex[0] = '\0';
    const char *why = lv_nettle_error(); /* loaded on first use: io/nettle_dl.c */
    if (why != NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot compute its SHA-256: %s", path, why);
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", path, lv_strerror(errno, text, sizeof text));
    struct sha256_ctx ctx;
    sha256_init(&ctx);
    unsigned char buf[1 << 16];
    unsigned long long n = 0;
    size_t got;
    while ((got = fread(buf, 1, sizeof buf, fp)) > 0) {
        sha256_update(&ctx, got, buf);
        n += got;
    }
    const int bad = ferror(fp);
    const int e = errno;
    fclose(fp);
    if (bad)
        return lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", path, lv_strerror(e ? e : EIO, text, sizeof text));
    unsigned char d[SHA256_DIGEST_SIZE];
    sha256_digest(&ctx, sizeof d, d);
    for (size_t i = 0; i < sizeof d; i++)
        snprintf(hex + 2 * i, 3, "%02x", d[i]);
    if (bytes != NULL)
        *bytes = n;
    return LV_OK;
}
