/* mat_records.h - a parameter's record in a dsres MAT v4 result file, read from the file itself
 * (docs/result-files.md): the names in `name` (char, one name per column), their places in
 * `dataInfo` (int32, 4 x n: matrix 1 = data_1, column), the values in `data_1` (double,
 * (1 + np) x 2, column-major: column 1 at t0). A reader independent of the writer
 * (src/io/result_mat.c), for the tests that check what a file records. */
#ifndef LV_TEST_MAT_RECORDS_H
#define LV_TEST_MAT_RECORDS_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The value that the dsres file `path` records for parameter `name` at t0. Returns 0, -1 when
 * the file cannot be read, 1 when `name` is no parameter of it. */
static int mat_param(const char *path, const char *name, double *value)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return -1;
    char *names = NULL;
    int32_t *info = NULL;
    double *d1 = NULL;
    int32_t nm_rows = 0, nm_cols = 0, in_rows = 0, in_cols = 0, d1_rows = 0;
    int rc = -1;
    int32_t h[5];
    while (fread(h, sizeof h, 1, fp) == 1) {
        char mname[32];
        if (h[4] < 1 || h[4] > (int32_t)sizeof mname || fread(mname, (size_t)h[4], 1, fp) != 1)
            goto done;
        mname[h[4] - 1] = '\0';
        const int prec = (h[0] / 10) % 10; /* 0 double, 2 int32, 5 uint8 */
        const size_t elem = prec == 0 ? 8 : prec == 1 || prec == 2 ? 4 : prec == 5 ? 1 : 2;
        const size_t n = (size_t)h[1] * (size_t)h[2];
        void **dst = NULL;
        if (strcmp(mname, "name") == 0 && prec == 5) {
            dst = (void **)&names;
            nm_rows = h[1], nm_cols = h[2];
        } else if (strcmp(mname, "dataInfo") == 0 && prec == 2) {
            dst = (void **)&info;
            in_rows = h[1], in_cols = h[2];
        } else if (strcmp(mname, "data_1") == 0 && prec == 0) {
            dst = (void **)&d1;
            d1_rows = h[1];
        }
        if (dst == NULL) {
            if (fseek(fp, (long)(n * elem), SEEK_CUR) != 0)
                goto done;
            continue;
        }
        if ((*dst = malloc(n * elem + 1)) == NULL || fread(*dst, elem, n, fp) != n)
            goto done;
    }
    if (names == NULL || info == NULL || d1 == NULL || in_rows < 2 || in_cols != nm_cols)
        goto done;
    rc = 1;
    for (int32_t j = 0; j < nm_cols; j++) {
        char buf[256];
        int32_t len = nm_rows < (int32_t)sizeof buf - 1 ? nm_rows : (int32_t)sizeof buf - 1;
        memcpy(buf, names + (size_t)j * (size_t)nm_rows, (size_t)len);
        buf[len] = '\0';
        for (int32_t i = len - 1; i >= 0 && (buf[i] == ' ' || buf[i] == '\0'); i--)
            buf[i] = '\0';
        if (strcmp(buf, name) != 0)
            continue;
        const int32_t mat = info[(size_t)j * (size_t)in_rows], col = info[(size_t)j * (size_t)in_rows + 1];
        const int32_t row = (col < 0 ? -col : col) - 1;
        if (mat == 1 && row >= 0 && row < d1_rows) {
            *value = (col < 0 ? -1.0 : 1.0) * d1[row];
            rc = 0;
        }
        break;
    }
done:
    free(names);
    free(info);
    free(d1);
    fclose(fp);
    return rc;
}

#endif
