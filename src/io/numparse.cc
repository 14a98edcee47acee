// numparse.cc - lv_numparse_double() (numparse.h): decimal text to the nearest double with
// fast_float (Lemire's Eisel-Lemire algorithm with an exact fallback; Debian package
// libfast-float-dev, header-only), for the plain decimal numbers lvsim's own files hold;
// anything else (blanks, '+', hexadecimal, "infinity", ...) goes to strtod(). Both round
// correctly, so the value is strtod's either way. No exceptions, no allocation, no libstdc++.
#include "io/numparse.h"

#include <cerrno>
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
