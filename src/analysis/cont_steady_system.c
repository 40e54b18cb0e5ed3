/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady_system.c — a branch of steady motions as a system of continuation
 * (cont_steady_system.h): the residual of the steady equations chosen at the start in
 * z = (u, p) and its Jacobian by central differences, the reduced linearization B of a point
 * (A_min of dyn_linear_reduce on E, less the zero eigenvalues of the family of steady motions
 * that the held states F = E \ U label: its null vectors N = [-G_U^+ G_F; I] make
 * T = [[I, S], [0, I]], S = -G_U^+ G_F, reduce A_E to block triangular form, so
 * B = A_UU - S A_FU carries the other eigenvalues; Golub & Van Loan, Matrix Computations,
 * 4th ed., sec. 7.1.4, deflation by a similarity), the test functions as AUTO-07p's
 * (Doedel et al., AUTO-07p manual, ch. 5: LP the parameter's tangent component, BP det B
 * times its sign, HB the real part of B's complex eigenvalue nearest the imaginary axis; on a
 * spectrum symmetric under lambda -> -lambda, HH, cont_steady_krein.c, with BP det B alone
 * and no HB) and the points stored. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cont_steady_system.h"
#include "ode/cholesky.h"
#include "ode/linalg.h"

/* -1, with the model's reason (set by cont_model_set or cont_model_f) as the branch's
 * message where none is there yet */
static int sc_model_failed(sc_ctx *c)
{
    if (!c->message[0] && c->cm->message[0])
        snprintf(c->message, sizeof c->message, "%s", c->cm->message);
    return -1;
}

/* y for z = (u, p): the parameter prepared, the base state, the unknowns, the completion */
int sc_state_at(sc_ctx *c, const double *z)
{
    cont_model *cm = c->cm;
    const dyn_steady_problem *sp = c->sp;
    if (cont_model_set(cm, z[c->nu], c->p2))
        return sc_model_failed(c);
    dyn_model_initial_state(cm->m, cm->par, c->y);
    for (int i = 0; i < c->n; i++)
        if (!sp->follow || !sp->follow[i])
            c->y[i] = c->y0[i];
    for (int j = 0; j < c->nu; j++)
        c->y[sp->unknowns[j]] = z[j];
    if (sp->complete &&
        sp->complete(sp->complete_ctx, cm->t, c->y, cm->par, c->message, sizeof c->message))
        return -1;
    return cont_model_f(cm, c->y, c->f) ? sc_model_failed(c) : 0;
}

/* -1, remembering why the model or the reduction failed at z (c->why: a branch that
 * stops on failed steps says it; c->message is kept for the curves, which clear it) */
static int sc_failed_at(sc_ctx *c, const double *z)
{
    snprintf(c->why, sizeof c->why, "at %.24s = %.10g: %.100s",
             c->cm->m->params[c->cm->ip].name, z[c->nu],
             c->message[0] ? c->message : "the right-hand side failed");
    return -1;
}

static int sc_residual(void *ctx, const double *z, double *g)
{
    sc_ctx *c = ctx;
    if (sc_state_at(c, z))
        return sc_failed_at(c, z);
    for (int i = 0; i < c->nu; i++)
        g[i] = c->f[c->sp->equations[c->sel[i]]];
    return 0;
}

/* central differences of the residual, steps 2^-20 max(|z_j|, 1) */
static int sc_jacobian(void *ctx, const double *z, double *J)
{
    sc_ctx *c = ctx;
    return cont_central_jacobian(sc_residual, c, c->nu, CONT_STEPS_POW2, z, J, c->H);
}

double sc_det_lu(int n, double *a)
{
    double det = 1.0;
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

/* det of the nu x nu matrix a (overwritten), each row scaled to unit max norm first */
static double scaled_det(int n, double *a)
{
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int j = 0; j < n; j++)
            s = fmax(s, fabs(a[i * n + j]));
        if (!(s > 0.0))
            return 0.0;
        for (int j = 0; j < n; j++)
            a[i * n + j] /= s;
    }
    return sc_det_lu(n, a);
}

/* The basis P (n x k) of the admissible directions turned into the one whose rows at the
 * start's kept states are the identity: P R^-1, R = P's rows there (the same directions,
 * so the same A_min as if the constraints had kept those states). Their complete pivoting
 * keeps the states of the largest entries, which can change along a branch (the bicycle's
 * wheel rates as its steer grows) without the start's choice becoming singular. 0, or -1
 * (c->message) when the constraints keep another number of states or R is singular within
 * 1e-10 of its largest entry. */
static int keep_start_states(sc_ctx *c, int k)
{
    const size_t K = (size_t)k;
    double *R = c->Amin; /* scratch: A_min is formed after */
    if (k != c->k0) {
        snprintf(c->message, sizeof c->message,
                 "the constraints keep %d states here, %d at the start", k, c->k0);
        return -1;
    }
    /* R^T, so that each row p of P solves R^T x = p^T for its row x of P R^-1 */
    double big = 0.0;
    for (size_t a = 0; a < K; a++)
        for (size_t j = 0; j < K; j++) {
            R[j * K + a] = c->P[(size_t)c->kept0[a] * K + j];
            big = fmax(big, fabs(R[j * K + a]));
        }
    int singular = dyn_lu_factor(k, R, c->piv) != 0;
    for (size_t a = 0; a < K && !singular; a++)
        singular = !(fabs(R[a * K + a]) > 1e-10 * big);
    if (singular) {
        snprintf(c->message, sizeof c->message,
                 "the constraints no longer determine the states they determined at the start");
        return -1;
    }
    for (int i = 0; i < c->n; i++)
        dyn_lu_solve(k, R, c->piv, c->P + (size_t)i * K);
    memcpy(c->kept, c->kept0, K * sizeof *c->kept);
    return 0;
}

/* B and its eigenvalues at z (after state_at) */
int sc_reduce(sc_ctx *c)
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
        if ((k != c->k0 || memcmp(c->kept, c->kept0, (size_t)k * sizeof *c->kept) != 0) &&
            keep_start_states(c, k))
            return -1;
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
    sc_ctx *c = ctx;
    const int nu = c->nu;
    if (sc_state_at(c, z) || sc_reduce(c))
        return sc_failed_at(c, z);
    psi[0] = t[nu];
    count[0] = -1;
    double omega;
    psi[2] = hopf_test(c, &count[2], &omega);
    /* a conservative spectrum leaves the axis only in collisions: no Hopf crossing between
     * two such points (their counts are the same), while psi stays the real part, so that
     * a crossing through a point where the spectrum is conservative alone (the bicycle's
     * weave pair at v = 0) is located where that real part vanishes */
    psi[3] = sc_krein_test(nu, c->re, c->im, c->tol_b, &count[3], NULL);
    const int conservative = count[3] != -2;
    if (conservative)
        count[2] = INT_MAX;
    /* det B times the sign of the parameter's tangent component, so that a fold, where
     * det B changes sign with it, is LP alone; a conservative spectrum's det B, the product
     * of the -lambda^2 of its pairs, only touches zero at a fold (a pair through 0 and
     * back to the axis) and changes sign where a real pair crosses 0: det B itself */
    memcpy(c->Bc, c->B, (size_t)nu * (size_t)nu * sizeof *c->B);
    psi[1] = scaled_det(nu, c->Bc) * (t[nu] < 0.0 && !conservative ? -1.0 : 1.0);
    count[1] = -1;
    /* det [G_z; t^T], the continuation's own equations (Keller's test, as for equilibria):
     * its sign changes where another family of steady motions crosses, also where det B
     * does not (a conservative pitchfork crossed along its curved branch, where det B only
     * touches zero and the tangent turns: not a fold) */
    psi[4] = det;
    count[4] = -1;
    return 0;
}

static int sc_store(void *ctx, const double *z, const double *t, dyn_cont_label label)
{
    (void)t;
    sc_ctx *c = ctx;
    if (sc_state_at(c, z) || sc_reduce(c))
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
    if (label == DYN_LABEL_HH)
        sc_krein_test(c->nu, c->re, c->im, c->tol_b, &unstable, &pt.omega);
    const int critical = label == DYN_LABEL_LP || label == DYN_LABEL_BP ||
                         label == DYN_LABEL_HB || label == DYN_LABEL_HH;
    pt.stable = !critical && dyn_classify(c->nu, c->re, c->tol_b) == DYN_STABLE;
    if (dyn_branch_append(&c->d->branches[c->bi], &pt, c->y, NULL, c->re, c->im) < 0) {
        snprintf(c->message, sizeof c->message, "out of memory");
        return -1;
    }
    return 0;
}
void sc_system(cont_system *s, sc_ctx *c)
{
    memset(s, 0, sizeof *s);
    s->N = c->nu;
    s->ip = c->nu;
    s->ip2 = -1;
    s->ctx = c;
    s->residual = sc_residual;
    s->jacobian = sc_jacobian;
    s->n_tests = 5;
    s->test_label[0] = DYN_LABEL_LP;
    s->test_label[1] = DYN_LABEL_BP;
    s->test_label[2] = DYN_LABEL_HB;
    s->test_label[3] = DYN_LABEL_HH;
    s->test_label[4] = DYN_LABEL_BP;
    s->tests = sc_tests;
    s->store = sc_store;
}

int sc_follow(sc_ctx *c, const cont_system *s, cont_work *w, const dyn_cont_opts *o,
              const double *z_bp, const double *z, const double *t, dyn_cont_label start,
              int parent, long parent_point)
{
    dyn_branch *b = dyn_diagram_add(c->d, DYN_BRANCH_STEADY, c->n, c->nu, o->ip, -1);
    if (!b) {
        snprintf(c->message, sizeof c->message, "out of memory");
        return -1;
    }
    b->parent = parent;
    b->parent_point = parent_point;
    c->bi = c->d->count - 1;
    if (z_bp && s->store(s->ctx, z_bp, t, DYN_LABEL_BP))
        return -1;
    cont_loop L;
    cont_loop_from_opts(o, &L, start);
    L.missed = &c->cm->missed;
    char stop[160];
    c->why[0] = '\0';
    c->message[0] = '\0';
    const int rc = cont_follow(s, w, &L, z, t, stop, sizeof stop);
    dyn_branch *nb = &c->d->branches[c->bi];
    if (c->why[0] && strncmp(stop, "no convergence", 14) == 0)
        /* the steps failed down to the smallest where the model or the reduction fails:
         * that is why the branch ends */
        snprintf(nb->stop, sizeof nb->stop, "failed %.151s", c->why);
    else
        snprintf(nb->stop, sizeof nb->stop, "%s", stop);
    if (rc == -2 && nb->count == 0) {
        cont_diagram_drop_last(c->d);
        return -2;
    }
    return rc == -1 ? -1 : 0;
}
