/* SPDX-License-Identifier: BSD-3-Clause */
/* equilibria.c — every equilibrium of a model in a box by Newton's method from many
 * starts (multistart; e.g. Seydel, Practical Bifurcation and Stability Analysis, 3rd ed.,
 * sec. 4.1): dyn_equilibrium from the box's centre, an optional guess and the points of
 * Halton's sequence scaled to the box; the solutions inside the box merged when every state
 * agrees within DYN_EQUILIBRIA_MERGE of its scale; each linearized (dyn_linearize, or the
 * caller's reduction to admissible directions), its eigenvalues computed by the caller's
 * solver, sorted and classified (eq_type.c). A discrete map y_{k+1} = F(t, y_k) is solved
 * as F(y) - y = 0 through a model that wraps it, and judged by the multipliers of dF/dy. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/equilibria.h"

/* ---- a map's fixed points as the zeros of G(y) = F(y) - y ---- */

typedef struct map_par {
    const dyn_model *m;
    void *par;
} map_par;

static int map_residual(double t, const double *y, double *g, void *ctx)
{
    const map_par *mp = ctx;
    const int rc = mp->m->rhs(t, y, g, mp->par);
    for (int i = 0; i < mp->m->n_states && !rc; i++)
        g[i] -= y[i];
    return rc;
}

static int map_residual_jac(double t, const double *y, double *J, void *ctx)
{
    const map_par *mp = ctx;
    const int n = mp->m->n_states;
    const int rc = mp->m->jacobian(t, y, J, mp->par);
    for (int i = 0; i < n && !rc; i++)
        J[(size_t)i * (size_t)n + (size_t)i] -= 1.0;
    return rc;
}

/* ---- the result's storage ---- */

static int grow(dyn_equilibria *e, int cap)
{
    const size_t n = (size_t)e->n, c = (size_t)cap;
    double *y = realloc(e->y, c * n * sizeof *y);
    if (y)
        e->y = y;
    double *r = realloc(e->residual, c * sizeof *r);
    if (r)
        e->residual = r;
    int *k = realloc(e->k, c * sizeof *k);
    if (k)
        e->k = k;
    double *re = realloc(e->re, c * n * sizeof *re);
    if (re)
        e->re = re;
    double *im = realloc(e->im, c * n * sizeof *im);
    if (im)
        e->im = im;
    dyn_eq_type *ty = realloc(e->type, c * sizeof *ty);
    if (ty)
        e->type = ty;
    int *d = realloc(e->dims, 3 * c * sizeof *d);
    if (d)
        e->dims = d;
    double *tol = realloc(e->tol, c * sizeof *tol);
    if (tol)
        e->tol = tol;
    return y && r && k && re && im && ty && d && tol ? 0 : -1;
}

void dyn_equilibria_free(dyn_equilibria *e)
{
    if (!e)
        return;
    free(e->y);
    free(e->residual);
    free(e->k);
    free(e->re);
    free(e->im);
    free(e->type);
    free(e->dims);
    free(e->tol);
    e->y = e->residual = e->re = e->im = e->tol = NULL;
    e->k = e->dims = NULL;
    e->type = NULL;
    e->count = 0;
}

/* ---- the search ---- */

static double scale_of(const dyn_equilibria_opts *o, int i, double a, double b)
{
    return fmax(fmax(o->hi[i] - o->lo[i], 1e-3), fmax(fabs(a), fabs(b)));
}

/* The index of the equilibrium y agrees with, or -1. */
static int find_same(const dyn_equilibria *e, const dyn_equilibria_opts *o, double merge,
                     const double *y)
{
    const int n = e->n;
    for (int c = 0; c < e->count; c++) {
        const double *z = e->y + (size_t)c * (size_t)n;
        int same = 1;
        for (int i = 0; i < n && same; i++)
            same = fabs(y[i] - z[i]) <= merge * scale_of(o, i, y[i], z[i]);
        if (same)
            return c;
    }
    return -1;
}

static int inside(const dyn_equilibria_opts *o, int n, const double *y)
{
    for (int i = 0; i < n; i++) {
        const double slack = 1e-9 * fmax(o->hi[i] - o->lo[i], fmax(fabs(y[i]), 1e-3));
        if (!(y[i] >= o->lo[i] - slack && y[i] <= o->hi[i] + slack))
            return 0;
    }
    return 1;
}

/* Eigenvalues and type of equilibrium c (its y set): A by dyn_linearize of the model
 * itself (a map: dF/dy), reduced when asked. */
static int classify_one(const dyn_model *m, double t, void *par, const dyn_equilibria_opts *o,
                        dyn_equilibria *e, int c, double *A, double *Amin, double *lw)
{
    const int n = e->n;
    const size_t N = (size_t)n;
    const double *y = e->y + (size_t)c * N;
    double *re = e->re + (size_t)c * N, *im = e->im + (size_t)c * N;
    e->k[c] = 0;
    e->type[c] = DYN_EQ_UNCLASSIFIED;
    e->tol[c] = 0.0;
    memset(e->dims + 3 * (size_t)c, 0, 3 * sizeof *e->dims);
    if (!o->eig)
        return 0;
    const dyn_linearize_opts lo = {o->scheme, NULL};
    dyn_linearize_info li;
    int rc = dyn_linearize(m, t, y, par, &lo, A, lw, &li);
    e->rhs_calls += li.rhs_calls;
    if (rc) {
        snprintf(e->message, sizeof e->message, "%s", li.message);
        return rc;
    }
    int k = n;
    const double *use = A;
    if (o->reduce) {
        char err[200] = "";
        if (o->reduce(o->reduce_ctx, t, y, par, A, Amin, &k, err, sizeof err)) {
            snprintf(e->message, sizeof e->message, "the admissible directions: %s",
                     err[0] ? err : "their basis is singular");
            return DYN_ERR_ARG;
        }
        use = Amin;
    }
    double tol = dyn_stability_tol(k, use, o->stability_rtol);
    if (o->map)
        tol = fmax(tol, o->stability_rtol > 0.0 ? o->stability_rtol : DYN_STABILITY_RTOL);
    memmove(A, use, (size_t)k * (size_t)k * sizeof *A);
    char err[200] = "";
    if (k > 0 && o->eig->eigenvalues(k, A, re, im, err, sizeof err)) {
        snprintf(e->message, sizeof e->message, "eigenvalues: %s", err);
        return DYN_ERR_RHS;
    }
    dyn_eig_sort(k, re, im);
    e->k[c] = k;
    e->tol[c] = tol;
    e->type[c] = dyn_eq_classify(k, re, im, o->map, tol, e->dims + 3 * (size_t)c);
    return 0;
}

/* Sort the equilibria by their states, first state first, states that agree within the
 * merging tolerance counted equal (rounding does not decide the order); insertion sort: a
 * handful, in a stable order. */
static int before(const dyn_equilibria_opts *o, double merge, int n, const double *p,
                  const double *q)
{
    for (int i = 0; i < n; i++)
        if (fabs(p[i] - q[i]) > merge * scale_of(o, i, p[i], q[i]))
            return p[i] < q[i];
    return 0;
}

static void sort_by_state(dyn_equilibria *e, const dyn_equilibria_opts *o, double merge)
{
    const size_t N = (size_t)e->n;
    for (int a = 1; a < e->count; a++)
        for (int b = a; b > 0; b--) {
            double *p = e->y + (size_t)(b - 1) * N, *q = e->y + (size_t)b * N;
            if (!before(o, merge, e->n, q, p))
                break;
            for (size_t j = 0; j < N; j++) {
                const double s = p[j];
                p[j] = q[j];
                q[j] = s;
            }
            const double r = e->residual[b - 1];
            e->residual[b - 1] = e->residual[b];
            e->residual[b] = r;
        }
}

static int check_args(const dyn_model *m, const dyn_equilibria_opts *o, dyn_equilibria *e)
{
    if (!o || !o->lo || !o->hi) {
        snprintf(e->message, sizeof e->message, "the box (lo, hi) is required");
        return DYN_ERR_ARG;
    }
    for (int i = 0; i < m->n_states; i++)
        if (!isfinite(o->lo[i]) || !isfinite(o->hi[i]) || o->lo[i] > o->hi[i]) {
            snprintf(e->message, sizeof e->message,
                     "the box of %s is [%.17g, %.17g]: give finite lo <= hi", m->states[i].name,
                     o->lo[i], o->hi[i]);
            return DYN_ERR_ARG;
        }
    if (m->delay || m->volterra) {
        snprintf(e->message, sizeof e->message, "%s has %s: its equilibria are not supported",
                 m->name,
                 m->delay ? "delays (delay(x, tau))" : "Volterra integrals (int{...}, volt)");
        return DYN_ERR_ARG;
    }
    return 0;
}

int dyn_equilibria_find(const dyn_model *m, double t, void *par, const dyn_equilibria_opts *o,
                        dyn_equilibria *e)
{
    memset(e, 0, sizeof *e);
    e->n = m->n_states;
    int rc = check_args(m, o, e);
    if (rc)
        return rc;
    const int n = m->n_states;
    const size_t N = (size_t)n;
    /* the model solved for zeros: m itself, or a map's F(y) - y */
    dyn_model wrapped = *m;
    map_par mp = {m, par};
    const dyn_model *g = m;
    void *gpar = par;
    if (o->map) {
        wrapped.rhs = map_residual;
        wrapped.jacobian = m->jacobian ? map_residual_jac : NULL;
        wrapped.jac_banded = 0;
        wrapped.jacobian_band = NULL;
        wrapped.jacobian_sparse = NULL;
        g = &wrapped;
        gpar = &mp;
    }
    const int starts = o->starts > 0 ? o->starts : DYN_EQUILIBRIA_STARTS;
    const double merge = o->merge > 0.0 ? o->merge : DYN_EQUILIBRIA_MERGE;
    double *work = malloc(
        (dyn_equilibrium_work_size(n) + N + 2 * N * N + dyn_linearize_work_size(n)) * sizeof *work);
    int cap = 8;
    if (!work || grow(e, cap)) {
        free(work);
        snprintf(e->message, sizeof e->message, "out of memory");
        return DYN_ERR_CAPACITY;
    }
    double *y = work + dyn_equilibrium_work_size(n), *A = y + N, *Amin = A + N * N,
           *lw = Amin + N * N;
    const dyn_equilibrium_opts eo = {{o->scheme, NULL}, o->tol, o->max_iter > 0 ? o->max_iter : 60};
    const int total = starts + (o->guess != NULL);
    for (int s = 0; s < total && !rc; s++) {
        /* the guess, then the centre, then Halton's points 1, 2, ... */
        const int k = o->guess ? s - 1 : s;
        for (int i = 0; i < n; i++)
            y[i] = k < 0    ? o->guess[i]
                   : k == 0 ? 0.5 * (o->lo[i] + o->hi[i])
                            : o->lo[i] + (o->hi[i] - o->lo[i]) * dyn_halton(k, i);
        e->starts++;
        dyn_equilibrium_info info;
        const int st = dyn_equilibrium(g, t, y, gpar, &eo, work, &info);
        e->rhs_calls += info.rhs_calls;
        if (st == DYN_ERR_ARG) {
            snprintf(e->message, sizeof e->message, "%s", info.message);
            rc = st;
            break;
        }
        if (st)
            continue; /* no equilibrium from this start */
        e->converged++;
        if (!inside(o, n, y)) {
            e->outside++;
            continue;
        }
        const int same = find_same(e, o, merge, y);
        if (same >= 0) {
            if (info.residual < e->residual[same]) {
                memcpy(e->y + (size_t)same * N, y, N * sizeof *y);
                e->residual[same] = info.residual;
            }
            continue;
        }
        if (e->count == cap && grow(e, cap *= 2)) {
            snprintf(e->message, sizeof e->message, "out of memory");
            rc = DYN_ERR_CAPACITY;
            break;
        }
        memcpy(e->y + (size_t)e->count * N, y, N * sizeof *y);
        e->residual[e->count++] = info.residual;
    }
    if (!rc) {
        sort_by_state(e, o, merge);
        for (int c = 0; c < e->count && !rc; c++)
            rc = classify_one(m, t, par, o, e, c, A, Amin, lw);
    }
    free(work);
    return rc;
}
