/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_format_double (io.h, src/io/shortest_double.c, Ryu): every string reads back with
 * strtod to the same double, bit for bit, and is the shortest one:
 * - the published test vectors of Ryu's reference implementation (ulfjack/ryu,
 *   ryu/tests/d2s_test.cc: basic values, min and max, subnormal switch, trailing zeros,
 *   regressions, powers of five near q = 22, output lengths, shift bounds, small integers),
 *   compared as digits and exponent;
 * - 2 million random bit patterns (every exponent, subnormals, both signs) read back;
 * - the edges: every power of two from 2^-1074 to 2^1023, every power of ten from 1e-323 to
 *   1e308 and their neighbours, subnormals, DBL_MIN, DBL_MAX, -0, integers up to 2^53
 *   (written as the integer itself), the boundaries of every digit count (10^d - 1, 10^d);
 * - shortness: a decimal of d <= 15 significant digits (normal range) reads to a double
 *   that no other decimal of at most 15 digits reads to, so its shortest string is that
 *   decimal's digits; checked on 200,000 random ones (tests/shortest_oracle.py compares
 *   with Python's repr, David Gay's correctly rounded shortest);
 * - the layout of docs/data-files.md and JSON's number grammar (RFC 8259 sec. 6);
 * - the 64-bit-only multiply (no unsigned __int128) writes the same strings;
 * - dyn_text_writer and the CSV rows: read back exactly across buffer boundaries, and a
 *   full disk (/dev/full) reported by the writer. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "dynkit/io.h"
#include "dynkit/ode.h"

/* the same conversion compiled without unsigned __int128 (the portable multiply) */
#define dyn_format_double dyn_format_double_portable
#define DYNKIT_NO_INT128
#include "io/shortest_double.c"
#undef dyn_format_double
#undef DYNKIT_NO_INT128

static double from_bits(uint64_t u)
{
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

static uint64_t to_bits(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

/* xorshift64* (Vigna 2016): the random bit patterns */
static uint64_t next_random(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * UINT64_C(2685821657736338717);
}

/* RFC 8259 sec. 6: -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)? */
static int json_number(const char *s)
{
    if (*s == '-')
        s++;
    if (*s == '0')
        s++;
    else if (*s >= '1' && *s <= '9')
        while (*s >= '0' && *s <= '9')
            s++;
    else
        return 0;
    if (*s == '.') {
        if (!(*++s >= '0' && *s <= '9'))
            return 0;
        while (*s >= '0' && *s <= '9')
            s++;
    }
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-')
            s++;
        if (!(*s >= '0' && *s <= '9'))
            return 0;
        while (*s >= '0' && *s <= '9')
            s++;
    }
    return *s == '\0';
}

/* The significant digits (no leading or trailing zeros) and the decimal exponent of the
 * first one, of a finite string of dyn_format_double; sign dropped. */
static void digits_of(const char *s, char *digits, int *x10)
{
    int n = 0, point = -1, exp = 0, lead = 1, first = 0, pos = 0;
    if (*s == '-')
        s++;
    for (; *s && *s != 'e'; s++) {
        if (*s == '.') {
            point = pos;
            continue;
        }
        if (lead && *s == '0') {
            pos++;
            continue;
        }
        if (lead) {
            first = pos;
            lead = 0;
        }
        digits[n++] = *s;
        pos++;
    }
    if (*s == 'e')
        exp = atoi(s + 1);
    if (point < 0)
        point = pos;
    while (n > 1 && digits[n - 1] == '0')
        n--;
    if (n == 0)
        digits[n++] = '0';
    digits[n] = '\0';
    *x10 = point - first - 1 + exp;
}

/* x formatted, checked to read back, to fit and to be a JSON number (finite x) */
static const char *formatted(double x, char *buf)
{
    int len = dyn_format_double(x, buf);
    assert_int_equal(len, (int)strlen(buf));
    assert_true(len <= 24);
    if (isfinite(x)) {
        double back = strtod(buf, NULL);
        if (to_bits(back) != to_bits(x))
            fail_msg("%s reads back as %a, not %a", buf, back, x);
        if (!json_number(buf))
            fail_msg("%s is not a JSON number", buf);
    }
    return buf;
}

static const struct {
    uint64_t bits;
    const char *ryu; /* as the reference's d2s prints it */
} ryu_vectors[] = {
    {UINT64_C(0x0000000000000000), "0E0"},
    {UINT64_C(0x8000000000000000), "-0E0"},
    {UINT64_C(0x3ff0000000000000), "1E0"},
    {UINT64_C(0xbff0000000000000), "-1E0"},
    {UINT64_C(0x0010000000000000), "2.2250738585072014E-308"},
    {UINT64_C(0x7fefffffffffffff), "1.7976931348623157E308"},
    {UINT64_C(0x0000000000000001), "5E-324"},
    {UINT64_C(0x3e60000000000000), "2.9802322387695312E-8"},
    {UINT64_C(0xc352bd2668e077c4), "-2.109808898695963E16"},
    {UINT64_C(0x00000000000f4240), "4.940656E-318"},
    {UINT64_C(0x00000000016e3600), "1.18575755E-316"},
    {UINT64_C(0x0000008cdcdea440), "2.989102097996E-312"},
    {UINT64_C(0x434018601510c000), "9.0608011534336E15"},
    {UINT64_C(0x43d055dc36f24000), "4.708356024711512E18"},
    {UINT64_C(0x43e052961c6f8000), "9.409340012568248E18"},
    {UINT64_C(0x3ff3c0ca2a5b1d5d), "1.2345678E0"},
    {UINT64_C(0x4830f0cf064dd592), "5.764607523034235E39"},
    {UINT64_C(0x4840f0cf064dd592), "1.152921504606847E40"},
    {UINT64_C(0x4850f0cf064dd592), "2.305843009213694E40"},
    {UINT64_C(0x3ff3333333333333), "1.2E0"},
    {UINT64_C(0x3ff3ae147ae147ae), "1.23E0"},
    {UINT64_C(0x3ff3be76c8b43958), "1.234E0"},
    {UINT64_C(0x3ff3c083126e978d), "1.2345E0"},
    {UINT64_C(0x3ff3c0c1fc8f3238), "1.23456E0"},
    {UINT64_C(0x3ff3c0c9539b8887), "1.234567E0"},
    {UINT64_C(0x3ff3c0ca4283de1b), "1.23456789E0"},
    {UINT64_C(0x3ff3c0ca43db770a), "1.234567895E0"},
    {UINT64_C(0x3ff3c0ca428abd53), "1.2345678901E0"},
    {UINT64_C(0x3ff3c0ca428c1d2b), "1.23456789012E0"},
    {UINT64_C(0x3ff3c0ca428c51f2), "1.234567890123E0"},
    {UINT64_C(0x3ff3c0ca428c58fc), "1.2345678901234E0"},
    {UINT64_C(0x3ff3c0ca428c59dd), "1.23456789012345E0"},
    {UINT64_C(0x3ff3c0ca428c59f8), "1.234567890123456E0"},
    {UINT64_C(0x3ff3c0ca428c59fb), "1.2345678901234567E0"},
    {UINT64_C(0x40112e0be8047a7d), "4.294967294E0"},
    {UINT64_C(0x40112e0be815a889), "4.294967295E0"},
    {UINT64_C(0x40112e0be826d695), "4.294967296E0"},
    {UINT64_C(0x40112e0be83804a1), "4.294967297E0"},
    {UINT64_C(0x40112e0be84932ad), "4.294967298E0"},
    {UINT64_C(0x0040000000000000), "1.7800590868057611E-307"},
    {UINT64_C(0x007fffffffffffff), "2.8480945388892175E-306"},
    {UINT64_C(0x0290000000000000), "2.446494580089078E-296"},
    {UINT64_C(0x029fffffffffffff), "4.8929891601781557E-296"},
    {UINT64_C(0x4350000000000000), "1.8014398509481984E16"},
    {UINT64_C(0x435fffffffffffff), "3.6028797018963964E16"},
    {UINT64_C(0x1330000000000000), "2.900835519859558E-216"},
    {UINT64_C(0x133fffffffffffff), "5.801671039719115E-216"},
    {UINT64_C(0x3a6fa7161a4d6e0c), "3.196104012172126E-27"},
    {UINT64_C(0x433fffffffffffff), "9.007199254740991E15"},
    {UINT64_C(0x4340000000000000), "9.007199254740992E15"},
    {UINT64_C(0x3ff0000000000000), "1E0"},
    {UINT64_C(0x4028000000000000), "1.2E1"},
    {UINT64_C(0x405ec00000000000), "1.23E2"},
    {UINT64_C(0x4093480000000000), "1.234E3"},
    {UINT64_C(0x40c81c8000000000), "1.2345E4"},
    {UINT64_C(0x40fe240000000000), "1.23456E5"},
    {UINT64_C(0x4132d68700000000), "1.234567E6"},
    {UINT64_C(0x41678c29c0000000), "1.2345678E7"},
    {UINT64_C(0x419d6f3454000000), "1.23456789E8"},
    {UINT64_C(0x41d26580b4800000), "1.23456789E9"},
    {UINT64_C(0x41d26580b5c00000), "1.234567895E9"},
    {UINT64_C(0x4206fee0e1a80000), "1.2345678901E10"},
    {UINT64_C(0x423cbe991a140000), "1.23456789012E11"},
    {UINT64_C(0x4271f71fb04cb000), "1.234567890123E12"},
    {UINT64_C(0x42a674e79c5fe400), "1.2345678901234E13"},
    {UINT64_C(0x42dc12218377de40), "1.23456789012345E14"},
    {UINT64_C(0x43118b54f22aeb00), "1.234567890123456E15"},
    {UINT64_C(0x3ff0000000000000), "1E0"},
    {UINT64_C(0x4024000000000000), "1E1"},
    {UINT64_C(0x4059000000000000), "1E2"},
    {UINT64_C(0x408f400000000000), "1E3"},
    {UINT64_C(0x40c3880000000000), "1E4"},
    {UINT64_C(0x40f86a0000000000), "1E5"},
    {UINT64_C(0x412e848000000000), "1E6"},
    {UINT64_C(0x416312d000000000), "1E7"},
    {UINT64_C(0x4197d78400000000), "1E8"},
    {UINT64_C(0x41cdcd6500000000), "1E9"},
    {UINT64_C(0x4202a05f20000000), "1E10"},
    {UINT64_C(0x42374876e8000000), "1E11"},
    {UINT64_C(0x426d1a94a2000000), "1E12"},
    {UINT64_C(0x42a2309ce5400000), "1E13"},
    {UINT64_C(0x42d6bcc41e900000), "1E14"},
    {UINT64_C(0x430c6bf526340000), "1E15"},
    {UINT64_C(0x430c6bf526340008), "1.000000000000001E15"},
    {UINT64_C(0x430c6bf526340050), "1.00000000000001E15"},
    {UINT64_C(0x430c6bf526340320), "1.0000000000001E15"},
    {UINT64_C(0x430c6bf526341f40), "1.000000000001E15"},
    {UINT64_C(0x430c6bf526353880), "1.00000000001E15"},
    {UINT64_C(0x430c6bf526403500), "1.0000000001E15"},
    {UINT64_C(0x430c6bf526ae1200), "1.000000001E15"},
    {UINT64_C(0x430c6bf52af8b400), "1.00000001E15"},
    {UINT64_C(0x430c6bf555e30800), "1.0000001E15"},
    {UINT64_C(0x430c6bf7030a5000), "1.000001E15"},
    {UINT64_C(0x430c6c07c6932000), "1.00001E15"},
    {UINT64_C(0x430c6caf69eb4000), "1.0001E15"},
    {UINT64_C(0x430c733bcb5c8000), "1.001E15"},
    {UINT64_C(0x430cb4b799c90000), "1.01E15"},
    {UINT64_C(0x430f438daa060000), "1.1E15"},
    {UINT64_C(0x4020000000000000), "8E0"},
    {UINT64_C(0x40bf400000000000), "8E3"},
    {UINT64_C(0x4050000000000000), "6.4E1"},
    {UINT64_C(0x40ef400000000000), "6.4E4"},
    {UINT64_C(0x4080000000000000), "5.12E2"},
    {UINT64_C(0x411f400000000000), "5.12E5"},
    {UINT64_C(0x40c0000000000000), "8.192E3"},
    {UINT64_C(0x415f400000000000), "8.192E6"},
    {UINT64_C(0x40f0000000000000), "6.5536E4"},
    {UINT64_C(0x418f400000000000), "6.5536E7"},
    {UINT64_C(0x4120000000000000), "5.24288E5"},
    {UINT64_C(0x41bf400000000000), "5.24288E8"},
    {UINT64_C(0x4160000000000000), "8.388608E6"},
    {UINT64_C(0x41ff400000000000), "8.388608E9"},
    {UINT64_C(0x4190000000000000), "6.7108864E7"},
    {UINT64_C(0x422f400000000000), "6.7108864E10"},
    {UINT64_C(0x41c0000000000000), "5.36870912E8"},
    {UINT64_C(0x425f400000000000), "5.36870912E11"},
    {UINT64_C(0x4200000000000000), "8.589934592E9"},
    {UINT64_C(0x429f400000000000), "8.589934592E12"},
    {UINT64_C(0x4230000000000000), "6.8719476736E10"},
    {UINT64_C(0x42cf400000000000), "6.8719476736E13"},
    {UINT64_C(0x4260000000000000), "5.49755813888E11"},
    {UINT64_C(0x42ff400000000000), "5.49755813888E14"},
    {UINT64_C(0x42a0000000000000), "8.796093022208E12"},
    {UINT64_C(0x433f400000000000), "8.796093022208E15"},
    {UINT64_C(0x42d0000000000000), "7.0368744177664E13"},
    {UINT64_C(0x4300000000000000), "5.62949953421312E14"},
    {UINT64_C(0x4340000000000000), "9.007199254740992E15"},
};

static void test_ryu_published_vectors(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof ryu_vectors / sizeof ryu_vectors[0]; i++) {
        char buf[DYN_DOUBLE_CHARS], digits[32], expect[40];
        int x10;
        const double x = from_bits(ryu_vectors[i].bits);
        formatted(x, buf);
        digits_of(buf, digits, &x10);
        /* Ryu's layout: d.dddEx */
        snprintf(expect, sizeof expect, "%s%c%s%sE%d", buf[0] == '-' ? "-" : "", digits[0],
                 digits[1] ? "." : "", digits + 1, x10);
        if (strcmp(expect, ryu_vectors[i].ryu) != 0)
            fail_msg("%a: wrote %s (%s), the reference writes %s", x, buf, expect,
                     ryu_vectors[i].ryu);
    }
}

static void test_layout(void **state)
{
    (void)state;
    static const struct {
        double x;
        const char *s;
    } cases[] = {
        {0.0, "0"},
        {-0.0, "-0"},
        {1.0, "1"},
        {-2.5, "-2.5"},
        {20.0, "20"},
        {0.01, "0.01"},
        {0.1, "0.1"},
        {0.3, "0.3"},
        {1.0 / 3.0, "0.3333333333333333"},
        {2.0 / 3.0, "0.6666666666666666"},
        {0.0001, "0.0001"},
        {0.00012345, "0.00012345"},
        {1e-5, "1e-5"},
        {-1.5e-7, "-1.5e-7"},
        {123.456, "123.456"},
        {1e15, "1000000000000000"},
        {9007199254740992.0, "9007199254740992"},
        {1234567890123456.7, "1234567890123456.8"},
        {1e16, "1e16"},
        {1.5e16, "1.5e16"},
        {1e22, "1e22"},
        {1e23, "1e23"},
        {1e100, "1e100"},
        {DBL_MAX, "1.7976931348623157e308"},
        {-DBL_MAX, "-1.7976931348623157e308"},
        {DBL_MIN, "2.2250738585072014e-308"},
        {4.9406564584124654e-324, "5e-324"},
        {-2.2250738585072009e-308, "-2.225073858507201e-308"},
        {1e-308, "1e-308"},
        {1e308, "1e308"},
        {INFINITY, "inf"},
        {-INFINITY, "-inf"},
        {NAN, "nan"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char buf[DYN_DOUBLE_CHARS];
        formatted(cases[i].x, buf);
        if (strcmp(buf, cases[i].s) != 0)
            fail_msg("%a: wrote %s, expected %s", cases[i].x, buf, cases[i].s);
    }
    char buf[DYN_DOUBLE_CHARS];
    assert_string_equal(formatted(-NAN, buf), "nan");
    assert_string_equal(formatted(from_bits(UINT64_C(0x7ff0000000000001)), buf), "nan");
}

static void test_round_trip_random(void **state)
{
    (void)state;
    uint64_t s = UINT64_C(0x9e3779b97f4a7c15);
    char buf[DYN_DOUBLE_CHARS];
    long tested = 0;
    for (long i = 0; i < 2000000; i++) {
        uint64_t u = next_random(&s);
        if (i % 4 == 0) /* a quarter subnormal or near the ends of the exponent range */
            u &= (i % 8 == 0) ? UINT64_C(0x800fffffffffffff) : UINT64_C(0x803fffffffffffff);
        const double x = from_bits(u);
        if (isnan(x))
            continue;
        formatted(x, buf);
        tested++;
    }
    assert_true(tested > 1990000);
}

static void test_edges(void **state)
{
    (void)state;
    char buf[DYN_DOUBLE_CHARS], text[40];
    for (int e = -1074; e <= 1023; e++) { /* powers of two and their neighbours */
        const double p = ldexp(1.0, e);
        formatted(p, buf);
        formatted(-p, buf);
        formatted(nextafter(p, 0.0), buf);
        formatted(nextafter(p, INFINITY), buf);
    }
    for (int e = -323; e <= 308; e++) { /* powers of ten: "1e-N" or the plain form */
        snprintf(text, sizeof text, "1e%d", e);
        const double p = strtod(text, NULL);
        formatted(p, buf);
        char digits[32];
        int x10;
        digits_of(buf, digits, &x10);
        assert_string_equal(digits, "1");
        assert_int_equal(x10, e);
        formatted(nextafter(p, 0.0), buf);
        formatted(nextafter(p, INFINITY), buf);
    }
    for (uint64_t m = 1; m < 100000; m++) { /* subnormals from the smallest */
        formatted(from_bits(m), buf);
        formatted(from_bits(UINT64_C(0x000fffffffffffff) + 1 - m), buf);
    }
    assert_string_equal(formatted(from_bits(UINT64_C(0x000fffffffffffff)), buf),
                        "2.225073858507201e-308");
    formatted(DBL_MIN, buf);
    formatted(DBL_MAX, buf);
    formatted(nextafter(DBL_MAX, 0.0), buf);
    /* integers: the integer itself, as printf writes it exactly */
    uint64_t s = 12345;
    for (long i = 0; i < 300000; i++) {
        const double v = i < 100000 ? (double)i
                                    : (double)(next_random(&s) >> (11 + (unsigned)(i % 50)));
        snprintf(text, sizeof text, "%.0f", v);
        if (strcmp(formatted(v, buf), text) != 0)
            fail_msg("integer %s written as %s", text, buf);
    }
    const double top = 9007199254740992.0; /* 2^53 */
    assert_string_equal(formatted(top - 1, buf), "9007199254740991");
    assert_string_equal(formatted(top, buf), "9007199254740992");
    assert_string_equal(formatted(2 * top, buf), "1.8014398509481984e16");
    /* every digit count: 10^d - 1, 10^d, and the largest d-digit decimals below 1 */
    for (int d = 1; d <= 17; d++) {
        snprintf(text, sizeof text, "%.*s", d, "99999999999999999");
        formatted(strtod(text, NULL), buf);
        if (d <= 15)
            assert_string_equal(buf, text);
        snprintf(text, sizeof text, "1e%d", d);
        formatted(strtod(text, NULL), buf);
        snprintf(text, sizeof text, "0.%.*s", d, "99999999999999999");
        formatted(strtod(text, NULL), buf);
        if (d <= 15)
            assert_string_equal(buf, text);
    }
}

/* A decimal of d <= 15 digits is the only one of at most 15 digits that reads to its double,
 * so the shortest string has exactly its digits. */
static void test_shortest_digits(void **state)
{
    (void)state;
    uint64_t s = 777;
    char buf[DYN_DOUBLE_CHARS], text[64], digits[32], want[32];
    for (long i = 0; i < 200000; i++) {
        const int d = 1 + (int)(next_random(&s) % 15);
        const int e = (int)(next_random(&s) % 600) - 300; /* normal range */
        uint64_t m = next_random(&s) % UINT64_C(1000000000000000);
        snprintf(want, sizeof want, "%015llu", (unsigned long long)m);
        want[d] = '\0';
        want[0] = (char)('1' + (m % 9)); /* d significant digits */
        snprintf(text, sizeof text, "%c.%se%d", want[0], want + 1, e);
        int n = d;
        while (n > 1 && want[n - 1] == '0')
            want[--n] = '\0';
        int x10;
        digits_of(formatted(strtod(text, NULL), buf), digits, &x10);
        if (strcmp(digits, want) != 0 || x10 != e)
            fail_msg("%s written as %s", text, buf);
    }
}

static void test_portable_multiply(void **state)
{
    (void)state;
    uint64_t s = 4242;
    char a[DYN_DOUBLE_CHARS], b[DYN_DOUBLE_CHARS];
    for (long i = 0; i < 1000000; i++) {
        const double x = from_bits(next_random(&s));
        dyn_format_double(x, a);
        dyn_format_double_portable(x, b);
        if (strcmp(a, b) != 0)
            fail_msg("%a: %s with unsigned __int128, %s without", x, a, b);
    }
}

static void test_writer_rows_read_back(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    assert_non_null(f);
    static dyn_text_writer w;
    dyn_text_writer_init(&w, f);
    assert_int_equal(dyn_text_write(&w, "t,a,b\n", 6), DYN_OK);
    uint64_t s = 99;
    enum { ROWS = 30000 };
    static double want[ROWS][3];
    for (int r = 0; r < ROWS; r++) {
        for (int j = 0; j < 3; j++) {
            double x;
            do
                x = from_bits(next_random(&s));
            while (!isfinite(x));
            want[r][j] = x;
        }
        assert_int_equal(dyn_csv_write_row_to(&w, want[r][0], &want[r][1], 1, &want[r][2], 1),
                         DYN_OK);
    }
    assert_int_equal(dyn_text_writer_flush(&w), DYN_OK);
    rewind(f);
    dyn_table tab;
    char err[256];
    assert_int_equal(dyn_table_read(f, "rows", 0, &tab, err, sizeof err), DYN_OK);
    assert_int_equal(tab.rows, ROWS);
    for (int r = 0; r < ROWS; r++)
        for (int j = 0; j < 3; j++)
            assert_true(to_bits(tab.data[3 * r + j]) == to_bits(want[r][j]));
    dyn_table_free(&tab);
    fclose(f);

    /* a row wider than the stack buffer of dyn_csv_write_row */
    static double wide[600];
    for (int j = 0; j < 600; j++)
        wide[j] = 1.0 / (j + 3.0);
    f = tmpfile();
    assert_non_null(f);
    fputs("t", f);
    for (int j = 0; j < 599; j++)
        fprintf(f, ",c%d", j);
    fputc('\n', f);
    assert_int_equal(dyn_csv_write_row(f, wide[0], wide + 1, 599, NULL, 0), DYN_OK);
    rewind(f);
    assert_int_equal(dyn_table_read(f, "wide", 0, &tab, err, sizeof err), DYN_OK);
    assert_int_equal(tab.cols, 600);
    for (int j = 0; j < 600; j++)
        assert_true(to_bits(tab.data[j]) == to_bits(wide[j]));
    dyn_table_free(&tab);
    fclose(f);
}

static void test_writer_full_disk(void **state)
{
    (void)state;
    FILE *f = fopen("/dev/full", "w");
    if (!f)
        skip();
    static dyn_text_writer w;
    dyn_text_writer_init(&w, f);
    int status = DYN_OK;
    const double y[2] = {0.1, -2.5e-300};
    for (int r = 0; r < 20000 && status == DYN_OK; r++)
        status = dyn_csv_write_row_to(&w, r * 0.01, y, 2, NULL, 0);
    assert_int_equal(status, DYN_ERR_IO); /* the first full buffer failed */
    assert_int_equal(dyn_text_write_double(&w, 1.0), DYN_ERR_IO);
    assert_int_equal(dyn_text_writer_flush(&w), DYN_ERR_IO);
    fclose(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ryu_published_vectors),
        cmocka_unit_test(test_layout),
        cmocka_unit_test(test_round_trip_random),
        cmocka_unit_test(test_edges),
        cmocka_unit_test(test_shortest_digits),
        cmocka_unit_test(test_portable_multiply),
        cmocka_unit_test(test_writer_rows_read_back),
        cmocka_unit_test(test_writer_full_disk),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
