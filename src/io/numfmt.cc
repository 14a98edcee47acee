// numfmt.cc - lv_numfmt_double() (numfmt.h): the shortest round-trip decimal digits of a double
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

// Number of decimal digits of s (1..20): from its bit length, log10(2) ~ 1233 / 4096, and
// one comparison.
int digit_count(std::uint64_t s)
{
    static constexpr std::uint64_t kPow10[] = {
        1u, 10u, 100u, 1000u, 10000u, 100000u, 1000000u, 10000000u, 100000000u, 1000000000u,
        10000000000u, 100000000000u, 1000000000000u, 10000000000000u, 100000000000000u,
        1000000000000000u, 10000000000000000u, 100000000000000000u, 1000000000000000000u,
        10000000000000000000u};
    const int bits = 64 - __builtin_clzll(s | 1u);
    const int n = (bits * 1233) >> 12;
    return n + (s >= kPow10[n] ? 1 : 0);
}

// Writes the n decimal digits of s (n = digit_count(s)) into d[0..n), from the right: blocks
// of eight digits in 32-bit arithmetic, two digits a lookup.
void write_digits(std::uint64_t s, int n, char *d)
{
    char *p = d + n;
    while (s >= 100000000u) {
        std::uint32_t low = static_cast<std::uint32_t>(s % 100000000u);
        s /= 100000000u;
        for (int k = 0; k < 4; k++) {
            const std::uint32_t q = low % 100u;
            low /= 100u;
            p -= 2;
            std::memcpy(p, kPairs + 2 * q, 2);
        }
    }
    std::uint32_t v = static_cast<std::uint32_t>(s);
    while (v >= 100u) {
        const std::uint32_t q = v % 100u;
        v /= 100u;
        p -= 2;
        std::memcpy(p, kPairs + 2 * q, 2);
    }
    if (v >= 10u) {
        p -= 2;
        std::memcpy(p, kPairs + 2 * v, 2);
    } else {
        *--p = static_cast<char>('0' + v);
    }
}

} // namespace

extern "C" size_t lv_numfmt_double(double v, char *buf)
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
    const int n = digit_count(dec.significand);
    write_digits(dec.significand, n, d);
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
