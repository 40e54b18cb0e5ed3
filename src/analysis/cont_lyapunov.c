/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_lyapunov.c — the first Lyapunov coefficient of a Hopf point (dynkit/continuation.h,
 * dyn_first_lyapunov): Kuznetsov, "Elements of Applied Bifurcation Theory", 3rd ed.,
 * sec. 3.5, formula (3.20), with q and p the eigenvectors of A and A^T for i omega and
 * -i omega, <q, q> = 1 and <p, q> = 1 (<p, q> = conj(p)^T q). The multilinear forms are
 * derivatives of the Jacobian along the vectors: B(u, v) = D_x(J u) v by central differences
 * of J along v, and C(q, q, conj q) = sum over w in {Re q, Im q} of the second differences
 * of J along w applied to q (C is symmetric). With the model's exact Jacobian the differences
 * are extrapolated (Richardson: steps h, h/2, h/4, error O(h^6) for the second, h, h/2 and
 * O(h^4) for the first), so that their rounding and truncation errors both stay near 1e-11
 * and l1 is accurate enough to locate a generalized Hopf point to 1e-10. Complex vectors are kept as real and imaginary
 * parts; the complex linear systems are solved as real systems of twice the size by LU
 * (src/ode/linalg.h); eigenvectors by inverse iteration on those systems. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/continuation.h"
#include "ode/linalg.h"

typedef struct lyap_ctx {
    const dyn_model *m;
    double t;
    const double *x;
    void *par;
    dyn_linearize_opts lo;
    int n;
    double h1, h2;  /* steps of the first and second differences */
    int levels;     /* Richardson's levels: 1 (none) or 3 */
    double *xs, *Jp, *Jm, *J0, *E1, *E2, *work;
} lyap_ctx;

static int jac_at(lyap_ctx *c, const double *v, double h, double *J)
{
    for (int i = 0; i < c->n; i++)
        c->xs[i] = c->x[i] + h * v[i];
    dyn_linearize_info info;
    return dyn_linearize(c->m, c->t, c->xs, c->par, &c->lo, J, c->work, &info);
}

static double norm2(const double *v, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += v[i] * v[i];
    return sqrt(s);
}

/* one central difference of J along v with step h (h in v's units): first or second */
static int jac_diff(lyap_ctx *c, const double *v, double h, int order, double *D)
{
    const size_t nn = (size_t)c->n * (size_t)c->n;
    if (jac_at(c, v, h, c->Jp) || jac_at(c, v, -h, c->Jm))
        return -1;
    for (size_t k = 0; k < nn; k++)
        D[k] = order == 1 ? (c->Jp[k] - c->Jm[k]) / (2.0 * h)
                          : (c->Jp[k] - 2.0 * c->J0[k] + c->Jm[k]) / (h * h);
    return 0;
}

/* D = the first (order 1) or second (order 2) derivative of J along v (n x n). With
 * c->levels > 1, Richardson's extrapolation over the steps h, h/2 (first: error O(h^4)) or
 * h, h/2, h/4 (second: O(h^6)); each level removes the next even power of h. */
static int jac_dir(lyap_ctx *c, const double *v, int order, double *D)
{
    const int n = c->n;
    const double nv = norm2(v, n);
    const size_t nn = (size_t)n * (size_t)n;
    if (!(nv > 0.0)) {
        memset(D, 0, nn * sizeof *D);
        return 0;
    }
    const double h = (order == 1 ? c->h1 : c->h2) / nv;
    const int levels = c->levels <= 1 ? 1 : order == 1 ? 2 : 3;
    if (jac_diff(c, v, h, order, D))
        return -1;
    if (levels == 1)
        return 0;
    if (jac_diff(c, v, h / 2, order, c->E1))
        return -1;
    for (size_t k = 0; k < nn; k++) /* A11 = E1 + (E1 - E0) / 3, kept in D */
        D[k] = c->E1[k] + (c->E1[k] - D[k]) / 3.0;
    if (levels == 2)
        return 0;
    if (jac_diff(c, v, h / 4, order, c->E2))
        return -1;
    for (size_t k = 0; k < nn; k++) {
        const double a21 = c->E2[k] + (c->E2[k] - c->E1[k]) / 3.0;
        D[k] = a21 + (a21 - D[k]) / 15.0;
    }
    return 0;
}

/* y (+)= D u */
static void mv(int n, const double *D, const double *u, double *y, double sign, int add)
{
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int j = 0; j < n; j++)
            s += D[(size_t)i * (size_t)n + (size_t)j] * u[j];
        y[i] = (add ? y[i] : 0.0) + sign * s;
    }
}

/* A unit null vector of K (N x N, overwritten; copy: N x N doubles of room) by inverse
 * iteration. An exactly singular K (an exact Hopf point) is moved off singularity by
 * 1e-14 ||K|| on the diagonal, which moves the null vector by as little. */
static int null_vector(int N, double *K, double *copy, int *piv, double *v)
{
    const size_t NN = (size_t)N * (size_t)N;
    memcpy(copy, K, NN * sizeof *K);
    if (dyn_lu_factor(N, K, piv)) {
        double big = 0.0;
        for (size_t k = 0; k < NN; k++)
            big = fmax(big, fabs(copy[k]));
        memcpy(K, copy, NN * sizeof *K);
        for (int i = 0; i < N; i++)
            K[(size_t)i * (size_t)N + (size_t)i] += 1e-14 * (big > 0.0 ? big : 1.0) * (1.0 + 0.1 * i);
        if (dyn_lu_factor(N, K, piv))
            return -1;
    }
    for (int i = 0; i < N; i++)
        v[i] = 1.0 + 0.37 * i - 0.01 * i * i;
    for (int it = 0; it < 3; it++) {
        dyn_lu_solve(N, K, piv, v);
        const double nv = norm2(v, N);
        if (!(nv > 0.0) || !isfinite(nv))
            return -1;
        for (int i = 0; i < N; i++)
            v[i] /= nv;
    }
    return 0;
}

/* K = [[B, s w I], [-s w I, B]] with B = A or A^T (2n x 2n) */
static void eig_system(int n, const double *A, int transpose, double sw, double *K)
{
    const int N = 2 * n;
    memset(K, 0, (size_t)N * (size_t)N * sizeof *K);
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            const double a = transpose ? A[(size_t)j * (size_t)n + (size_t)i]
                                       : A[(size_t)i * (size_t)n + (size_t)j];
            K[(size_t)i * (size_t)N + (size_t)j] = a;
            K[(size_t)(i + n) * (size_t)N + (size_t)(j + n)] = a;
        }
        K[(size_t)i * (size_t)N + (size_t)(i + n)] = sw;
        K[(size_t)(i + n) * (size_t)N + (size_t)i] = -sw;
    }
}

int dyn_first_lyapunov(const dyn_model *m, double t, const double *x, void *par,
                       dyn_jac_scheme jac, const double *A, double omega, double *l1,
                       char *err, size_t errlen)
{
    const int n = m->n_states, N = 2 * n;
    if (!(omega > 0.0) || !isfinite(omega)) {
        snprintf(err, errlen, "omega must be a finite number > 0");
        return DYN_ERR_ARG;
    }
    const size_t nn = (size_t)n * (size_t)n, NN = (size_t)N * (size_t)N;
    double *buf = malloc((2 * NN + 10 * nn + 24 * (size_t)n + dyn_linearize_work_size(n)) *
                         sizeof *buf);
    int *piv = malloc((size_t)N * sizeof *piv);
    if (!buf || !piv) {
        free(buf);
        free(piv);
        snprintf(err, errlen, "out of memory");
        return DYN_ERR_ARG;
    }
    lyap_ctx c = {m, t, x, par, {jac, NULL}, n, 0.0, 0.0, 1, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    double *K = buf, *Kc = K + NN, *D = Kc + NN, *Dr = D + nn, *Di = Dr + nn, *Ac = Di + nn;
    c.Jp = Ac + nn;
    c.Jm = c.Jp + nn;
    c.J0 = c.Jm + nn;
    c.E1 = c.J0 + nn;
    c.E2 = c.E1 + nn;
    c.xs = c.E2 + nn;
    double *q = c.xs + n, *p = q + N, *r1 = p + N, *a = r1 + n, *bq = a + n, *bqq = bq + N,
           *cc = bqq + N, *bqc = cc + N, *cq = bqc + N, *tmp = cq + N;
    c.work = tmp + N;
    double xscale = 1.0;
    for (int i = 0; i < n; i++)
        xscale = fmax(xscale, fabs(x[i]));
    const int exact = m->jacobian && (jac == DYN_JAC_AUTO || jac == DYN_JAC_ANALYTIC);
    /* exact: steps where rounding (eps |J| / step^k) and the extrapolated truncation error
     * are both near 1e-11; by differences of a difference Jacobian: the plain steps */
    c.levels = exact ? 3 : 1;
    c.h1 = (exact ? 1e-3 : cbrt(DBL_EPSILON)) * xscale;
    c.h2 = (exact ? 1e-2 : 1e-3) * xscale;
    int rc = DYN_ERR_ARG;
    const char *why = "the eigenvectors for +-i omega were not found";
    memcpy(c.J0, A, nn * sizeof *A);
    /* q: A q = i omega q, i.e. A qr + omega qi = 0, A qi - omega qr = 0 */
    eig_system(n, A, 0, omega, K);
    if (null_vector(N, K, Kc, piv, q))
        goto done;
    /* p: A^T p = -i omega p, i.e. A^T pr - omega pi = 0, A^T pi + omega pr = 0 */
    eig_system(n, A, 1, -omega, K);
    if (null_vector(N, K, Kc, piv, p))
        goto done;
    {
        const double *qr = q, *qi = q + n;
        double *pr = p, *pi = p + n;
        /* <p, q> = (pr.qr + pi.qi) + i (pr.qi - pi.qr); p <- p / conj(<p, q>) */
        double cr = 0.0, ci = 0.0;
        for (int i = 0; i < n; i++) {
            cr += pr[i] * qr[i] + pi[i] * qi[i];
            ci += pr[i] * qi[i] - pi[i] * qr[i];
        }
        const double d2 = cr * cr + ci * ci;
        if (!(d2 > 1e-20)) {
            why = "the eigenvectors of A and A^T are orthogonal (a double eigenvalue)";
            goto done;
        }
        /* 1 / conj(c) = c / |c|^2 */
        for (int i = 0; i < n; i++) {
            const double r = pr[i], s = pi[i];
            pr[i] = (r * cr - s * ci) / d2;
            pi[i] = (r * ci + s * cr) / d2;
        }
        why = "the Jacobian could not be differentiated along the eigenvectors";
        /* B(q, conj q) = B(qr, qr) + B(qi, qi) */
        if (jac_dir(&c, qr, 1, Dr) || jac_dir(&c, qi, 1, Di))
            goto done;
        mv(n, Dr, qr, r1, 1.0, 0);
        mv(n, Di, qi, r1, 1.0, 1);
        /* a = A^-1 B(q, conj q) */
        memcpy(Ac, A, nn * sizeof *A);
        if (dyn_lu_factor(n, Ac, piv)) {
            why = "A is singular at the Hopf point (a zero eigenvalue too)";
            goto done;
        }
        memcpy(a, r1, (size_t)n * sizeof *a);
        dyn_lu_solve(n, Ac, piv, a);
        /* B(q, a) = D_a q */
        if (jac_dir(&c, a, 1, D))
            goto done;
        mv(n, D, qr, bq, 1.0, 0);
        mv(n, D, qi, bq + n, 1.0, 0);
        /* B(q, q) = B(qr, qr) - B(qi, qi) + 2 i B(qr, qi) */
        mv(n, Dr, qr, bqq, 1.0, 0);
        mv(n, Di, qi, bqq, -1.0, 1);
        mv(n, Di, qr, bqq + n, 2.0, 0);
        /* c = (2 i omega - A)^-1 B(q, q): [[-A, -2w], [2w, -A]] [cr; ci] = [br; bi] */
        eig_system(n, A, 0, 2.0 * omega, K);
        for (size_t k = 0; k < NN; k++)
            K[k] = -K[k];
        memcpy(cc, bqq, (size_t)N * sizeof *cc);
        if (dyn_lu_factor(N, K, piv)) {
            why = "2 i omega is an eigenvalue too (a 1:2 resonance)";
            goto done;
        }
        dyn_lu_solve(N, K, piv, cc);
        /* B(conj q, c) = D_cr conj q + i D_ci conj q */
        if (jac_dir(&c, cc, 1, D))
            goto done;
        mv(n, D, qr, bqc, 1.0, 0);
        mv(n, D, qi, bqc + n, -1.0, 0);
        if (jac_dir(&c, cc + n, 1, D))
            goto done;
        /* i (D_ci (qr - i qi)) = D_ci qi + i D_ci qr */
        mv(n, D, qi, bqc, 1.0, 1);
        mv(n, D, qr, bqc + n, 1.0, 1);
        /* C(q, q, conj q) = D2_qr q + D2_qi q */
        if (jac_dir(&c, qr, 2, Dr) || jac_dir(&c, qi, 2, Di))
            goto done;
        mv(n, Dr, qr, cq, 1.0, 0);
        mv(n, Di, qr, cq, 1.0, 1);
        mv(n, Dr, qi, cq + n, 1.0, 0);
        mv(n, Di, qi, cq + n, 1.0, 1);
        /* Re <p, y> = pr.yr + pi.yi */
        double s = 0.0;
        for (int i = 0; i < n; i++)
            s += pr[i] * (cq[i] - 2.0 * bq[i] + bqc[i]) +
                 pi[i] * (cq[i + n] - 2.0 * bq[i + n] + bqc[i + n]);
        *l1 = s / (2.0 * omega);
        rc = isfinite(*l1) ? 0 : DYN_ERR_NONFINITE;
        why = "the coefficient is not finite";
    }
done:
    if (rc)
        snprintf(err, errlen, "%s", why);
    free(buf);
    free(piv);
    return rc;
}
