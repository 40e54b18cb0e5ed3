/* SPDX-License-Identifier: BSD-3-Clause */
/* vdp_reference.c — reference values of the van der Pol oscillator
 *   y1' = y2,  y2' = mu (1 - y1^2) y2 - y1,   y(0) = (2, 0),
 * in quadruple precision (__float128, 113-bit significand, eps = 1.9e-34), by two
 * independent methods:
 *
 *  A. Taylor series: the Taylor coefficients of y1, y2 at the current point by the usual
 *     recurrences (Moore; Jorba & Zou, Experimental Math. 14 (2005)) for
 *       a_{k+1} = b_k / (k+1),  b_{k+1} = (mu b_k - mu (y1^2 y2)_k - a_k) / (k+1),
 *     with the Cauchy products (y1^2)_k and (y1^2 y2)_k, of order P; the step is
 *     h = min(rho, S / |J|) where rho = min_k (TOL / |c_k|)^(1/k) over the last two orders
 *     (Jorba & Zou's estimate of the error of the truncated series) and the second bound
 *     keeps h |lambda| inside the stability region of the truncated exponential (needed for
 *     mu = 1000, where lambda ~ -mu (y1^2 - 1) on the slow branches). The last step ends
 *     exactly on each output time.
 *  B. Classical fourth-order Runge-Kutta with N, 2N, 4N, 8N, 16N equal steps and Richardson
 *     extrapolation eliminating the h^4, h^5, h^6, h^7 terms of the global error (only for
 *     mu = 1: for mu = 1000 explicit RK4 needs steps below 1e-3 over 3000 time units).
 *
 * Run: gcc -O2 -o vdp_reference tools/vdp_reference.c -lquadmath -lm && ./vdp_reference
 * (gcc on x86-64; takes about a minute). The values it prints, and the agreement of the two
 * methods, are copied into src/problems/references.c. For mu = 1000 it also prints
 * t = 2000, where the Test Set for IVP Solvers (Bari, problem vdpolm) publishes a
 * reference, as an independent check.
 */
#include <math.h>
#include <quadmath.h>
#include <stdio.h>
#include <string.h>

typedef __float128 real;

#define PMAX 60

static real qabs(real x) { return x < 0 ? -x : x; }

static void print_state(const char *what, real t, const real *y)
{
    char a[64], b[64], c[64];
    quadmath_snprintf(c, sizeof c, "%.6Qf", t);
    quadmath_snprintf(a, sizeof a, "%+.32Qe", y[0]);
    quadmath_snprintf(b, sizeof b, "%+.32Qe", y[1]);
    printf("%-28s t = %s  y1 = %s  y2 = %s\n", what, c, a, b);
}

/* ---- A: Taylor series ---- */
typedef struct taylor_stats {
    long steps;
    real hmin, hmax;
} taylor_stats;

static void taylor_coefficients(real mu, const real *y, int P, real *a, real *b)
{
    real s[PMAX + 1], w[PMAX + 1];
    a[0] = y[0];
    b[0] = y[1];
    for (int k = 0; k < P; k++) {
        real sk = 0, wk = 0;
        for (int i = 0; i <= k; i++)
            sk += a[i] * a[k - i];
        s[k] = sk;
        for (int i = 0; i <= k; i++)
            wk += s[i] * b[k - i];
        w[k] = wk;
        a[k + 1] = b[k] / (k + 1);
        b[k + 1] = (mu * b[k] - mu * w[k] - a[k]) / (k + 1);
    }
}

static real horner(const real *c, int P, real h)
{
    real v = c[P];
    for (int k = P - 1; k >= 0; k--)
        v = v * h + c[k];
    return v;
}

/* Integrate from (t, y) to t_out; returns the new t (= t_out). */
static real taylor_to(real mu, real t, real *y, real t_out, int P, real tol, real S,
                      taylor_stats *st)
{
    real a[PMAX + 2], b[PMAX + 2];
    while (t < t_out) {
        taylor_coefficients(mu, y, P, a, b);
        real rho = 1e30Q;
        for (int k = P - 1; k <= P; k++) {
            real c = qabs(a[k]) > qabs(b[k]) ? qabs(a[k]) : qabs(b[k]);
            if (c > 0) {
                real r = powq(tol / c, (real)1 / k);
                if (r < rho)
                    rho = r;
            }
        }
        /* |J|_inf of the system at y: rows (0, 1) and (-2 mu y1 y2 - 1, mu (1 - y1^2)) */
        real jn = qabs(-2 * mu * y[0] * y[1] - 1) + qabs(mu * (1 - y[0] * y[0]));
        if (jn < 1)
            jn = 1;
        real h = rho;
        if (h > S / jn)
            h = S / jn;
        int last = 0;
        if (t + h >= t_out) {
            h = t_out - t;
            last = 1;
        }
        y[0] = horner(a, P, h);
        y[1] = horner(b, P, h);
        t = last ? t_out : t + h;
        st->steps++;
        if (h < st->hmin || st->steps == 1)
            st->hmin = h;
        if (h > st->hmax)
            st->hmax = h;
    }
    return t;
}

/* ---- B: RK4 with Richardson extrapolation ---- */
static void f(real mu, const real *y, real *d)
{
    d[0] = y[1];
    d[1] = mu * (1 - y[0] * y[0]) * y[1] - y[0];
}

static void rk4(real mu, real t1, long N, real *y)
{
    const real h = t1 / N;
    real k1[2], k2[2], k3[2], k4[2], Y[2];
    for (long n = 0; n < N; n++) {
        f(mu, y, k1);
        for (int i = 0; i < 2; i++)
            Y[i] = y[i] + h / 2 * k1[i];
        f(mu, Y, k2);
        for (int i = 0; i < 2; i++)
            Y[i] = y[i] + h / 2 * k2[i];
        f(mu, Y, k3);
        for (int i = 0; i < 2; i++)
            Y[i] = y[i] + h * k3[i];
        f(mu, Y, k4);
        for (int i = 0; i < 2; i++)
            y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
}

static void richardson(real mu, real t1, long N0, int levels, real *out)
{
    real T[8][8][2];
    for (int l = 0; l < levels; l++) {
        real y[2] = {2, 0};
        rk4(mu, t1, N0 << l, y);
        T[l][0][0] = y[0];
        T[l][0][1] = y[1];
        for (int j = 1; j <= l; j++) {
            /* eliminate the h^(3 + j) term: halving h divides it by 2^(3 + j) */
            real r = powq(2, 3 + j);
            for (int i = 0; i < 2; i++)
                T[l][j][i] = T[l][j - 1][i] + (T[l][j - 1][i] - T[l - 1][j - 1][i]) / (r - 1);
        }
        char a[64], b[64];
        quadmath_snprintf(a, sizeof a, "%+.32Qe", T[l][l][0]);
        quadmath_snprintf(b, sizeof b, "%+.32Qe", T[l][l][1]);
        printf("  RK4 N = %8ld, extrapolated (order %d): y1 = %s  y2 = %s\n", N0 << l, 4 + l,
               a, b);
    }
    out[0] = T[levels - 1][levels - 1][0];
    out[1] = T[levels - 1][levels - 1][1];
}

static void mu1(void)
{
    printf("== mu = 1, t = 15\n");
    real ya[2] = {2, 0}, yb[2] = {2, 0};
    taylor_stats s1 = {0}, s2 = {0};
    taylor_to(1, 0, ya, 15, 30, 1e-36Q, 10, &s1);
    taylor_to(1, 0, yb, 15, 40, 1e-40Q, 10, &s2);
    print_state("Taylor P=30 tol=1e-36", 15, ya);
    printf("   (%ld steps, h in [%g, %g])\n", s1.steps, (double)s1.hmin, (double)s1.hmax);
    print_state("Taylor P=40 tol=1e-40", 15, yb);
    printf("   (%ld steps, h in [%g, %g])\n", s2.steps, (double)s2.hmin, (double)s2.hmax);
    real yr[2];
    richardson(1, 15, 1L << 12, 5, yr);
    print_state("RK4 + Richardson", 15, yr);
    char d0[32], d1[32];
    quadmath_snprintf(d0, sizeof d0, "%.3Qe", qabs(yr[0] - yb[0]));
    quadmath_snprintf(d1, sizeof d1, "%.3Qe", qabs(yr[1] - yb[1]));
    printf("   |RK4 Richardson - Taylor| = %s, %s\n", d0, d1);
    quadmath_snprintf(d0, sizeof d0, "%.3Qe", qabs(ya[0] - yb[0]));
    quadmath_snprintf(d1, sizeof d1, "%.3Qe", qabs(ya[1] - yb[1]));
    printf("   |Taylor 30 - Taylor 40|   = %s, %s\n", d0, d1);
}

static void mu1000(void)
{
    printf("== mu = 1000, t = 2000 (Bari vdpolm: 1.706167732170469, -8.928097010248125e-4) "
           "and t = 3000\n");
    const int P[2] = {30, 40};
    const real tol[2] = {1e-34Q, 1e-38Q};
    const real S[2] = {6, 9};
    real res[2][2][2];
    for (int r = 0; r < 2; r++) {
        real y[2] = {2, 0}, t = 0;
        taylor_stats st = {0};
        t = taylor_to(1000, t, y, 2000, P[r], tol[r], S[r], &st);
        memcpy(res[r][0], y, sizeof y);
        char w[64];
        snprintf(w, sizeof w, "Taylor P=%d", P[r]);
        print_state(w, t, y);
        t = taylor_to(1000, t, y, 3000, P[r], tol[r], S[r], &st);
        memcpy(res[r][1], y, sizeof y);
        print_state(w, t, y);
        printf("   (%ld steps, h in [%g, %g])\n", st.steps, (double)st.hmin, (double)st.hmax);
    }
    for (int k = 0; k < 2; k++) {
        char d0[32], d1[32];
        quadmath_snprintf(d0, sizeof d0, "%.3Qe", qabs(res[0][k][0] - res[1][k][0]));
        quadmath_snprintf(d1, sizeof d1, "%.3Qe", qabs(res[0][k][1] - res[1][k][1]));
        printf("   t = %d: |P30 - P40| = %s, %s\n", k ? 3000 : 2000, d0, d1);
    }
    printf("   t = 2000 against Bari: %.3e, %.3e\n",
           fabs((double)(res[1][0][0] - 1.706167732170469Q)),
           fabs((double)(res[1][0][1] + 0.8928097010248125e-3Q)));
}

int main(int argc, char **argv)
{
    int which = argc > 1 ? argv[1][0] - '0' : 0;
    if (which == 0 || which == 1)
        mu1();
    if (which == 0 || which == 2)
        mu1000();
    return 0;
}
