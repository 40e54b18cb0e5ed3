/* SPDX-License-Identifier: BSD-3-Clause */
/* eig_hqr.c — eigenvalues of a small real nonsymmetric matrix without LAPACK, for the
 * stability and the Hopf test of continuation (dynkit/continuation.h, dyn_eig_hqr):
 * balancing by powers of the radix (EISPACK balanc), reduction to upper Hessenberg form by
 * stabilized elementary similarity transformations (elmhes), and Francis' implicit
 * double-shift QR iteration with exceptional shifts (hqr). Wilkinson & Reinsch, "Handbook
 * for Automatic Computation II: Linear Algebra" (1971), contributions II/11, II/13, II/14;
 * the 0-based layout of Press et al., "Numerical Recipes", sec. 11.5-11.6. */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "dynkit/continuation.h"

#define A_(i, j) a[(size_t)(i) * (size_t)n + (size_t)(j)]

static void balance(int n, double *a)
{
    const double radix = 2.0, sqrdx = radix * radix;
    int last = 0;
    while (last == 0) {
        last = 1;
        for (int i = 0; i < n; i++) {
            double r = 0.0, c = 0.0;
            for (int j = 0; j < n; j++)
                if (j != i) {
                    c += fabs(A_(j, i));
                    r += fabs(A_(i, j));
                }
            if (c != 0.0 && r != 0.0) {
                double g = r / radix, f = 1.0;
                const double s = c + r;
                while (c < g) {
                    f *= radix;
                    c *= sqrdx;
                }
                g = r * radix;
                while (c > g) {
                    f /= radix;
                    c /= sqrdx;
                }
                if ((c + r) / f < 0.95 * s) {
                    last = 0;
                    g = 1.0 / f;
                    for (int j = 0; j < n; j++)
                        A_(i, j) *= g;
                    for (int j = 0; j < n; j++)
                        A_(j, i) *= f;
                }
            }
        }
    }
}

static void hessenberg(int n, double *a)
{
    for (int m = 1; m < n - 1; m++) {
        double x = 0.0;
        int i = m;
        for (int j = m; j < n; j++)
            if (fabs(A_(j, m - 1)) > fabs(x)) {
                x = A_(j, m - 1);
                i = j;
            }
        if (i != m) {
            for (int j = m - 1; j < n; j++) {
                const double t = A_(i, j);
                A_(i, j) = A_(m, j);
                A_(m, j) = t;
            }
            for (int j = 0; j < n; j++) {
                const double t = A_(j, i);
                A_(j, i) = A_(j, m);
                A_(j, m) = t;
            }
        }
        if (x != 0.0)
            for (i = m + 1; i < n; i++) {
                double y = A_(i, m - 1);
                if (y != 0.0) {
                    y /= x;
                    A_(i, m - 1) = y;
                    for (int j = m; j < n; j++)
                        A_(i, j) -= y * A_(m, j);
                    for (int j = 0; j < n; j++)
                        A_(j, m) += y * A_(j, i);
                }
            }
    }
    for (int i = 2; i < n; i++)
        for (int j = 0; j < i - 1; j++)
            A_(i, j) = 0.0;
}

static int hqr(int n, double *a, double *wr, double *wi)
{
    double anorm = 0.0, p = 0.0, q = 0.0, r = 0.0, s, t = 0.0, w, x, y, z;
    for (int i = 0; i < n; i++)
        for (int j = i > 0 ? i - 1 : 0; j < n; j++)
            anorm += fabs(A_(i, j));
    int nn = n - 1;
    while (nn >= 0) {
        int its = 0, l;
        do {
            for (l = nn; l >= 1; l--) {
                s = fabs(A_(l - 1, l - 1)) + fabs(A_(l, l));
                if (s == 0.0)
                    s = anorm;
                if (fabs(A_(l, l - 1)) <= DBL_EPSILON * s) {
                    A_(l, l - 1) = 0.0;
                    break;
                }
            }
            x = A_(nn, nn);
            if (l == nn) {
                wr[nn] = x + t;
                wi[nn--] = 0.0;
            } else {
                y = A_(nn - 1, nn - 1);
                w = A_(nn, nn - 1) * A_(nn - 1, nn);
                if (l == nn - 1) {
                    p = 0.5 * (y - x);
                    q = p * p + w;
                    z = sqrt(fabs(q));
                    x += t;
                    if (q >= 0.0) {
                        z = p + copysign(z, p);
                        wr[nn - 1] = wr[nn] = x + z;
                        if (z != 0.0)
                            wr[nn] = x - w / z;
                        wi[nn - 1] = wi[nn] = 0.0;
                    } else {
                        wr[nn - 1] = wr[nn] = x + p;
                        wi[nn - 1] = z;
                        wi[nn] = -z;
                    }
                    nn -= 2;
                } else {
                    if (its == 30 * (n > 1 ? n : 1))
                        return -1;
                    if (its == 10 || its == 20) {
                        /* an exceptional shift */
                        t += x;
                        for (int i = 0; i <= nn; i++)
                            A_(i, i) -= x;
                        s = fabs(A_(nn, nn - 1)) + fabs(A_(nn - 1, nn - 2));
                        y = x = 0.75 * s;
                        w = -0.4375 * s * s;
                    }
                    ++its;
                    int m;
                    for (m = nn - 2; m >= l; m--) {
                        z = A_(m, m);
                        r = x - z;
                        s = y - z;
                        p = (r * s - w) / A_(m + 1, m) + A_(m, m + 1);
                        q = A_(m + 1, m + 1) - z - r - s;
                        r = A_(m + 2, m + 1);
                        s = fabs(p) + fabs(q) + fabs(r);
                        p /= s;
                        q /= s;
                        r /= s;
                        if (m == l)
                            break;
                        const double u = fabs(A_(m, m - 1)) * (fabs(q) + fabs(r));
                        const double v = fabs(p) * (fabs(A_(m - 1, m - 1)) + fabs(z) +
                                                    fabs(A_(m + 1, m + 1)));
                        if (u <= DBL_EPSILON * v)
                            break;
                    }
                    for (int i = m; i < nn - 1; i++) {
                        A_(i + 2, i) = 0.0;
                        if (i != m)
                            A_(i + 2, i - 1) = 0.0;
                    }
                    for (int k = m; k < nn; k++) {
                        if (k != m) {
                            p = A_(k, k - 1);
                            q = A_(k + 1, k - 1);
                            r = 0.0;
                            if (k + 1 != nn)
                                r = A_(k + 2, k - 1);
                            if ((x = fabs(p) + fabs(q) + fabs(r)) != 0.0) {
                                p /= x;
                                q /= x;
                                r /= x;
                            }
                        }
                        s = copysign(sqrt(p * p + q * q + r * r), p);
                        if (s != 0.0) {
                            if (k == m) {
                                if (l != m)
                                    A_(k, k - 1) = -A_(k, k - 1);
                            } else {
                                A_(k, k - 1) = -s * x;
                            }
                            p += s;
                            x = p / s;
                            y = q / s;
                            z = r / s;
                            q /= p;
                            r /= p;
                            for (int j = k; j <= nn; j++) {
                                p = A_(k, j) + q * A_(k + 1, j);
                                if (k + 1 != nn) {
                                    p += r * A_(k + 2, j);
                                    A_(k + 2, j) -= p * z;
                                }
                                A_(k + 1, j) -= p * y;
                                A_(k, j) -= p * x;
                            }
                            const int mmin = nn < k + 3 ? nn : k + 3;
                            for (int i = l; i <= mmin; i++) {
                                p = x * A_(i, k) + y * A_(i, k + 1);
                                if (k + 1 != nn) {
                                    p += z * A_(i, k + 2);
                                    A_(i, k + 2) -= p * r;
                                }
                                A_(i, k + 1) -= p * q;
                                A_(i, k) -= p;
                            }
                        }
                    }
                }
            }
        } while (l < nn - 1);
    }
    return 0;
}

int dyn_eig_hqr(int n, double *a, double *re, double *im, char *err, size_t errlen)
{
    for (size_t k = 0; k < (size_t)n * (size_t)n; k++)
        if (!isfinite(a[k])) {
            if (err && errlen)
                snprintf(err, errlen, "the matrix has an entry that is not finite");
            return DYN_ERR_NONFINITE;
        }
    if (n <= 0)
        return 0;
    balance(n, a);
    hessenberg(n, a);
    if (hqr(n, a, re, im)) {
        if (err && errlen)
            snprintf(err, errlen, "the QR iteration did not converge in %d sweeps", 30 * n);
        return DYN_ERR_MAX_STEPS;
    }
    /* each complex pair with the positive imaginary part first */
    for (int i = 0; i + 1 < n; i++)
        if (im[i] != 0.0 && im[i + 1] == -im[i]) {
            if (im[i] < 0.0) {
                im[i] = -im[i];
                im[i + 1] = -im[i + 1];
            }
            i++;
        }
    return 0;
}
