/* SPDX-License-Identifier: BSD-3-Clause */
/* The shortest decimal string that reads back to the same double (dyn_format_double, io.h).
 *
 * Digits and exponent follow Ryu, d2s (U. Adams, "Ryu: fast float-to-string conversion",
 * PLDI 2018, sec. 3: the interval of the decimal numbers that round to the double, computed
 * with 125-bit fixed-point powers of five, sec. 5: removing digits while the interval allows
 * and rounding the last one to nearest, ties to even). The tables of powers of five are exact
 * integers from tools/ryu_tables.py (ryu_tables.h). Ryu rather than Schubfach (R. Giulietti,
 * "The Schubfach way to render doubles", 2020), which is as fast: Ryu's correctness is proven
 * for exactly this table layout, its published test vectors (the d2s tests of the reference
 * implementation) are checked here, and its tables are reproducible from their definition
 * with exact integers. Integers in [1, 2^53) take Ryu's short path (their digits are exact).
 *
 * The string's layout (docs/data-files.md): plain decimal when the decimal exponent X of the
 * first digit is -4 <= X < 16 ("0.0001", "0.01", "1234.5", "9007199254740992"; integers have
 * no decimal point), else one digit, the others after a point, 'e' and the exponent without
 * '+' or leading zeros ("1e-5", "1.5e16", "4.9406564584124654e-324" is "5e-324"); "-0" for
 * negative zero, "nan", "inf", "-inf" otherwise. These are the choices of Python's repr()
 * except that repr writes "1.0" and "1e-05". strtod, JSON (finite values), NumPy and pandas
 * read every such string back to the same double.
 */
#include <stdint.h>
#include <string.h>

#include "dynkit/io.h"
#include "ryu_tables.h"

#define MANTISSA_BITS 52
#define EXPONENT_BITS 11
#define EXPONENT_BIAS 1023

/* bit length of 5^e, 0 <= e <= 3528 (PLDI 2018, sec. 5) */
static inline int32_t pow5_bits(int32_t e)
{
    return (int32_t)(((uint32_t)e * 1217359u) >> 19) + 1;
}

/* floor(e log10 2), 0 <= e <= 1650 */
static inline uint32_t log10_pow2(int32_t e) { return ((uint32_t)e * 78913u) >> 18; }

/* floor(e log10 5), 0 <= e <= 2620 */
static inline uint32_t log10_pow5(int32_t e) { return ((uint32_t)e * 732923u) >> 20; }

static inline uint32_t pow5_factor(uint64_t v)
{
    uint32_t count = 0;
    while (v % 5 == 0) {
        v /= 5;
        count++;
    }
    return count;
}

static inline int multiple_of_pow5(uint64_t v, uint32_t p) { return pow5_factor(v) >= p; }

static inline int multiple_of_pow2(uint64_t v, uint32_t p)
{
    return (v & ((UINT64_C(1) << p) - 1)) == 0;
}

#if defined(__SIZEOF_INT128__) && !defined(DYNKIT_NO_INT128)
__extension__ typedef unsigned __int128 u128;

/* (m * mul) >> j for a 126-bit mul = {low, high} and 64 < j < 128 */
static inline uint64_t mul_shift(uint64_t m, const uint64_t mul[2], int32_t j)
{
    const u128 low = (u128)m * mul[0];
    const u128 high = (u128)m * mul[1];
    return (uint64_t)(((low >> 64) + high) >> (j - 64));
}
#else
/* the same with 64-bit arithmetic only: 64 x 64 -> 128 bits from 32-bit halves */
static inline uint64_t mul_64x64(uint64_t a, uint64_t b, uint64_t *high)
{
    const uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
    const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    const uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
    *high = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    return (mid << 32) | (p00 & 0xffffffffu);
}

static inline uint64_t mul_shift(uint64_t m, const uint64_t mul[2], int32_t j)
{
    uint64_t high0, high1;
    (void)mul_64x64(m, mul[0], &high0);
    const uint64_t low1 = mul_64x64(m, mul[1], &high1);
    const uint64_t sum = high0 + low1;
    if (sum < high0)
        high1++;
    const int32_t dist = j - 64; /* 0 < dist < 64 for every double */
    return (high1 << (64 - dist)) | (sum >> dist);
}
#endif

/* A decimal floating-point number digits * 10^exponent. */
typedef struct decimal {
    uint64_t digits;
    int32_t exponent;
} decimal;

/* Ryu's shortest correctly rounded decimal of a positive finite double given by its fields. */
static decimal shortest_decimal(uint64_t ieee_mantissa, uint32_t ieee_exponent)
{
    int32_t e2;
    uint64_t m2;
    if (ieee_exponent == 0) {
        e2 = 1 - EXPONENT_BIAS - MANTISSA_BITS - 2;
        m2 = ieee_mantissa;
    } else {
        e2 = (int32_t)ieee_exponent - EXPONENT_BIAS - MANTISSA_BITS - 2;
        m2 = (UINT64_C(1) << MANTISSA_BITS) | ieee_mantissa;
    }
    /* the interval of decimals that read back: (4 m2 - 1 - mm_shift, 4 m2 + 2) * 2^e2, its
     * ends included when m2 is even (round half to even) */
    const int accept_bounds = (m2 & 1) == 0;
    const uint64_t mv = 4 * m2;
    const uint32_t mm_shift = ieee_mantissa != 0 || ieee_exponent <= 1;

    uint64_t vr, vp, vm;
    int32_t e10;
    int vm_trailing_zeros = 0, vr_trailing_zeros = 0;
    if (e2 >= 0) {
        const uint32_t q = log10_pow2(e2) - (e2 > 3);
        e10 = (int32_t)q;
        const int32_t k = RYU_POW5_INV_BITCOUNT + pow5_bits((int32_t)q) - 1;
        const int32_t i = -e2 + (int32_t)q + k;
        vr = mul_shift(mv, RYU_POW5_INV[q], i);
        vp = mul_shift(mv + 2, RYU_POW5_INV[q], i);
        vm = mul_shift(mv - 1 - mm_shift, RYU_POW5_INV[q], i);
        if (q <= 21) {
            /* at most one of vp, vr, vm can be a multiple of 5 */
            if (mv % 5 == 0)
                vr_trailing_zeros = multiple_of_pow5(mv, q);
            else if (accept_bounds)
                vm_trailing_zeros = multiple_of_pow5(mv - 1 - mm_shift, q);
            else
                vp -= (uint64_t)multiple_of_pow5(mv + 2, q);
        }
    } else {
        const uint32_t q = log10_pow5(-e2) - (-e2 > 1);
        e10 = (int32_t)q + e2;
        const int32_t i = -e2 - (int32_t)q;
        const int32_t k = pow5_bits(i) - RYU_POW5_BITCOUNT;
        const int32_t j = (int32_t)q - k;
        vr = mul_shift(mv, RYU_POW5[i], j);
        vp = mul_shift(mv + 2, RYU_POW5[i], j);
        vm = mul_shift(mv - 1 - mm_shift, RYU_POW5[i], j);
        if (q <= 1) {
            /* mv has at least q trailing binary zeros, so all three are exact */
            vr_trailing_zeros = 1;
            if (accept_bounds)
                vm_trailing_zeros = mm_shift == 1;
            else
                vp--;
        } else if (q < 63) {
            vr_trailing_zeros = multiple_of_pow2(mv, q);
        }
    }

    /* drop digits while the interval [vm, vp] still holds a shorter number */
    int32_t removed = 0;
    uint8_t last_removed = 0;
    uint64_t out;
    if (vm_trailing_zeros || vr_trailing_zeros) {
        /* the rare exact case: ties and an included lower end need the removed digits */
        while (vp / 10 > vm / 10) {
            vm_trailing_zeros &= vm % 10 == 0;
            vr_trailing_zeros &= last_removed == 0;
            last_removed = (uint8_t)(vr % 10);
            vr /= 10;
            vp /= 10;
            vm /= 10;
            removed++;
        }
        if (vm_trailing_zeros) {
            while (vm % 10 == 0) {
                vr_trailing_zeros &= last_removed == 0;
                last_removed = (uint8_t)(vr % 10);
                vr /= 10;
                vp /= 10;
                vm /= 10;
                removed++;
            }
        }
        if (vr_trailing_zeros && last_removed == 5 && vr % 2 == 0)
            last_removed = 4; /* exactly halfway: round to even */
        out = vr + ((vr == vm && (!accept_bounds || !vm_trailing_zeros)) || last_removed >= 5);
    } else {
        int round_up = 0;
        /* several digits at once where the interval allows (removing k digits is allowed
         * exactly when vp / 10^k > vm / 10^k, and then for every smaller k too); round_up
         * is decided by the last digit removed, the highest of the group */
        while (vp / 10000 > vm / 10000) { /* short numbers such as 0.01 or 12.345 */
            round_up = vr % 10000 >= 5000;
            vr /= 10000;
            vp /= 10000;
            vm /= 10000;
            removed += 4;
        }
        if (vp / 100 > vm / 100) { /* most doubles lose 1 or 2 digits in all */
            round_up = vr % 100 >= 50;
            vr /= 100;
            vp /= 100;
            vm /= 100;
            removed += 2;
        }
        while (vp / 10 > vm / 10) {
            round_up = vr % 10 >= 5;
            vr /= 10;
            vp /= 10;
            vm /= 10;
            removed++;
        }
        out = vr + (vr == vm || round_up);
    }
    return (decimal){out, e10 + removed};
}

/* An integer value in [1, 2^53) exactly, its trailing zeros moved to the exponent; 0 if
 * the double is not such an integer. */
static int small_integer(uint64_t ieee_mantissa, uint32_t ieee_exponent, decimal *d)
{
    const uint64_t m2 = (UINT64_C(1) << MANTISSA_BITS) | ieee_mantissa;
    const int32_t e2 = (int32_t)ieee_exponent - EXPONENT_BIAS - MANTISSA_BITS;
    if (e2 > 0 || e2 < -MANTISSA_BITS)
        return 0;
    const uint64_t fraction_mask = (UINT64_C(1) << -e2) - 1;
    if (m2 & fraction_mask)
        return 0;
    d->digits = m2 >> -e2;
    d->exponent = 0;
    while (d->digits % 10 == 0) {
        d->digits /= 10;
        d->exponent++;
    }
    return 1;
}

static const uint64_t POW10[18] = {UINT64_C(1),
                                   UINT64_C(10),
                                   UINT64_C(100),
                                   UINT64_C(1000),
                                   UINT64_C(10000),
                                   UINT64_C(100000),
                                   UINT64_C(1000000),
                                   UINT64_C(10000000),
                                   UINT64_C(100000000),
                                   UINT64_C(1000000000),
                                   UINT64_C(10000000000),
                                   UINT64_C(100000000000),
                                   UINT64_C(1000000000000),
                                   UINT64_C(10000000000000),
                                   UINT64_C(100000000000000),
                                   UINT64_C(1000000000000000),
                                   UINT64_C(10000000000000000),
                                   UINT64_C(100000000000000000)};

/* Decimal digits of 0 < v < 10^17: from the bit length b, floor(b log10 2) (1233 / 4096 is
 * log10 2 to 4 digits, exact for b <= 64) is the digit count or one more. */
static inline int decimal_length(uint64_t v)
{
#if defined(__GNUC__)
    const int bits = 64 - __builtin_clzll(v);
#else
    int bits = 0;
    for (uint64_t u = v; u; u >>= 1)
        bits++;
#endif
    const int t = (bits * 1233) >> 12;
    return t + (v >= POW10[t]);
}

static const char DIGIT_PAIRS[200] = "00010203040506070809101112131415161718192021222324252627282930"
                                     "31323334353637383940414243444546474849505152535455565758596061"
                                     "62636465666768697071727374757677787980818283848586878889909192"
                                     "93949596979899";

/* The n decimal digits of v < 10^9 into p[0..n-1]: four at a time, as two pairs. */
static inline void write_digits32(char *p, uint32_t v, int n)
{
    while (n >= 4) {
        const uint32_t c = v % 10000;
        v /= 10000;
        n -= 4;
        memcpy(p + n, DIGIT_PAIRS + 2 * (c / 100), 2);
        memcpy(p + n + 2, DIGIT_PAIRS + 2 * (c % 100), 2);
    }
    if (n >= 2) {
        const uint32_t c = v % 100;
        v /= 100;
        n -= 2;
        memcpy(p + n, DIGIT_PAIRS + 2 * c, 2);
    }
    if (n)
        p[0] = (char)('0' + v);
}

/* The n decimal digits of v < 10^17 into p[0..n-1]: the last eight and the others as two
 * independent 32-bit conversions (as Ryu does), not one long chain of 64-bit divisions. */
static inline void write_digits(char *p, uint64_t v, int n)
{
    if (n > 8) {
        const uint64_t high = v / 100000000u;
        write_digits32(p + n - 8, (uint32_t)(v - 100000000u * high), 8);
        write_digits32(p, (uint32_t)high, n - 8);
    } else {
        write_digits32(p, (uint32_t)v, n);
    }
}

int dyn_format_double(double x, char *buf)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    const int negative = (int)(bits >> 63);
    const uint64_t ieee_mantissa = bits & ((UINT64_C(1) << MANTISSA_BITS) - 1);
    const uint32_t ieee_exponent =
        (uint32_t)((bits >> MANTISSA_BITS) & ((1u << EXPONENT_BITS) - 1));
    char *p = buf;

    if (ieee_exponent == (1u << EXPONENT_BITS) - 1) {
        if (ieee_mantissa) {
            memcpy(p, "nan", 4);
            return 3;
        }
        if (negative)
            *p++ = '-';
        memcpy(p, "inf", 4);
        return (int)(p - buf) + 3;
    }
    if (negative)
        *p++ = '-';
    if (ieee_exponent == 0 && ieee_mantissa == 0) {
        memcpy(p, "0", 2);
        return (int)(p - buf) + 1;
    }

    decimal d;
    if (!small_integer(ieee_mantissa, ieee_exponent, &d))
        d = shortest_decimal(ieee_mantissa, ieee_exponent);
    const int n = decimal_length(d.digits);
    const int x10 = d.exponent + n - 1; /* the decimal exponent of the first digit */

    if (x10 >= -4 && x10 < 16) {
        if (d.exponent >= 0) { /* an integer: the digits and zeros */
            write_digits(p, d.digits, n);
            memset(p + n, '0', (size_t)d.exponent);
            p += n + d.exponent;
        } else if (x10 >= 0) { /* a point inside the digits: the integer part moved left */
            write_digits(p + 1, d.digits, n);
            for (int k = 0; k <= x10; k++)
                p[k] = p[k + 1];
            p[x10 + 1] = '.';
            p += n + 1;
        } else { /* 0.000ddd */
            const int zeros = -x10 - 1;
            p[0] = '0';
            p[1] = '.';
            memset(p + 2, '0', (size_t)zeros);
            write_digits(p + 2 + zeros, d.digits, n);
            p += 2 + zeros + n;
        }
    } else {
        /* d.ddde-X: the digits one place right, the first moved before the point */
        write_digits(p + 1, d.digits, n);
        p[0] = p[1];
        if (n > 1) {
            p[1] = '.';
            p += n + 1;
        } else {
            p += 1;
        }
        *p++ = 'e';
        int e = x10;
        if (e < 0) {
            *p++ = '-';
            e = -e;
        }
        if (e >= 100) {
            *p++ = (char)('0' + e / 100);
            e %= 100;
            memcpy(p, DIGIT_PAIRS + 2 * e, 2);
            p += 2;
        } else if (e >= 10) {
            memcpy(p, DIGIT_PAIRS + 2 * e, 2);
            p += 2;
        } else {
            *p++ = (char)('0' + e);
        }
    }
    *p = '\0';
    return (int)(p - buf);
}
