/* SPDX-License-Identifier: BSD-3-Clause */
/* A program of one's own on dynkit::lapack (dynkit/lapack.h): the eigenvalues of the damped
 * linear oscillator x'' + 2 zeta w x' + w^2 x = 0 as a first-order system, the matrix
 * [0 1; -w^2 -2 zeta w], by LAPACK's dgeev, against the closed form -zeta w +- i wd,
 * wd = w sqrt(1 - zeta^2) (zeta = 0.1, w = 2, as tests/install/oscillator.ode). Prints them;
 * exits 1 when either part differs by more than 1e-14. */
#include <math.h>
#include <stdio.h>

#include <dynkit/lapack.h>

int main(void)
{
    const double zeta = 0.1, w = 2.0, wd = w * sqrt(1.0 - zeta * zeta);
    double a[4] = {0.0, 1.0, -w * w, -2.0 * zeta * w}, re[2], im[2];
    char err[256];
    if (dyn_eig_solver_lapack.eigenvalues(2, a, re, im, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    dyn_eig_sort(2, re, im);
    printf("eigenvalues %.15g %+.15gi, %.15g %+.15gi (closed form %.15g +- %.15gi)\n", re[0],
           im[0], re[1], im[1], -zeta * w, wd);
    int bad = 0;
    for (int k = 0; k < 2; k++)
        bad |= !(fabs(re[k] + zeta * w) <= 1e-14 && fabs(fabs(im[k]) - wd) <= 1e-14);
    return bad;
}
