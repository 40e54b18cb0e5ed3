/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_mesh.c — the collocation mesh: a solution moved onto a new mesh by evaluating its
 * piecewise polynomial at the new nodes, and AUTO-07p's adaptation (Doedel's ADAPT/NEWMSH;
 * Russell & Christiansen, SIAM J. Numer. Anal. 15 (1978) 59-80): the ncol-th derivative of
 * the solution, a constant on each interval, is differenced across the mesh points to
 * estimate the (ncol+1)-th, and the new mesh equidistributes the integral of its norm raised
 * to 1/(ncol+1), the leading term of the local error. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/colloc_internal.h"

int dyn_colloc_remesh(dyn_colloc_sol *x, int ntst, const double *newmesh)
{
    dyn_colloc_sol y;
    int st = dyn_colloc_sol_alloc(&y, x->n, ntst, x->ncol, x->npar);
    if (st)
        return st;
    if (newmesh)
        memcpy(y.mesh, newmesh, ((size_t)ntst + 1) * sizeof(double));
    y.mesh[0] = 0.0;
    y.mesh[ntst] = 1.0;
    const long nodes = dyn_colloc_nodes(&y);
    for (long g = 0; g < nodes; g++) {
        const double t = dyn_colloc_node_time(&y, g);
        dyn_colloc_eval(x, t, y.u + (size_t)g * x->n);
    }
    /* the end nodes exactly (t = 1 falls in the last interval's end) */
    memcpy(y.u, x->u, (size_t)x->n * sizeof(double));
    memcpy(y.u + (size_t)(nodes - 1) * x->n, x->u + (size_t)(dyn_colloc_nodes(x) - 1) * x->n,
           (size_t)x->n * sizeof(double));
    memcpy(y.par, x->par, (size_t)x->npar * sizeof(double));
    dyn_colloc_sol_free(x);
    *x = y;
    return 0;
}

int dyn_colloc_adapt(dyn_colloc_sol *x, int ntst, int periodic, dyn_colloc_sol **extra,
                     int nextra)
{
    colloc_basis b;
    if (colloc_basis_init(&b, x->ncol) || ntst < 1)
        return DYN_COLLOC_ERR_ARG;
    const int n = x->n, N = x->ntst, ncol = x->ncol;
    double *d = malloc((size_t)N * n * sizeof(double));
    double *q = calloc((size_t)N + 1, sizeof(double));
    double *cum = malloc(((size_t)N + 1) * sizeof(double));
    double *mesh = malloc(((size_t)ntst + 1) * sizeof(double));
    int st = 0;
    if (!d || !q || !cum || !mesh) {
        st = DYN_COLLOC_ERR_NOMEM;
        goto done;
    }
    for (int j = 0; j < N; j++) {
        const double h = x->mesh[j + 1] - x->mesh[j];
        const double hp = pow(h, ncol);
        for (int i = 0; i < n; i++) {
            double v = 0.0;
            for (int l = 0; l <= ncol; l++)
                v += b.dn[l] * x->u[((size_t)j * ncol + l) * n + i];
            d[(size_t)j * n + i] = v / hp;
        }
    }
    /* q_j: the (ncol+1)-th derivative at mesh point j */
    for (int j = 0; j <= N; j++) {
        int a = j - 1, c = j;
        double span;
        if (j == 0 || j == N) {
            if (N == 1 || !periodic) {
                q[j] = -1.0; /* filled from the neighbour below */
                continue;
            }
            a = N - 1;
            c = 0;
            span = 0.5 * ((x->mesh[N] - x->mesh[N - 1]) + (x->mesh[1] - x->mesh[0]));
        } else {
            span = 0.5 * (x->mesh[j + 1] - x->mesh[j - 1]);
        }
        double s = 0.0;
        for (int i = 0; i < n; i++) {
            const double e = d[(size_t)c * n + i] - d[(size_t)a * n + i];
            s += e * e;
        }
        q[j] = sqrt(s) / span;
    }
    if (q[0] < 0)
        q[0] = N > 1 ? q[1] : 0.0;
    if (q[N] < 0)
        q[N] = N > 1 ? q[N - 1] : 0.0;
    cum[0] = 0.0;
    for (int j = 0; j < N; j++) {
        const double psi = pow(0.5 * (q[j] + q[j + 1]), 1.0 / (ncol + 1));
        cum[j + 1] = cum[j] + (x->mesh[j + 1] - x->mesh[j]) * psi;
    }
    const double mean = cum[N];
    /* a floor of 5% of the mean share: intervals stay bounded where the measure vanishes */
    const double floor_share = mean > 0 ? 0.05 * mean : 1.0;
    for (int j = 0; j <= N; j++)
        cum[j] += floor_share * x->mesh[j];
    const double total = cum[N];
    if (!(total > 0) || !isfinite(total)) {
        st = DYN_COLLOC_ERR_FN;
        goto done;
    }
    mesh[0] = 0.0;
    int j = 0;
    for (int k = 1; k < ntst; k++) {
        const double target = total * k / ntst;
        while (j < N - 1 && cum[j + 1] < target)
            j++;
        const double w = cum[j + 1] - cum[j];
        const double f = w > 0 ? (target - cum[j]) / w : 0.0;
        mesh[k] = x->mesh[j] + f * (x->mesh[j + 1] - x->mesh[j]);
    }
    mesh[ntst] = 1.0;
    for (int e = 0; e < nextra && !st; e++)
        st = dyn_colloc_remesh(extra[e], ntst, mesh);
    if (!st)
        st = dyn_colloc_remesh(x, ntst, mesh);
done:
    free(d);
    free(q);
    free(cum);
    free(mesh);
    return st;
}
