/* SPDX-License-Identifier: BSD-3-Clause */
/* The Roessler system x' = -y - z, y' = x + a y, z' = b + z (x - c), b = 0.2, c = 5.7
 * (O. E. Roessler, Phys. Lett. A 57, 1976), as a dyn_po_system's right-hand side of the
 * parameter a, and the Hopf point in a of its equilibrium near the origin, found by 80
 * bisections of [0.001, 0.02] on the sign of the real part of the complex pair (LAPACK's
 * eigenvalues). Shared by tests/test_colloc.c and bench/bench_colloc.c, which start their
 * periodic branch there. Needs dynkit/lapack.h. */
#ifndef DYNKIT_TESTS_ROESSLER_HOPF_H
#define DYNKIT_TESTS_ROESSLER_HOPF_H

#include <math.h>
#include <string.h>

#include "dynkit/lapack.h"

static int roessler(const double *x, double a, double *f, double *J, void *ctx)
{
    (void)ctx;
    const double b = 0.2, c = 5.7;
    f[0] = -x[1] - x[2];
    f[1] = x[0] + a * x[1];
    f[2] = b + x[2] * (x[0] - c);
    if (J) {
        const double j[9] = {0, -1, -1, 1, a, 0, x[2], 0, x[0] - c};
        memcpy(J, j, sizeof j);
    }
    return 0;
}

/* The Hopf point: *a_h, the equilibrium x0 there and the pair's frequency *omega; 0, or
 * the status of the first eigenvalue computation that failed. */
static int roessler_hopf_point(double *a_h, double *x0, double *omega)
{
    const double b = 0.2, c = 5.7;
    double lo = 0.001, hi = 0.02;
    int status = 0;
    for (int it = 0; it < 80; it++) {
        const double a = 0.5 * (lo + hi);
        const double y = (-c + sqrt(c * c - 4 * a * b)) / (2 * a);
        const double xe[3] = {-a * y, y, -y};
        double f[3], J[9], re[3], im[3];
        char err[64];
        roessler(xe, a, f, J, NULL);
        const int rc = dyn_eig_solver_lapack.eigenvalues(3, J, re, im, err, sizeof err);
        if (rc && !status)
            status = rc;
        double best = -INFINITY;
        for (int i = 0; i < 3; i++)
            if (im[i] != 0 && re[i] > best) {
                best = re[i];
                *omega = fabs(im[i]);
            }
        if (best > 0)
            hi = a;
        else
            lo = a;
        memcpy(x0, xe, sizeof xe);
    }
    *a_h = 0.5 * (lo + hi);
    return status;
}

#endif
