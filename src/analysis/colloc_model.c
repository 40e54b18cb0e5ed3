/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_model.c — a model (dynkit/model.h) as the system x' = f(x, lambda) of the periodic
 * branches: lambda is one of its parameters, set in a private copy of the parameter struct
 * (prepared again when it changes, for derived parameters); f at the model's t0; the
 * Jacobian the model's analytic one, or central differences with the step
 * eps^(1/3) max(|x_j|, 1). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/colloc.h"

static int set_par(dyn_po_model *pm, double lambda)
{
    if (lambda == pm->current)
        return 0;
    memcpy((char *)pm->par + pm->m->params[pm->ipar].offset, &lambda, sizeof lambda);
    pm->current = lambda;
    if (pm->m->prepare) {
        char err[128];
        return pm->m->prepare(pm->par, err, sizeof err);
    }
    return 0;
}

static int model_f(const double *x, double lambda, double *fx, double *J, void *ctx)
{
    dyn_po_model *pm = ctx;
    const dyn_model *m = pm->m;
    const int n = m->n_states;
    if (set_par(pm, lambda) || m->rhs(m->t0, x, fx, pm->par))
        return 1;
    if (!J)
        return 0;
    if (m->jacobian)
        return m->jacobian(m->t0, x, J, pm->par);
    double *xp = pm->work, *fp = xp + n, *fm = fp + n;
    memcpy(xp, x, (size_t)n * sizeof(double));
    for (int j = 0; j < n; j++) {
        const double h = cbrt(DBL_EPSILON) * fmax(fabs(x[j]), 1.0);
        xp[j] = x[j] + h;
        if (m->rhs(m->t0, xp, fp, pm->par))
            return 1;
        xp[j] = x[j] - h;
        if (m->rhs(m->t0, xp, fm, pm->par))
            return 1;
        xp[j] = x[j];
        for (int i = 0; i < n; i++)
            J[(size_t)i * n + j] = (fp[i] - fm[i]) / (2 * h);
    }
    return 0;
}

int dyn_po_model_init(dyn_po_model *pm, const dyn_model *m, const void *par, int ipar,
                      dyn_po_system *sys)
{
    memset(pm, 0, sizeof *pm);
    if (ipar < 0 || ipar >= m->n_params)
        return DYN_COLLOC_ERR_ARG;
    pm->m = m;
    pm->ipar = ipar;
    pm->par = malloc(m->par_size ? m->par_size : 1);
    pm->work = malloc(3 * (size_t)m->n_states * sizeof(double));
    if (!pm->par || !pm->work) {
        dyn_po_model_free(pm);
        return DYN_COLLOC_ERR_NOMEM;
    }
    memcpy(pm->par, par, m->par_size);
    memcpy(&pm->current, (const char *)par + m->params[ipar].offset, sizeof(double));
    sys->n = m->n_states;
    sys->f = model_f;
    sys->ctx = pm;
    return 0;
}

void dyn_po_model_free(dyn_po_model *pm)
{
    free(pm->par);
    free(pm->work);
    memset(pm, 0, sizeof *pm);
}
