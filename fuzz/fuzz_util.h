/* fuzz_util.h - what the libFuzzer targets share: a private temporary folder and the contract
 * every fallible call is held to (a terminated message on failure). Header-only: each target
 * is one translation unit. */
#ifndef LV_FUZZ_UTIL_H
#define LV_FUZZ_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lvsim/lv_status.h"

/* dir = $TMPDIR (else /tmp) + "/lvsim-fuzz-<tag>-XXXXXX", created; aborts when it cannot be. */
static inline void lv_fuzz_tempdir(char *dir, size_t cap, const char *tag)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, cap, "%s/lvsim-fuzz-%s-XXXXXX",
             tmp != NULL && tmp[0] != '\0' && strlen(tmp) < 4096 ? tmp : "/tmp", tag);
    if (mkdtemp(dir) == NULL) {
        fprintf(stderr, "fuzz_%s: mkdtemp %s: ", tag, dir);
        perror(NULL);
        abort();
    }
}

/* The contract of every fallible call: a terminated message on failure (shown with
 * LV_FUZZ_VERBOSE set, to see where a seed goes). */
static inline void lv_fuzz_check_status(lv_status st, const lv_err *err)
{
    if (st != LV_OK && memchr(err->msg, '\0', sizeof err->msg) == NULL)
        __builtin_trap();
    if (st != LV_OK && getenv("LV_FUZZ_VERBOSE") != NULL)
        fprintf(stderr, "status %d: %s\n", (int)st, err->msg);
}

#endif
