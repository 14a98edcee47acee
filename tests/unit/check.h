/* check.h - minimal test assertions for lvsim unit tests (one executable per module).
 *
 * CHECK(cond), CHECK_CLOSE(a, b, abs_tol), CHECK_REL(a, b, rel_tol), CHECK_OK(status_expr, err).
 * Failures print file:line and the values; main() returns check_report().
 */
#ifndef LV_TEST_CHECK_H
#define LV_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static int check_failures_ = 0;
static int check_count_ = 0;

static inline void check_true_(int ok, const char *expr, const char *file, int line)
{
    check_count_++;
    if (!ok) {
        check_failures_++;
        fprintf(stderr, "%s:%d: CHECK failed: %s\n", file, line, expr);
    }
}
static inline void check_close_(double a, double b, double tol, const char *ea, const char *eb,
                                const char *file, int line)
{
    check_count_++;
    if (!(fabs(a - b) <= tol)) {
        check_failures_++;
        fprintf(stderr, "%s:%d: CHECK_CLOSE failed: %s = %.17g, %s = %.17g, |diff| = %.3g > %.3g\n",
                file, line, ea, a, eb, b, fabs(a - b), tol);
    }
}
static inline void check_rel_(double a, double b, double rtol, const char *ea, const char *eb,
                              const char *file, int line)
{
    check_count_++;
    double scale = fabs(b) > 0 ? fabs(b) : 1.0;
    if (!(fabs(a - b) <= rtol * scale)) {
        check_failures_++;
        fprintf(stderr, "%s:%d: CHECK_REL failed: %s = %.17g, %s = %.17g, rel diff = %.3g > %.3g\n",
                file, line, ea, a, eb, b, fabs(a - b) / scale, rtol);
    }
}

#define CHECK(cond) check_true_(!!(cond), #cond, __FILE__, __LINE__)
#define CHECK_CLOSE(a, b, tol) check_close_((a), (b), (tol), #a, #b, __FILE__, __LINE__)
#define CHECK_REL(a, b, rtol) check_rel_((a), (b), (rtol), #a, #b, __FILE__, __LINE__)
/* Expect LV_OK; print the error message otherwise. */
#define CHECK_OK(expr, errp)                                                              \
    do {                                                                                  \
        lv_status st_ = (expr);                                                           \
        check_count_++;                                                                   \
        if (st_ != LV_OK) {                                                               \
            check_failures_++;                                                            \
            fprintf(stderr, "%s:%d: %s failed: %s\n", __FILE__, __LINE__, #expr, (errp)->msg); \
        }                                                                                 \
    } while (0)
/* Expect a failure with `code` whose message contains `needle`. */
#define CHECK_FAILS(expr, errp, code, needle)                                             \
    do {                                                                                  \
        (errp)->msg[0] = '\0';                                                            \
        lv_status st_ = (expr);                                                           \
        check_count_++;                                                                   \
        if (st_ != (code) || strstr((errp)->msg, (needle)) == NULL) {                     \
            check_failures_++;                                                            \
            fprintf(stderr, "%s:%d: %s: expected status %d with \"%s\", got %d: \"%s\"\n", \
                    __FILE__, __LINE__, #expr, (int)(code), (needle), (int)st_, (errp)->msg); \
        }                                                                                 \
    } while (0)

static inline int check_report(const char *name)
{
    printf("%s: %d checks, %d failed\n", name, check_count_, check_failures_);
    return check_failures_ == 0 ? 0 : 1;
}

#endif
