/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_curves.c — curves of folds and of Hopf points in two parameters (dynkit/
 * continuation.h, dyn_continue with ip2 >= 0), by the standard extended systems (Govaerts,
 * "Numerical Methods for Bifurcations of Dynamical Equilibria", 2000, ch. 4; Kuznetsov,
 * "Elements", sec. 10.2):
 *   folds:  f(x, p) = 0, J v = 0, c . v = 1                  (x, v, p1, p2)
 *   Hopf:   f(x, p) = 0, (J^2 + kappa I) v = 0, c1 . v = 1, c2 . v = 0   (x, v, kappa, p1, p2)
 * with kappa = omega^2, so that the Hopf curve goes on through a Bogdanov-Takens point
 * (kappa = 0) as a curve of neutral saddles (kappa < 0). Their Jacobians are central
 * differences of the residual (its f_x the model's exact Jacobian). Test functions: on a
 * fold curve w . v (BT: the zero eigenvalue becomes double; w the left null vector from a
 * bordered system) and w . B(v, v) (CP: the fold's quadratic coefficient vanishes); on a
 * Hopf curve kappa (BT) and the first Lyapunov coefficient times the sign of det J (GH;
 * the sign keeps a fold-Hopf point, where l1 has a pole, from passing for one). A map's
 * folds are those of F(x) - x, and its flips (period doublings, a multiplier -1) the same
 * system with J + 2 I (Kuznetsov, "Elements", sec. 10.3); on a map's curves BT would be a
 * 1:1 resonance and the cusp test a fold's, so only the cusp of its fold curves is located.
 * A map's Neimark-Sacker points (multipliers exp(+-i theta) of A = J + I, J the Jacobian of
 * F(x) - x) are the Hopf system with A^2 - 2 cos(theta) A + I = J^2 + kappa (J + I),
 * kappa = 2 - 2 cos(theta) (Kuznetsov, "Elements", sec. 10.3.3), without tests. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cont_equilibrium.h"
#include "ode/linalg.h"

typedef struct curve_ctx {
    cont_model *cm;
    dyn_diagram *d;
    int bi;
    int hopf;        /* 0: folds, 1: Hopf points or a map's Neimark-Sacker points */
    int ns;          /* 1: a map's Neimark-Sacker points */
    double shift;    /* a map's flips: 2 (J + 2 I singular); else 0 */
    int N;           /* equations */
    double *c1, *c2; /* the normalizations (n each) */
    double *w_prev;  /* the left null vector's border (folds) */
    double *g0, *g1, *zz, *M, *rhs, *J2, *Jv; /* workspace */
    int *piv;
} curve_ctx;

/* indices in z: x 0..n-1, v n..2n-1, [kappa 2n,] p1, p2 */
static int ip1(const curve_ctx *c)
{
    return 2 * c->cm->n + c->hopf;
}

static int curve_residual(void *ctx, const double *z, double *g)
{
    curve_ctx *c = ctx;
    cont_model *cm = c->cm;
    const int n = cm->n, k = ip1(c);
    if (cont_model_set(cm, z[k], z[k + 1]) || cont_model_f(cm, z, g) ||
        cont_model_jx(cm, z, cm->J, n))
        return -1;
    const double *v = z + n;
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int j = 0; j < n; j++)
            s += cm->J[(size_t)i * (size_t)n + (size_t)j] * v[j];
        c->Jv[i] = s + c->shift * v[i];
    }
    if (!c->hopf) {
        memcpy(g + n, c->Jv, (size_t)n * sizeof *g);
    } else {
        for (int i = 0; i < n; i++) {
            double s = 0.0;
            for (int j = 0; j < n; j++)
                s += cm->J[(size_t)i * (size_t)n + (size_t)j] * c->Jv[j];
            g[n + i] = s + z[2 * n] * (v[i] + (c->ns ? c->Jv[i] : 0.0));
        }
    }
    double a = -1.0, b = 0.0;
    for (int i = 0; i < n; i++) {
        a += c->c1[i] * v[i];
        if (c->hopf)
            b += c->c2[i] * v[i];
    }
    g[2 * n] = a;
    if (c->hopf)
        g[2 * n + 1] = b;
    return 0;
}

static int curve_jacobian(void *ctx, const double *z, double *Jout)
{
    curve_ctx *c = ctx;
    /* g0, g1 and zz follow each other: 3 (N + 1) values */
    return cont_central_jacobian(curve_residual, c, c->N, CONT_STEPS_CBRT, z, Jout, c->g0);
}

/* the left null vector w of J (cm->J) bordered by v and w_prev: [[J^T, v], [w_prev^T, 0]]
 * [w; h] = [0; 1]. 0 or non-zero */
static int left_null(curve_ctx *c, const double *v, double *w)
{
    const int n = c->cm->n, K = n + 1;
    for (int i = 0; i < K; i++)
        for (int j = 0; j < K; j++) {
            double a;
            if (i < n && j < n)
                a = c->cm->J[(size_t)j * (size_t)n + (size_t)i] + (i == j ? c->shift : 0.0);
            else if (i < n)
                a = v[i];
            else if (j < n)
                a = c->w_prev[j];
            else
                a = 0.0;
            c->M[(size_t)i * (size_t)K + (size_t)j] = a;
        }
    if (dyn_lu_factor(K, c->M, c->piv))
        return -1;
    for (int i = 0; i < K; i++)
        c->rhs[i] = i == n ? 1.0 : 0.0;
    dyn_lu_solve(K, c->M, c->piv, c->rhs);
    memcpy(w, c->rhs, (size_t)n * sizeof *w);
    return 0;
}

static double norm2(const double *v, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += v[i] * v[i];
    return sqrt(s);
}

/* det J / (the product of J's rows' norms), n x n (copied into work): 0 when a pivot
 * vanishes */
static double det_scaled(int n, const double *J, double *work, int *piv)
{
    memcpy(work, J, (size_t)n * (size_t)n * sizeof *work);
    if (dyn_lu_factor(n, work, piv))
        return 0.0;
    double det = 1.0;
    for (int k = 0; k < n; k++)
        det *= (piv[k] != k ? -1.0 : 1.0) * work[(size_t)k * (size_t)n + (size_t)k] /
               fmax(norm2(J + (size_t)k * (size_t)n, n), DBL_MIN);
    return det;
}

static int curve_tests(void *ctx, const double *z, const double *t, double det, double *psi,
                       int *count)
{
    (void)t;
    (void)det;
    curve_ctx *c = ctx;
    cont_model *cm = c->cm;
    const int n = cm->n, k = ip1(c);
    if (cont_model_set(cm, z[k], z[k + 1]) || cont_model_jx(cm, z, cm->J, n))
        return -1;
    count[0] = count[1] = count[2] = -1;
    psi[2] = NAN;
    if (c->ns) { /* no tests: strong resonances and Chenciner points are not located */
        psi[0] = psi[1] = NAN;
        return 0;
    }
    if (c->hopf) {
        const double kappa = z[2 * n];
        psi[0] = kappa;
        psi[1] = NAN;
        /* ZH: det J = kappa times the product of the other eigenvalues, so det J / kappa
         * changes sign where one of them passes through 0 (and not at BT, where kappa
         * does); where kappa > 0 only, the neutral saddles having no zero-Hopf point */
        const double ds = det_scaled(n, cm->J, c->J2, c->piv);
        if (kappa > 0.0)
            psi[2] = ds / kappa;
        /* l1 times the sign of det J: where a real eigenvalue passes through zero (the
         * fold-Hopf point ZH) l1 changes sign through a pole (its formula solves with J),
         * det J through zero, and the product keeps its sign; it changes at GH */
        const int sd = ds > 0.0 ? 1 : ds < 0.0 ? -1 : 0;
        if (kappa > 0.0 && sd != 0) {
            double l1;
            char err[128];
            if (dyn_first_lyapunov(cm->m, cm->t, z, cm->par, cm->jac, cm->J, sqrt(kappa), &l1,
                                   err, sizeof err) == 0)
                psi[1] = sd * l1;
        }
        return 0;
    }
    const double *v = z + n;
    double *w = c->rhs + n + 1; /* room after the bordered system's right-hand side */
    if (left_null(c, v, w))
        return -1;
    const double nw = norm2(w, n), nv = norm2(v, n);
    psi[0] = 0.0;
    for (int i = 0; i < n; i++)
        psi[0] += w[i] * v[i];
    psi[0] /= nw * nv;
    /* w . B(v, v), B(v, v) = (J(x + h v) - J(x - h v)) v / (2 h) */
    const double h = cbrt(DBL_EPSILON) * fmax(1.0, norm2(z, n)) / nv;
    double *Jp = c->J2;
    double wb = 0.0;
    for (int sgn = 1; sgn >= -1; sgn -= 2) {
        for (int i = 0; i < n; i++)
            c->zz[i] = z[i] + sgn * h * v[i];
        if (cont_model_jx(cm, c->zz, Jp, n))
            return -1;
        for (int i = 0; i < n; i++) {
            double s = 0.0;
            for (int j = 0; j < n; j++)
                s += Jp[(size_t)i * (size_t)n + (size_t)j] * v[j];
            wb += sgn * w[i] * s / (2.0 * h);
        }
    }
    psi[1] = wb / (nw * nv * nv);
    if (cm->map) { /* no BT (a 1:1 resonance) on a map's curves, no cusp on its flips */
        psi[0] = 1.0;
        if (c->shift > 0.0)
            psi[1] = 1.0;
    } else {
        /* ZH: a complex pair of the other eigenvalues crosses the axis (the equilibria's
         * Hopf test; the zero eigenvalue is real, so it does not enter) */
        if (cont_model_eig(cm, cm->J))
            return -1;
        psi[2] = cont_hopf_test(n, cm->re, cm->im, 0.0, &count[2], NULL);
    }
    memcpy(c->w_prev, w, (size_t)n * sizeof *w);
    const double nwp = norm2(c->w_prev, n);
    for (int i = 0; i < n; i++)
        c->w_prev[i] /= nwp * nwp; /* w_prev . w = 1 at this point */
    return 0;
}

static int curve_store(void *ctx, const double *z, const double *t, dyn_cont_label label)
{
    (void)t;
    curve_ctx *c = ctx;
    cont_model *cm = c->cm;
    const int n = cm->n, k = ip1(c);
    if (cont_model_set(cm, z[k], z[k + 1]) || cont_model_jx(cm, z, cm->J, n) ||
        cont_model_eig(cm, cm->J))
        return -1;
    double l1 = NAN, omega = NAN;
    if (c->ns) {
        omega = acos(fmax(-1.0, fmin(1.0, 1.0 - 0.5 * z[2 * n]))); /* the angle theta */
    } else if (c->hopf) {
        omega = z[2 * n];
        char err[128];
        if (omega > 0.0 && label != DYN_LABEL_ZH &&
            dyn_first_lyapunov(cm->m, cm->t, z, cm->par, cm->jac, cm->J,
                                              sqrt(omega), &l1, err, sizeof err))
            l1 = NAN;
    }
    dyn_branch_point pt = {label, {z[k], z[k + 1]}, NAN, -1, l1, omega};
    return dyn_branch_append(&c->d->branches[c->bi], &pt, z, NULL, cm->re, cm->im) < 0;
}

/* A unit null vector of the n x n matrix A (copied) by inverse iteration: 0 or non-zero */
static int null_of(int n, const double *A, double *work, int *piv, double *v)
{
    const size_t nn = (size_t)n * (size_t)n;
    memcpy(work, A, nn * sizeof *A);
    if (dyn_lu_factor(n, work, piv)) {
        double big = 0.0;
        for (size_t k = 0; k < nn; k++)
            big = fmax(big, fabs(A[k]));
        memcpy(work, A, nn * sizeof *A);
        for (int i = 0; i < n; i++)
            work[(size_t)i * (size_t)n + (size_t)i] += 1e-14 * (big > 0.0 ? big : 1.0) * (1.0 + 0.1 * i);
        if (dyn_lu_factor(n, work, piv))
            return -1;
    }
    for (int i = 0; i < n; i++)
        v[i] = 1.0 + 0.37 * i - 0.01 * i * i;
    for (int it = 0; it < 3; it++) {
        dyn_lu_solve(n, work, piv, v);
        const double nv = norm2(v, n);
        if (!(nv > 0.0) || !isfinite(nv))
            return -1;
        for (int i = 0; i < n; i++)
            v[i] /= nv;
    }
    return 0;
}

/* coordinate i of point k of a curve: its states, p1, p2, and on a Hopf curve omega^2 */
static double curve_coord(const dyn_branch *b, long k, int i)
{
    const int n = b->n;
    return i < n ? b->x[(size_t)k * (size_t)n + (size_t)i]
                 : i == n ? b->pts[k].par[0] : i == n + 1 ? b->pts[k].par[1] : b->pts[k].omega;
}

/* Whether the start y (dim = n + 2 + hopf coordinates as curve_coord's) lies on a curve of
 * the same kind computed already: within a tenth of a chord's length of that chord (a chord
 * of length L misses its arc by about kappa L^2 / 8, kappa the curvature), or within 1e-9
 * of a point. A fold or Hopf curve through two points of the equilibrium branches (the
 * cusp's fold curve through both folds) is then followed once. */
static int on_computed_curve(const dyn_diagram *d, dyn_branch_kind kind, const double *y, int n)
{
    const int hopf = kind == DYN_BRANCH_HOPF;
    const int dim = n + 2 + hopf;
    double scale = 1.0;
    for (int i = 0; i < dim; i++)
        scale = fmax(scale, fabs(y[i]));
    for (int bi = 0; bi < d->count; bi++) {
        const dyn_branch *b = &d->branches[bi];
        if (b->kind != kind || b->n != n)
            continue;
        for (long k = 0; k + 1 < b->count; k++) {
            double dd = 0.0, dy = 0.0;
            for (int i = 0; i < dim; i++) {
                const double c0 = curve_coord(b, k, i), c1 = curve_coord(b, k + 1, i);
                dd += (c1 - c0) * (c1 - c0);
                dy += (y[i] - c0) * (c1 - c0);
            }
            const double u = dd > 0.0 ? fmin(1.0, fmax(0.0, dy / dd)) : 0.0;
            double dist = 0.0;
            for (int i = 0; i < dim; i++) {
                const double c0 = curve_coord(b, k, i), c1 = curve_coord(b, k + 1, i);
                const double r = y[i] - (c0 + u * (c1 - c0));
                dist += r * r;
            }
            if (sqrt(dist) <= 0.1 * sqrt(dd) + 1e-9 * scale)
                return 1;
        }
    }
    return 0;
}

int cont_curves_from(cont_model *cm, const dyn_cont_opts *o, dyn_diagram *d, int branch,
                     long point, dyn_cont_info *info)
{
    const int n = cm->n;
    const dyn_branch *b = &d->branches[branch];
    const int ns = b->pts[point].label == DYN_LABEL_TR && cm->map;
    const int hopf = b->pts[point].label == DYN_LABEL_HB || ns;
    const int flip = b->pts[point].label == DYN_LABEL_PD && cm->map;
    const dyn_branch_kind kind = ns     ? DYN_BRANCH_NEIMARK_SACKER
                                 : hopf ? DYN_BRANCH_HOPF
                                 : flip ? DYN_BRANCH_FLIP
                                        : DYN_BRANCH_FOLD;
    const double omega = b->pts[point].omega; /* a map's Neimark-Sacker point: its angle */
    if (hopf && !(omega > 0.0))
        return 0;
    /* the Hopf system's kappa: omega^2, or for a map 2 - 2 cos(theta) */
    const double kappa = ns ? 2.0 - 2.0 * cos(omega) : omega * omega;
    {
        double *y = malloc(((size_t)n + 3) * sizeof *y);
        if (!y)
            return -1;
        memcpy(y, b->x + (size_t)point * (size_t)n, (size_t)n * sizeof *y);
        y[n] = b->pts[point].par[0];
        y[n + 1] = cm->p2_base;
        y[n + 2] = kappa;
        const int seen = on_computed_curve(d, kind, y, n);
        free(y);
        if (seen)
            return 0;
    }
    curve_ctx c;
    memset(&c, 0, sizeof c);
    c.cm = cm;
    c.d = d;
    c.hopf = hopf;
    c.ns = ns;
    c.shift = flip ? 2.0 : 0.0;
    c.N = 2 * n + 1 + hopf;
    const int N = c.N, M = N + 1;
    const size_t nn = (size_t)n * (size_t)n;
    double *buf = malloc((3 * (size_t)n + 4 * (size_t)M + 2 * (size_t)(n + 1) * (n + 1) +
                          2 * nn + 4 * (size_t)M + 8 * (size_t)n + 16) * sizeof *buf);
    c.piv = malloc((size_t)(2 * n + 2) * sizeof *c.piv);
    cont_work w;
    memset(&w, 0, sizeof w);
    if (!buf || !c.piv || cont_work_init(&w, N)) {
        free(buf);
        free(c.piv);
        cont_work_free(&w);
        return -1;
    }
    c.c1 = buf;
    c.c2 = c.c1 + n;
    c.w_prev = c.c2 + n;
    c.g0 = c.w_prev + n;
    c.g1 = c.g0 + M;
    c.zz = c.g1 + M;
    c.M = c.zz + M;
    c.rhs = c.M + (size_t)(n + 1) * (n + 1);
    c.J2 = c.rhs + 2 * (size_t)(n + 1) + 2;
    c.Jv = c.J2 + 2 * nn;
    double *z = c.Jv + n + 1, *t = z + M, *e = t + M, *v = e + M;
    /* the start: the point, its null vector(s) */
    const double p1 = b->pts[point].par[0];
    const double p2 = cm->p2_base;
    memcpy(z, b->x + (size_t)point * (size_t)n, (size_t)n * sizeof *z);
    int rc = 0;
    if (cont_model_set(cm, p1, p2) || cont_model_jx(cm, z, cm->J, n))
        rc = -1;
    if (rc == 0 && !hopf) {
        memcpy(c.J2, cm->J, nn * sizeof *c.J2);
        for (int i = 0; i < n; i++)
            c.J2[(size_t)i * (size_t)n + (size_t)i] += c.shift;
        if (null_of(n, c.J2, c.J2 + nn, c.piv, v))
            rc = -1;
        if (rc == 0) {
            memcpy(z + n, v, (size_t)n * sizeof *v);
            memcpy(c.c1, v, (size_t)n * sizeof *v); /* c . v = 1, |v| = 1 */
            /* the left null vector's first border */
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++)
                    c.J2[(size_t)i * (size_t)n + (size_t)j] =
                        cm->J[(size_t)j * (size_t)n + (size_t)i] + (i == j ? c.shift : 0.0);
            if (null_of(n, c.J2, c.J2 + nn, c.piv, c.w_prev))
                rc = -1;
        }
    } else if (rc == 0) {
        /* J^2 + omega^2 I, or a map's J^2 + kappa (J + I): its null space is spanned by
         * Re q and Im q */
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                double s = i == j ? kappa : 0.0;
                if (ns)
                    s += kappa * cm->J[(size_t)i * (size_t)n + (size_t)j];
                for (int k = 0; k < n; k++)
                    s += cm->J[(size_t)i * (size_t)n + (size_t)k] * cm->J[(size_t)k * (size_t)n + (size_t)j];
                c.J2[(size_t)i * (size_t)n + (size_t)j] = s;
            }
        if (null_of(n, c.J2, c.J2 + nn, c.piv, v))
            rc = -1;
        if (rc == 0) {
            /* the other direction of the null space (invariant under J): J v / omega, made
             * orthogonal to v */
            double *u = c.c2;
            for (int i = 0; i < n; i++) {
                double s = 0.0;
                for (int k = 0; k < n; k++)
                    s += cm->J[(size_t)i * (size_t)n + (size_t)k] * v[k];
                u[i] = s / omega;
            }
            double uv = 0.0;
            for (int i = 0; i < n; i++)
                uv += u[i] * v[i];
            for (int i = 0; i < n; i++)
                u[i] -= uv * v[i];
            memcpy(c.c1, v, (size_t)n * sizeof *v);
            memcpy(z + n, v, (size_t)n * sizeof *v);
            z[2 * n] = kappa;
        }
    }
    const int k1 = 2 * n + hopf;
    z[k1] = p1;
    z[k1 + 1] = p2;
    cont_system s;
    memset(&s, 0, sizeof s);
    s.N = N;
    s.ip = k1;
    s.ip2 = k1 + 1;
    s.ctx = &c;
    s.residual = curve_residual;
    s.jacobian = curve_jacobian;
    s.n_tests = 3;
    s.test_label[0] = DYN_LABEL_BT; /* none on a map's Neimark-Sacker curves (curve_tests) */
    s.test_label[1] = hopf ? DYN_LABEL_GH : DYN_LABEL_CP;
    s.test_label[2] = DYN_LABEL_ZH;
    s.tests = curve_tests;
    s.store = curve_store;
    /* Newton's method at the fixed second parameter, then both directions */
    for (int i = 0; i < M; i++)
        e[i] = i == k1 + 1 ? 1.0 : 0.0;
    if (rc == 0 && cont_correct(&s, &w, z, e, 0.0, z, NULL))
        rc = -2;
    const int parent = b->id;
    for (int dir = 1; rc == 0 && dir >= -1 && d->count < o->max_branches; dir -= 2) {
        for (int i = 0; i < M; i++)
            e[i] = i == k1 + 1 ? dir : 0.0;
        double det;
        if (cont_tangent(&s, &w, z, e, t, &det)) {
            rc = -2;
            break;
        }
        dyn_branch *nb = dyn_diagram_add(d, kind, n, n, o->ip, o->ip2);
        if (!nb) {
            rc = -1;
            break;
        }
        nb->parent = parent;
        nb->parent_point = point;
        c.bi = d->count - 1;
        cont_loop L;
        memset(&L, 0, sizeof L);
        L.ds = fabs(o->ds);
        L.dsmin = o->dsmin;
        L.dsmax = o->dsmax;
        L.nmax = o->nmax;
        L.pmin = o->parmin;
        L.pmax = o->parmax;
        L.p2min = o->par2min;
        L.p2max = o->par2max;
        L.start_label = ns     ? DYN_LABEL_TR
                        : hopf ? DYN_LABEL_HB
                        : flip ? DYN_LABEL_PD
                               : DYN_LABEL_LP;
        L.stop_closed = 1;
        L.missed = &cm->missed;
        char stop[160];
        const int st = cont_follow(&s, &w, &L, z, t, stop, sizeof stop);
        snprintf(d->branches[c.bi].stop, sizeof d->branches[c.bi].stop, "%s", stop);
        if (st == -1)
            rc = -1;
        if (st == 1) /* a closed curve: the other direction is the same curve */
            break;
    }
    if (rc == -2 && info && !info->message[0])
        snprintf(info->message, sizeof info->message,
                 "the %s curve through point %ld of branch %d could not be started",
                 hopf ? "Hopf" : dyn_branch_kind_name(kind), point + 1, parent);
    info->newton_steps += w.newton;
    cont_work_free(&w);
    free(buf);
    free(c.piv);
    return rc == -1 ? -1 : 0;
}
