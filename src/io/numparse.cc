// numparse.cc - lv_numparse_double() (numparse.h): decimal text to the nearest double with
// fast_float (Lemire's Eisel-Lemire algorithm with an exact fallback; Debian package
// libfast-float-dev, header-only), for the plain decimal numbers lvsim's own files hold;
// anything else (blanks, '+', hexadecimal, "infinity", ...) goes to strtod(). Both round
// correctly, so the value is strtod's either way. No exceptions, no allocation, no libstdc++.
#include "io/numparse.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdlib>

#include <fast_float/fast_float.h>

extern "C" double lv_numparse_double(const char *s, char **end)
{
    const char *p = s;
    if (*p == '-')
        p++;
    // the fast path: [-]digits[.digits][(e|E)[+-]digits], or [-]nan / [-]inf as lvsim writes
    if ((*p >= '0' && *p <= '9') || (*p == '.' && p[1] >= '0' && p[1] <= '9') || *p == 'n' ||
        *p == 'i') {
        const char *stop = s;
        while (*stop != '\0' && *stop != ',' && *stop != ' ' && *stop != '\t' && *stop != '\n' &&
               *stop != '\r')
            stop++;
        double v = 0.0;
        const auto r = fast_float::from_chars(s, stop, v);
        if (r.ec == std::errc() && r.ptr == stop && (*p != 'i' || stop - p == 3)) {
            *end = const_cast<char *>(stop);
            return v;
        }
    }
    return std::strtod(s, end); // the rest, with strtod's own rules
}

extern "C" int lv_numparse_field(const char *s, size_t len, double *v)
{
    if (len == 0 || len >= 64)
        return -1;
    const char *p = s, *e = s + len;
    if (*p == '-')
        p++;
    if (p < e && ((*p >= '0' && *p <= '9') || (*p == '.' && p + 1 < e && p[1] >= '0' && p[1] <= '9'))) {
        double x = 0.0;
        const auto r = fast_float::from_chars(s, e, x);
        // normal results only: fast_float 3.9 rounds an underflow to 0 or a subnormal and an
        // overflow to inf without saying so, where strtod sets ERANGE; those go to strtod
        if (r.ec == std::errc() && r.ptr == e && std::isnormal(x)) {
            *v = x;
            return 0;
        }
    }
    char buf[64];
    std::memcpy(buf, s, len);
    buf[len] = '\0';
    char *end = nullptr;
    errno = 0;
    const double x = std::strtod(buf, &end);
    if (end != buf + len || !std::isfinite(x) || errno == ERANGE)
        return -1;
    *v = x;
    return 0;
}
