/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_model.c — a model's f(x, p) for continuation (cont_equilibrium.h): the working
 * parameter struct prepared again only when a parameter changes, df/dx from dyn_linearize
 * (the model's exact Jacobian when it has one), df/dp by central differences with the step
 * eps^(1/3) max(1, |p|) taken as the representable difference (an error of about 1e-10
 * relative, which slows Newton's convergence but does not move the solution), and the
 * eigenvalues of the Jacobian by dyn_eig_hqr. A discrete map's fixed points are the zeros
 * of F(x) - x, judged by the multipliers, the eigenvalues of dF/dx. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cont_equilibrium.h"

int cont_model_init(cont_model *cm, const dyn_model *m, const void *par, const dyn_cont_opts *o)
{
    memset(cm, 0, sizeof *cm);
    cm->m = m;
    cm->n = m->n_states;
    cm->t = o->t;
    cm->jac = o->jac;
    cm->ip = o->ip;
    cm->ip2 = o->ip2;
    cm->map = o->map;
    cm->period = o->map && o->map_period > 1 ? o->map_period : 1;
    const size_t n = (size_t)cm->n;
    if (o->map && !(cm->map_work = malloc((2 * n + 3 * n * n) * sizeof *cm->map_work)))
        return -1;
    cm->par = malloc(m->par_size ? m->par_size : 1);
    cm->f = malloc((5 * n + 2 * n * n + dyn_linearize_work_size(cm->n)) * sizeof *cm->f);
    if (!cm->par || !cm->f) {
        cont_model_free(cm);
        return -1;
    }
    memcpy(cm->par, par, m->par_size);
    cm->fp = cm->f + n;
    cm->fm = cm->fp + n;
    cm->re = cm->fm + n;
    cm->im = cm->re + n;
    cm->J = cm->im + n;
    cm->eig_a = cm->J + n * n;
    cm->lin_work = cm->eig_a + n * n;
    cm->p_set[0] = dyn_model_get_param(m, cm->par, o->ip);
    cm->p_set[1] = o->ip2 >= 0 ? dyn_model_get_param(m, cm->par, o->ip2) : NAN;
    cm->p2_base = cm->p_set[1];
    return 0;
}

void cont_model_free(cont_model *cm)
{
    free(cm->par);
    free(cm->f);
    free(cm->map_work);
    cm->par = NULL;
    cm->f = NULL;
    cm->map_work = NULL;
}

int cont_model_set(cont_model *cm, double p, double p2)
{
    if (cm->ip2 >= 0 && isnan(p2))
        p2 = cm->p2_base;
    if (p == cm->p_set[0] && (cm->ip2 < 0 || p2 == cm->p_set[1]))
        return 0;
    if (!isfinite(p) || (cm->ip2 >= 0 && !isfinite(p2)))
        return -1;
    dyn_model_set_param(cm->m, cm->par, cm->ip, p);
    if (cm->ip2 >= 0)
        dyn_model_set_param(cm->m, cm->par, cm->ip2, p2);
    cm->p_set[0] = NAN;
    if (cm->m->prepare && cm->m->prepare(cm->par, cm->message, sizeof cm->message))
        return -1;
    cm->p_set[0] = p;
    cm->p_set[1] = p2;
    return 0;
}

int cont_model_f(cont_model *cm, const double *x, double *f)
{
    if (cm->map && cm->period > 1) { /* a map's cycles: F^period (cont_map.c) */
        if (cont_map_iterate(cm, x, f))
            return -1;
    } else {
        cm->rhs_calls++;
        if (cm->m->rhs(cm->t, x, f, cm->par)) {
            snprintf(cm->message, sizeof cm->message, "the right-hand side failed");
            return -1;
        }
    }
    for (int i = 0; i < cm->n; i++) {
        if (cm->map)
            f[i] -= x[i];
        if (!isfinite(f[i])) {
            snprintf(cm->message, sizeof cm->message, "f of state '%s' is not finite",
                     cm->m->states[i].name);
            return -1;
        }
    }
    return 0;
}

int cont_model_jx(cont_model *cm, const double *x, double *J, int ld)
{
    const dyn_linearize_opts lo = {cm->jac, NULL};
    dyn_linearize_info info;
    const int n = cm->n;
    double *A = ld == n ? J : cm->eig_a;
    if (cm->map && cm->period > 1) {
        if (cont_map_jacobian(cm, x, A))
            return -1;
        info.rhs_calls = 0;
    } else if (dyn_linearize(cm->m, cm->t, x, cm->par, &lo, A, cm->lin_work, &info)) {
        snprintf(cm->message, sizeof cm->message, "%s", info.message);
        return -1;
    }
    cm->rhs_calls += info.rhs_calls;
    if (A != J)
        for (int i = 0; i < n; i++)
            memcpy(J + (size_t)i * (size_t)ld, A + (size_t)i * (size_t)n, (size_t)n * sizeof *J);
    for (int i = 0; i < n && cm->map; i++)
        J[(size_t)i * (size_t)ld + (size_t)i] -= 1.0;
    return 0;
}

int cont_model_fp(cont_model *cm, const double *x, double p, double p2, int q, double *col,
                  int ld)
{
    const double v = q == 0 ? p : p2;
    const double h0 = cbrt(DBL_EPSILON) * fmax(1.0, fabs(v));
    const double vp = v + h0, vm = v - h0;
    if (cont_model_set(cm, q == 0 ? vp : p, q == 0 ? p2 : vp) || cont_model_f(cm, x, cm->fp) ||
        cont_model_set(cm, q == 0 ? vm : p, q == 0 ? p2 : vm) || cont_model_f(cm, x, cm->fm) ||
        cont_model_set(cm, p, p2))
        return -1;
    for (int i = 0; i < cm->n; i++)
        col[(size_t)i * (size_t)ld] = (cm->fp[i] - cm->fm[i]) / (vp - vm);
    return 0;
}

int cont_model_eig(cont_model *cm, const double *J)
{
    const size_t n = (size_t)cm->n;
    memcpy(cm->eig_a, J, n * n * sizeof *J);
    for (size_t i = 0; i < n && cm->map; i++)
        cm->eig_a[i * n + i] += 1.0;
    if (dyn_eig_hqr(cm->n, cm->eig_a, cm->re, cm->im, cm->message, sizeof cm->message))
        return -1;
    dyn_eig_sort(cm->n, cm->re, cm->im);
    return 0;
}

int cont_model_store(cont_model *cm, dyn_branch *b, const double *x, double p, double p2,
                     int eig, dyn_cont_label label, double l1, double omega)
{
    dyn_branch_point pt;
    pt.label = label;
    pt.par[0] = p;
    pt.par[1] = b->n_par == 2 ? p2 : NAN;
    pt.period = cm->map ? cm->period : NAN; /* a map's: its points' period in iterations */
    pt.l1 = l1;
    pt.omega = omega;
    pt.stable = -1;
    if (eig) {
        const double tol = dyn_stability_tol(cm->n, cm->J, 0.0);
        /* a fold, a branch point and a Hopf point have an eigenvalue on the axis (a map's
         * period doubling and Neimark-Sacker point a multiplier on the unit circle) */
        const int critical = label == DYN_LABEL_LP || label == DYN_LABEL_BP ||
                             label == DYN_LABEL_HB || label == DYN_LABEL_BT ||
                             label == DYN_LABEL_PD || label == DYN_LABEL_TR;
        pt.stable = !critical && (cm->map ? cont_map_stable(cm, tol)
                                          : dyn_classify(cm->n, cm->re, tol) == DYN_STABLE);
    }
    return dyn_branch_append(b, &pt, x, NULL, eig ? cm->re : NULL, eig ? cm->im : NULL) < 0;
}

void cont_diagram_drop_last(dyn_diagram *d)
{
    dyn_branch *b = &d->branches[d->count - 1];
    free(b->pts);
    free(b->x);
    free(b->xmin);
    free(b->eig);
    free(b->orbit);
    d->count--;
}
