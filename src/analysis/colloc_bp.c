/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_bp.c — branch points of periodic orbits on the collocation system G(X) = 0,
 * X = (u, T, lambda) (colloc_po.c): where a Floquet multiplier other than the trivial one
 * passes through +1 and the branch does not fold, two families of cycles cross (a
 * pitchfork of cycles where a symmetric cycle loses its symmetry, a transcritical one).
 * Detection is Keller's test (Keller 1977; Doedel, Keller & Kernevez 1991, part II;
 * AUTO-07p's FNBPBV, the determinant of its reduced system): along a branch with tangent t
 * the bordered matrix [G_X; t^T] is regular at ordinary points and at folds, and its
 * determinant changes sign at a simple branch point, where G_X has a two-dimensional null
 * space. The other family's direction is the null vector of the same bordered matrix at
 * the branch point, the part of that null space orthogonal to the known branch (AUTO-07p's
 * branch switching for boundary-value problems, ISW = -1: STDRBV with the old direction as
 * the last row), found by inverse iteration with the collocation solver's own
 * factorization. The location stops short of the singular point and interpolates (below). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/colloc_internal.h"

int colloc_bp_test(const dyn_colloc_problem *p, const dyn_colloc_sol *x,
                   const dyn_colloc_sol *t, int *sign, double *logabs)
{
    return dyn_colloc_bordered(p, x, x, t, NULL, NULL, sign, logabs);
}

/* the largest |v_i|, or 0 */
static double max_abs(long n, const double *v)
{
    double m = 0.0;
    for (long i = 0; i < n; i++)
        m = fmax(m, fabs(v[i]));
    return m;
}

int colloc_bp_direction(const dyn_colloc_problem *p, const dyn_colloc_sol *x,
                        const dyn_colloc_sol *t, dyn_colloc_sol *v)
{
    const long Nu = dyn_colloc_nodes(x) * x->n, Nx = Nu + x->npar;
    double *b = malloc(2 * (size_t)Nx * sizeof(double));
    if (!b)
        return DYN_COLLOC_ERR_NOMEM;
    double *y = b + Nx;
    /* inverse iteration: a fixed right-hand side with no special structure, then the
     * iterate itself (unknowns and equations are as many); the null vector dominates the
     * solution as 1 / (the distance to singularity) */
    for (long i = 0; i < Nx; i++)
        b[i] = 1.0 + 0.5 * sin(1.7 * (double)i + 0.3);
    int sign, st = 0;
    double logabs;
    for (int it = 0; it < 3 && !st; it++) {
        st = dyn_colloc_bordered(p, x, x, t, b, y, &sign, &logabs);
        const double m = st ? 0.0 : max_abs(Nx, y);
        if (!st && !(m > 0 && isfinite(m)))
            st = DYN_COLLOC_ERR_SINGULAR;
        for (long i = 0; i < Nx && !st; i++)
            b[i] = y[i] / m;
    }
    if (!st)
        st = dyn_colloc_sol_copy(v, x);
    if (st) {
        free(b);
        return st;
    }
    memcpy(v->u, b, (size_t)Nu * sizeof(double));
    memcpy(v->par, b + Nu, (size_t)x->npar * sizeof(double));
    free(b);
    /* orthogonal to t (it is, to the iteration's accuracy), unit length, the sign fixed by
     * its largest state component */
    const double tt = dyn_colloc_dot(t, t), vt = dyn_colloc_dot(v, t);
    if (tt > 0) {
        for (long i = 0; i < Nu; i++)
            v->u[i] -= vt / tt * t->u[i];
        for (int k = 0; k < x->npar; k++)
            v->par[k] -= vt / tt * t->par[k];
    }
    const double nrm = sqrt(dyn_colloc_dot(v, v));
    if (!(nrm > 0) || !isfinite(nrm)) {
        dyn_colloc_sol_free(v);
        return DYN_COLLOC_ERR_SINGULAR;
    }
    long big = 0;
    for (long i = 1; i < Nu; i++)
        if (fabs(v->u[i]) > fabs(v->u[big]))
            big = i;
    const double s = v->u[big] < 0 ? -1.0 / nrm : 1.0 / nrm;
    for (long i = 0; i < Nu; i++)
        v->u[i] *= s;
    for (int k = 0; k < x->npar; k++)
        v->par[k] *= s;
    return 0;
}

/* the branch point's bracket in colloc_bp_locate: its ends' arclengths, test values (as computed,
 * g; as the Illinois steps scale them, f) and solutions, and in s[2], g[2], y[2] the end
 * replaced last (none yet: y[2] empty) */
typedef struct bp_bracket {
    double s[3], f[2], g[3];
    dyn_colloc_sol y[3];
} bp_bracket;

/* the bracket's end that the point at s with value g replaces (the side of its sign) */
static void bp_set(bp_bracket *k, double s, double g, dyn_colloc_sol *y)
{
    const int e = (g > 0) == (k->g[1] > 0);
    dyn_colloc_sol_free(&k->y[2]);
    k->y[2] = k->y[e];
    k->s[2] = k->s[e];
    k->g[2] = k->g[e];
    k->y[e] = *y;
    k->s[e] = s;
    k->f[e] = k->g[e] = g;
}

/* x := the quadratic (with k->y[2]; else linear) interpolant of the bracket's solutions at
 * the zero of the same interpolant of the test in the bracket; its arclength into *s_at */
static void bp_interpolate(const bp_bracket *k, dyn_colloc_sol *x, double *s_at)
{
    const int m = k->y[2].u ? 3 : 2;
    const double *s = k->s, *g = k->g;
    double z = s[0] - g[0] * (s[1] - s[0]) / (g[1] - g[0]), L[3] = {0};
    for (int it = 0; it < (m == 3 ? 8 : 1); it++) { /* Newton's method on the quadratic */
        double q = 0.0, dq = 0.0;
        for (int i = 0; i < m; i++) {
            double l = 1.0, dl = 0.0;
            for (int j = 0; j < m; j++)
                if (j != i) {
                    dl = dl * (z - s[j]) / (s[i] - s[j]) + l / (s[i] - s[j]);
                    l *= (z - s[j]) / (s[i] - s[j]);
                }
            L[i] = l;
            q += g[i] * l;
            dq += g[i] * dl;
        }
        if (m == 2 || !(dq != 0.0))
            break;
        const double zn = z - q / dq;
        if (!((zn - s[0]) * (zn - s[1]) <= 0.0)) /* out of the bracket: the linear root */
            break;
        z = zn;
    }
    for (int i = 0; i < m; i++) { /* the weights at z */
        L[i] = 1.0;
        for (int j = 0; j < m; j++)
            if (j != i)
                L[i] *= (z - s[j]) / (s[i] - s[j]);
    }
    const long N = dyn_colloc_nodes(x) * x->n;
    for (long i = 0; i < N; i++) {
        double v = 0.0;
        for (int e = 0; e < m; e++)
            v += L[e] * k->y[e].u[i];
        x->u[i] = v;
    }
    for (int p = 0; p < x->npar; p++) {
        double v = 0.0;
        for (int e = 0; e < m; e++)
            v += L[e] * k->y[e].par[p];
        x->par[p] = v;
    }
    *s_at = z;
}

/* the bracket at which colloc_bp_locate stops, and the test's value (relative to its value at the
 * step's start) below which a point is too near the branch point to be solved accurately:
 * fractions of the step */
#define BP_BRACKET 1e-3
#define BP_NEAR 1e-4

/* the branch point in (0, ds) along a step from x0 (see colloc_internal.h): secant steps
 * on the test, but not into the branch point itself, where the step's solution is
 * determined only to about the rounding divided by the test's value (the two branches'
 * points on the step's hyperplane merge there: 1e-8 in the parameter at 1e-5 of the test's
 * value at the step's start on van der Pol's cycles). The steps stop at a bracket of
 * BP_BRACKET |ds|; a point whose value is below BP_NEAR of the start's is replaced by the
 * two at BP_BRACKET |ds| / 2 on either side of it. The solutions at the bracket's ends and
 * at the end replaced last are kept, and the point is their quadratic interpolant at the
 * zero of the test's quadratic interpolant in the bracket (its error of the order of the
 * bracket's cube). */
int colloc_bp_locate(colloc_bp_eval eval, void *ctx, const dyn_colloc_sol *x0, double ds,
                     double psi0, double psi1, dyn_colloc_sol *x, double *s_at)
{
    bp_bracket k = {{0.0, ds, 0.0}, {psi0, psi1}, {psi0, psi1, 0.0}, {{0}, {0}, {0}}};
    const double near = BP_NEAR * fmin(fabs(psi0), fabs(psi1));
    int side = 0, st = dyn_colloc_sol_copy(&k.y[0], x0);
    for (int it = 0; it < 24 && !st && fabs(k.s[1] - k.s[0]) > BP_BRACKET * fabs(ds); it++) {
        const double s = k.s[1] - k.f[1] * (k.s[1] - k.s[0]) / (k.f[1] - k.f[0]);
        dyn_colloc_sol y;
        double g;
        if (eval(ctx, s, &y, &g))
            break; /* the bracket is the answer */
        if (fabs(g) < near) { /* too near: the points on either side of it instead */
            dyn_colloc_sol_free(&y);
            for (int e = -1; e <= 1; e += 2) {
                const double se = s + e * 0.5 * BP_BRACKET * ds;
                if (eval(ctx, se, &y, &g) == 0)
                    bp_set(&k, se, g, &y);
            }
            break;
        }
        const int end = (g > 0) == (k.g[1] > 0);
        bp_set(&k, s, g, &y);
        if (side == (end ? -1 : 1)) /* the Illinois step: the end kept twice is halved */
            k.f[!end] *= 0.5;
        side = end ? -1 : 1;
    }
    if (!st && !k.y[1].u)
        st = DYN_COLLOC_ERR_NEWTON; /* no point beyond it: not located */
    if (!st && !(st = dyn_colloc_sol_copy(x, &k.y[0])))
        bp_interpolate(&k, x, s_at);
    for (int e = 0; e < 3; e++)
        dyn_colloc_sol_free(&k.y[e]);
    return st;
}
