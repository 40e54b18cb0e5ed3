/* SPDX-License-Identifier: BSD-3-Clause */
/* eigen_classify.c — eigenvalues of a linearization put in order and read: sorted by
 * imaginary, then real part; stability by the signs of the real parts with a tolerance
 * relative to the matrix's infinity norm (a real part within it counts as zero: marginal);
 * natural frequency |lambda| and damping ratio -re/|lambda| of an oscillating pair (the
 * second-order form s^2 + 2 zeta wn s + wn^2, e.g. Ogata, Modern Control Engineering). */
#include <float.h>
#include <math.h>

#include "dynkit/analysis.h"

static int before(double re1, double im1, double re2, double im2)
{
    return im1 < im2 || (im1 == im2 && re1 < re2);
}

void dyn_eig_sort(int n, double *re, double *im)
{
    /* insertion sort: n is the number of states, and the order must not depend on how a
     * library's sort breaks ties */
    for (int i = 1; i < n; i++) {
        const double r = re[i], m = im[i];
        int k = i - 1;
        while (k >= 0 && before(r, m, re[k], im[k])) {
            re[k + 1] = re[k];
            im[k + 1] = im[k];
            k--;
        }
        re[k + 1] = r;
        im[k + 1] = m;
    }
}

dyn_stability dyn_classify(int n, const double *re, double tol)
{
    int marginal = 0;
    for (int i = 0; i < n; i++) {
        if (re[i] > tol)
            return DYN_UNSTABLE;
        if (!(re[i] < -tol))
            marginal = 1;
    }
    return marginal ? DYN_MARGINAL : DYN_STABLE;
}

double dyn_stability_tol(int n, const double *A, double rtol)
{
    if (!(rtol > 0.0))
        rtol = DYN_STABILITY_RTOL;
    double norm = 0.0;
    for (int i = 0; i < n; i++) {
        double row = 0.0;
        for (int j = 0; j < n; j++)
            row += fabs(A[(size_t)i * (size_t)n + (size_t)j]);
        norm = fmax(norm, row);
    }
    return fmax(rtol * norm, DBL_MIN);
}

const char *dyn_stability_name(dyn_stability s)
{
    switch (s) {
    case DYN_STABLE: return "asymptotically stable";
    case DYN_UNSTABLE: return "unstable";
    default: return "marginal";
    }
}

void dyn_eig_mode(double re, double im, double *wn, double *zeta)
{
    const double mag = hypot(re, im);
    *wn = mag;
    *zeta = mag > 0.0 ? -re / mag : 0.0;
}
