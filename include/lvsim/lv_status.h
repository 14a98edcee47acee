/* lv_status.h - status codes and the error record every fallible lvsim call fills.
 *
 * Contract: a fallible function returns lv_status and takes `lv_err *err` last;
 * `err` may be NULL. On failure err->msg names the file/line/field or the
 * model, time and reason. The library never prints and never exits.
 */
#ifndef LVSIM_LV_STATUS_H
#define LVSIM_LV_STATUS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(LV_BUILDING_LIBRARY) && defined(__GNUC__)
#define LV_API __attribute__((visibility("default")))
#else
#define LV_API
#endif

#define LV_STATUS_LIST(X)                                 \
    X(LV_OK, 0, "success")                                \
    X(LV_ERR_NOMEM, -1, "out of memory")                  \
    X(LV_ERR_INPUT, -2, "invalid input")                  \
    X(LV_ERR_SOLVER, -3, "integration failed")            \
    X(LV_ERR_IO, -4, "input/output error")                \
    X(LV_ERR_NOTFOUND, -5, "name not found")             \
    X(LV_ERR_CANCELLED, -6, "cancelled")

#define LV_STATUS_ENUM_(name, value, text) name = value,
typedef enum lv_status { LV_STATUS_LIST(LV_STATUS_ENUM_) } lv_status;
#undef LV_STATUS_ENUM_

#define LV_ERR_MSG_MAX 1024

typedef struct lv_err {
    lv_status code;
    char msg[LV_ERR_MSG_MAX];
} lv_err;

/* Short English text for a status code ("invalid input"). Never NULL. */
LV_API const char *lv_status_str(lv_status st);
/* The code's name as in this header ("LV_ERR_INPUT"), NULL for a number that is no status:
 * bindings build their list of statuses from it instead of re-typing LV_STATUS_LIST. */
LV_API const char *lv_status_name(lv_status st);

/* The library's version, LVSIM_VERSION of the headers it was built from ("0.1.0"). */
LV_API const char *lv_version(void);
/* sizeof the public structure named `type` ("lv_run_options", "lv_phase_result", ...) as
 * this library was compiled, 0 for a name it does not know: bindings that mirror the
 * structures (the Python package's ctypes) check at load time that they match. */
LV_API size_t lv_abi_sizeof(const char *type);

#ifdef __cplusplus
}
#endif
#endif
