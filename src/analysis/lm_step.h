/* SPDX-License-Identifier: BSD-3-Clause */
/* lm_step.h — the pieces of a Levenberg–Marquardt step shared by equilibrium.c and
 * steady.c (Nocedal & Wright, Numerical Optimization, 2nd ed., sec. 10.3): the norms of a
 * residual, the normal equations H = J^T J, -g = -J^T r of a row-major ne x nu Jacobian,
 * and the damped step (H + lambda max_i H_ii I) d = -g by Cholesky. Internal. */
#ifndef DYNKIT_ANALYSIS_LM_STEP_H
#define DYNKIT_ANALYSIS_LM_STEP_H

#include <math.h>
#include <stddef.h>

#include "ode/cholesky.h"

static inline double lm_norm_inf(int n, const double *v)
{
    double r = 0.0;
    for (int i = 0; i < n; i++)
        r = fmax(r, fabs(v[i]));
    return r;
}

static inline double lm_norm_2(int n, const double *v)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += v[i] * v[i];
    return sqrt(s);
}

/* H = J^T J (nu x nu) and minus_g = -J^T r; returns max_i H_ii (not > 0: J is zero). */
static inline double lm_normal_equations(int ne, int nu, const double *J, const double *r,
                                         double *H, double *minus_g)
{
    const size_t NU = (size_t)nu;
    double hmax = 0.0;
    for (size_t a = 0; a < NU; a++) {
        double g = 0.0;
        for (size_t l = 0; l < (size_t)ne; l++)
            g += J[l * NU + a] * r[l];
        minus_g[a] = -g;
        for (size_t b = 0; b <= a; b++) {
            double h = 0.0;
            for (size_t l = 0; l < (size_t)ne; l++)
                h += J[l * NU + a] * J[l * NU + b];
            H[a * NU + b] = H[b * NU + a] = h;
        }
        hmax = fmax(hmax, H[a * NU + a]);
    }
    return hmax;
}

/* d (given -g) becomes the step of (A + lambda hmax I) d = -g, A (H on entry) factored in
 * place; 0, or -1 when the factorization fails (d is then left as it was). */
static inline int lm_damped_solve(int nu, double *A, double lambda, double hmax, double *d)
{
    for (size_t a = 0; a < (size_t)nu; a++)
        A[a * (size_t)nu + a] += lambda * hmax;
    if (dyn_cholesky_factor(nu, A))
        return -1;
    dyn_cholesky_solve(nu, A, d);
    return 0;
}

#endif
