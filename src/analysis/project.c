/* SPDX-License-Identifier: BSD-3-Clause */
/* project.c — an initial state moved onto a mechanism's constraints by minimal-norm
 * corrections (dynkit/analysis.h, dyn_project_constraints): Gauss-Newton for the
 * underdetermined system f(q) = 0 (the step q <- q - G^+ f with the pseudo-inverse
 * G^+ = G' (G G')^-1 of the full-rank Jacobian G = df/dq (dyn_holonomic_gradient, central
 * differences in q of the values f(t, q) — not dh/du, which is df/dq W with declared speeds
 * q' = W(q) u), halved until |f|^2 decreases, and Levenberg-Marquardt's damped
 * G' (G G' + mu I)^-1 where G G' is singular;
 * Nocedal & Wright, Numerical Optimization, 2nd ed., sec. 10.3 and 11.2), then the speeds'
 * linear system D u + h_t = 0 (D = dh/du) by the same minimal-norm solution. A projection
 * that ends above dyn_constraint_tolerance is an error. The normal equations are solved by
 * src/ode/cholesky.h. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/analysis.h"
#include "dynkit/ode.h"
#include "ode/cholesky.h"

typedef struct pctx {
    const dyn_model *cm;
    const void *par;
    double t;
    int n, m;
    double *h, *f, *hp, *fp, *D, *F, *A, *w, *yy;
    int *hol;
} pctx;

/* F = df/dq (m x n, zero on the rows that are not holonomic) at y */
static int coordinate_rows(pctx *p, const double *y)
{
    return dyn_holonomic_gradient(p->cm, p->par, p->t, y, p->F, NULL) == p->m ? 0 : -1;
}

/* h, f at y and D = dh/du (m x n) by central differences of unit steps in u */
static int rows(pctx *p, const double *y)
{
    const int n = p->n, m = p->m;
    if (dyn_constraint_values(p->cm, p->par, p->t, y, p->h, p->f, p->hol) != m)
        return -1;
    memcpy(p->yy, y, (size_t)(2 * n) * sizeof *p->yy);
    for (int k = 0; k < n; k++) {
        const double s = fmax(1.0, fabs(y[n + k]));
        p->yy[n + k] = y[n + k] + s;
        if (dyn_constraint_values(p->cm, p->par, p->t, p->yy, p->hp, p->fp, p->hol) != m)
            return -1;
        for (int r = 0; r < m; r++)
            p->D[r * n + k] = p->hp[r];
        p->yy[n + k] = y[n + k] - s;
        if (dyn_constraint_values(p->cm, p->par, p->t, p->yy, p->hp, p->fp, p->hol) != m)
            return -1;
        for (int r = 0; r < m; r++)
            p->D[r * n + k] = (p->D[r * n + k] - p->hp[r]) / (2.0 * s);
        p->yy[n + k] = y[n + k];
    }
    return 0;
}

/* x (n) -= R' (R R' + mu I)^-1 v for the rows R of J (D or F) picked by sel (all when
 * NULL); with mu = 0 the index of the first dependent row, or -1 */
static int min_norm_step(pctx *p, const double *J, const int *sel, const double *v, double *x,
                         double mu)
{
    const int n = p->n;
    int k = 0, idx[512];
    for (int r = 0; r < p->m && k < 512; r++)
        if (!sel || sel[r])
            idx[k++] = r;
    if (k == 0)
        return -1;
    for (int a = 0; a < k; a++) {
        for (int b = 0; b <= a; b++) {
            double s = 0.0;
            for (int j = 0; j < n; j++)
                s += J[idx[a] * n + j] * J[idx[b] * n + j];
            p->A[a * k + b] = p->A[b * k + a] = s;
        }
        p->w[a] = v[idx[a]];
    }
    double big = 0.0;
    for (int a = 0; a < k; a++)
        big = fmax(big, p->A[a * k + a]);
    for (int a = 0; a < k; a++)
        p->A[a * k + a] += mu * big;
    const int bad = dyn_cholesky_factor_tol(k, p->A, 1e-12, 1);
    if (bad)
        return idx[bad - 1];
    dyn_cholesky_solve(k, p->A, p->w);
    for (int a = 0; a < k; a++)
        for (int j = 0; j < n; j++)
            x[j] -= J[idx[a] * n + j] * p->w[a];
    return -1;
}

static double largest(const double *v, const int *sel, int want, int m)
{
    double big = 0.0;
    for (int r = 0; r < m; r++)
        if (!sel || sel[r] == want)
            big = fmax(big, fabs(v[r]));
    return big;
}

static double squares(const double *v, const int *sel, int m)
{
    double s = 0.0;
    for (int r = 0; r < m; r++)
        if (sel[r])
            s += v[r] * v[r];
    return s;
}

double dyn_constraint_tolerance(const double *v, int n)
{
    double scale = 1.0;
    for (int j = 0; j < n; j++)
        scale = fmax(scale, fabs(v[j]));
    return 1e-9 * fmin(scale, 1e6);
}

int dyn_project_constraints(const dyn_model *cm, const void *par, double t, double *y,
                            double residual[2], int *bad, char *err, size_t errlen)
{
    const int N = cm->n_states, n = N / 2;
    int mo = cm->n_outputs + 1;
    *bad = -1;
    if (N % 2 || mo > 512) {
        snprintf(err, errlen, "not a mechanism's constraints (%d states, %d outputs)", N,
                 cm->n_outputs);
        return DYN_ERR_ARG;
    }
    pctx p = {cm, par, t, n, 0, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    double *buf = malloc(((size_t)mo * (4 + 2 * (size_t)n + (size_t)mo + 1) + 2 * (size_t)N +
                          (size_t)n + 1) * sizeof *buf);
    p.hol = malloc((size_t)mo * sizeof *p.hol);
    if (!buf || !p.hol) {
        free(buf);
        free(p.hol);
        snprintf(err, errlen, "out of memory");
        return DYN_ERR_ARG;
    }
    p.h = buf;
    p.f = p.h + mo;
    p.hp = p.f + mo;
    p.fp = p.hp + mo;
    p.D = p.fp + mo;
    p.F = p.D + (size_t)mo * n;
    p.A = p.F + (size_t)mo * n;
    p.w = p.A + (size_t)mo * mo;
    p.yy = p.w + mo;
    double *step = p.yy + N, *trial = step + n; /* a step of the coordinates, a state */
    int rc = 0;
    p.m = dyn_constraint_values(cm, par, t, y, p.h, p.f, p.hol);
    if (p.m < 0) {
        snprintf(err, errlen, "the constraints' values failed at the initial state");
        rc = DYN_ERR_ARG;
    }
    /* the coordinates: Gauss-Newton until |f| stops decreasing, each step halved until
     * the sum of the squares of f decreases (its direction is one of descent); at a state
     * where the rows are dependent, Levenberg-Marquardt's damped step (R R' + mu I) */
    for (int it = 0; it < 100 && !rc && p.m > 0; it++) {
        if ((rc = rows(&p, y)) != 0 || (rc = coordinate_rows(&p, y)) != 0) {
            snprintf(err, errlen, "the constraints' values failed while projecting");
            rc = DYN_ERR_ARG;
            break;
        }
        const double now = largest(p.f, p.hol, 1, p.m), sq = squares(p.f, p.hol, p.m);
        double scale = 1.0;
        for (int j = 0; j < n; j++)
            scale = fmax(scale, fabs(y[j]));
        if (!isfinite(sq) || now == 0.0 || (now <= 4.0 * DBL_EPSILON * scale && it > 0))
            break;
        int any = 0;
        for (int r = 0; r < p.m; r++)
            any |= p.hol[r];
        if (!any)
            break;
        memset(step, 0, (size_t)n * sizeof *step);
        if (min_norm_step(&p, p.F, p.hol, p.f, step, 0.0) >= 0) {
            memset(step, 0, (size_t)n * sizeof *step);
            min_norm_step(&p, p.F, p.hol, p.f, step, 1e-8);
        }
        int taken = 0;
        memcpy(trial, y, (size_t)N * sizeof *trial);
        for (double alpha = 1.0; alpha > 1e-6 && !taken; alpha *= 0.5) {
            for (int j = 0; j < n; j++)
                trial[j] = y[j] + alpha * step[j];
            if (dyn_constraint_values(cm, par, t, trial, p.hp, p.fp, p.hol) != p.m)
                break;
            taken = squares(p.fp, p.hol, p.m) < sq;
        }
        if (!taken)
            break; /* no step decreases f: y is the best */
        memcpy(y, trial, (size_t)n * sizeof *y);
    }
    /* the coordinates reached: within the tolerance, or the projection failed (y is left at
     * the best coordinates found, for the caller to name what is left) */
    if (!rc && p.m > 0) {
        if (dyn_constraint_values(cm, par, t, y, p.h, p.f, p.hol) != p.m) {
            snprintf(err, errlen, "the constraints' values failed while projecting");
            rc = DYN_ERR_ARG;
        } else {
            const double left = largest(p.f, p.hol, 1, p.m);
            const double tol = dyn_constraint_tolerance(y, n);
            if (!(left <= tol)) {
                snprintf(err, errlen, "the coordinates did not reach the constraints: the "
                         "largest value left is %.17g, the tolerance %.3g", left, tol);
                if (residual)
                    residual[0] = left;
                rc = DYN_ERR_ARG;
            }
        }
    }
    /* the speeds: linear, one step and one for rounding */
    for (int it = 0; it < 2 && !rc && p.m > 0; it++) {
        if (rows(&p, y) != 0) {
            snprintf(err, errlen, "the constraints' values failed while projecting");
            rc = DYN_ERR_ARG;
            break;
        }
        const int dep = min_norm_step(&p, p.D, NULL, p.h, y + n, 0.0);
        if (dep >= 0) {
            *bad = dep;
            snprintf(err, errlen, "the constraints' rows are dependent");
            rc = DYN_ERR_ARG;
        }
    }
    if (!rc && residual) {
        if (dyn_constraint_values(cm, par, t, y, p.h, p.f, p.hol) != p.m) {
            snprintf(err, errlen, "the constraints' values failed at the projected state");
            rc = DYN_ERR_ARG;
        } else {
            residual[0] = largest(p.f, p.hol, 1, p.m);
            residual[1] = largest(p.h, NULL, 0, p.m);
            if (!(residual[1] <= dyn_constraint_tolerance(y + n, n))) {
                snprintf(err, errlen, "the speeds did not reach the constraints: the largest "
                         "value left is %.17g", residual[1]);
                rc = DYN_ERR_ARG;
            }
        }
    }
    free(buf);
    free(p.hol);
    return rc;
}
