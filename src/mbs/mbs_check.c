/* SPDX-License-Identifier: BSD-3-Clause */
/* Checks of a mechanism at its initial state, before any C is written (docs/mechanisms.md,
 * "Errors"): the constraints hold (positions and speeds), the mass matrix M is positive
 * definite (else the coordinates that move no mass of their own are named) and the
 * constraints' rows D are independent (D M^-1 D' positive definite; else the redundant
 * constraints are named); each body's mass is not negative, and its inertia about the mass
 * centre is one a rigid body has: principal moments (the eigenvalues, by Jacobi's rotations)
 * not negative, none greater than the sum of the other two (the triangle inequality of
 * the moments: I_1 + I_2 - I_3 = 2 integral of z^2 dm >= 0; Goldstein, Classical
 * Mechanics, 3rd ed., sec. 5.4). Values come from src/lang's evaluation of the symbolic formulas
 * with the states and t as arguments; the factorization of src/ode/cholesky.h. */
#include <math.h>
#include <string.h>

#include "mbs/mbs_check.h"
#include "ode/cholesky.h"

static node *as_args(lang_ctx *c, const node *e, int nstates)
{
    if (e->kind == N_STATE || e->kind == N_TIME) {
        node *a = lang_node(c, N_ARG, e->pos);
        a->index = e->kind == N_STATE ? e->index : nstates;
        return a;
    }
    if (e->nargs == 0)
        return (node *)e;
    node *r = lang_node(c, e->kind, e->pos);
    *r = *e;
    r->args = lang_alloc(c, (size_t)e->nargs * sizeof *r->args);
    for (int i = 0; i < e->nargs; i++)
        r->args[i] = as_args(c, e->args[i], nstates);
    return r;
}

void mbs_initial_values(lang_ctx *c, mbs_initial *ini)
{
    lang_model *m = &c->m;
    const int np = m->params.n, nd = m->derived.n, n = m->states.n;
    ini->pv = lang_alloc(c, ((size_t)np + nd + 1) * sizeof *ini->pv);
    for (int i = 0; i < np; i++)
        ini->pv[i] = LVEC_AT(m->params, lang_param, i).value;
    for (int i = 0; i < nd; i++) {
        const int k = m->derived_order[i];
        ini->pv[np + k] = lang_eval(c, LVEC_AT(m->derived, lang_formula, k).expr, NULL, ini->pv);
    }
    ini->args = lang_alloc(c, ((size_t)n + 1) * sizeof *ini->args);
    for (int i = 0; i < n; i++) {
        const node *in = LVEC_AT(m->states, lang_state, i).init;
        ini->args[i] = in ? lang_eval(c, in, NULL, ini->pv) : 0.0;
    }
    ini->args[n] = m->t0;
    ini->nstates = n;
}

double mbs_value(lang_ctx *c, const mbs_initial *ini, const node *e)
{
    return lang_eval(c, as_args(c, e, ini->nstates), ini->args, ini->pv);
}

/* where a formula begins (a binary operation's position is its operator's) */
static lpos start_of(const node *e)
{
    while ((e->kind == N_BIN || e->kind == N_IF) && e->nargs > 0)
        e = e->args[0];
    return e->pos;
}

/* the eigenvalues of the symmetric 3 x 3 matrix S (row-major) into ev, ascending, by
 * cyclic Jacobi rotations (Golub and Van Loan, Matrix Computations, sec. 8.5) */
static void eigenvalues3(const double S[9], double ev[3])
{
    double a[9];
    memcpy(a, S, sizeof a);
    for (int sweep = 0; sweep < 50; sweep++) {
        const double off = a[1] * a[1] + a[2] * a[2] + a[5] * a[5];
        const double all = off + a[0] * a[0] + a[4] * a[4] + a[8] * a[8];
        if (!(off > 1e-32 * all))
            break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                const double apq = a[3 * p + q];
                if (apq == 0.0)
                    continue;
                const double theta = (a[3 * q + q] - a[3 * p + p]) / (2.0 * apq);
                const double t = (theta >= 0 ? 1.0 : -1.0) /
                                 (fabs(theta) + sqrt(theta * theta + 1.0));
                const double cs = 1.0 / sqrt(t * t + 1.0), sn = t * cs;
                for (int k = 0; k < 3; k++) { /* columns p, q */
                    const double akp = a[3 * k + p], akq = a[3 * k + q];
                    a[3 * k + p] = cs * akp - sn * akq;
                    a[3 * k + q] = sn * akp + cs * akq;
                }
                for (int k = 0; k < 3; k++) { /* rows p, q */
                    const double apk = a[3 * p + k], aqk = a[3 * q + k];
                    a[3 * p + k] = cs * apk - sn * aqk;
                    a[3 * q + k] = sn * apk + cs * aqk;
                }
            }
    }
    ev[0] = a[0], ev[1] = a[4], ev[2] = a[8];
    for (int i = 1; i < 3; i++)
        for (int j = i; j > 0 && ev[j - 1] > ev[j]; j--) {
            const double t = ev[j];
            ev[j] = ev[j - 1];
            ev[j - 1] = t;
        }
}

void mbs_check_body(lang_ctx *c, const mbs_body *b, double mass, const double *I)
{
    const lpos mpos = start_of(LVEC_AT(c->m.fixes, lang_formula, b->mass).expr);
    if (mass < 0)
        lang_fail(c, mpos, "the mass of '%s' is %.17g at the initial state: a mass is not "
                  "negative", b->name, mass);
    if (!I)
        return;
    double ev[3];
    eigenvalues3(I, ev);
    if (!isfinite(ev[0]) || !isfinite(ev[2]))
        return; /* not known here (a table, an input) */
    const double tol = 1e-9 * (fabs(ev[0]) + fabs(ev[1]) + fabs(ev[2]));
    const lpos ipos = start_of(LVEC_AT(c->m.fixes, lang_formula, b->inertia[0]).expr);
    const char *about = b->about[0] >= 0 ? " (moved to the mass centre from the point it is "
                                           "given about)" : "";
    if (ev[0] < -tol)
        lang_fail(c, ipos, "the inertia of '%s' about its mass centre%s has a negative principal "
                  "moment, %.17g (its principal moments %.6g, %.6g, %.6g): no rigid body has "
                  "one (each is an integral of squared distances times dm)", b->name, about,
                  ev[0], ev[0], ev[1], ev[2]);
    if (ev[2] > ev[0] + ev[1] + tol)
        lang_fail(c, ipos, "the inertia of '%s' about its mass centre%s has a principal moment "
                  "greater than the sum of the other two, %.6g > %.6g + %.6g: no rigid body "
                  "has one (the triangle inequality I1 <= I2 + I3; a thin rod along x has "
                  "(0, I, I), a plate in the xy plane Izz = Ixx + Iyy)", b->name, about, ev[2],
                  ev[0], ev[1]);
}

/* Cholesky in place (lower triangle of A, n x n); returns the first column whose pivot is
 * not above 1e-12 of the largest diagonal entry, or -1. */
static int cholesky(double *A, int n) { return dyn_cholesky_factor_tol(n, A, 1e-12, 1) - 1; }

/* After cholesky(L) failed at column j of the n x n matrix A: the combination that makes
 * column j, x (j) with A11 x = A[0..j-1, j] (A11 = the factor's leading j x j block),
 * so that v = (-x, 1) has A v = 0 to the tolerance */
static void dependence(const double *L, const double *A, int n, int j, double *x)
{
    for (int i = 0; i < j; i++) {
        double t = A[i * n + j];
        for (int k = 0; k < i; k++)
            t -= L[i * n + k] * x[k];
        x[i] = t / L[i * n + i];
    }
    for (int i = j - 1; i >= 0; i--) {
        double t = x[i];
        for (int k = i + 1; k < j; k++)
            t -= L[k * n + i] * x[k];
        x[i] = t / L[i * n + i];
    }
}

/* "a, b" for the entries of x (j) that count, and "LHS = 2 a - 1 b" into *formula */
static const char *involved(lang_ctx *c, const double *x, int j,
                            const char *(*name)(const void *, int), const void *of,
                            const char *lhs, const char **formula)
{
    double big = 0.0;
    for (int i = 0; i < j; i++)
        big = fmax(big, fabs(x[i]));
    const char *names = "", *f = lhs;
    for (int i = 0; i < j; i++) {
        if (!(fabs(x[i]) > 1e-9 * big))
            continue;
        names = lang_printf(c, "%s%s%s", names, *names ? ", " : "", name(of, i));
        f = lang_printf(c, "%s %s %.6g D[%s]", f, f == lhs ? "=" : x[i] < 0 ? "-" : "+",
                        f == lhs ? x[i] : fabs(x[i]), name(of, i));
    }
    *formula = f;
    return names;
}

static const char *coord_name(const void *mb, int i)
{
    return LVEC_AT(((const mbs_model *)mb)->coords, mbs_coord, i).name;
}

static const char *cons_name(const void *mb, int i)
{
    return LVEC_AT(((const mbs_model *)mb)->cons, mbs_constraint, i).name;
}

int mbs_positive_definite(lang_ctx *c, const double *M, int n)
{
    for (int i = 0; i < n * n; i++)
        if (!isfinite(M[i]))
            return 1; /* not known before the run: taken as it is */
    double *L = lang_alloc(c, (size_t)n * n * sizeof *L);
    memcpy(L, M, (size_t)n * n * sizeof *L);
    return cholesky(L, n) < 0;
}

void mbs_check_initial(lang_ctx *c, const mbs_model *mb, double *M, const double *D)
{
    const int n = mb->coords.n, m = mb->cons.n;
    for (int i = 0; i < n * n; i++)
        if (!isfinite(M[i]))
            return; /* not known before the run (an input, a table): not checked */
    double *L = lang_alloc(c, (size_t)n * n * sizeof *L);
    memcpy(L, M, (size_t)n * n * sizeof *L);
    const int j = cholesky(L, n);
    if (j >= 0) {
        const char *names = "";
        int first = -1;
        double big = 0.0;
        for (int i = 0; i < n; i++)
            big = fmax(big, fabs(M[i * n + i]));
        for (int i = 0; i < n; i++)
            if (!(fabs(M[i * n + i]) > 1e-12 * big) && (first < 0 ? (first = i) : i) >= 0)
                names = lang_printf(c, "%s%s%s", names, *names ? ", " : "",
                                    LVEC_AT(mb->coords, mbs_coord, i).name);
        const mbs_coord *q = &LVEC_AT(mb->coords, mbs_coord, first >= 0 ? first : j);
        if (*names)
            lang_fail(c, q->pos, "the mass matrix is singular at the initial state: no mass or "
                      "inertia moves with %s (give the bodies that move with it a mass, or "
                      "their rotation an inertia)", names);
        double *x = lang_alloc(c, ((size_t)j + 1) * sizeof *x);
        dependence(L, M, n, j, x);
        double most = 0.0;
        for (int i = 0; i < j; i++)
            most = fmax(most, fabs(x[i]));
        /* the direction v = (-x, 1) with M v = 0: the rates that move no mass */
        const char *dir = lang_printf(c, "d%s = 1", coord_name(mb, j));
        for (int i = 0; i < j; i++)
            if (fabs(x[i]) > 1e-9 * most)
                dir = lang_printf(c, "%s, d%s = %.6g", dir, coord_name(mb, i), -x[i]);
        lang_fail(c, LVEC_AT(mb->coords, mbs_coord, j).pos, "the mass matrix is singular at the "
                  "initial state: %s moves no mass that the coordinates before it do not (the "
                  "rates %s together move no mass; choose independent coordinates, or give "
                  "the bodies inertia)", coord_name(mb, j), dir);
    }
    if (m == 0)
        return;
    for (int i = 0; i < m * n; i++)
        if (!isfinite(D[i]))
            return;
    double *X = lang_alloc(c, (size_t)m * n * sizeof *X);
    double *A = lang_alloc(c, (size_t)m * m * sizeof *A);
    memcpy(X, D, (size_t)m * n * sizeof *X);
    for (int r = 0; r < m; r++)
        dyn_cholesky_solve(n, L, X + r * n);
    for (int r = 0; r < m; r++)
        for (int s = 0; s < m; s++) {
            double v = 0.0;
            for (int k = 0; k < n; k++)
                v += D[r * n + k] * X[s * n + k];
            A[r * m + s] = v;
        }
    double *G = lang_alloc(c, (size_t)m * m * sizeof *G); /* A before its factorization */
    memcpy(G, A, (size_t)m * m * sizeof *G);
    const int bad = cholesky(A, m);
    if (bad >= 0) {
        const mbs_constraint *k = &LVEC_AT(mb->cons, mbs_constraint, bad);
        double *x = lang_alloc(c, ((size_t)bad + 1) * sizeof *x);
        dependence(A, G, m, bad, x);
        const char *formula;
        const char *before = involved(c, x, bad, cons_name, mb,
                                      lang_printf(c, "D[%s]", k->name), &formula);
        if (*before)
            lang_fail(c, k->pos, "constraint '%s' is redundant at the initial state: its row "
                      "depends on those of %s (%s, D the rows on the coordinates' rates; remove "
                      "one, or start away from this configuration)", k->name, before, formula);
        lang_fail(c, k->pos, "constraint '%s' is redundant at the initial state: its row "
                  "is zero: it depends on no coordinate there (remove it, or start away from "
                  "this configuration)", k->name);
    }
}
