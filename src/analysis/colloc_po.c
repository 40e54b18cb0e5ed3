/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_po.c — branches of periodic orbits by orthogonal collocation and pseudo-arclength
 * continuation, as AUTO-07p computes them (Doedel, AUTO-07p manual, ch. 11 and 13; Doedel,
 * Keller & Kernevez 1991): the orbit's time scaled to [0, 1], u' = T f(u, lambda), periodic
 * boundary conditions, the integral phase condition against the previous orbit, the period
 * T and the parameter lambda free. The start from a Hopf point steps along the critical
 * eigenvector's oscillation; the start from a period doubling steps along the eigenfunction
 * of the multiplier -1 on the orbit traversed twice (branch switching as at a branch point).
 * Floquet multipliers are the eigenvalues of the collocation system's monodromy matrix
 * (colloc_newton.c). Folds of cycles (LPC: d lambda/ds changes sign), period doublings (PD:
 * prod (mu_i + 1) over the non-trivial multipliers changes sign) and torus bifurcations (TR:
 * a complex pair crosses the unit circle, prod (mu_i mu_j - 1) changes sign with as many
 * pairs on both sides) are located by secant steps in the arclength from the last point
 * before the change (when several change in one step, the first along it); a branch that
 * reaches another Hopf point (the orbit's oscillation reverses) ends there, and one that
 * comes back onto its own orbits (a closed loop of cycles) ends where it does. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h"
#include "analysis/colloc_internal.h"
#include "ode/linalg.h"

typedef struct po_ctx {
    const dyn_po_system *sys;
    double *J; /* n x n */
} po_ctx;

static int po_f(double t, const double *u, const double *par, double *f, double *fu, void *ctx)
{
    (void)t;
    po_ctx *c = ctx;
    const int n = c->sys->n;
    if (c->sys->f(u, par[1], f, fu ? c->J : NULL, c->sys->ctx))
        return 1;
    for (int i = 0; i < n; i++)
        f[i] *= par[0];
    if (fu)
        for (int i = 0; i < n * n; i++)
            fu[i] = par[0] * c->J[i];
    return 0;
}

static int po_bc(const double *u0, const double *u1, const double *par, double *g, void *ctx)
{
    (void)par;
    const po_ctx *c = ctx;
    for (int i = 0; i < c->sys->n; i++)
        g[i] = u0[i] - u1[i];
    return 0;
}

void dyn_po_branch_free(dyn_po_branch *b)
{
    for (int k = 0; k < b->npoints; k++) {
        free(b->pts[k].xmax);
        dyn_colloc_sol_free(&b->pts[k].orbit);
        dyn_colloc_sol_free(&b->pts[k].tangent);
    }
    free(b->pts);
    memset(b, 0, sizeof *b);
}

/* multipliers of orbit x (sorted: the nearest to 1 first) */
static int multipliers(dyn_colloc_problem *p, const dyn_colloc_sol *x, const dyn_eig_solver *eig,
                       double *re, double *im)
{
    const int n = x->n;
    double *M = malloc((size_t)n * n * sizeof(double));
    if (!M)
        return DYN_COLLOC_ERR_NOMEM;
    int st = dyn_colloc_monodromy(p, x, M);
    char err[128];
    if (!st && eig->eigenvalues(n, M, re, im, err, sizeof err))
        st = DYN_COLLOC_ERR_SINGULAR;
    free(M);
    if (st)
        return st;
    int k1 = 0;
    for (int i = 1; i < n; i++)
        if (hypot(re[i] - 1, im[i]) < hypot(re[k1] - 1, im[k1]))
            k1 = i;
    double r = re[k1], m = im[k1];
    re[k1] = re[0];
    im[k1] = im[0];
    re[0] = r;
    im[0] = m;
    return 0;
}

int dyn_po_multipliers(const dyn_po_system *sys, const dyn_colloc_sol *orbit,
                       const dyn_eig_solver *eig, double *re, double *im)
{
    double *J = malloc((size_t)sys->n * sys->n * sizeof(double));
    if (!J)
        return DYN_COLLOC_ERR_NOMEM;
    po_ctx c = {sys, J};
    dyn_colloc_problem p = {sys->n, 2, sys->n, 1, po_f, po_bc, &c};
    int st = multipliers(&p, orbit, eig, re, im);
    free(J);
    return st;
}

/* the test functions of a point: LPC, PD, TR */
typedef struct po_tests {
    double lpc, pd, tr;
    int tr_complex; /* the multiplier nearest the unit circle is complex */
    int tr_pairs;   /* the number of complex pairs in tr's product */
    int have_mult;
    int pd_tr;      /* PD and TR can be told: 3 states or more and the multipliers accurate */
    int bp_ok;      /* Keller's determinant computed (and the multipliers accurate) */
    int bp_sign;    /* its sign and */
    double bp_log;  /* log |det| (colloc_bp.c) */
} po_tests;

/* the trivial multiplier's largest distance from 1 at which the others are trusted for PD
 * and TR (AUTO-07p's FNSPBV: detection stops beyond 5e-2) */
#define PO_TRIVIAL_TOL 5e-2

/* the largest correction of a step, in steps (see the loop) */
#define PO_JUMP 2.0

static void tests_of(const double *re, const double *im, int n, double dlambda, int have,
                     po_tests *t)
{
    t->lpc = dlambda;
    t->have_mult = have;
    t->pd = t->tr = 1.0;
    t->tr_complex = t->tr_pairs = 0;
    /* a planar flow has no PD or TR: its one non-trivial multiplier is exp(int div f) > 0;
     * a trivial multiplier far from 1 says the others are rounding (an orbit near a
     * homoclinic one, its multipliers ~1e6 and more, on too coarse a mesh) */
    t->pd_tr = have && n >= 3 && hypot(re[0] - 1.0, im[0]) <= PO_TRIVIAL_TOL;
    if (!have)
        return;
    double pr = 1.0, pi = 0.0;
    for (int i = 1; i < n; i++) { /* prod (mu + 1), complex */
        const double a = re[i] + 1.0, b = im[i];
        const double r2 = pr * a - pi * b, i2 = pr * b + pi * a;
        pr = r2;
        pi = i2;
    }
    t->pd = pr;
    double tr = 1.0, best = INFINITY;
    for (int i = 1; i < n; i++) {
        for (int j = i + 1; j < n; j++) { /* Re(mu_i mu_j) - 1 for conjugates: |mu|^2 - 1 */
            if (fabs(im[i] + im[j]) > 1e-12 * (1 + fabs(im[i])) || im[i] == 0.0)
                continue;
            if (fabs(re[i] - re[j]) > 1e-9 * (1 + fabs(re[i])))
                continue;
            tr *= re[i] * re[i] + im[i] * im[i] - 1.0;
            t->tr_pairs++;
        }
        const double d = fabs(hypot(re[i], im[i]) - 1.0);
        if (d < best) {
            best = d;
            t->tr_complex = fabs(im[i]) > 1e-6;
        }
    }
    t->tr = tr;
}

/* the branch-point test's value, its determinant relative to exp(ref) (a continuous
 * function for the secant steps) */
static double bp_value(const po_tests *t, double ref)
{
    return t->bp_sign * exp(fmin(fmax(t->bp_log - ref, -700.0), 700.0));
}

/* the value of test `which` (0 LPC, 1 PD, 2 TR, 5 BP relative to exp(ref)) */
static double test_value(const po_tests *t, int which, double ref)
{
    return which == 0 ? t->lpc : which == 1 ? t->pd : which == 2 ? t->tr : bp_value(t, ref);
}

static void set_test_value(po_tests *t, int which, double v)
{
    if (which == 0)
        t->lpc = v;
    else if (which == 1)
        t->pd = v;
    else if (which == 2)
        t->tr = v;
    else
        t->bp_sign = v > 0 ? 1 : -1;
}

/* A cycle's parameter is computed to the collocation's discretization error, which moves
 * with the mesh as it adapts: along a branch that has settled at a homoclinic orbit's
 * parameter, the period growing, it wanders by a few 1e-8 (a published pituitary cell
 * model, 37 such "folds" within 7e-8 at periods 940 to 1180). A fold whose parameter is
 * within this of both ends of its step is that wandering. */
#define PO_FOLD_NOISE 1e-7

/* the first of the tests LPC, BP, PD, TR (other than `skip`; 0, 5, 1, 2) that changed sign
 * from a to b, or -1. LPC: |d lambda/ds| above the rounding of a vertical branch on one
 * side at least; TR: a pair's modulus through 1, not two real multipliers meeting as a
 * pair (the product then gains a factor |mu|^2 - 1 wherever the pair lies) */
static int first_change(const po_tests *a, const po_tests *b, int skip)
{
    if (skip != 0 && (b->lpc > 0) != (a->lpc > 0) &&
        fmax(fabs(b->lpc), fabs(a->lpc)) > DYN_CONT_FOLD_NOISE)
        return 0;
    if (skip != 5 && b->bp_ok && a->bp_ok && b->bp_sign != a->bp_sign)
        return 5;
    if (skip != 1 && b->pd_tr && a->pd_tr && (b->pd > 0) != (a->pd > 0))
        return 1;
    if (skip != 2 && b->pd_tr && a->pd_tr && (b->tr > 0) != (a->tr > 0) &&
        b->tr_complex && b->tr_pairs == a->tr_pairs)
        return 2;
    return -1;
}

typedef struct po_run {
    const dyn_po_system *sys;
    const dyn_po_opts *o;
    po_ctx c;
    dyn_colloc_problem p;
    dyn_colloc_opts nopts;
    dyn_po_branch *b;
    double *re, *im, *scratch; /* n, n and 3 n doubles */
    double bound; /* the parameter's bound crossed (locate's test 3) */
    double bp_ref; /* log |det| of the branch-point test at the step's start (test 5) */
} po_run;

/* the extreme of state i near node g (sign 1: a maximum, -1: a minimum) of the orbit's
 * piecewise polynomial, by golden-section search between the neighbouring nodes (periodic:
 * the nodes wrap around); u: n doubles of scratch */
static double refine_extreme(const dyn_colloc_sol *x, int i, long g, double sign, double *u)
{
    const long last = dyn_colloc_nodes(x) - 1;
    const double tg = dyn_colloc_node_time(x, g);
    double a = g > 0 ? dyn_colloc_node_time(x, g - 1) : dyn_colloc_node_time(x, last - 1) - 1;
    double b = g < last ? dyn_colloc_node_time(x, g + 1) : 1 + dyn_colloc_node_time(x, 1);
    double best = sign * x->u[(size_t)g * x->n + i];
    (void)tg;
    const double gr = 0.5 * (sqrt(5.0) - 1.0);
#define AT(t) (dyn_colloc_eval(x, (t) - floor(t), u), sign * u[i])
    double c = b - gr * (b - a), d = a + gr * (b - a), fc = AT(c), fd = AT(d);
    for (int it = 0; it < 60; it++) {
        if (fc > fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - gr * (b - a);
            fc = AT(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + gr * (b - a);
            fd = AT(d);
        }
    }
#undef AT
    best = fmax(best, fmax(fc, fd));
    return sign * best;
}

/* append x as a point; keep its orbit when keep */
static int record(po_run *r, const dyn_colloc_sol *x, const double *re, const double *im,
                  int have_mult, const char *label, int keep)
{
    dyn_po_branch *b = r->b;
    const int n = r->sys->n;
    if (b->npoints == b->cap) {
        const int cap = b->cap ? 2 * b->cap : 64;
        dyn_po_point *np = realloc(b->pts, (size_t)cap * sizeof *np);
        if (!np)
            return DYN_COLLOC_ERR_NOMEM;
        b->pts = np;
        b->cap = cap;
    }
    dyn_po_point *pt = &b->pts[b->npoints];
    memset(pt, 0, sizeof *pt);
    pt->xmax = malloc(4 * (size_t)n * sizeof(double));
    if (!pt->xmax)
        return DYN_COLLOC_ERR_NOMEM;
    pt->xmin = pt->xmax + n;
    pt->mult_re = pt->xmin + n;
    pt->mult_im = pt->mult_re + n;
    pt->period = x->par[0];
    pt->par = x->par[1];
    const long nodes = dyn_colloc_nodes(x);
    for (int i = 0; i < n; i++) {
        pt->xmax[i] = -INFINITY;
        pt->xmin[i] = INFINITY;
    }
    for (int i = 0; i < n; i++) {
        long gmax = 0, gmin = 0;
        for (long g = 1; g < nodes; g++) {
            const double v = x->u[(size_t)g * n + i];
            if (v > x->u[(size_t)gmax * n + i])
                gmax = g;
            if (v < x->u[(size_t)gmin * n + i])
                gmin = g;
        }
        pt->xmax[i] = refine_extreme(x, i, gmax, 1.0, r->scratch);
        pt->xmin[i] = refine_extreme(x, i, gmin, -1.0, r->scratch);
    }
    dyn_colloc_sol u = *x;
    u.npar = 0;
    pt->l2norm = sqrt(dyn_colloc_dot(&u, &u));
    pt->stable = -1;
    for (int i = 0; i < n; i++) {
        pt->mult_re[i] = have_mult ? re[i] : NAN;
        pt->mult_im[i] = have_mult ? im[i] : NAN;
    }
    if (have_mult) {
        pt->stable = 1;
        for (int i = 1; i < n; i++)
            if (!(hypot(re[i], im[i]) < 1.0))
                pt->stable = 0;
        /* a located fold, flip, torus or branch point has a multiplier on the unit circle,
         * whatever side of it the computed one fell (Roessler's PD at a = 0.8478:
         * -0.9999999999994) */
        if (!strcmp(label, "LPC") || !strcmp(label, "PD") || !strcmp(label, "TR") ||
            !strcmp(label, "BP"))
            pt->stable = 0;
    }
    snprintf(pt->label, sizeof pt->label, "%s", label);
    b->npoints++;
    if (keep && dyn_colloc_sol_copy(&pt->orbit, x))
        return DYN_COLLOC_ERR_NOMEM;
    return 0;
}

/* a corrector step from x0 along t0 by ds into x (allocated), its tangent into t */
static int step(po_run *r, const dyn_colloc_sol *x0, const dyn_colloc_sol *t0, double ds,
                dyn_colloc_sol *x, dyn_colloc_sol *t, dyn_colloc_info *inf)
{
    int st = dyn_colloc_sol_copy(x, x0);
    if (st)
        return st;
    const long N = dyn_colloc_nodes(x0) * x0->n;
    for (long i = 0; i < N; i++)
        x->u[i] += ds * t0->u[i];
    for (int k = 0; k < x0->npar; k++)
        x->par[k] += ds * t0->par[k];
    dyn_colloc_sol ref;
    st = dyn_colloc_sol_copy(&ref, x);
    if (st) {
        dyn_colloc_sol_free(x);
        return st;
    }
    dyn_colloc_arc arc = {x0, t0, ds};
    st = dyn_colloc_solve(&r->p, x, &ref, &arc, &r->nopts, inf);
    dyn_colloc_sol_free(&ref);
    if (!st && !(x->par[0] > 0))
        st = DYN_COLLOC_ERR_NEWTON; /* a period that is not positive */
    if (!st)
        st = dyn_colloc_tangent(&r->p, x, x, t0, t);
    if (st)
        dyn_colloc_sol_free(x);
    return st;
}

/* the corrector's distance from the predictor x0 + ds t0 to x (the collocation norm with
 * the parameter; not the period, which near a Hopf point of a small frequency moves by
 * many steps while the orbit moves by one: the Gray-Scott cycles of period 148 at k =
 * 0.0583 gain 0.01 in period at the step 0.002), or -1 without memory */
static double correction(const dyn_colloc_sol *x0, const dyn_colloc_sol *t0, double ds,
                         const dyn_colloc_sol *x)
{
    dyn_colloc_sol d;
    if (dyn_colloc_sol_copy(&d, x))
        return -1.0;
    const long N = dyn_colloc_nodes(x0) * x0->n;
    for (long i = 0; i < N; i++)
        d.u[i] -= x0->u[i] + ds * t0->u[i];
    for (int k = 0; k < x0->npar; k++)
        d.par[k] -= x0->par[k] + ds * t0->par[k];
    d.par[0] = 0.0; /* the period */
    const double c = sqrt(dyn_colloc_dot(&d, &d));
    dyn_colloc_sol_free(&d);
    return c;
}

/* the mean over [0, 1] of the states of x into mean (n doubles), by the trapezoidal rule
 * over the nodes */
static void orbit_mean(const dyn_colloc_sol *x, double *mean)
{
    const int n = x->n;
    const long nodes = dyn_colloc_nodes(x);
    for (int i = 0; i < n; i++)
        mean[i] = 0.0;
    for (long g = 0; g + 1 < nodes; g++) {
        const double h = dyn_colloc_node_time(x, g + 1) - dyn_colloc_node_time(x, g);
        for (int i = 0; i < n; i++)
            mean[i] += 0.5 * h * (x->u[(size_t)g * n + i] + x->u[(size_t)(g + 1) * n + i]);
    }
}

/* the integral over [0, 1] of (u - mean u) . (v - mean v): how much the oscillation of u is
 * that of v. Two orbits on either side of a Hopf point that the step went through give a
 * negative value: there the amplitude passes through zero and the orbit comes back on
 * itself shifted by half a period (the phase condition aligns it so), while the
 * parameter turns as at a fold. Trapezoidal rule over u's nodes, v evaluated there; w:
 * 3 n doubles of scratch. */
static double oscillation_dot(const dyn_colloc_sol *u, const dyn_colloc_sol *v, double *w)
{
    const int n = u->n;
    double *mu = w, *mv = w + n, *vg = w + 2 * n;
    orbit_mean(u, mu);
    orbit_mean(v, mv);
    const long nodes = dyn_colloc_nodes(u);
    double sum = 0.0, prev = 0.0;
    for (long g = 0; g < nodes; g++) {
        const double tg = dyn_colloc_node_time(u, g);
        dyn_colloc_eval(v, tg, vg);
        double d = 0.0;
        for (int i = 0; i < n; i++)
            d += (u->u[(size_t)g * n + i] - mu[i]) * (vg[i] - mv[i]);
        if (g > 0)
            sum += 0.5 * (tg - dyn_colloc_node_time(u, g - 1)) * (d + prev);
        prev = d;
    }
    return sum;
}

/* whether a multiplier other than the trivial one (re[0], im[0]) lies near 1: within
 * PO_TRIVIAL_TOL (two multipliers at 1 form a Jordan block, each accurate to about the
 * square root of the rounding) */
static int second_unit_multiplier(const double *re, const double *im, int n)
{
    for (int i = 1; i < n; i++)
        if (hypot(re[i] - 1.0, im[i]) <= PO_TRIVIAL_TOL)
            return 1;
    return 0;
}

static int point_tests(po_run *r, const dyn_colloc_sol *x, const dyn_colloc_sol *t, po_tests *pt)
{
    int have = 0;
    if (r->o->eig) {
        int st = multipliers(&r->p, x, r->o->eig, r->re, r->im);
        if (st)
            return st;
        have = 1;
    }
    tests_of(r->re, r->im, x->n, t->par[1], have, pt);
    /* Keller's test, trusted where the multipliers are (the trivial one near 1) */
    pt->bp_sign = 1;
    pt->bp_log = 0.0;
    pt->bp_ok = !colloc_bp_test(&r->p, x, t, &pt->bp_sign, &pt->bp_log) &&
                isfinite(pt->bp_log) &&
                (!have || hypot(r->re[0] - 1.0, r->im[0]) <= PO_TRIVIAL_TOL);
    return 0;
}

/* the arclength in (0, ds) where test `which` (0 LPC, 1 PD, 2 TR, 3 the parameter minus
 * r->bound, 4 the oscillation's product with x0's: a Hopf point) is zero, by the Illinois
 * variant of regula falsi; the point and its tangent into x, t, its arclength into *s_at */
static int locate(po_run *r, const dyn_colloc_sol *x0, const dyn_colloc_sol *t0, double ds,
                  double psi0, double psi1, int which, dyn_colloc_sol *x, dyn_colloc_sol *t,
                  double *s_at)
{
    double sa = 0.0, sb = ds, fa = psi0, fb = psi1;
    int side = 0, st = DYN_COLLOC_ERR_NEWTON;
    for (int it = 0; it < 16; it++) {
        const double s = sb - fb * (sb - sa) / (fb - fa);
        dyn_colloc_info inf;
        dyn_colloc_sol xs, ts;
        st = step(r, x0, t0, s, &xs, &ts, &inf);
        if (st)
            return st;
        po_tests pt;
        st = point_tests(r, &xs, &ts, &pt);
        if (st) {
            dyn_colloc_sol_free(&xs);
            dyn_colloc_sol_free(&ts);
            return st;
        }
        const double fs = which == 0   ? pt.lpc
                          : which == 1 ? pt.pd
                          : which == 2 ? pt.tr
                          : which == 3 ? xs.par[1] - r->bound
                                       : oscillation_dot(&xs, x0, r->scratch);
        if (x->u)
            dyn_colloc_sol_free(x);
        if (t->u)
            dyn_colloc_sol_free(t);
        *x = xs;
        *t = ts;
        *s_at = s;
        if (fabs(sb - sa) < 1e-12 * fabs(ds) || fs == 0.0 ||
            fabs(s - sa) < 1e-11 * fabs(ds) || fabs(s - sb) < 1e-11 * fabs(ds))
            break;
        if ((fs > 0) == (fb > 0)) {
            sb = s;
            fb = fs;
            if (side == -1)
                fa *= 0.5;
            side = -1;
        } else {
            sa = s;
            fa = fs;
            if (side == 1)
                fb *= 0.5;
            side = 1;
        }
        if (fabs(fs) < 1e-13)
            break;
    }
    return 0;
}

/* the step of arclength s from x0 along t0 (a bp_step) and its branch-point test into *y,
 * *g: colloc_bp_locate's points */
typedef struct bp_step {
    po_run *r;
    const dyn_colloc_sol *x0, *t0;
} bp_step;

static int bp_point(void *ctx, double s, dyn_colloc_sol *y, double *g)
{
    const bp_step *c = ctx;
    dyn_colloc_info inf;
    dyn_colloc_sol ts;
    int st = step(c->r, c->x0, c->t0, s, y, &ts, &inf);
    if (st)
        return st;
    po_tests pt;
    st = point_tests(c->r, y, &ts, &pt);
    dyn_colloc_sol_free(&ts);
    if (st)
        dyn_colloc_sol_free(y);
    else
        *g = bp_value(&pt, c->r->bp_ref);
    return st;
}

/* locate for the branch-point test (its value psi0 at x0, psi1 at ds; colloc_bp.c). t: x0's
 * tangent t0 (at the branch point the bordered system that gives the tangent is singular,
 * any mix of the two branches' directions solving it: the branch goes on, and the other
 * leaves orthogonally to it, along t0) */
static int locate_bp(po_run *r, const dyn_colloc_sol *x0, const dyn_colloc_sol *t0, double ds,
                     double psi0, double psi1, dyn_colloc_sol *x, dyn_colloc_sol *t,
                     double *s_at)
{
    bp_step c = {r, x0, t0};
    int st = colloc_bp_locate(bp_point, &c, x0, ds, psi0, psi1, x, s_at);
    if (!st && (st = dyn_colloc_sol_copy(t, t0)))
        dyn_colloc_sol_free(x);
    return st;
}

/* the orbit's amplitude (the largest max - min of a state over the nodes); its size (the
 * largest |u|) into *size */
static double orbit_amplitude(const dyn_colloc_sol *x, double *size)
{
    const int n = x->n;
    const long nodes = dyn_colloc_nodes(x);
    double amp = 0.0, big = 0.0;
    for (int i = 0; i < n; i++) {
        double lo = INFINITY, hi = -INFINITY;
        for (long g = 0; g < nodes; g++) {
            lo = fmin(lo, x->u[(size_t)g * n + i]);
            hi = fmax(hi, x->u[(size_t)g * n + i]);
        }
        amp = fmax(amp, hi - lo);
        big = fmax(big, fmax(fabs(lo), fabs(hi)));
    }
    if (size)
        *size = big;
    return amp;
}

static int amplitude_small(const dyn_colloc_sol *x)
{
    double size;
    const double amp = orbit_amplitude(x, &size);
    return amp < 1e-7 * (1.0 + size);
}

/* the value of o->at that the parameter crosses from p0 to p1 nearest p0, or -1; a value
 * p0 sits on (a UZ point just computed) is not crossed again */
static int at_crossed(const dyn_po_opts *o, double p0, double p1)
{
    int best = -1;
    for (int u = 0; u < o->n_at; u++) {
        const double v = o->at[u], a = p0 - v, b = p1 - v;
        if (fabs(a) <= 1e-9 * fmax(1.0, fabs(v)))
            continue;
        if (!((a < 0 && b >= 0) || (a > 0 && b <= 0)))
            continue;
        if (best < 0 || fabs(a) < fabs(p0 - o->at[best]))
            best = u;
    }
    return best;
}

/* the distance between points a and b of a branch in what does not depend on the orbits'
 * phase: the parameter, the period, each state's maximum and minimum */
static double point_distance(const dyn_po_point *a, const dyn_po_point *b, int n)
{
    double s = (a->par - b->par) * (a->par - b->par) +
               (a->period - b->period) * (a->period - b->period);
    for (int i = 0; i < n; i++)
        s += (a->xmax[i] - b->xmax[i]) * (a->xmax[i] - b->xmax[i]) +
             (a->xmin[i] - b->xmin[i]) * (a->xmin[i] - b->xmin[i]);
    return sqrt(s);
}

/* the distance from point p to the chord from a to c (the same coordinates) */
static double chord_distance(const dyn_po_point *p, const dyn_po_point *a,
                             const dyn_po_point *c, int n)
{
    const double ac = point_distance(a, c, n), ap = point_distance(a, p, n);
    if (!(ac > 0))
        return ap;
    const double cp = point_distance(c, p, n);
    /* the foot of the perpendicular, from the three sides (law of cosines) */
    const double f = (ap * ap - cp * cp + ac * ac) / (2.0 * ac);
    if (f <= 0)
        return ap;
    if (f >= ac)
        return cp;
    return sqrt(fmax(0.0, ap * ap - f * f));
}

/* whether the branch's last point came back onto a chord of the branch computed before it:
 * within a tenth of that chord's length (or of the last step's, the larger), the branch
 * having gone more than ten times as far from that chord in between (a closed loop of
 * cycles, as the period-doubled cycles that meet their own primary branch at both ends,
 * followed round again). The chord's first point, or -1. */
static int back_on_branch(const dyn_po_branch *b)
{
    const int last = b->npoints - 1, n = b->n;
    if (last < 4)
        return -1;
    const dyn_po_point *p = &b->pts[last];
    const double step = point_distance(p, &b->pts[last - 1], n);
    for (int k = 0; k + 1 < last - 2; k++) {
        const dyn_po_point *a = &b->pts[k], *c = &b->pts[k + 1];
        const double tol = 0.1 * fmax(point_distance(a, c, n), step);
        if (!(chord_distance(p, a, c, n) <= tol))
            continue;
        for (int j = k + 2; j < last; j++)
            if (chord_distance(&b->pts[j], a, c, n) > 10.0 * tol)
                return k;
    }
    return -1;
}

/* continue from x (a solution or the Hopf point) along t; x and t are consumed */
static int po_continue(po_run *r, dyn_colloc_sol *x, dyn_colloc_sol *t)
{
    const dyn_po_opts *o = r->o;
    dyn_po_branch *b = r->b;
    const double dsmax = o->dsmax > 0 ? o->dsmax : 0.5;
    const double dsmin = o->dsmin > 0 ? o->dsmin : 1e-5;
    double ds = o->ds != 0 ? o->ds : 0.01;
    if (fabs(ds) > dsmax)
        ds = copysign(dsmax, ds);
    const int nmax = o->nmax > 0 ? o->nmax : 100;
    const int adapt = o->adapt == 0 ? 3 : o->adapt;
    const int ntst = x->ntst;
    const int bounded = o->par_max > o->par_min;
    po_tests prev_tests = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0.0};
    int have_prev = 0, st = 0, since_adapt = 0;
    snprintf(b->message, sizeof b->message, "%d points (nmax)", nmax);
    /* the new point and its tangent: moved into x, t when it is stored, else freed after
     * the loop (empty ones free nothing) */
    dyn_colloc_sol xn = {0}, tn = {0};
    while (b->npoints < nmax) {
        dyn_colloc_info inf;
        st = step(r, x, t, ds, &xn, &tn, &inf);
        /* a corrector that went farther from the predictor than twice the step went over
         * to other orbits (Morris-Lecar's small cycles near their Hopf point jumped onto the
         * large ones): the step is halved as after a failure */
        if (!st && correction(x, t, ds, &xn) > PO_JUMP * fabs(ds)) {
            dyn_colloc_sol_free(&xn);
            dyn_colloc_sol_free(&tn);
            st = DYN_COLLOC_ERR_NEWTON;
        }
        if (st) {
            if (st == DYN_COLLOC_ERR_NOMEM)
                break;
            ds *= 0.5;
            if (fabs(ds) < dsmin) {
                snprintf(b->message, sizeof b->message,
                         "no convergence with the step at dsmin = %g at parameter %.10g, "
                         "period %.10g", dsmin, x->par[1], x->par[0]);
                break;
            }
            st = 0;
            continue;
        }
        po_tests now;
        st = point_tests(r, &xn, &tn, &now);
        if (st) {
            snprintf(b->message, sizeof b->message, "the Floquet multipliers failed");
            break;
        }
        /* through a Hopf point (the parameter turned and the oscillation reversed): the
         * branch ends there, on the point located where the oscillation vanishes, or on x
         * when it is not found */
        int hopf_end = 0;
        const double osc0 = oscillation_dot(x, x, r->scratch);
        const double osc1 = oscillation_dot(&xn, x, r->scratch);
        if (have_prev && (now.lpc > 0) != (prev_tests.lpc > 0) &&
            osc1 < -0.5 * sqrt(osc0 * oscillation_dot(&xn, &xn, r->scratch))) {
            dyn_colloc_sol xh = {0}, th = {0};
            double s_h;
            dyn_colloc_sol_free(&xn);
            dyn_colloc_sol_free(&tn);
            if (locate(r, x, t, ds, osc0, osc1, 4, &xh, &th, &s_h) ||
                point_tests(r, &xh, &th, &now)) {
                dyn_colloc_sol_free(&xh);
                dyn_colloc_sol_free(&th);
                snprintf(b->message, sizeof b->message,
                         "the orbit shrank to an equilibrium: a Hopf point past parameter "
                         "%.10g", x->par[1]);
                b->hopf_end = 1;
                break;
            }
            xn = xh;
            tn = th;
            hopf_end = 1;
        }
        /* a value of o->at crossed: the step ends there (a UZ point) unless a label
         * comes before it */
        double s_end = ds;
        int uz = hopf_end ? -1 : at_crossed(o, x->par[1], xn.par[1]);
        if (uz >= 0) {
            dyn_colloc_sol xu = {0}, tu = {0};
            r->bound = o->at[uz];
            if (!locate(r, x, t, ds, x->par[1] - r->bound, xn.par[1] - r->bound, 3, &xu, &tu,
                        &s_end)) {
                dyn_colloc_sol_free(&xn);
                dyn_colloc_sol_free(&tn);
                xn = xu;
                tn = tu;
                st = point_tests(r, &xn, &tn, &now);
                if (st)
                    break;
            } else {
                s_end = ds;
                uz = -1;
            }
        }
        /* a test that changed sign in the step is located; when another one changed between
         * the step's start and the located point, that one comes first along the branch and
         * is located instead (a PD just before a fold of cycles is not lost to the LPC) */
        int which = have_prev && !hopf_end ? first_change(&prev_tests, &now, -1) : -1;
        const double lambda_end = xn.par[1];
        double s_far = s_end;
        po_tests far = now;
        for (int round = 0; which >= 0; round++) {
            r->bp_ref = prev_tests.bp_log;
            const double p0 = test_value(&prev_tests, which, r->bp_ref),
                         p1 = test_value(&far, which, r->bp_ref);
            dyn_colloc_sol xl = {0}, tl = {0};
            double s_l;
            po_tests at;
            if (which == 5 ? locate_bp(r, x, t, s_far, p0, p1, &xl, &tl, &s_l)
                           : locate(r, x, t, s_far, p0, p1, which, &xl, &tl, &s_l)) {
                dyn_colloc_sol_free(&xl);
                dyn_colloc_sol_free(&tl);
                which = -1; /* the whole step, its multipliers again (locate's were last) */
                st = point_tests(r, &xn, &tn, &now);
                break;
            }
            st = point_tests(r, &xl, &tl, &at);
            if (st) {
                dyn_colloc_sol_free(&xl);
                dyn_colloc_sol_free(&tl);
                break;
            }
            const int before = round < 3 ? first_change(&prev_tests, &at, which) : -1;
            if (before >= 0) {
                dyn_colloc_sol_free(&xl);
                dyn_colloc_sol_free(&tl);
                s_far = s_l;
                far = at;
                which = before;
                continue;
            }
            dyn_colloc_sol_free(&xn);
            dyn_colloc_sol_free(&tn);
            xn = xl;
            tn = tl;
            s_end = s_l;
            uz = -1; /* the label comes first: the UZ point is found on the next step */
            now = at;
            set_test_value(&now, which, p1); /* beyond the point the far side's sign */
            break;
        }
        if (st)
            break;
        /* a fold whose parameter stays within PO_FOLD_NOISE of both ends of its step is
         * the jitter of a vertical branch (cycles near a homoclinic orbit, the parameter
         * settled while the period grows), not a fold: no label */
        if (which == 0 && fmax(fabs(xn.par[1] - x->par[1]), fabs(xn.par[1] - lambda_end)) <=
                              PO_FOLD_NOISE * fmax(1.0, fabs(xn.par[1])))
            which = -1;
        /* a branch point has a second multiplier at 1 (the determinant's sign changed
         * otherwise only by rounding: no label) */
        if (which == 5 && now.have_mult && !second_unit_multiplier(r->re, r->im, xn.n))
            which = -1;
        /* past a bound of the parameter: the point on the bound ends the branch */
        const double pn = xn.par[1];
        int at_bound = 0;
        if (which < 0 && !hopf_end && bounded && (pn < o->par_min || pn > o->par_max)) {
            r->bound = pn > o->par_max ? o->par_max : o->par_min;
            dyn_colloc_sol xl = {0}, tl = {0};
            double s_b;
            if (!locate(r, x, t, s_end, x->par[1] - r->bound, pn - r->bound, 3, &xl, &tl,
                        &s_b)) {
                dyn_colloc_sol_free(&xn);
                dyn_colloc_sol_free(&tn);
                xn = xl;
                tn = tl;
                st = point_tests(r, &xn, &tn, &now);
                if (st)
                    break;
                at_bound = 1;
            }
        }
        if (at_bound)
            uz = -1;
        const char *label = hopf_end ? "EP" : which == 0 ? "LPC" : which == 1 ? "PD"
                            : which == 2 ? "TR" : which == 5 ? "BP" : at_bound ? "EP"
                            : uz >= 0 ? "UZ" : "";
        st = record(r, &xn, r->re, r->im, now.have_mult, label,
                    which >= 0 || uz >= 0 || b->npoints == 0 || o->keep_orbits);
        /* a branch point keeps its tangent: the other branch leaves orthogonally to it */
        if (!st && which == 5 && dyn_colloc_sol_copy(&b->pts[b->npoints - 1].tangent, &tn))
            st = DYN_COLLOC_ERR_NOMEM;
        if (st)
            break;
        dyn_colloc_sol_free(x);
        dyn_colloc_sol_free(t);
        *x = xn;
        *t = tn;
        memset(&xn, 0, sizeof xn);
        memset(&tn, 0, sizeof tn);
        prev_tests = now;
        have_prev = 1;
        if (inf.iterations <= 3)
            ds = copysign(fmin(1.5 * fabs(ds), dsmax), ds);
        else if (inf.iterations >= 8)
            ds *= 0.5;
        if (adapt > 0 && ++since_adapt >= adapt) {
            dyn_colloc_sol *ex[1] = {t};
            since_adapt = 0;
            if (dyn_colloc_adapt(x, ntst, 1, ex, 1) == 0) {
                dyn_colloc_sol t2;
                if (dyn_colloc_tangent(&r->p, x, x, t, &t2) == 0) {
                    dyn_colloc_sol_free(t);
                    *t = t2;
                }
            }
        }
        if (hopf_end) {
            snprintf(b->message, sizeof b->message,
                     "the orbit shrank to an equilibrium: a Hopf point at parameter %.10g",
                     x->par[1]);
            b->hopf_end = 1;
            break;
        }
        if (at_bound || (bounded && (x->par[1] < o->par_min || x->par[1] > o->par_max))) {
            snprintf(b->message, sizeof b->message, "reached %s = %s",
                     x->par[1] >= 0.5 * (o->par_min + o->par_max) ? "parmax" : "parmin",
                     dyn_shortest(x->par[1] >= 0.5 * (o->par_min + o->par_max) ? o->par_max
                                                                               : o->par_min).s);
            break;
        }
        if (o->period_max > 0 && x->par[0] > o->period_max) {
            snprintf(b->message, sizeof b->message,
                     "the period %.6g exceeds %g (a homoclinic orbit near?)", x->par[0],
                     o->period_max);
            break;
        }
        if (amplitude_small(x)) {
            snprintf(b->message, sizeof b->message, "the orbit shrank to an equilibrium");
            b->hopf_end = 1;
            break;
        }
        const int back = back_on_branch(b);
        if (back >= 0) {
            snprintf(b->message, sizeof b->message,
                     "closed: back on the orbits between its points %d and %d", back + 1,
                     back + 2);
            break;
        }
    }
    dyn_colloc_sol_free(&xn);
    dyn_colloc_sol_free(&tn);
    if (b->npoints > 0) {
        dyn_po_point *last = &b->pts[b->npoints - 1];
        if (!last->label[0])
            snprintf(last->label, sizeof last->label, "EP");
        if (!last->orbit.u)
            dyn_colloc_sol_copy(&last->orbit, x);
    }
    dyn_colloc_sol_free(x);
    dyn_colloc_sol_free(t);
    b->status = st;
    return b->npoints > 0 ? 0 : (st ? st : DYN_COLLOC_ERR_NEWTON);
}

static int run_init(po_run *r, const dyn_po_system *sys, const dyn_po_opts *o, dyn_po_branch *b)
{
    memset(r, 0, sizeof *r);
    memset(b, 0, sizeof *b);
    b->n = sys->n;
    r->sys = sys;
    r->o = o;
    r->c.sys = sys;
    const size_t n = (size_t)sys->n;
    r->c.J = malloc((n * n + 5 * n) * sizeof(double));
    if (!r->c.J)
        return DYN_COLLOC_ERR_NOMEM;
    r->re = r->c.J + n * n;
    r->im = r->re + n;
    r->scratch = r->im + n;
    dyn_colloc_problem p = {sys->n, 2, sys->n, 1, po_f, po_bc, &r->c};
    r->p = p;
    r->nopts.tol = o->tol > 0 ? o->tol : 1e-9;
    r->nopts.max_iter = 12;
    r->b = b;
    return 0;
}

/* a null vector of the real 2n x 2n matrix K (row-major) by inverse iteration */
static int null_vector(int m, double *K, double *v)
{
    int *piv = malloc((size_t)m * sizeof(int));
    if (!piv)
        return DYN_COLLOC_ERR_NOMEM;
    double scale = 0.0;
    for (int i = 0; i < m * m; i++)
        scale = fmax(scale, fabs(K[i]));
    for (int i = 0; i < m; i++)
        K[(size_t)i * m + i] += 1e-13 * (scale > 0 ? scale : 1.0);
    int st = dyn_lu_factor(m, K, piv) ? DYN_COLLOC_ERR_SINGULAR : 0;
    for (int i = 0; i < m; i++)
        v[i] = 1.0 + 0.1 * i;
    for (int it = 0; it < 4 && !st; it++) {
        dyn_lu_solve(m, K, piv, v);
        double nrm = 0.0;
        for (int i = 0; i < m; i++)
            nrm += v[i] * v[i];
        nrm = sqrt(nrm);
        if (!(nrm > 0) || !isfinite(nrm))
            st = DYN_COLLOC_ERR_SINGULAR;
        else
            for (int i = 0; i < m; i++)
                v[i] /= nrm;
    }
    free(piv);
    return st;
}

static int default_ncol(const dyn_po_opts *o)
{
    return o->ncol >= 2 && o->ncol <= DYN_COLLOC_MAX_NCOL ? o->ncol : 4;
}

int dyn_po_from_hopf(const dyn_po_system *sys, const double *x0, double p0, double omega,
                     const dyn_po_opts *o, dyn_po_branch *b)
{
    po_run r;
    int st = run_init(&r, sys, o, b);
    if (st)
        return st;
    const int n = sys->n;
    const size_t m = 2 * (size_t)n;
    double *K = calloc(m * m + m, sizeof(double));
    dyn_colloc_sol x = {0}, t = {0};
    if (!K || !(omega > 0) || n < 2) {
        st = K ? DYN_COLLOC_ERR_ARG : DYN_COLLOC_ERR_NOMEM;
        snprintf(b->message, sizeof b->message, "%s",
                 K ? "a Hopf point needs omega > 0 and at least 2 states"
                   : "out of memory");
        goto done;
    }
    double *v = K + m * m;
    if (sys->f(x0, p0, v, r.c.J, sys->ctx)) {
        st = DYN_COLLOC_ERR_FN;
        snprintf(b->message, sizeof b->message, "the right-hand side failed at the Hopf point");
        goto done;
    }
    /* [J, w I; -w I, J] [qr; qi] = 0: J q = i w q for q = qr + i qi */
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            K[(size_t)i * m + j] = r.c.J[(size_t)i * n + j];
            K[(size_t)(i + n) * m + j + n] = r.c.J[(size_t)i * n + j];
        }
        K[(size_t)i * m + i + n] = omega;
        K[(size_t)(i + n) * m + i] = -omega;
    }
    st = null_vector((int)m, K, v);
    if (st) {
        snprintf(b->message, sizeof b->message, "no eigenvector for i omega at the Hopf point");
        goto done;
    }
    const int ntst = o->ntst > 0 ? o->ntst : 20;
    if ((st = dyn_colloc_sol_alloc(&x, n, ntst, default_ncol(o), 2)) ||
        (st = dyn_colloc_sol_alloc(&t, n, ntst, default_ncol(o), 2)))
        goto done;
    const long nodes = dyn_colloc_nodes(&x);
    for (long g = 0; g < nodes; g++) {
        const double s = 2.0 * DYN_PI * dyn_colloc_node_time(&x, g);
        for (int i = 0; i < n; i++) {
            x.u[(size_t)g * n + i] = x0[i];
            t.u[(size_t)g * n + i] = v[i] * cos(s) - v[i + n] * sin(s);
        }
    }
    x.par[0] = 2.0 * DYN_PI / omega;
    x.par[1] = p0;
    const double nrm = sqrt(dyn_colloc_dot(&t, &t));
    for (long i = 0; i < nodes * n; i++)
        t.u[i] /= nrm;
    free(K);
    st = po_continue(&r, &x, &t);
    free(r.c.J);
    return st;
done:
    free(K);
    dyn_colloc_sol_free(&x);
    dyn_colloc_sol_free(&t);
    free(r.c.J);
    b->status = st;
    return st;
}

/* the eigenfunction of a multiplier: phi' = T J(u(t)) phi from phi(0) = v */
typedef struct eigf_ctx {
    const dyn_po_system *sys;
    const dyn_colloc_sol *orbit;
    const double *v;
    double *J, *u, *fx;
} eigf_ctx;

static int eigf_f(double t, const double *phi, const double *par, double *f, double *fu,
                  void *ctx)
{
    (void)par;
    eigf_ctx *c = ctx;
    const int n = c->sys->n;
    dyn_colloc_eval(c->orbit, t, c->u);
    if (c->sys->f(c->u, c->orbit->par[1], c->fx, c->J, c->sys->ctx))
        return 1;
    const double T = c->orbit->par[0];
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int j = 0; j < n; j++)
            s += c->J[(size_t)i * n + j] * phi[j];
        f[i] = T * s;
    }
    if (fu)
        for (int i = 0; i < n * n; i++)
            fu[i] = T * c->J[i];
    return 0;
}

static int eigf_bc(const double *u0, const double *u1, const double *par, double *g, void *ctx)
{
    (void)u1;
    (void)par;
    const eigf_ctx *c = ctx;
    for (int i = 0; i < c->sys->n; i++)
        g[i] = u0[i] - c->v[i];
    return 0;
}

int dyn_po_from_pd(const dyn_po_system *sys, const dyn_po_point *pd, const dyn_po_opts *o,
                   dyn_po_branch *b)
{
    po_run r;
    int st = run_init(&r, sys, o, b);
    if (st)
        return st;
    const dyn_colloc_sol *orb = &pd->orbit;
    const int n = sys->n;
    const size_t nn = (size_t)n;
    double *M = malloc((nn * nn + 4 * nn) * sizeof(double));
    dyn_colloc_sol phi = {0}, x = {0}, t = {0};
    if (!M || !orb->u || orb->n != n) {
        st = M ? DYN_COLLOC_ERR_ARG : DYN_COLLOC_ERR_NOMEM;
        snprintf(b->message, sizeof b->message, "%s",
                 M ? "the PD point keeps no orbit" : "out of memory");
        goto done;
    }
    double *v = M + nn * nn;
    /* v: the null vector of M + I */
    if ((st = dyn_colloc_monodromy(&r.p, orb, M)))
        goto fail;
    for (int i = 0; i < n; i++)
        M[(size_t)i * nn + i] += 1.0;
    {
        double *K = malloc(nn * nn * sizeof(double));
        if (!K) {
            st = DYN_COLLOC_ERR_NOMEM;
            goto fail;
        }
        memcpy(K, M, nn * nn * sizeof(double));
        st = null_vector(n, K, v);
        free(K);
        if (st)
            goto fail;
    }
    eigf_ctx ec = {sys, orb, v, r.c.J, v + nn, v + 2 * nn};
    dyn_colloc_problem pe = {n, 0, n, 0, eigf_f, eigf_bc, &ec};
    if ((st = dyn_colloc_sol_copy(&phi, orb)))
        goto fail;
    phi.npar = 0;
    memset(phi.u, 0, (size_t)dyn_colloc_nodes(&phi) * nn * sizeof(double));
    if ((st = dyn_colloc_solve(&pe, &phi, NULL, NULL, NULL, NULL)))
        goto fail;
    /* the orbit twice on [0, 1]: period 2T; the eigenfunction phi, then -phi */
    const int N = orb->ntst, ncol = orb->ncol;
    if ((st = dyn_colloc_sol_alloc(&x, n, 2 * N, ncol, 2)) ||
        (st = dyn_colloc_sol_alloc(&t, n, 2 * N, ncol, 2)))
        goto fail;
    for (int j = 0; j <= N; j++) {
        x.mesh[j] = 0.5 * orb->mesh[j];
        x.mesh[N + j] = 0.5 + 0.5 * orb->mesh[j];
    }
    t.mesh[0] = 0.0;
    memcpy(t.mesh, x.mesh, (2 * (size_t)N + 1) * sizeof(double));
    const long half = dyn_colloc_nodes(orb) - 1;
    for (long g = 0; g <= 2 * half; g++) {
        const long k = g <= half ? g : g - half;
        const double sgn = g <= half ? 1.0 : -1.0;
        for (int i = 0; i < n; i++) {
            x.u[(size_t)g * n + i] = orb->u[(size_t)k * n + i];
            t.u[(size_t)g * n + i] = sgn * phi.u[(size_t)k * n + i];
        }
    }
    x.par[0] = 2.0 * orb->par[0];
    x.par[1] = orb->par[1];
    const double nrm = sqrt(dyn_colloc_dot(&t, &t));
    if (!(nrm > 0)) {
        st = DYN_COLLOC_ERR_SINGULAR;
        goto fail;
    }
    for (long i = 0; i < dyn_colloc_nodes(&t) * n; i++)
        t.u[i] /= nrm;
    {
        dyn_colloc_sol *ex[1] = {&t};
        const int ntst = o->ntst > 0 ? o->ntst : N;
        if ((st = dyn_colloc_adapt(&x, ntst, 1, ex, 1)))
            goto fail;
    }
    dyn_colloc_sol_free(&phi);
    free(M);
    st = po_continue(&r, &x, &t);
    free(r.c.J);
    return st;
fail:
    snprintf(b->message, sizeof b->message, "no eigenfunction of the multiplier -1 (%d)", st);
done:
    free(M);
    dyn_colloc_sol_free(&phi);
    dyn_colloc_sol_free(&x);
    dyn_colloc_sol_free(&t);
    free(r.c.J);
    b->status = st;
    return st;
}

int dyn_po_from_bp(const dyn_po_system *sys, const dyn_po_point *bp, int direction,
                   const dyn_po_opts *o, dyn_po_branch *b)
{
    po_run r;
    int st = run_init(&r, sys, o, b);
    if (st)
        return st;
    dyn_colloc_sol x = {0}, v = {0};
    if (!bp->orbit.u || !bp->tangent.u || bp->orbit.n != sys->n) {
        st = DYN_COLLOC_ERR_ARG;
        snprintf(b->message, sizeof b->message, "the BP point keeps no orbit and tangent");
    } else if ((st = colloc_bp_direction(&r.p, &bp->orbit, &bp->tangent, &v))) {
        snprintf(b->message, sizeof b->message, "no second null vector at the BP (%d)", st);
    } else if ((st = dyn_colloc_sol_copy(&x, &bp->orbit))) {
        snprintf(b->message, sizeof b->message, "out of memory");
    }
    if (st) {
        dyn_colloc_sol_free(&v);
        free(r.c.J);
        b->status = st;
        return st;
    }
    if (direction < 0) {
        for (long i = 0; i < dyn_colloc_nodes(&v) * v.n; i++)
            v.u[i] = -v.u[i];
        for (int k = 0; k < v.npar; k++)
            v.par[k] = -v.par[k];
    }
    st = po_continue(&r, &x, &v);
    free(r.c.J);
    return st;
}
