/* SPDX-License-Identifier: BSD-3-Clause */
/* zero_outputs.c — the parameters that make chosen outputs of a model zero at a state
 * (dynkit/analysis.h, dyn_zero_outputs): Newton's method on k equations in k unknowns
 * (Dennis & Schnabel, Numerical Methods for Unconstrained Optimization and Nonlinear
 * Equations, ch. 5), the Jacobian by forward differences of steps max(1, |p|) (exact but
 * for rounding when the outputs are affine in the parameters, as a mechanism's
 * multipliers are in its loads), solved by LU with partial pivoting (src/ode/linalg.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dynkit/analysis.h"
#include "ode/linalg.h"

static int values(const dyn_model *m, void *par, double t, const double *y, int k,
                  const int *outs, double *all, double *r)
{
    char e[256];
    if (m->prepare && m->prepare(par, e, sizeof e))
        return -1;
    if (m->compute_outputs(t, y, par, all))
        return -1;
    for (int i = 0; i < k; i++) {
        r[i] = all[outs[i]];
        if (!isfinite(r[i]))
            return -1;
    }
    return 0;
}

static double norm_inf(const double *v, int k)
{
    double big = 0.0;
    for (int i = 0; i < k; i++)
        big = fmax(big, fabs(v[i]));
    return big;
}

int dyn_zero_outputs(const dyn_model *m, void *par, double t, const double *y, int k,
                     const int *params, const int *outs, double *residual, int *bad,
                     char *err, size_t errlen)
{
    *bad = -1;
    if (k <= 0 || !m->compute_outputs) {
        snprintf(err, errlen, "no outputs to make zero");
        return DYN_ERR_ARG;
    }
    double *buf = malloc(((size_t)m->n_outputs + 1 + (size_t)k * (k + 4)) * sizeof *buf);
    int *piv = malloc((size_t)k * sizeof *piv);
    if (!buf || !piv) {
        free(buf);
        free(piv);
        snprintf(err, errlen, "out of memory");
        return DYN_ERR_ARG;
    }
    double *all = buf, *r = all + m->n_outputs + 1, *rp = r + k, *J = rp + k, *p = J + k * k,
           *best = p + k;
    int rc = 0;
    for (int j = 0; j < k; j++)
        best[j] = p[j] = dyn_model_get_param(m, par, params[j]);
    double now = INFINITY;
    for (int it = 0; it < 30; it++) {
        for (int j = 0; j < k; j++)
            dyn_model_set_param(m, par, params[j], p[j]);
        if (values(m, par, t, y, k, outs, all, r)) {
            rc = DYN_ERR_ARG;
            snprintf(err, errlen, "the outputs are not finite at t = %g", t);
            break;
        }
        const double size = norm_inf(r, k);
        if (!(size < now)) /* no progress: the last best is the answer */
            break;
        now = size;
        for (int j = 0; j < k; j++)
            best[j] = p[j];
        if (size == 0.0)
            break;
        for (int j = 0; j < k && !rc; j++) {
            const double h = fmax(1.0, fabs(p[j]));
            dyn_model_set_param(m, par, params[j], p[j] + h);
            const double step = (p[j] + h) - p[j];
            if (values(m, par, t, y, k, outs, all, rp)) {
                rc = DYN_ERR_ARG;
                snprintf(err, errlen, "the outputs are not finite at t = %g", t);
            }
            dyn_model_set_param(m, par, params[j], p[j]);
            for (int i = 0; i < k && !rc; i++)
                J[i * k + j] = (rp[i] - r[i]) / step;
        }
        if (rc)
            break;
        const int sing = dyn_lu_factor(k, J, piv);
        if (sing) {
            *bad = sing - 1;
            snprintf(err, errlen, "the parameters do not move the outputs independently");
            rc = DYN_ERR_ARG;
            break;
        }
        dyn_lu_solve(k, J, piv, r);
        for (int j = 0; j < k; j++)
            p[j] -= r[j];
    }
    for (int j = 0; j < k; j++)
        dyn_model_set_param(m, par, params[j], best[j]);
    if (!rc && values(m, par, t, y, k, outs, all, r)) {
        rc = DYN_ERR_ARG;
        snprintf(err, errlen, "the outputs are not finite at t = %g", t);
    }
    if (residual)
        *residual = rc ? NAN : norm_inf(r, k);
    free(buf);
    free(piv);
    return rc;
}
