// numfmt.cc - lv_fmt_double() (numfmt.h): the shortest round-trip decimal digits of a double
// from Dragonbox (jkj::dragonbox::to_decimal: correctly rounded, fewest digits that read back
// to the same double; Debian package libdragonbox-dev), laid out the way %.17g lays numbers
// out. The only C++ in lvsim: a C interface, no exceptions, no allocation, no libstdc++.
#include "io/numfmt.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include <dragonbox/dragonbox.h>

namespace {

// Two decimal digits at a time: "00" .. "99".
constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Writes the decimal digits of s (no leading zeros) into d; returns their count (1..17).
int digits_of(std::uint64_t s, char *d)
{
    char tmp[24];
    int n = 0;
    while (s >= 100) {
        const unsigned q = static_cast<unsigned>(s % 100);
        s /= 100;
        tmp[n++] = kPairs[2 * q + 1];
        tmp[n++] = kPairs[2 * q];
    }
    if (s >= 10) {
        const unsigned q = static_cast<unsigned>(s);
        tmp[n++] = kPairs[2 * q + 1];
        tmp[n++] = kPairs[2 * q];
    } else {
        tmp[n++] = static_cast<char>('0' + s);
    }
    for (int i = 0; i < n; i++)
        d[i] = tmp[n - 1 - i];
    return n;
}

} // namespace

extern "C" size_t lv_fmt_double(double v, char *buf)
{
    char *p = buf;
    if (std::signbit(v))
        *p++ = '-';
    if (std::isnan(v)) {
        std::memcpy(p, "nan", 4);
        return static_cast<size_t>(p - buf) + 3;
    }
    if (std::isinf(v)) {
        std::memcpy(p, "inf", 4);
        return static_cast<size_t>(p - buf) + 3;
    }
    if (v == 0.0) {
        std::memcpy(p, "0", 2);
        return static_cast<size_t>(p - buf) + 1;
    }
    // v = s * 10^e with the fewest digits of s that round-trip (trailing zeros removed).
    const auto dec = jkj::dragonbox::to_decimal(v, jkj::dragonbox::policy::sign::ignore);
    char d[24];
    const int n = digits_of(dec.significand, d);
    const int k = n + dec.exponent; // v = 0.d1 d2 .. dn * 10^k
    const int x = k - 1;            // the exponent %g would print
    if (x >= -4 && x < 17) {        // %.17g's rule for plain decimal notation
        if (k <= 0) {
            *p++ = '0';
            *p++ = '.';
            for (int i = 0; i < -k; i++)
                *p++ = '0';
            std::memcpy(p, d, static_cast<size_t>(n));
            p += n;
        } else if (k < n) {
            std::memcpy(p, d, static_cast<size_t>(k));
            p += k;
            *p++ = '.';
            std::memcpy(p, d + k, static_cast<size_t>(n - k));
            p += n - k;
        } else {
            std::memcpy(p, d, static_cast<size_t>(n));
            p += n;
            for (int i = n; i < k; i++)
                *p++ = '0';
        }
    } else { // d1[.d2..dn]e+XX, two exponent digits at least, as C prints them
        *p++ = d[0];
        if (n > 1) {
            *p++ = '.';
            std::memcpy(p, d + 1, static_cast<size_t>(n - 1));
            p += n - 1;
        }
        *p++ = 'e';
        int ex = x;
        if (ex < 0) {
            *p++ = '-';
            ex = -ex;
        } else {
            *p++ = '+';
        }
        if (ex >= 100) {
            *p++ = static_cast<char>('0' + ex / 100);
            ex %= 100;
        }
        *p++ = kPairs[2 * ex];
        *p++ = kPairs[2 * ex + 1];
    }
    *p = '\0';
    return static_cast<size_t>(p - buf);
}
