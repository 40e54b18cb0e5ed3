/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady_krein.c — the test function of a Hamiltonian Hopf bifurcation (a Krein
 * collision) on a branch of steady motions (private; cont_steady_system.h). A conservative
 * steady motion's spectrum is symmetric under lambda -> -lambda (and conjugation), so its
 * eigenvalues are the square roots of mu = lambda^2, one mu per pair +-lambda: real and
 * negative for a pair on the imaginary axis, positive for a real pair, a conjugate pair of
 * mu for a quadruple +-a +-ib. Two imaginary pairs +-i w1, +-i w2 that collide and leave the
 * axis are two real mu that meet and become complex: the discriminant of the polynomial of
 * the mu, prod_{j<k} (mu_j - mu_k)^2, changes sign there (its sign is (-1)^(the number of
 * complex pairs of mu)), smoothly, while pairs of the same Krein signature that pass through
 * each other only touch zero (Meyer, Hall & Offin, Introduction to Hamiltonian Dynamical
 * Systems and the N-Body Problem, 2nd ed., sec. 4.4 and 11.4; van der Meer, The Hamiltonian
 * Hopf Bifurcation, LNM 1160). Each factor is divided by (|mu_j| + |mu_k|)^2, which leaves
 * the sign and keeps the product of order one. */
#include <math.h>

#include "cont_steady_system.h"

/* 1 when every eigenvalue's negative is one too (within tol): a spectrum that can be
 * conservative */
static int symmetric(int n, const double *re, const double *im, double tol)
{
    for (int i = 0; i < n; i++) {
        int found = 0;
        for (int j = 0; j < n && !found; j++)
            found = fabs(re[j] + re[i]) <= tol && fabs(im[j] + im[i]) <= tol;
        if (!found)
            return 0;
    }
    return 1;
}

double sc_krein_test(int n, const double *re, const double *im, double tol, int *off_axis,
                     double *omega)
{
    double big = 0.0;
    for (int i = 0; i < n; i++)
        big = fmax(big, hypot(re[i], im[i]));
    *off_axis = -2;
    if (omega)
        *omega = NAN;
    if (!(big > 0.0) || !symmetric(n, re, im, 1e-6 * big) || n > 128)
        return 1.0; /* not a conservative spectrum, or more pairs than the test holds */
    /* one eigenvalue of each pair +-lambda: above the real axis, or real and not negative */
    const double tol_im = 1e-8 * big;
    double mr[64], mi[64], wim[64];
    int m = 0;
    *off_axis = 0;
    for (int i = 0; i < n; i++) {
        *off_axis += fabs(re[i]) > tol;
        if ((im[i] > tol_im || (fabs(im[i]) <= tol_im && re[i] >= 0.0)) && m < 64) {
            mr[m] = re[i] * re[i] - im[i] * im[i];
            mi[m] = 2.0 * re[i] * im[i];
            wim[m++] = fabs(im[i]);
        }
    }
    double pr = 1.0, pi = 0.0, closest = INFINITY;
    for (int j = 0; j < m; j++)
        for (int k = j + 1; k < m; k++) {
            const double s = hypot(mr[j], mi[j]) + hypot(mr[k], mi[k]);
            if (!(s > 0.0))
                continue;
            const double dr = (mr[j] - mr[k]) / s, di = (mi[j] - mi[k]) / s;
            const double fr = dr * dr - di * di, fi = 2.0 * dr * di;
            const double qr = pr * fr - pi * fi;
            pi = pr * fi + pi * fr;
            pr = qr;
            const double dist = hypot(dr, di);
            if (dist < closest && omega) {
                closest = dist;
                *omega = 0.5 * (wim[j] + wim[k]);
            }
        }
    return pr;
}
