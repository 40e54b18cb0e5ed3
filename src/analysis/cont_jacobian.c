/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_jacobian.c — the Jacobian of a continuation system's residual by central differences
 * (cont_core.h), for the systems whose Jacobian is not formed otherwise: the curves of
 * folds and Hopf points (cont_curves.c, cont_steady_curves.c) and the branches of steady
 * motions (cont_steady_system.c). Each column from two evaluations of the residual; error
 * O(h^2) from the third derivatives plus rounding of order eps / h (Nocedal & Wright,
 * Numerical Optimization, 2nd ed., sec. 8.1). */
#include <float.h>
#include <math.h>
#include <string.h>

#include "cont_core.h"

int cont_central_jacobian(int (*residual)(void *ctx, const double *z, double *g), void *ctx,
                          int N, int steps, const double *z, double *J, double *work)
{
    const int M = N + 1;
    double *zt = work, *gp = zt + M, *gm = gp + N;
    memcpy(zt, z, (size_t)M * sizeof *zt);
    for (int j = 0; j < M; j++) {
        double h, den;
        if (steps == CONT_STEPS_POW2) {
            int ex;
            frexp(fmax(fabs(z[j]), 1.0), &ex);
            h = ldexp(1.0, ex - 21);
        } else {
            h = cbrt(DBL_EPSILON) * fmax(1.0, fabs(z[j]));
        }
        const double zp = z[j] + h, zm = z[j] - h;
        den = steps == CONT_STEPS_POW2 ? 2.0 * h : zp - zm;
        zt[j] = zp;
        if (residual(ctx, zt, gp))
            return -1;
        zt[j] = zm;
        if (residual(ctx, zt, gm))
            return -1;
        zt[j] = z[j];
        for (int i = 0; i < N; i++)
            J[(size_t)i * (size_t)M + (size_t)j] = (gp[i] - gm[i]) / den;
    }
    return 0;
}
