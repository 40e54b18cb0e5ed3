/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady.c — a branch of steady motions (relative equilibria) in one parameter
 * (dynkit/steady.h, dyn_steady_continue): the unknowns U and the parameter p followed by the
 * pseudo-arclength loop of cont_core.c on as many of the steady equations (the derivatives
 * of the non-cyclic kept states E) as there are unknowns, chosen at the start by complete
 * pivoting. Stability and the special points come from the reduced linearization: A_min
 * (dyn_linear_reduce) on E, less the zero eigenvalues of the family of steady motions that
 * the held states F = E \ U label. Its null vectors N = [-G_U^+ G_F; I] (a steady motion
 * moved along the family stays steady) make T = [[I, S], [0, I]], S = -G_U^+ G_F, reduce
 * A_E to block triangular form, so B = A_UU - S A_FU carries the other eigenvalues
 * (Golub & Van Loan, Matrix Computations, 4th ed., sec. 7.1.4: deflation by a similarity).
 * Test functions as AUTO-07p's (Doedel et al., AUTO-07p manual, ch. 5): LP the parameter's
 * tangent component, BP det B times its sign, HB the real part of B's complex eigenvalue
 * nearest the imaginary axis. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cont_equilibrium.h"
#include "ode/cholesky.h"
#include "dynkit/steady.h"

typedef struct sc_ctx {
    cont_model *cm;
    const dyn_steady_problem *sp;
    const double *y0;
    int n, nu, ne, nf;
    int *sel;           /* the equations used: positions in E (nu) */
    int *upos, *fpos;   /* positions in E of the unknowns (nu) and the held states (nf) */
    int *epos;          /* positions in the kept states of E's states (ne) */
    int *kept, *kept0, k0;
    double *y, *f, *A, *P, *Amin, *lwork, *rwork, *AE, *S, *H, *B, *Bc, *re, *im;
    double tol_b;       /* dyn_stability_tol of B at the last reduction */
    double dropped;     /* the largest |f| of the equations left out, relative */
    dyn_diagram *d;
    int bi;
    char message[256];
} sc_ctx;

/* y for z = (u, p): the parameter prepared, the base state, the unknowns, the completion */
static int state_at(sc_ctx *c, const double *z)
{
    cont_model *cm = c->cm;
    const dyn_steady_problem *sp = c->sp;
    if (cont_model_set(cm, z[c->nu], NAN))
        return -1;
    dyn_model_initial_state(cm->m, cm->par, c->y);
    for (int i = 0; i < c->n; i++)
        if (!sp->follow || !sp->follow[i])
            c->y[i] = c->y0[i];
    for (int j = 0; j < c->nu; j++)
        c->y[sp->unknowns[j]] = z[j];
    if (sp->complete &&
        sp->complete(sp->complete_ctx, cm->t, c->y, cm->par, c->message, sizeof c->message))
        return -1;
    return cont_model_f(cm, c->y, c->f);
}

static int sc_residual(void *ctx, const double *z, double *g)
{
    sc_ctx *c = ctx;
    if (state_at(c, z))
        return -1;
    for (int i = 0; i < c->nu; i++)
        g[i] = c->f[c->sp->equations[c->sel[i]]];
    return 0;
}

/* central differences of the residual, steps 2^-20 max(|z_j|, 1) */
static int sc_jacobian(void *ctx, const double *z, double *J)
{
    sc_ctx *c = ctx;
    const int N = c->nu, M = N + 1;
    double *zt = c->H, *gp = zt + M, *gm = gp + N;
    memcpy(zt, z, (size_t)M * sizeof *zt);
    for (int j = 0; j < M; j++) {
        int ex;
        frexp(fmax(fabs(z[j]), 1.0), &ex);
        const double h = ldexp(1.0, ex - 21);
        zt[j] = z[j] + h;
        const int a = sc_residual(c, zt, gp);
        zt[j] = z[j] - h;
        const int b = a ? a : sc_residual(c, zt, gm);
        zt[j] = z[j];
        if (a || b)
            return -1;
        for (int i = 0; i < N; i++)
            J[(size_t)i * (size_t)M + (size_t)j] = (gp[i] - gm[i]) / (2.0 * h);
    }
    return 0;
}

/* det of the nu x nu matrix a (overwritten), each row scaled to unit max norm first:
 * Gaussian elimination with partial pivoting */
static double scaled_det(int n, double *a)
{
    double det = 1.0;
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int j = 0; j < n; j++)
            s = fmax(s, fabs(a[i * n + j]));
        if (!(s > 0.0))
            return 0.0;
        for (int j = 0; j < n; j++)
            a[i * n + j] /= s;
    }
    for (int col = 0; col < n; col++) {
        int p = col;
        for (int i = col + 1; i < n; i++)
            if (fabs(a[i * n + col]) > fabs(a[p * n + col]))
                p = i;
        if (a[p * n + col] == 0.0)
            return 0.0;
        if (p != col) {
            for (int j = 0; j < n; j++) {
                const double x = a[p * n + j];
                a[p * n + j] = a[col * n + j];
                a[col * n + j] = x;
            }
            det = -det;
        }
        det *= a[col * n + col];
        for (int i = col + 1; i < n; i++) {
            const double l = a[i * n + col] / a[col * n + col];
            for (int j = col; j < n; j++)
                a[i * n + j] -= l * a[col * n + j];
        }
    }
    return det;
}

/* B and its eigenvalues at z (after state_at) */
static int reduce(sc_ctx *c)
{
    cont_model *cm = c->cm;
    const dyn_steady_problem *sp = c->sp;
    const int n = c->n, ne = c->ne, nu = c->nu, nf = c->nf;
    const dyn_linearize_opts lo = {cm->jac, NULL};
    dyn_linearize_info li;
    if (dyn_linearize(cm->m, cm->t, c->y, cm->par, &lo, c->A, c->lwork, &li)) {
        snprintf(c->message, sizeof c->message, "%s", li.message);
        return -1;
    }
    cm->rhs_calls += li.rhs_calls;
    int k = n;
    if (sp->basis) {
        if (sp->basis(sp->basis_ctx, cm->t, c->y, cm->par, c->P, c->kept, &k, c->message,
                      sizeof c->message))
            return -1;
        if (k != c->k0 || memcmp(c->kept, c->kept0, (size_t)k * sizeof *c->kept) != 0) {
            snprintf(c->message, sizeof c->message,
                     "the constraints keep other states than at the start");
            return -1;
        }
    } else {
        memset(c->P, 0, (size_t)n * (size_t)n * sizeof *c->P);
        for (int i = 0; i < n; i++)
            c->P[(size_t)i * (size_t)n + (size_t)i] = 1.0;
    }
    if (dyn_linear_reduce(n, k, c->A, c->P, c->Amin, c->rwork)) {
        snprintf(c->message, sizeof c->message, "the admissible directions are dependent");
        return -1;
    }
    const size_t K = (size_t)k, NE = (size_t)ne;
    for (int a = 0; a < ne; a++)
        for (int b = 0; b < ne; b++)
            c->AE[(size_t)a * NE + (size_t)b] =
                c->Amin[(size_t)c->epos[a] * K + (size_t)c->epos[b]];
#define AE_(a, b) c->AE[(size_t)(a) * NE + (size_t)(b)]
    /* S' = G_U^+ G_F by the normal equations (G_U of full column rank) */
    const size_t NU = (size_t)nu;
    for (int a = 0; a < nu; a++)
        for (int b = 0; b <= a; b++) {
            double s = 0.0;
            for (int r = 0; r < ne; r++)
                s += AE_(r, c->upos[a]) * AE_(r, c->upos[b]);
            c->H[(size_t)a * NU + (size_t)b] = c->H[(size_t)b * NU + (size_t)a] = s;
        }
    /* a ridge of 1e-13 of the largest diagonal entry: at a branch point G_U is singular
     * and G_F lies in its range, so S stays continuous through it */
    double hmax = 0.0;
    for (int a = 0; a < nu; a++)
        hmax = fmax(hmax, c->H[(size_t)a * NU + (size_t)a]);
    for (int a = 0; a < nu; a++)
        c->H[(size_t)a * NU + (size_t)a] += 1e-13 * hmax;
    if (nf > 0 && dyn_cholesky_factor(nu, c->H)) {
        snprintf(c->message, sizeof c->message,
                 "the unknowns are not determined by the steady equations here");
        return -1;
    }
    for (int l = 0; l < nf; l++) {
        double *col = c->re; /* scratch of nu values */
        for (int a = 0; a < nu; a++) {
            double s = 0.0;
            for (int r = 0; r < ne; r++)
                s += AE_(r, c->upos[a]) * AE_(r, c->fpos[l]);
            col[a] = s;
        }
        dyn_cholesky_solve(nu, c->H, col);
        for (int a = 0; a < nu; a++)
            c->S[(size_t)a * (size_t)nf + (size_t)l] = col[a];
    }
    for (int a = 0; a < nu; a++)
        for (int b = 0; b < nu; b++) {
            double s = AE_(c->upos[a], c->upos[b]);
            for (int l = 0; l < nf; l++)
                s += c->S[(size_t)a * (size_t)nf + (size_t)l] * AE_(c->fpos[l], c->upos[b]);
            c->B[(size_t)a * NU + (size_t)b] = s;
        }
#undef AE_
    c->tol_b = dyn_stability_tol(nu, c->B, 0.0);
    memcpy(c->Bc, c->B, NU * NU * sizeof *c->B);
    if (dyn_eig_hqr(nu, c->Bc, c->re, c->im, c->message, sizeof c->message))
        return -1;
    dyn_eig_sort(nu, c->re, c->im);
    return 0;
}

/* the Hopf test on B's eigenvalues, counting the complex ones above the stability
 * tolerance (so that a conservative pair's rounding is not taken for a crossing) */
static double hopf_test(const sc_ctx *c, int *unstable, double *omega)
{
    return cont_hopf_test(c->nu, c->re, c->im, c->tol_b, unstable, omega);
}

static int sc_tests(void *ctx, const double *z, const double *t, double det, double *psi,
                    int *count)
{
    (void)det;
    sc_ctx *c = ctx;
    const int nu = c->nu;
    if (state_at(c, z) || reduce(c))
        return -1;
    psi[0] = t[nu];
    count[0] = -1;
    memcpy(c->Bc, c->B, (size_t)nu * (size_t)nu * sizeof *c->B);
    psi[1] = scaled_det(nu, c->Bc) * (t[nu] < 0.0 ? -1.0 : 1.0);
    count[1] = -1;
    double omega;
    psi[2] = hopf_test(c, &count[2], &omega);
    return 0;
}

static int sc_store(void *ctx, const double *z, const double *t, dyn_cont_label label)
{
    (void)t;
    sc_ctx *c = ctx;
    if (state_at(c, z) || reduce(c))
        return -1;
    /* the equations left out must hold too */
    double fmax_all = 1.0, worst = 0.0;
    for (int i = 0; i < c->n; i++)
        fmax_all = fmax(fmax_all, fabs(c->f[i]));
    for (int e = 0; e < c->ne; e++)
        worst = fmax(worst, fabs(c->f[c->sp->equations[e]]));
    c->dropped = fmax(c->dropped, worst / fmax_all);
    dyn_branch_point pt;
    pt.label = label;
    pt.par[0] = z[c->nu];
    pt.par[1] = NAN;
    pt.period = NAN;
    pt.l1 = NAN;
    int unstable;
    double omega;
    hopf_test(c, &unstable, &omega);
    pt.omega = label == DYN_LABEL_HB ? omega : NAN;
    const int critical = label == DYN_LABEL_LP || label == DYN_LABEL_BP || label == DYN_LABEL_HB;
    pt.stable = !critical && dyn_classify(c->nu, c->re, c->tol_b) == DYN_STABLE;
    if (dyn_branch_append(&c->d->branches[c->bi], &pt, c->y, NULL, c->re, c->im) < 0) {
        snprintf(c->message, sizeof c->message, "out of memory");
        return -1;
    }
    return 0;
}

/* The nu equations among E's ne whose rows of G_U (ne x nu, row-major) are independent:
 * Gaussian elimination with complete pivoting, pivots below 1e-10 of the largest entry
 * refused. Positions into sel; 0, or -1 when G_U's rank is below nu. */
static int select_equations(int ne, int nu, double *G, int *sel)
{
    double big = 0.0;
    for (int i = 0; i < ne * nu; i++)
        big = fmax(big, fabs(G[i]));
    int *row_used = calloc((size_t)ne, sizeof *row_used), *col_used = calloc((size_t)nu, sizeof *col_used);
    int rc = row_used && col_used && big > 0.0 ? 0 : -1;
    for (int r = 0; r < nu && !rc; r++) {
        int bi = -1, bj = -1;
        double best = 0.0;
        for (int i = 0; i < ne; i++)
            for (int j = 0; j < nu; j++)
                if (!row_used[i] && !col_used[j] && fabs(G[i * nu + j]) > best) {
                    best = fabs(G[i * nu + j]);
                    bi = i;
                    bj = j;
                }
        if (!(best > 1e-10 * big)) {
            rc = -1;
            break;
        }
        row_used[bi] = col_used[bj] = 1;
        for (int i = 0; i < ne; i++) {
            if (row_used[i])
                continue;
            const double l = G[i * nu + bj] / G[bi * nu + bj];
            for (int j = 0; j < nu; j++)
                G[i * nu + j] -= l * G[bi * nu + j];
        }
    }
    for (int i = 0, r = 0; i < ne && !rc; i++)
        if (row_used[i])
            sel[r++] = i;
    free(row_used);
    free(col_used);
    return rc;
}

static int position(const int *list, int count, int value)
{
    for (int i = 0; i < count; i++)
        if (list[i] == value)
            return i;
    return -1;
}

static int fail(dyn_cont_info *info, const char *what)
{
    snprintf(info->message, sizeof info->message, "%s", what);
    return DYN_ERR_ARG;
}

/* the start: the guess solved at the parameter's value (dyn_steady_solve), the equations
 * chosen, the kept states and positions found; z the start (u, p) */
static int start(sc_ctx *c, const dyn_model *m, const dyn_cont_opts *o, double *z,
                 dyn_cont_info *info)
{
    const dyn_steady_problem *sp = c->sp;
    const int n = c->n, nu = c->nu, ne = c->ne;
    cont_model *cm = c->cm;
    /* the base state at the start's parameters */
    dyn_model_initial_state(m, cm->par, c->y);
    for (int i = 0; i < n; i++)
        if (!sp->follow || !sp->follow[i])
            c->y[i] = c->y0[i];
    dyn_steady_unknown *un = malloc((size_t)nu * sizeof *un);
    if (!un)
        return fail(info, "out of memory");
    for (int j = 0; j < nu; j++) {
        un[j].is_param = 0;
        un[j].index = sp->unknowns[j];
    }
    const dyn_steady_opts so = {nu,          un, ne, sp->equations, sp->complete,
                                sp->complete_ctx, 0.0, 0};
    dyn_steady_info si;
    const int st = dyn_steady_solve(m, o->t, c->y, cm->par, &so, &si);
    free(un);
    if (st) {
        snprintf(info->message, sizeof info->message,
                 "no steady motion found near the start at %.40s = %.17g: %.120s",
                 m->params[o->ip].name, cm->p_set[0], si.message);
        return DYN_ERR_ARG;
    }
    for (int j = 0; j < nu; j++)
        z[j] = c->y[sp->unknowns[j]];
    z[nu] = cm->p_set[0];
    /* the kept states and E's positions among them */
    c->k0 = n;
    if (sp->basis) {
        if (sp->basis(sp->basis_ctx, o->t, c->y, cm->par, c->P, c->kept0, &c->k0, c->message,
                      sizeof c->message)) {
            snprintf(info->message, sizeof info->message, "the admissible directions: %.200s",
                     c->message);
            return DYN_ERR_ARG;
        }
    } else {
        for (int i = 0; i < n; i++)
            c->kept0[i] = i;
    }
    for (int e = 0; e < ne; e++)
        if ((c->epos[e] = position(c->kept0, c->k0, sp->equations[e])) < 0)
            return fail(info, "a state of the steady equations is not among the kept states");
    int nf = 0;
    for (int e = 0; e < ne; e++) {
        const int u = position(sp->unknowns, nu, sp->equations[e]);
        if (u >= 0)
            c->upos[u] = e;
        else
            c->fpos[nf++] = e;
    }
    for (int j = 0; j < nu; j++)
        if (position(sp->equations, ne, sp->unknowns[j]) < 0)
            return fail(info, "an unknown is not a state of the steady equations");
    c->nf = nf;
    /* G_U on every equation by differences, then the equations used */
    double *G = malloc((size_t)ne * (size_t)nu * sizeof *G), *ut = malloc(2 * (size_t)n * sizeof *ut);
    int rc = G && ut ? 0 : -1;
    for (int j = 0; j < nu && !rc; j++) {
        int ex;
        frexp(fmax(fabs(z[j]), 1.0), &ex);
        const double h = ldexp(1.0, ex - 21);
        memcpy(c->H, z, (size_t)(nu + 1) * sizeof *z);
        c->H[j] = z[j] + h;
        rc = state_at(c, c->H);
        for (int e = 0; e < ne && !rc; e++)
            ut[e] = c->f[sp->equations[e]];
        c->H[j] = z[j] - h;
        rc = rc ? rc : state_at(c, c->H);
        for (int e = 0; e < ne && !rc; e++)
            G[(size_t)e * (size_t)nu + (size_t)j] = (ut[e] - c->f[sp->equations[e]]) / (2.0 * h);
    }
    if (!rc && select_equations(ne, nu, G, c->sel))
        rc = -2;
    free(G);
    free(ut);
    if (rc == -2)
        return fail(info, "the steady equations do not determine the unknowns at the start "
                          "(a family of steady motions through it): hold some of them "
                          "(fewer unknowns)");
    if (rc)
        return fail(info, c->message[0] ? c->message : "out of memory");
    return 0;
}

int dyn_steady_continue(const dyn_model *m, const void *par, const double *y0,
                        const dyn_cont_opts *o, const dyn_steady_problem *sp, dyn_diagram *d,
                        dyn_cont_info *info)
{
    dyn_cont_info local;
    if (!info)
        info = &local;
    memset(info, 0, sizeof *info);
    if (!m || !par || !y0 || !o || !sp || !d)
        return fail(info, "a NULL argument");
    if (o->ip < 0 || o->ip >= m->n_params)
        return fail(info, "the parameter's index is out of range");
    if (!(o->ds != 0.0) || !(o->dsmin > 0.0) || !(o->dsmax >= o->dsmin) ||
        !(fabs(o->ds) >= o->dsmin) || !isfinite(o->dsmax))
        return fail(info, "the steps must satisfy 0 < dsmin <= |ds| <= dsmax (finite)");
    if (o->nmax < 2)
        return fail(info, "nmax must be at least 2");
    const int n = m->n_states, nu = sp->n_unknowns, ne = sp->n_equations;
    if (nu < 1 || ne < nu || ne > n)
        return fail(info, "give at least one unknown, and no more than the steady equations");
    cont_model cm;
    dyn_cont_opts oc = *o;
    oc.ip2 = -1;
    if (cont_model_init(&cm, m, par, &oc))
        return fail(info, "out of memory");
    const size_t N = (size_t)n, NU = (size_t)nu, NE = (size_t)ne;
    sc_ctx c;
    memset(&c, 0, sizeof c);
    c.cm = &cm;
    c.sp = sp;
    c.y0 = y0;
    c.n = n;
    c.nu = nu;
    c.ne = ne;
    c.d = d;
    int *ints = malloc((3 * N + 3 * NE + NU) * sizeof *ints);
    const size_t nd = 4 * N + 5 * N * N + dyn_linearize_work_size(n) + NE * NE + NU * NE +
                      3 * NU * NU + 6 * NU + 4;
    double *mem = malloc(nd * sizeof *mem);
    cont_work w;
    const int w_bad = cont_work_init(&w, nu);
    if (!ints || !mem || w_bad) {
        free(ints);
        free(mem);
        if (!w_bad)
            cont_work_free(&w);
        cont_model_free(&cm);
        return fail(info, "out of memory");
    }
    c.kept = ints;
    c.kept0 = c.kept + N;
    c.sel = c.kept0 + N;
    c.upos = c.sel + NU;
    c.fpos = c.upos + NE;
    c.epos = c.fpos + NE;
    c.y = mem;
    c.f = c.y + N;
    double *z = c.f + N; /* (N values: at most nu + 1 used) */
    c.A = z + N;
    c.P = c.A + N * N;
    c.Amin = c.P + N * N;
    c.rwork = c.Amin + N * N; /* dyn_linear_reduce's n k + k k + k */
    c.lwork = c.rwork + 2 * N * N + N;
    c.AE = c.lwork + dyn_linearize_work_size(n);
    c.S = c.AE + NE * NE;
    c.H = c.S + NU * NE;
    c.B = c.H + NU * NU + 4 * NU + 4; /* H is also the Jacobian's scratch: 3 nu + 1 values */
    c.Bc = c.B + NU * NU;
    c.re = c.Bc + NU * NU;
    c.im = c.re + NU;
    int rc = start(&c, m, &oc, z, info);
    if (rc == 0 && !(z[nu] >= o->parmin && z[nu] <= o->parmax)) {
        snprintf(info->message, sizeof info->message,
                 "the start %.40s = %.17g is outside [parmin, parmax] = [%.17g, %.17g]",
                 m->params[o->ip].name, z[nu], o->parmin, o->parmax);
        rc = DYN_ERR_ARG;
    }
    cont_system s;
    memset(&s, 0, sizeof s);
    s.N = nu;
    s.ip = nu;
    s.ip2 = -1;
    s.ctx = &c;
    s.residual = sc_residual;
    s.jacobian = sc_jacobian;
    s.n_tests = 3;
    s.test_label[0] = DYN_LABEL_LP;
    s.test_label[1] = DYN_LABEL_BP;
    s.test_label[2] = DYN_LABEL_HB;
    s.tests = sc_tests;
    s.store = sc_store;
    /* the residual at its rounding, as dyn_steady_solve's: 1e-12 max(||f||_inf, 1) */
    if (rc == 0 && state_at(&c, z))
        rc = fail(info, c.message[0] ? c.message : "the right-hand side failed at the start");
    s.gtol = 1.0;
    for (int i = 0; i < n && rc == 0; i++)
        s.gtol = fmax(s.gtol, fabs(c.f[i]));
    s.gtol *= 1e-12;
    double *t = NULL, *e = NULL;
    if (rc == 0) {
        t = malloc(2 * (NU + 1) * sizeof *t);
        if (!t)
            rc = fail(info, "out of memory");
        else
            e = t + NU + 1;
    }
    if (rc == 0) {
        /* Newton's method at the fixed parameter, then the tangent in the direction of ds */
        for (int i = 0; i <= nu; i++)
            e[i] = i == nu ? 1.0 : 0.0;
        if (cont_correct(&s, &w, z, e, 0.0, z, NULL))
            rc = fail(info, c.message[0] ? c.message : "Newton's method diverged at the start");
    }
    if (rc == 0) {
        e[nu] = o->ds > 0.0 ? 1.0 : -1.0;
        double det;
        if (cont_tangent(&s, &w, z, e, t, &det))
            rc = fail(info, "the start is singular (a fold or a branch point): start elsewhere");
    }
    if (rc == 0) {
        dyn_branch *b = dyn_diagram_add(d, DYN_BRANCH_STEADY, n, nu, o->ip, -1);
        if (!b) {
            rc = fail(info, "out of memory");
        } else {
            c.bi = d->count - 1;
            cont_loop L;
            cont_loop_from_opts(o, &L, DYN_LABEL_EP);
            char stop[160];
            const int fr = cont_follow(&s, &w, &L, z, t, stop, sizeof stop);
            snprintf(d->branches[c.bi].stop, sizeof d->branches[c.bi].stop, "%s", stop);
            if (fr)
                rc = fail(info, c.message[0] ? c.message : "out of memory");
        }
    }
    if (rc == 0 && c.dropped > 1e-8)
        snprintf(info->message, sizeof info->message,
                 "the steady equations not used hold only to %.3g relative", c.dropped);
    info->points = rc == 0 ? d->branches[c.bi].count : 0;
    info->newton_steps = w.newton;
    info->rhs_calls = cm.rhs_calls;
    free(t);
    free(ints);
    free(mem);
    cont_work_free(&w);
    cont_model_free(&cm);
    return rc;
}
