/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_bvp.c — a model's two-point boundary-value problem (its bdry conditions, XPPAUT's
 * bdry lines) by orthogonal collocation (colloc_newton.c): y' = f(t, y) on [t0, t1] scaled
 * to [0, 1], the n conditions g(y(t0), y(t1)) = 0, no free scalars. The first guess is the
 * initial-value problem's solution from the given state (the start of XPPAUT's shooting);
 * when Newton's method fails from it, the conditions are reached by a homotopy from the
 * initial-value problem's condition u(t0) = y0, (1 - h) (u(t0) - y0) + h g = 0, h from 0 to 1;
 * the mesh is then adapted to the solution (colloc_mesh.c) and the error estimated against
 * a solve on twice as many intervals. A free parameter (XPPAUT's periodic boundary-value
 * option, its manual's "BVP solver": a frequency parameter and a section x(t0) = x0) is one
 * free scalar of the collocation with the section as one more condition. XPPAUT's
 * hom_bcs(k) conditions (a homoclinic or heteroclinic orbit, colloc_hom.c) come with one
 * condition fewer than states: the last is AUTO's integral phase condition
 * int (u - u0) . u0' dt = 0 against the first guess u0, which fixes the orbit's shift in
 * time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/colloc_hom.h"
#include "dynkit/colloc.h"

typedef struct bvp_ctx {
    const dyn_model *m;
    void *par;
    double t0, len;
    double *work; /* 3 n */
    /* the homotopy from the initial-value problem: (1 - h) (u(0) - y0) + h g = 0 */
    double h;
    const double *y0;
    /* the free parameter (index, -1: none), its value in par, the section u_sec(0) = value */
    int ifree;
    double free_set;
    int sec;
    double sec_value;
    /* hom_bcs: the projections (hom.m NULL: none) and the phase condition's reference */
    bvp_hom hom;
    dyn_colloc_sol *ref;
} bvp_ctx;

/* the free scalar (when there is one and it is given) into the model's parameters */
static int use_free(bvp_ctx *c, const double *par)
{
    if (c->ifree < 0 || !par || par[0] == c->free_set)
        return 0;
    if (!isfinite(par[0]))
        return 1;
    dyn_model_set_param(c->m, c->par, c->ifree, par[0]);
    c->free_set = NAN;
    if (c->m->prepare && c->m->prepare(c->par, NULL, 0))
        return 1;
    c->free_set = par[0];
    return 0;
}

static int bvp_f(double s, const double *u, const double *par, double *f, double *fu, void *ctx)
{
    bvp_ctx *c = ctx;
    if (use_free(c, par))
        return 1;
    const dyn_model *m = c->m;
    const int n = m->n_states;
    const double t = c->t0 + c->len * s;
    if (m->rhs(t, u, f, c->par))
        return 1;
    for (int i = 0; i < n; i++)
        f[i] *= c->len;
    if (!fu)
        return 0;
    if (m->jacobian) {
        if (m->jacobian(t, u, fu, c->par))
            return 1;
    } else {
        double *xp = c->work, *fp = xp + n, *fm = fp + n;
        memcpy(xp, u, (size_t)n * sizeof(double));
        for (int j = 0; j < n; j++) {
            const double h = 6e-6 * fmax(fabs(u[j]), 1.0);
            xp[j] = u[j] + h;
            if (m->rhs(t, xp, fp, c->par))
                return 1;
            xp[j] = u[j] - h;
            if (m->rhs(t, xp, fm, c->par))
                return 1;
            xp[j] = u[j];
            for (int i = 0; i < n; i++)
                fu[(size_t)i * n + j] = (fp[i] - fm[i]) / (2 * h);
        }
    }
    for (int i = 0; i < n * n; i++)
        fu[i] *= c->len;
    return 0;
}

/* the model's conditions at the ends, the projections among them */
static int conditions(bvp_ctx *c, const double *u0, const double *u1, double *g)
{
    if (c->m->bdry(u0, u1, c->par, g))
        return 1;
    return c->hom.m && bvp_hom_rows(&c->hom, u0, u1, g);
}

static int bvp_bc(const double *u0, const double *u1, const double *par, double *g, void *ctx)
{
    bvp_ctx *c = ctx;
    if (use_free(c, par) || conditions(c, u0, u1, g))
        return 1;
    if (c->h < 1.0)
        for (int i = 0; i < c->m->n_bdry; i++)
            g[i] = (1.0 - c->h) * (u0[i] - c->y0[i]) + c->h * g[i];
    if (c->ifree >= 0) /* the section, which the homotopy keeps */
        g[c->m->n_bdry] = u0[c->sec] - c->sec_value;
    return 0;
}

/* the initial-value problem from y0 at the nodes (RK4, 8 steps per node); where it stops
 * being finite, the last finite state is kept */
static void first_guess(bvp_ctx *c, const double *y0, dyn_colloc_sol *x)
{
    const int n = x->n;
    const long nodes = dyn_colloc_nodes(x);
    double *k = c->work, *y = malloc(6 * (size_t)n * sizeof(double));
    if (!y) {
        for (long g = 0; g < nodes; g++)
            memcpy(x->u + (size_t)g * n, y0, (size_t)n * sizeof(double));
        return;
    }
    double *k1 = y + n, *k2 = k1 + n, *k3 = k2 + n, *k4 = k3 + n, *tmp = k4 + n;
    (void)k;
    memcpy(y, y0, (size_t)n * sizeof(double));
    memcpy(x->u, y, (size_t)n * sizeof(double));
    int ok = 1;
    for (long g = 1; g < nodes; g++) {
        const double s0 = dyn_colloc_node_time(x, g - 1), s1 = dyn_colloc_node_time(x, g);
        const double h = (s1 - s0) / 8;
        for (int st = 0; st < 8 && ok; st++) {
            const double s = s0 + st * h;
            ok = !bvp_f(s, y, NULL, k1, NULL, c);
            for (int i = 0; i < n; i++)
                tmp[i] = y[i] + 0.5 * h * k1[i];
            ok = ok && !bvp_f(s + 0.5 * h, tmp, NULL, k2, NULL, c);
            for (int i = 0; i < n; i++)
                tmp[i] = y[i] + 0.5 * h * k2[i];
            ok = ok && !bvp_f(s + 0.5 * h, tmp, NULL, k3, NULL, c);
            for (int i = 0; i < n; i++)
                tmp[i] = y[i] + h * k3[i];
            ok = ok && !bvp_f(s + h, tmp, NULL, k4, NULL, c);
            for (int i = 0; i < n && ok; i++) {
                const double v = y[i] + h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
                if (!isfinite(v) || fabs(v) > 1e8)
                    ok = 0;
                tmp[i] = v;
            }
            if (ok)
                memcpy(y, tmp, (size_t)n * sizeof(double));
        }
        memcpy(x->u + (size_t)g * n, y, (size_t)n * sizeof(double));
    }
    free(y);
}

/* the table of o (guess_t, guess_u) at the nodes, its first to last time onto [0, 1] */
static void table_guess(const dyn_bvp_opts *o, dyn_colloc_sol *x)
{
    const int n = x->n;
    const long rows = o->guess_rows, nodes = dyn_colloc_nodes(x);
    const double a = o->guess_t[0], span = o->guess_t[rows - 1] - a;
    long k = 0;
    for (long g = 0; g < nodes; g++) {
        const double t = a + span * dyn_colloc_node_time(x, g);
        while (k < rows - 2 && o->guess_t[k + 1] <= t)
            k++;
        const double dt = o->guess_t[k + 1] - o->guess_t[k];
        const double w = dt > 0 ? fmin(fmax((t - o->guess_t[k]) / dt, 0.0), 1.0) : 0.0;
        for (int i = 0; i < n; i++)
            x->u[(size_t)g * n + i] = (1 - w) * o->guess_u[(size_t)k * n + i] +
                                      w * o->guess_u[(size_t)(k + 1) * n + i];
    }
}

/* the free scalars of from into to, and into the model's parameters */
static void restore_par(bvp_ctx *c, dyn_colloc_sol *to, const dyn_colloc_sol *from)
{
    if (to->npar > 0) {
        memcpy(to->par, from->par, (size_t)to->npar * sizeof(double));
        (void)use_free(c, to->par);
    }
}

/* Newton from the guess x; when it fails, from the initial-value problem started again
 * where x ends; then the homotopy from the initial-value problem (whose solution x is at
 * h = 0) to the conditions (h = 1) in steps of h, halved on a failure (to 1e-4) and
 * doubled after an easy one */
static int solve_homotopy(const dyn_colloc_problem *p, bvp_ctx *c, dyn_colloc_sol *x,
                          const dyn_colloc_opts *no, dyn_colloc_info *inf)
{
    dyn_colloc_sol keep;
    int st = dyn_colloc_sol_copy(&keep, x);
    if (st)
        return st;
    c->h = 1.0;
    st = dyn_colloc_solve(p, x, c->ref, NULL, no, inf);
    if (st != DYN_COLLOC_ERR_NEWTON && st != DYN_COLLOC_ERR_SINGULAR &&
        st != DYN_COLLOC_ERR_FN) {
        dyn_colloc_sol_free(&keep);
        return st;
    }
    const long N = dyn_colloc_nodes(x) * x->n;
    /* a second guess: the initial-value problem again from where the first one ended (a
     * transient left behind, for conditions an attractor satisfies) */
    {
        const double *end = keep.u + (size_t)(N - x->n);
        double *y1 = malloc((size_t)x->n * sizeof(double));
        if (!y1) {
            dyn_colloc_sol_free(&keep);
            return DYN_COLLOC_ERR_NOMEM;
        }
        memcpy(y1, end, (size_t)x->n * sizeof(double));
        restore_par(c, x, &keep);
        first_guess(c, y1, x);
        free(y1);
        st = dyn_colloc_solve(p, x, c->ref, NULL, no, inf);
        if (!st) {
            dyn_colloc_sol_free(&keep);
            return 0;
        }
    }
    memcpy(x->u, keep.u, (size_t)N * sizeof(double));
    restore_par(c, x, &keep);
    double h = 0.0, dh = 0.125;
    while (h < 1.0) {
        const double next = fmin(1.0, h + dh);
        c->h = next;
        memcpy(keep.u, x->u, (size_t)N * sizeof(double));
        restore_par(c, &keep, x);
        st = dyn_colloc_solve(p, x, c->ref, NULL, no, inf);
        if (st == DYN_COLLOC_ERR_NOMEM)
            break;
        if (st) {
            memcpy(x->u, keep.u, (size_t)N * sizeof(double));
            restore_par(c, x, &keep);
            dh *= 0.5;
            if (dh < 1e-4)
                break;
            continue;
        }
        h = next;
        if (inf->iterations <= 4)
            dh = fmin(2 * dh, 0.5);
    }
    c->h = 1.0;
    dyn_colloc_sol_free(&keep);
    return st;
}

static const char *why(int st)
{
    switch (st) {
    case DYN_COLLOC_ERR_SINGULAR:
        return "Newton's matrix is singular: the conditions do not fix one solution (a "
               "periodic condition leaves the phase free?) or they contradict each other";
    case DYN_COLLOC_ERR_NEWTON:
        return "Newton's method did not converge from the initial-value problem's solution "
               "(change the initial state towards the solution, or the mesh with --ntst)";
    case DYN_COLLOC_ERR_FN:
        return "the right-hand side or a condition failed or gave NaN or Inf";
    case DYN_COLLOC_ERR_NOMEM:
        return "out of memory";
    default:
        return "bad sizes";
    }
}

void dyn_bvp_result_free(dyn_bvp_result *r)
{
    dyn_colloc_sol_free(&r->sol);
    free(r->residuals);
    r->residuals = NULL;
}

int dyn_bvp_solve(const dyn_model *m, const void *par, const double *y0, double t0, double t1,
                  const dyn_bvp_opts *o, dyn_bvp_result *r)
{
    memset(r, 0, sizeof *r);
    r->t0 = t0;
    r->t1 = t1;
    const int n = m->n_states;
    const int nphase = m->hom ? 1 : 0; /* hom_bcs: the phase condition completes them */
    if (!m->bdry || m->n_bdry + nphase != n) {
        snprintf(r->message, sizeof r->message,
                 "%s has %d boundary conditions for %d states (%s)", m->name, m->n_bdry, n,
                 nphase ? "with hom_bcs, one fewer than states is needed"
                        : "one per state is needed");
        return DYN_COLLOC_ERR_ARG;
    }
    if (!(t1 > t0)) {
        snprintf(r->message, sizeof r->message, "the interval [%g, %g] is empty", t0, t1);
        return DYN_COLLOC_ERR_ARG;
    }
    const int ifree = o ? o->free_par - 1 : -1;
    if (ifree >= m->n_params || ifree < -1 || (ifree >= 0 && o->section > n) ||
        (ifree >= 0 && o->section < 0)) {
        snprintf(r->message, sizeof r->message, "the free parameter %d or the section's state "
                 "%d is not one of the model's", ifree + 1, o->section);
        return DYN_COLLOC_ERR_ARG;
    }
    const int nfree = ifree >= 0;
    const int ntst = o && o->ntst > 0 ? o->ntst : 40;
    const int ncol = o && o->ncol > 0 ? o->ncol : 4;
    bvp_ctx c = {m, malloc(m->par_size ? m->par_size : 1), t0, t1 - t0,
                 malloc(3 * (size_t)n * sizeof(double)), 1.0, y0, ifree, NAN, 0, 0.0,
                 {0}, NULL};
    dyn_colloc_sol ref = {0}, fine_ref = {0};
    r->residuals = calloc((size_t)n, sizeof(double));
    r->section = -1;
    dyn_colloc_sol fine = {0};
    int st = !c.par || !c.work || !r->residuals ? DYN_COLLOC_ERR_NOMEM : 0;
    if (!st) {
        if (m->par_size > 0) /* a model without parameters may pass par = NULL */
            memcpy(c.par, par, m->par_size);
        st = dyn_colloc_sol_alloc(&r->sol, n, ntst, ncol, nfree);
    }
    if (!st && nfree) {
        r->sol.par[0] = c.free_set = dyn_model_get_param(m, c.par, ifree);
        if (o->section > 0) {
            c.sec = o->section - 1;
            c.sec_value = o->section_value;
        } else { /* the state moving fastest at y0, at its value there */
            if (m->rhs(t0, y0, c.work, c.par))
                st = DYN_COLLOC_ERR_FN;
            for (int i = 1; i < n && !st; i++)
                if (fabs(c.work[i]) > fabs(c.work[c.sec]))
                    c.sec = i;
            c.sec_value = y0[c.sec];
        }
        r->section = c.sec;
        r->section_value = c.sec_value;
    }
    const int table = o && o->guess_rows > 0;
    if (!st && table) {
        int ok = o->guess_rows >= 2 && o->guess_t && o->guess_u &&
                 o->guess_t[o->guess_rows - 1] > o->guess_t[0];
        for (long k = 1; ok && k < o->guess_rows; k++)
            ok = o->guess_t[k] >= o->guess_t[k - 1];
        if (!ok) {
            snprintf(r->message, sizeof r->message, "the first guess needs at least two rows "
                     "with increasing times");
            st = DYN_COLLOC_ERR_ARG;
        }
    }
    if (!st) {
        if (table)
            table_guess(o, &r->sol);
        else
            first_guess(&c, y0, &r->sol);
    }
    if (!st && m->hom) { /* the equilibria as the first guess holds them */
        if (bvp_hom_init(&c.hom, m, c.par, t0, r->sol.u, r->message, sizeof r->message))
            st = DYN_COLLOC_ERR_ARG;
        r->hom_left = c.hom.n_left;
        r->hom_right = c.hom.n_right;
    }
    const dyn_colloc_problem p = {n, nfree, m->n_bdry + nfree, 2 * nphase, bvp_f, bvp_bc,
                                  &c};
    const dyn_colloc_opts no = {o && o->tol > 0 ? o->tol : 1e-10, 40};
    dyn_colloc_info inf = {0, 0, 0};
    if (!st) {
        if (nphase && !(st = dyn_colloc_sol_copy(&ref, &r->sol)))
            c.ref = &ref;
        if (!st && table) /* Newton's method from the guess, no homotopy */
            st = dyn_colloc_solve(&p, &r->sol, c.ref, NULL, &no, &inf);
        else if (!st)
            st = solve_homotopy(&p, &c, &r->sol, &no, &inf);
        if (table && st == DYN_COLLOC_ERR_NEWTON)
            snprintf(r->message, sizeof r->message, "Newton's method did not converge from "
                     "the first guess given (a solution nearer this problem's, at parameters "
                     "nearer these, or a finer mesh with --ntst)");
    }
    if (!st) { /* a mesh adapted to the solution (the reference interpolated onto it) */
        dyn_colloc_sol *extra[1] = {&ref};
        st = dyn_colloc_adapt(&r->sol, ntst, 0, extra, nphase);
        if (!st)
            st = dyn_colloc_solve(&p, &r->sol, c.ref, NULL, &no, &inf);
    }
    r->iterations = inf.iterations;
    if (!st && !(st = dyn_colloc_sol_copy(&fine, &r->sol))) {
        double *mesh = malloc((2 * (size_t)ntst + 1) * sizeof(double));
        if (!mesh) {
            st = DYN_COLLOC_ERR_NOMEM;
        } else {
            for (int j = 0; j < ntst; j++) {
                mesh[2 * j] = r->sol.mesh[j];
                mesh[2 * j + 1] = 0.5 * (r->sol.mesh[j] + r->sol.mesh[j + 1]);
            }
            mesh[2 * ntst] = 1.0;
            st = dyn_colloc_remesh(&fine, 2 * ntst, mesh);
            if (!st && nphase && !(st = dyn_colloc_sol_copy(&fine_ref, &ref)))
                st = dyn_colloc_remesh(&fine_ref, 2 * ntst, mesh);
            free(mesh);
        }
        c.ref = nphase ? &fine_ref : NULL;
        if (!st && dyn_colloc_solve(&p, &fine, c.ref, NULL, &no, NULL)) {
            r->err_est = NAN; /* no estimate; the solution stands */
        } else if (!st) { /* at every node of the solution, not only the mesh points */
            double e = 0.0, *uf = c.work;
            const long nodes = dyn_colloc_nodes(&r->sol);
            for (long g = 0; g < nodes; g++) {
                dyn_colloc_eval(&fine, dyn_colloc_node_time(&r->sol, g), uf);
                for (int i = 0; i < n; i++)
                    e = fmax(e, fabs(r->sol.u[(size_t)g * n + i] - uf[i]));
            }
            if (nfree)
                e = fmax(e, fabs(r->sol.par[0] - fine.par[0]));
            r->err_est = e;
        }
    }
    if (!st) {
        const double *ul = r->sol.u + (size_t)(dyn_colloc_nodes(&r->sol) - 1) * n;
        if (use_free(&c, r->sol.par) || conditions(&c, r->sol.u, ul, r->residuals))
            st = DYN_COLLOC_ERR_FN;
    }
    if (st && !r->message[0])
        snprintf(r->message, sizeof r->message, "%s", why(st));
    dyn_colloc_sol_free(&fine);
    dyn_colloc_sol_free(&ref);
    dyn_colloc_sol_free(&fine_ref);
    bvp_hom_free(&c.hom);
    free(c.par);
    free(c.work);
    return st;
}
