/* SPDX-License-Identifier: BSD-3-Clause */
/* taylor_reference.c — quadruple-precision (__float128) Taylor-series solutions of the
 * HIRES, Robertson and Arenstorf problems (dynkit/problems.h): to check the Test Set's
 * published HIRES reference, to compute Robertson at t = 40 (where an explicit method is
 * still affordable; the Test Set's t = 1e11 is not), and to measure how far Arenstorf's
 * orbit is from closing after one period when its data are rounded to double.
 *
 * Method: Taylor series of order P at each step, the coefficients by the recurrences of the
 * polynomial right-hand sides, y_{k+1} = f_k / (k+1), where f_k is linear in the y_k except
 * for the Cauchy products (y6 y8)_k (HIRES) and (y2 y3)_k, (y2 y2)_k (Robertson), and the
 * powers r^-3 = (r^2)^(-3/2) of Arenstorf by Moore's recurrence for g = u^a:
 * k u_0 g_k = sum_{j<k} (a (k - j) - j) u_{k-j} g_j (Moore;
 * Jorba & Zou, Experimental Math. 14 (2005)). Step h = min(rho, S / |J|_inf): rho from the
 * last two coefficients and the tolerance, S / |J| keeps h |lambda| inside the stability
 * region of the truncated series (both problems are stiff). Two runs with different orders,
 * tolerances and stability bounds are compared.
 *
 * Run: gcc -O2 -o taylor_reference tools/taylor_reference.c -lquadmath -lm
 *      ./taylor_reference        (gcc on x86-64, a few seconds)
 */
#include <quadmath.h>
#include <stdio.h>
#include <string.h>

typedef __float128 real;

#define PMAX 48
#define NMAX 8

static real qabs(real x) { return x < 0 ? -x : x; }

/* Cauchy product (u v)_k of coefficient arrays. */
static real cauchy(const real *u, const real *v, int k)
{
    real s = 0;
    for (int i = 0; i <= k; i++)
        s += u[i] * v[k - i];
    return s;
}

/* ---- HIRES (Test Set constants) ---- */
static const real k1 = 1.71Q, k2 = 0.43Q, k3 = 8.32Q, k4 = 0.69Q, k5 = 0.035Q, k6 = 8.32Q,
                  k7 = 280, k8 = 0.69Q, k9 = 0.69Q, oks = 0.0007Q;

/* c[i][k]: coefficient k of state i. */
static void hires_coef(real c[NMAX][PMAX + 2], int P)
{
    for (int k = 0; k < P; k++) {
        const real p68 = cauchy(c[5], c[7], k);
        real f[8];
        f[0] = -k1 * c[0][k] + k2 * c[1][k] + k6 * c[2][k] + (k == 0 ? oks : 0);
        f[1] = k1 * c[0][k] - (k2 + k3) * c[1][k];
        f[2] = -(k6 + k1) * c[2][k] + k2 * c[3][k] + k5 * c[4][k];
        f[3] = k3 * c[1][k] + k1 * c[2][k] - (k4 + k2) * c[3][k];
        f[4] = -(k5 + k1) * c[4][k] + k2 * (c[5][k] + c[6][k]);
        f[5] = -k7 * p68 + k8 * c[3][k] + k1 * c[4][k] - k2 * c[5][k] + k8 * c[6][k];
        f[6] = k7 * p68 - (k2 + k8 + k9) * c[6][k];
        f[7] = -f[6];
        for (int i = 0; i < 8; i++)
            c[i][k + 1] = f[i] / (k + 1);
    }
}

static real hires_jnorm(const real *y)
{
    /* row sums of |J| (Test Set hires.f jacobian) */
    real r[8];
    r[0] = k1 + k2 + k6;
    r[1] = k1 + k2 + k3;
    r[2] = k6 + k1 + k2 + k5;
    r[3] = k3 + k1 + k4 + k2;
    r[4] = k5 + k1 + 2 * k2;
    r[5] = k8 + k1 + qabs(k7 * y[7]) + k2 + k8 + qabs(k7 * y[5]);
    r[6] = qabs(k7 * y[7]) + k2 + k8 + k9 + qabs(k7 * y[5]);
    r[7] = r[6];
    real m = 0;
    for (int i = 0; i < 8; i++)
        if (r[i] > m)
            m = r[i];
    return m;
}

/* ---- Robertson ---- */
static const real r1 = 0.04Q, r2 = 3e7Q, r3 = 1e4Q;

static void rober_coef(real c[NMAX][PMAX + 2], int P)
{
    for (int k = 0; k < P; k++) {
        const real p23 = cauchy(c[1], c[2], k), p22 = cauchy(c[1], c[1], k);
        real f[3];
        f[0] = -r1 * c[0][k] + r3 * p23;
        f[2] = r2 * p22;
        f[1] = r1 * c[0][k] - r3 * p23 - r2 * p22;
        for (int i = 0; i < 3; i++)
            c[i][k + 1] = f[i] / (k + 1);
    }
}

static real rober_jnorm(const real *y)
{
    real a = r1 + qabs(r3 * y[2]) + qabs(r3 * y[1]);
    real b = r1 + qabs(r3 * y[2] + 2 * r2 * y[1]) + qabs(r3 * y[1]);
    real c = qabs(2 * r2 * y[1]);
    return a > b ? (a > c ? a : c) : (b > c ? b : c);
}

/* ---- Arenstorf (HNW I sec. II.0); mu set by main ---- */
static real amu;

/* g = u^a from the coefficients of u (u_0 != 0), orders 0..k (g_0 set by the caller). */
static void power_coef(const real *u, real *g, real a, int k)
{
    real s = 0;
    for (int j = 0; j < k; j++)
        s += (a * (k - j) - j) * u[k - j] * g[j];
    g[k] = s / (k * u[0]);
}

static void arenstorf_coef(real c[NMAX][PMAX + 2], int P)
{
    real x1[PMAX + 2], x2[PMAX + 2], u1[PMAX + 2], u2[PMAX + 2], w1[PMAX + 2], w2[PMAX + 2];
    const real mup = 1 - amu;
    for (int k = 0; k < P; k++) {
        x1[k] = c[0][k] + (k == 0 ? amu : 0);
        x2[k] = c[0][k] - (k == 0 ? mup : 0);
        u1[k] = cauchy(x1, x1, k) + cauchy(c[1], c[1], k);
        u2[k] = cauchy(x2, x2, k) + cauchy(c[1], c[1], k);
        if (k == 0) {
            w1[0] = powq(u1[0], -1.5Q);
            w2[0] = powq(u2[0], -1.5Q);
        } else {
            power_coef(u1, w1, -1.5Q, k);
            power_coef(u2, w2, -1.5Q, k);
        }
        const real a1 = c[0][k] + 2 * c[3][k] - mup * cauchy(x1, w1, k) - amu * cauchy(x2, w2, k);
        const real a2 = c[1][k] - 2 * c[2][k] - mup * cauchy(c[1], w1, k) -
                        amu * cauchy(c[1], w2, k);
        c[0][k + 1] = c[2][k] / (k + 1);
        c[1][k + 1] = c[3][k] / (k + 1);
        c[2][k + 1] = a1 / (k + 1);
        c[3][k + 1] = a2 / (k + 1);
    }
}

static real arenstorf_jnorm(const real *y)
{
    const real mup = 1 - amu;
    real r1 = sqrtq((y[0] + amu) * (y[0] + amu) + y[1] * y[1]);
    real r2 = sqrtq((y[0] - mup) * (y[0] - mup) + y[1] * y[1]);
    return 3 + 3 * (mup / (r1 * r1 * r1) + amu / (r2 * r2 * r2));
}

typedef struct problem {
    int n;
    void (*coef)(real c[NMAX][PMAX + 2], int P);
    real (*jnorm)(const real *y);
} problem;

static long taylor_to(const problem *pb, real t, real *y, real t_out, int P, real tol, real S)
{
    real c[NMAX][PMAX + 2];
    long steps = 0;
    while (t < t_out) {
        for (int i = 0; i < pb->n; i++)
            c[i][0] = y[i];
        pb->coef(c, P);
        real rho = 1e30Q;
        for (int k = P - 1; k <= P; k++) {
            real m = 0;
            for (int i = 0; i < pb->n; i++)
                if (qabs(c[i][k]) > m)
                    m = qabs(c[i][k]);
            if (m > 0) {
                real r = powq(tol / m, (real)1 / k);
                if (r < rho)
                    rho = r;
            }
        }
        real h = rho, jn = pb->jnorm(y);
        if (jn > 0 && h > S / jn)
            h = S / jn;
        int last = 0;
        if (t + h >= t_out) {
            h = t_out - t;
            last = 1;
        }
        for (int i = 0; i < pb->n; i++) {
            real v = c[i][P];
            for (int k = P - 1; k >= 0; k--)
                v = v * h + c[i][k];
            y[i] = v;
        }
        t = last ? t_out : t + h;
        steps++;
    }
    return steps;
}

static void run(const char *name, const problem *pb, const real *y0, real t1, const double *pub,
                real res[2][NMAX])
{
    const int P[2] = {30, 40};
    const real tol[2] = {1e-34Q, 1e-38Q};
    const real S[2] = {6, 9};
    printf("== %s, t = %.10g\n", name, (double)t1);
    for (int r = 0; r < 2; r++) {
        memcpy(res[r], y0, sizeof(real) * (size_t)pb->n);
        long steps = taylor_to(pb, 0, res[r], t1, P[r], tol[r], S[r]);
        printf("  order %d: %ld steps\n", P[r], steps);
    }
    for (int i = 0; i < pb->n; i++) {
        char a[64], d[32];
        quadmath_snprintf(a, sizeof a, "%+.32Qe", res[1][i]);
        quadmath_snprintf(d, sizeof d, "%.2Qe", qabs(res[0][i] - res[1][i]));
        printf("  y%d = %s  |P30 - P40| = %s", i + 1, a, d);
        if (pub)
            printf("  published %.16e  rel. diff %.2e", pub[i],
                   (double)(qabs(res[1][i] - (real)pub[i]) / qabs(res[1][i])));
        printf("\n");
    }
}

int main(void)
{
    static const double hires_pub[8] = {
        0.7371312573325668e-3, 0.1442485726316185e-3, 0.5888729740967575e-4,
        0.1175651343283149e-2, 0.2386356198831331e-2, 0.6238968252742796e-2,
        0.2849998395185769e-2, 0.2850001604814231e-2};
    const real hires_y0[8] = {1, 0, 0, 0, 0, 0, 0, 0.0057Q};
    problem hires = {8, hires_coef, hires_jnorm};
    real res[2][NMAX];
    run("HIRES", &hires, hires_y0, 321.8122Q, hires_pub, res);
    const real rober_y0[3] = {1, 0, 0};
    problem rober = {3, rober_coef, rober_jnorm};
    run("Robertson", &rober, rober_y0, 40, NULL, res);
    const real T = 17.0652165601579625588917206249Q;
    const real ya[4] = {0.994Q, 0, 0, -2.00158510637908252240537862224Q};
    problem aren = {4, arenstorf_coef, arenstorf_jnorm};
    amu = 0.012277471Q;
    run("Arenstorf, data as published (30 digits)", &aren, ya, T, NULL, res);
    for (int i = 0; i < 4; i++)
        printf("  y%d(T) - y%d(0) = %.3e\n", i + 1, i + 1, (double)(res[1][i] - ya[i]));
    /* the data the library uses: mu, y0 and T rounded to double */
    const real yd[4] = {(double)0.994, 0, 0, (double)-2.00158510637908252240537862224};
    amu = (double)0.012277471;
    run("Arenstorf, data rounded to double", &aren, yd, (double)T, NULL, res);
    for (int i = 0; i < 4; i++)
        printf("  y%d(T) - y%d(0) = %.3e\n", i + 1, i + 1, (double)(res[1][i] - yd[i]));
    return 0;
}
