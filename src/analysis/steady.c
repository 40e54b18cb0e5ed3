/* SPDX-License-Identifier: BSD-3-Clause */
/* steady.c — steady motions (relative equilibria; Kuznetsov's "relative equilibria" of
 * systems with a symmetry, and Routh's steady motions of systems with ignorable
 * coordinates, e.g. Greenwood, Advanced Dynamics, sec. 4.6): the unknowns (states or
 * parameters) solved by Gauss-Newton with Levenberg-Marquardt damping (Nocedal & Wright,
 * 2nd ed., sec. 10.3) on the derivatives of the non-cyclic states, which may outnumber
 * them (identities such as a precession's own equation count as equations that hold); the
 * Jacobian by central differences of steps 2^-20 max(|u|, 1). Cyclic states: the kept
 * states whose column of the linearization along the admissible directions vanishes on
 * the rows of the states that must stay steady. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/lm_step.h"
#include "dynkit/analysis.h"
#include "dynkit/steady.h"

int dyn_steady_cyclic(int n, int k, const int *kept, const double *AP, double rel, int *cyclic)
{
    (void)n;
    memset(cyclic, 0, (size_t)k * sizeof *cyclic);
    int count = 0, changed = 1;
    while (changed) {
        changed = 0;
        double big = 0.0;
        for (int r = 0; r < k; r++)
            for (int j = 0; j < k && !cyclic[r]; j++)
                big = fmax(big, fabs(AP[(size_t)(kept ? kept[r] : r) * (size_t)k + (size_t)j]));
        for (int j = 0; j < k; j++) {
            if (cyclic[j])
                continue;
            int zero = 1;
            for (int r = 0; r < k && zero; r++)
                zero = cyclic[r] ||
                       fabs(AP[(size_t)(kept ? kept[r] : r) * (size_t)k + (size_t)j]) <= rel * big;
            if (zero) {
                cyclic[j] = 1;
                count++;
                changed = 1;
            }
        }
    }
    return count;
}

typedef struct steady_eval {
    const dyn_model *m;
    double t;
    double *y, *par_save, *f;
    void *par;
    const dyn_steady_opts *o;
    char *err;
    size_t errlen;
} steady_eval;

/* Set the unknowns to u, complete the state, the equations' f into r. */
static int evaluate(steady_eval *e, const double *u, double *r)
{
    const dyn_steady_opts *o = e->o;
    int params = 0;
    for (int j = 0; j < o->n_unknowns; j++) {
        const dyn_steady_unknown *x = &o->unknowns[j];
        if (x->is_param) {
            dyn_model_set_param(e->m, e->par, x->index, u[j]);
            params = 1;
        } else {
            e->y[x->index] = u[j];
        }
    }
    if (params && e->m->prepare && e->m->prepare(e->par, e->err, e->errlen))
        return DYN_ERR_ARG;
    if (o->complete && o->complete(o->complete_ctx, e->t, e->y, e->par, e->err, e->errlen))
        return DYN_ERR_ARG;
    if (e->m->rhs(e->t, e->y, e->f, e->par)) {
        snprintf(e->err, e->errlen, "the right-hand side of %s fails", e->m->name);
        return DYN_ERR_RHS;
    }
    for (int i = 0; i < o->n_equations; i++) {
        r[i] = e->f[o->equations[i]];
        if (!isfinite(r[i])) {
            snprintf(e->err, e->errlen, "the derivative of %s is not finite",
                     e->m->states[o->equations[i]].name);
            return DYN_ERR_RHS;
        }
    }
    return 0;
}

/* (J^T J + lambda max diag I) d = -J^T r; 0, or -1 when the factorization fails. */
static int lm_step(int ne, int nu, const double *J, const double *r, double lambda, double *H,
                   double *d)
{
    const double hmax = lm_normal_equations(ne, nu, J, r, H, d);
    if (!(hmax > 0.0))
        return -1;
    return lm_damped_solve(nu, H, lambda, hmax, d);
}

int dyn_steady_solve(const dyn_model *m, double t, double *y, void *par, const dyn_steady_opts *o,
                     dyn_steady_info *info)
{
    dyn_steady_info local;
    if (!info)
        info = &local;
    memset(info, 0, sizeof *info);
    const int nu = o->n_unknowns, ne = o->n_equations, n = m->n_states;
    if (nu < 1 || ne < nu) {
        snprintf(info->message, sizeof info->message,
                 "%d unknowns and %d states that must stay steady: give at least one unknown "
                 "and no more unknowns than such states",
                 nu, ne);
        return DYN_ERR_ARG;
    }
    const size_t NU = (size_t)nu, NE = (size_t)ne;
    double *mem = malloc((3 * NU + 3 * NE + NE * NU + NU * NU + 2 * (size_t)n) * sizeof *mem);
    if (!mem) {
        snprintf(info->message, sizeof info->message, "out of memory");
        return DYN_ERR_CAPACITY;
    }
    double *u = mem, *ut = u + NU, *d = ut + NU, *r = d + NU, *rt = r + NE, *rp = rt + NE,
           *J = rp + NE, *H = J + NE * NU, *f = H + NU * NU, *ybest = f + n;
    steady_eval e = {m, t, y, NULL, f, par, o, info->message, sizeof info->message};
    for (int j = 0; j < nu; j++)
        u[j] = o->unknowns[j].is_param ? dyn_model_get_param(m, par, o->unknowns[j].index)
                                       : y[o->unknowns[j].index];
    const double rtol = o->tol > 0.0 ? o->tol : 1e-12;
    const int max_iter = o->max_iter > 0 ? o->max_iter : 100;
    int rc = evaluate(&e, u, r);
    double lambda = 1e-3;
    while (!rc) {
        info->tol = rtol * fmax(lm_norm_inf(n, f), 1.0);
        info->residual = lm_norm_inf(ne, r);
        if (info->residual <= info->tol)
            break;
        if (info->iterations >= max_iter) {
            snprintf(info->message, sizeof info->message,
                     "no steady motion within %d iterations: residual %.3g", max_iter,
                     info->residual);
            rc = DYN_ERR_MAX_STEPS;
            break;
        }
        info->iterations++;
        memcpy(ybest, y, (size_t)n * sizeof *y);
        /* the Jacobian by central differences */
        for (int j = 0; j < nu && !rc; j++) {
            int ex;
            frexp(fmax(fabs(u[j]), 1.0), &ex);
            const double h = ldexp(1.0, ex - 21);
            memcpy(ut, u, NU * sizeof *u);
            ut[j] = u[j] + h;
            rc = evaluate(&e, ut, rp);
            ut[j] = u[j] - h;
            if (!rc)
                rc = evaluate(&e, ut, rt);
            for (int i = 0; i < ne && !rc; i++)
                J[(size_t)i * NU + (size_t)j] = (rp[i] - rt[i]) / (2.0 * h);
        }
        if (rc)
            break;
        const double rn = lm_norm_2(ne, r);
        int accepted = 0;
        while (!accepted && lambda <= 1e12) {
            if (lm_step(ne, nu, J, r, lambda, H, d)) {
                lambda *= 10.0;
                continue;
            }
            for (int j = 0; j < nu; j++)
                ut[j] = u[j] + d[j];
            memcpy(y, ybest, (size_t)n * sizeof *y);
            const int st = evaluate(&e, ut, rt);
            if (!st && lm_norm_2(ne, rt) < rn) {
                memcpy(u, ut, NU * sizeof *u);
                memcpy(r, rt, NE * sizeof *r);
                lambda = fmax(lambda / 10.0, 1e-15);
                accepted = 1;
            } else {
                lambda *= 10.0;
            }
        }
        if (!accepted) {
            memcpy(y, ybest, (size_t)n * sizeof *y);
            rc = evaluate(&e, u, r);
            if (!rc && lm_norm_inf(ne, r) <= 1e4 * info->tol)
                break; /* at its rounding */
            if (!rc) {
                snprintf(info->message, sizeof info->message,
                         "no step lowers the residual (no steady motion near the guess): "
                         "%.3g",
                         lm_norm_inf(ne, r));
                rc = DYN_ERR_STEP_SIZE;
            }
        }
    }
    info->residual = lm_norm_inf(ne, r);
    free(mem);
    return rc;
}
