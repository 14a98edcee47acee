/* test_numfmt.c - lv_numfmt_double (src/io/numfmt.h): every number reads back with strtod to the
 * same double, bit for bit, over millions of random bit patterns and of values like those a
 * run writes; the digits are the fewest that do (checked against %.{p}g for p = 1..17); the
 * layout is %.17g's (plain decimal for exponents -4..16, else d.ddde+XX); special values.
 * lv_numparse_double (src/io/numparse.h) gives strtod's value and end on all of these and on
 * the odd texts strtod accepts or refuses; lv_numparse_field follows the input tables' strtod
 * rule (whole field, finite, no ERANGE) on the same. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/numfmt.h"
#include "io/numparse.h"

static uint64_t rng_state = 0x9E3779B97F4A7C15u;

static uint64_t rng(void) /* xorshift64* */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 2685821657736338717u;
}

static double from_bits(uint64_t b)
{
    double v;
    memcpy(&v, &b, sizeof v);
    return v;
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Significant digits of a number printed in our layout ("-0.00123" -> 3, "1.5e+20" -> 2). */
static int sig_digits(const char *s)
{
    int n = 0, started = 0, trailing = 0;
    for (const char *c = s; *c != '\0' && *c != 'e'; c++) {
        if (*c < '0' || *c > '9')
            continue;
        if (*c != '0')
            started = 1;
        if (!started)
            continue;
        n++;
        trailing = *c == '0' ? trailing + 1 : 0;
    }
    /* trailing zeros of an integer such as 1200 are not significant */
    return n - (strchr(s, '.') == NULL ? trailing : 0);
}

/* The fewest digits p with which %.{p}g reads back to v. */
static int shortest_printf(double v)
{
    char buf[64];
    for (int p = 1; p <= 17; p++) {
        snprintf(buf, sizeof buf, "%.*g", p, v);
        if (same_bits(strtod(buf, NULL), v))
            return p;
    }
    return 17;
}

static long round_trips(long n, double (*gen)(void), int check_shortest)
{
    char buf[LV_NUMFMT_MAX];
    long bad = 0, longer = 0;
    for (long i = 0; i < n; i++) {
        const double v = gen();
        const size_t len = lv_numfmt_double(v, buf);
        if (len != strlen(buf) || len >= LV_NUMFMT_MAX - 7) {
            bad++;
            continue;
        }
        char *end = NULL;
        const double back = strtod(buf, &end);
        if (*end != '\0' || !(same_bits(back, v) || (isnan(v) && isnan(back)))) {
            if (bad++ < 5)
                fprintf(stderr, "round trip: %a printed as '%s' reads %a\n", v, buf, back);
        }
        if (check_shortest && isfinite(v) && v != 0.0 && sig_digits(buf) > shortest_printf(v)) {
            if (longer++ < 5)
                fprintf(stderr, "not shortest: %.17g printed as '%s' (%d digits)\n", v, buf,
                        shortest_printf(v));
        }
    }
    return bad + longer;
}

static double gen_bits(void) { return from_bits(rng()); }

/* Values like a run's: magnitudes 1e-12 .. 1e8, grid times, integers, halves. */
static double gen_physical(void)
{
    const uint64_t r = rng();
    const double u = (double)(r >> 11) * 0x1.0p-53;
    switch (r & 7) {
    case 0: return (double)(r % 100001) * 0.01;          /* grid times */
    case 1: return (double)((int64_t)(r % 2000001) - 1000000); /* integers */
    case 2: return (u - 0.5) * 1e7;
    case 3: return u * 1e-6;
    case 4: return pow(10.0, 20.0 * u - 12.0);
    case 5: return -pow(10.0, 30.0 * u - 15.0);
    case 6: return (double)(r % 1000) * 0.5;
    default: return u;
    }
}

/* lv_numparse_double == strtod: the value (bits) and where it stopped. */
static int parse_same(const char *text)
{
    char *e1 = NULL, *e2 = NULL;
    const double a = strtod(text, &e1), b = lv_numparse_double(text, &e2);
    const int ok = e1 == e2 && (same_bits(a, b) || (isnan(a) && isnan(b)));
    if (!ok)
        fprintf(stderr, "lv_numparse_double('%s') = %a (+%td), strtod %a (+%td)\n", text, b,
                e2 - text, a, e1 - text);
    return ok;
}

static void test_parse(void)
{
    const char *odd[] = {"0", "-0", "1", "-2.5", ".5", "-.5", "5.", "1e5", "1E+05", "1e-400",
                         "1e400", "-1e400", "nan", "-nan", "inf", "-inf", "infinity", "infx",
                         "Inf", "NaN", " 1.5", "+2", "0x1p3", "1e", "1e+", "abc", "", "-",
                         ".", "12,34", "3 ", "4\n", "1.7976931348623157e308",
                         "2.2250738585072011e-308", "4.9406564584124654e-324",
                         "0.30000000000000004", "123456789012345678901234567890"};
    for (size_t i = 0; i < sizeof odd / sizeof odd[0]; i++)
        CHECK(parse_same(odd[i]));
    char buf[64];
    long bad = 0;
    for (long i = 0; i < 1000000; i++) {
        const double v = (i & 1) ? gen_bits() : gen_physical();
        if (i % 3 == 0)
            snprintf(buf, sizeof buf, "%.17g", v);
        else
            lv_numfmt_double(v, buf);
        bad += !parse_same(buf);
        if (bad > 5)
            break;
    }
    CHECK(bad == 0);
}

/* The input tables' old rule, the reference for lv_numparse_field: strtod of the field alone,
 * the whole field consumed, finite, no ERANGE (src/io/table_load.c before fast_float). */
static int field_by_strtod(const char *s, size_t len, double *v)
{
    char buf[64];
    if (len == 0 || len >= sizeof buf)
        return -1;
    memcpy(buf, s, len);
    buf[len] = '\0';
    char *end = NULL;
    errno = 0;
    const double d = strtod(buf, &end);
    if (end != buf + len || !isfinite(d) || errno == ERANGE)
        return -1;
    *v = d;
    return 0;
}

static int field_same(const char *s, size_t len)
{
    double a = 42.0, b = 42.0;
    const int ra = field_by_strtod(s, len, &a), rb = lv_numparse_field(s, len, &b);
    const int ok = ra == rb && same_bits(a, b);
    if (!ok)
        fprintf(stderr, "lv_numparse_field('%.*s') = %d %a, strtod's rule %d %a\n", (int)len, s,
                rb, b, ra, a);
    return ok;
}

static void test_field(void)
{
    const char *odd[] = {"0", "-0", "0.0", "1", "-2.5", ".5", "-.5", "5.", "1e5", "1E+05",
                         "1e-400", "1e-310", "4.9406564584124654e-324", "1e400", "-1e400",
                         "nan", "inf", "-inf", "+2", "0x1p3", "1e", "1e+", "abc", "-", ".",
                         "1.5 ", " 1.5", "1,5", "1d5", "2.2250738585072014e-308",
                         "1.7976931348623157e308", "1.7976931348623159e308",
                         "123456789012345678901234567890", "0.30000000000000004",
                         "000000000000000000000000000000000000000000000000000000000000001"};
    for (size_t i = 0; i < sizeof odd / sizeof odd[0]; i++)
        CHECK(field_same(odd[i], strlen(odd[i])));
    /* a field inside a longer line: only its bytes count */
    const char *line = "12.5,7";
    CHECK(field_same(line, 4));
    CHECK(field_same(line, 2));
    CHECK(field_same(line, 6));
    char buf[64];
    long bad = 0;
    for (long i = 0; i < 300000 && bad <= 5; i++) {
        const double v = (i & 1) ? gen_bits() : gen_physical();
        if (i % 3 == 0)
            snprintf(buf, sizeof buf, "%.17g", v);
        else if (i % 3 == 1)
            snprintf(buf, sizeof buf, "%.6g", v); /* as a hand-written table holds them */
        else
            lv_numfmt_double(v, buf);
        bad += !field_same(buf, strlen(buf));
    }
    CHECK(bad == 0);
}

int main(void)
{
    test_parse();
    test_field();
    char buf[LV_NUMFMT_MAX];
    /* layout: the one of %.17g, with the fewest digits */
    const struct {
        double v;
        const char *text;
    } cases[] = {
        {0.0, "0"},           {-0.0, "-0"},         {1.0, "1"},           {-2.5, "-2.5"},
        {0.1, "0.1"},         {100.0, "100"},       {1e16, "10000000000000000"},
        {1e17, "1e+17"},      {1.5e17, "1.5e+17"},  {0.0001, "0.0001"},   {0.00012, "0.00012"},
        {1e-5, "1e-05"},      {-1.25e-7, "-1.25e-07"}, {1e100, "1e+100"}, {1e-300, "1e-300"},
        {123456.789, "123456.789"}, {5e-324, "5e-324"},
        {1.7976931348623157e308, "1.7976931348623157e+308"}, {0.30000000000000004,
        "0.30000000000000004"}, {20.8, "20.8"}, {INFINITY, "inf"}, {-INFINITY, "-inf"},
        {NAN, "nan"},         {-NAN, "-nan"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        lv_numfmt_double(cases[i].v, buf);
        if (strcmp(buf, cases[i].text) != 0) {
            fprintf(stderr, "%.17g: '%s', expected '%s'\n", cases[i].v, buf, cases[i].text);
            CHECK(0);
        }
    }
    /* %.17g and ours read back alike for the values of the old CSV files */
    for (int i = 0; i < 1000; i++) {
        const double v = gen_physical();
        snprintf(buf, sizeof buf, "%.17g", v);
        const double old = strtod(buf, NULL);
        lv_numfmt_double(v, buf);
        CHECK(same_bits(strtod(buf, NULL), old));
    }
    /* millions of round trips; the shortest property on a subset (its check is slow) */
    CHECK(round_trips(3000000, gen_bits, 0) == 0);
    CHECK(round_trips(1000000, gen_physical, 0) == 0);
    CHECK(round_trips(50000, gen_bits, 1) == 0);
    CHECK(round_trips(50000, gen_physical, 1) == 0);
    /* subnormals and powers of two at every exponent */
    for (int e = -1074; e <= 1023; e++) {
        const double v = ldexp(1.0, e);
        lv_numfmt_double(v, buf);
        CHECK(same_bits(strtod(buf, NULL), v));
        lv_numfmt_double(nextafter(v, 0.0), buf);
        CHECK(same_bits(strtod(buf, NULL), nextafter(v, 0.0)));
    }
    return check_report("test_numfmt");
}
