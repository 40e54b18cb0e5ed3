/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_basis.c — one collocation interval's basis (AUTO-07p's choice, Doedel's lecture
 * notes on collocation): the ncol Gauss-Legendre points on [0, 1] by Newton's method on
 * Legendre's three-term recurrence, the Lagrange polynomials of the ncol + 1 equally spaced
 * nodes with their derivatives at the Gauss points, their integrals (exact by the Gauss rule:
 * degree ncol < 2 ncol) and their constant ncol-th derivatives (for the mesh's error
 * measure); and the solution's helpers: allocation, evaluation, node times, inner product. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/colloc_internal.h"

/* P_m(x) and P_m'(x) by the recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1} */
static void legendre(int m, double x, double *p, double *dp)
{
    double p0 = 1.0, p1 = x;
    for (int k = 1; k < m; k++) {
        const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
        p0 = p1;
        p1 = p2;
    }
    *p = p1;
    *dp = m * (x * p1 - p0) / (x * x - 1.0);
}

void colloc_lagrange(int ncol, double z, double *L)
{
    for (int l = 0; l <= ncol; l++) {
        double v = 1.0;
        for (int m = 0; m <= ncol; m++)
            if (m != l)
                v *= (z - (double)m / ncol) / ((double)(l - m) / ncol);
        L[l] = v;
    }
}

static double lagrange_deriv(int ncol, int l, double z)
{
    double s = 0.0;
    for (int k = 0; k <= ncol; k++) {
        if (k == l)
            continue;
        double v = 1.0 / ((double)(l - k) / ncol);
        for (int m = 0; m <= ncol; m++)
            if (m != l && m != k)
                v *= (z - (double)m / ncol) / ((double)(l - m) / ncol);
        s += v;
    }
    return s;
}

int colloc_basis_init(colloc_basis *b, int ncol)
{
    if (ncol < 2 || ncol > DYN_COLLOC_MAX_NCOL)
        return 1;
    memset(b, 0, sizeof *b);
    b->ncol = ncol;
    double gw[CB_MAX];
    for (int k = 0; k < ncol; k++) {
        double x = cos(DYN_PI * (ncol - k - 0.25) / (ncol + 0.5)); /* ascending */
        double p, dp;
        for (int it = 0; it < 100; it++) {
            legendre(ncol, x, &p, &dp);
            const double dx = p / dp;
            x -= dx;
            if (fabs(dx) < 1e-16)
                break;
        }
        legendre(ncol, x, &p, &dp);
        b->z[k] = 0.5 * (x + 1.0);
        gw[k] = 1.0 / ((1.0 - x * x) * dp * dp); /* 2/((1-x^2)P'^2), halved for [0, 1] */
    }
    for (int k = 0; k <= ncol; k++)
        for (int l = 0; l <= ncol; l++)
            b->Dn[k][l] = lagrange_deriv(ncol, l, (double)k / ncol);
    for (int k = 0; k < ncol; k++) {
        colloc_lagrange(ncol, b->z[k], b->L[k]);
        for (int l = 0; l <= ncol; l++)
            b->D[k][l] = lagrange_deriv(ncol, l, b->z[k]);
    }
    double fact = 1.0;
    for (int k = 2; k <= ncol; k++)
        fact *= k;
    for (int l = 0; l <= ncol; l++) {
        double s = 0.0;
        for (int k = 0; k < ncol; k++)
            s += gw[k] * b->L[k][l];
        b->w[l] = s;
        double den = 1.0;
        for (int m = 0; m <= ncol; m++)
            if (m != l)
                den *= (double)(l - m) / ncol;
        b->dn[l] = fact / den;
    }
    return 0;
}

int dyn_colloc_sol_alloc(dyn_colloc_sol *s, int n, int ntst, int ncol, int npar)
{
    memset(s, 0, sizeof *s);
    if (n < 1 || ntst < 1 || ncol < 2 || ncol > DYN_COLLOC_MAX_NCOL || npar < 0)
        return DYN_COLLOC_ERR_ARG;
    s->n = n;
    s->ntst = ntst;
    s->ncol = ncol;
    s->npar = npar;
    s->mesh = calloc((size_t)ntst + 1, sizeof(double));
    s->u = calloc(((size_t)ntst * ncol + 1) * n, sizeof(double));
    s->par = calloc((size_t)npar + 1, sizeof(double));
    if (!s->mesh || !s->u || !s->par) {
        dyn_colloc_sol_free(s);
        return DYN_COLLOC_ERR_NOMEM;
    }
    dyn_colloc_uniform_mesh(s);
    return 0;
}

void dyn_colloc_sol_free(dyn_colloc_sol *s)
{
    free(s->mesh);
    free(s->u);
    free(s->par);
    memset(s, 0, sizeof *s);
}

int dyn_colloc_sol_copy(dyn_colloc_sol *dst, const dyn_colloc_sol *src)
{
    int st = dyn_colloc_sol_alloc(dst, src->n, src->ntst, src->ncol, src->npar);
    if (st)
        return st;
    memcpy(dst->mesh, src->mesh, ((size_t)src->ntst + 1) * sizeof(double));
    memcpy(dst->u, src->u, (size_t)dyn_colloc_nodes(src) * src->n * sizeof(double));
    if (src->npar)
        memcpy(dst->par, src->par, (size_t)src->npar * sizeof(double));
    return 0;
}

void dyn_colloc_uniform_mesh(dyn_colloc_sol *s)
{
    for (int j = 0; j <= s->ntst; j++)
        s->mesh[j] = (double)j / s->ntst;
}

double dyn_colloc_node_time(const dyn_colloc_sol *s, long g)
{
    const int j = (int)(g / s->ncol);
    if (j >= s->ntst)
        return s->mesh[s->ntst];
    const int l = (int)(g % s->ncol);
    return s->mesh[j] + (s->mesh[j + 1] - s->mesh[j]) * l / s->ncol;
}

int colloc_locate(const dyn_colloc_sol *s, double t, double *z)
{
    int lo = 0, hi = s->ntst; /* mesh[lo] <= t < mesh[hi] */
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (t < s->mesh[mid])
            hi = mid;
        else
            lo = mid;
    }
    const double h = s->mesh[lo + 1] - s->mesh[lo];
    *z = h > 0 ? (t - s->mesh[lo]) / h : 0.0;
    return lo;
}

void dyn_colloc_eval(const dyn_colloc_sol *s, double t, double *u)
{
    double z, L[CB_MAX];
    const int j = colloc_locate(s, t, &z);
    colloc_lagrange(s->ncol, z, L);
    const int n = s->n;
    for (int i = 0; i < n; i++)
        u[i] = 0.0;
    for (int l = 0; l <= s->ncol; l++) {
        const double *v = s->u + ((size_t)j * s->ncol + l) * n;
        for (int i = 0; i < n; i++)
            u[i] += L[l] * v[i];
    }
}

double dyn_colloc_dot(const dyn_colloc_sol *a, const dyn_colloc_sol *b)
{
    colloc_basis bs;
    if (colloc_basis_init(&bs, a->ncol))
        return NAN;
    const int n = a->n;
    double s = 0.0;
    for (int j = 0; j < a->ntst; j++) {
        const double h = a->mesh[j + 1] - a->mesh[j];
        for (int l = 0; l <= a->ncol; l++) {
            const size_t g = ((size_t)j * a->ncol + l) * n;
            double d = 0.0;
            for (int i = 0; i < n; i++)
                d += a->u[g + i] * b->u[g + i];
            s += h * bs.w[l] * d;
        }
    }
    for (int k = 0; k < a->npar; k++)
        s += a->par[k] * b->par[k];
    return s;
}
