/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady_curves.c — curves of folds and of Hopf points of steady motions in two
 * parameters (private; cont_steady_system.h): from each LP and HB of the branches, the
 * steady equations G(u, p1, p2) = 0 with one test function of the point's kind as one
 * more equation (a minimally extended system; Govaerts, "Numerical Methods for Bifurcations
 * of Dynamical Equilibria", 2000, sec. 4.2 and 4.4), followed by the pseudo-arclength loop
 * of cont_core.c in z = (u, p1, p2):
 *   folds:  G = 0, det G_u / s0 = 0     (s0: |det G_u|'s row-norm scale at the start)
 *   Hopf:   G = 0, Re lambda = 0        (lambda: B's complex eigenvalue nearest the axis)
 * the Jacobian by central differences of this residual. A curve that runs where the model
 * or the reduction fails ends at its last computed point (EP), its stop saying where and
 * why; the rest of the diagram is kept. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cont_steady_system.h"

typedef struct curve_ctx {
    sc_ctx *c;
    const cont_system *s1; /* the branch's system: G and G_z in (u, p1) at c->p2 */
    int hopf;
    double scale;          /* folds: the normalization of det G_u */
    double *J, *Gu, *zt, *gp, *gm;
    int bi;
    int failed;            /* a point could not be stored: the curve ends before it */
    int ended;             /* a curve of this start ended at a failure (its stop says why) */
    int kept;              /* directions of this start's curve kept */
    char why[140];         /* the last failure's reason, with where */
} curve_ctx;

/* remember why the model or the reduction failed at z (the curve's stop and note say it) */
static void failed_at(curve_ctx *k, const double *z)
{
    sc_ctx *c = k->c;
    const dyn_model *m = c->cm->m;
    const int nu = c->nu;
    snprintf(k->why, sizeof k->why, "at %.16s = %.8g, %.16s = %.8g: %.60s",
             m->params[c->cm->ip].name, z[nu], m->params[c->cm->ip2].name, z[nu + 1],
             c->message[0] ? c->message : "the right-hand side failed");
    c->message[0] = '\0';
}

/* det G_u at z = (u, p1) with c->p2 set, and the product of G_u's row norms */
static int det_gu(curve_ctx *k, const double *z, double *det, double *rows)
{
    const int nu = k->c->nu;
    if (k->s1->jacobian(k->c, z, k->J))
        return -1;
    *rows = 1.0;
    for (int i = 0; i < nu; i++) {
        double r = 0.0;
        for (int j = 0; j < nu; j++) {
            k->Gu[i * nu + j] = k->J[(size_t)i * (size_t)(nu + 1) + (size_t)j];
            r = fmax(r, fabs(k->Gu[i * nu + j]));
        }
        *rows *= r > 0.0 ? r : 1.0;
    }
    *det = sc_det_lu(nu, k->Gu);
    return 0;
}

static int curve_residual(void *ctx, const double *z, double *g)
{
    curve_ctx *k = ctx;
    sc_ctx *c = k->c;
    const int nu = c->nu;
    if (k->failed)
        return -1; /* the curve ends at the point that could not be stored */
    c->p2 = z[nu + 1];
    if (k->s1->residual(c, z, g)) {
        failed_at(k, z);
        return -1;
    }
    if (k->hopf) {
        int unstable;
        if (sc_state_at(c, z) || sc_reduce(c)) {
            failed_at(k, z);
            return -1;
        }
        g[nu] = cont_hopf_test(nu, c->re, c->im, c->tol_b, &unstable, NULL);
        return 0;
    }
    double det, rows;
    if (det_gu(k, z, &det, &rows)) {
        failed_at(k, z);
        return -1;
    }
    g[nu] = det / k->scale;
    return 0;
}

/* central differences of the residual, steps 2^-20 max(|z_j|, 1) */
static int curve_jacobian(void *ctx, const double *z, double *J)
{
    curve_ctx *k = ctx;
    return cont_central_jacobian(curve_residual, k, k->c->nu + 1, CONT_STEPS_POW2, z, J,
                                 k->zt); /* zt, gp, gm */
}

/* no points are located on the curves */
static int curve_tests(void *ctx, const double *z, const double *t, double det, double *psi,
                       int *count)
{
    (void)ctx;
    (void)z;
    (void)t;
    (void)det;
    (void)psi;
    (void)count;
    return 0;
}

static int curve_store(void *ctx, const double *z, const double *t, dyn_cont_label label)
{
    (void)t;
    curve_ctx *k = ctx;
    sc_ctx *c = k->c;
    const int nu = c->nu;
    if (k->failed)
        return 0;
    c->p2 = z[nu + 1];
    if (sc_state_at(c, z) || sc_reduce(c)) {
        /* the curve ends here, what is computed kept (one_curve says why) */
        failed_at(k, z);
        k->failed = 1;
        return 0;
    }
    dyn_branch_point pt;
    pt.label = label;
    pt.par[0] = z[nu];
    pt.par[1] = z[nu + 1];
    pt.period = NAN;
    pt.l1 = NAN;
    pt.stable = -1;
    pt.omega = NAN;
    if (k->hopf) {
        int unstable;
        double omega;
        cont_hopf_test(nu, c->re, c->im, c->tol_b, &unstable, &omega);
        pt.omega = omega * omega;
    }
    if (dyn_branch_append(&c->d->branches[k->bi], &pt, c->y, NULL, c->re, c->im) < 0) {
        snprintf(c->message, sizeof c->message, "out of memory");
        return -1;
    }
    return 0;
}

/* the curve through point pk of branch bi (an LP or HB), both ways: 0, -1 (out of memory
 * or the model failed: c->message), -2 when it could not be started */
static int one_curve(curve_ctx *k, cont_work *w, const dyn_cont_opts *o, int bi, long pk,
                     int max_branches)
{
    sc_ctx *c = k->c;
    const int nu = c->nu, M = nu + 2;
    const dyn_branch *b = &c->d->branches[bi];
    double *z = malloc(3 * (size_t)M * sizeof *z);
    if (!z) {
        snprintf(c->message, sizeof c->message, "out of memory");
        return -1;
    }
    double *e = z + M, *t = e + M;
    for (int j = 0; j < nu; j++)
        z[j] = b->x[(size_t)pk * (size_t)b->n + (size_t)c->sp->unknowns[j]];
    z[nu] = b->pts[pk].par[0];
    z[nu + 1] = c->cm->p2_base;
    c->p2 = z[nu + 1];
    k->scale = 1.0;
    if (!k->hopf) {
        double det, rows;
        if (det_gu(k, z, &det, &rows)) {
            free(z);
            return -2;
        }
        k->scale = rows;
    }
    cont_system s;
    memset(&s, 0, sizeof s);
    s.N = nu + 1;
    s.ip = nu;
    s.ip2 = nu + 1;
    s.ctx = k;
    s.residual = curve_residual;
    s.jacobian = curve_jacobian;
    s.tests = curve_tests;
    s.store = curve_store;
    /* Newton's method at the fixed second parameter, then both directions */
    for (int i = 0; i < M; i++)
        e[i] = i == nu + 1 ? 1.0 : 0.0;
    int rc = cont_correct(&s, w, z, e, 0.0, z, NULL) ? -2 : 0;
    for (int dir = 1; rc == 0 && dir >= -1 && c->d->count < max_branches; dir -= 2) {
        for (int i = 0; i < M; i++)
            e[i] = i == nu + 1 ? dir : 0.0;
        double det;
        if (cont_tangent(&s, w, z, e, t, &det)) {
            rc = -2;
            break;
        }
        dyn_branch *nb = dyn_diagram_add(c->d, k->hopf ? DYN_BRANCH_HOPF : DYN_BRANCH_FOLD, c->n,
                                         nu, o->ip, o->ip2);
        if (!nb) {
            snprintf(c->message, sizeof c->message, "out of memory");
            rc = -1;
            break;
        }
        nb->parent = c->d->branches[bi].id;
        nb->parent_point = pk;
        k->bi = c->d->count - 1;
        cont_loop L;
        cont_loop_from_opts(o, &L, k->hopf ? DYN_LABEL_HB : DYN_LABEL_LP);
        L.p2min = o->par2min;
        L.p2max = o->par2max;
        L.stop_closed = 1;
        L.missed = &c->cm->missed;
        char stop[160];
        k->failed = 0;
        k->why[0] = '\0';
        const int st = cont_follow(&s, w, &L, z, t, stop, sizeof stop);
        if (st == -1) {
            rc = -1;
            break;
        }
        if (st == -2 || c->d->branches[k->bi].count == 0) {
            cont_diagram_drop_last(c->d);
            rc = -2;
            break;
        }
        k->kept++;
        /* a point that could not be stored, or steps that failed to the smallest: the
         * curve ends, with the reason */
        dyn_branch *cb = &c->d->branches[k->bi];
        if (k->failed || (k->why[0] && strncmp(stop, "no convergence", 14) == 0)) {
            snprintf(cb->stop, sizeof cb->stop, "failed %.140s", k->why);
            cb->pts[cb->count - 1].label = DYN_LABEL_EP;
            k->ended = 1;
        } else {
            snprintf(cb->stop, sizeof cb->stop, "%s", stop);
        }
        if (st == 1) /* a closed curve: the other direction is the same curve */
            break;
    }
    c->p2 = NAN;
    free(z);
    return rc;
}

int sc_curves_all(sc_ctx *c, const cont_system *s1, const dyn_cont_opts *o, int first,
                  char *note, size_t notelen)
{
    const int nu = c->nu, M = nu + 2;
    const int max_branches = o->max_branches > 0 ? o->max_branches : 16;
    curve_ctx k;
    memset(&k, 0, sizeof k);
    k.c = c;
    k.s1 = s1;
    double *buf = malloc(((size_t)(nu + 1) * (size_t)(nu + 1) + (size_t)nu * (size_t)nu +
                          3 * (size_t)M) * sizeof *buf);
    cont_work w;
    const int w_bad = cont_work_init(&w, nu + 1);
    if (!buf || w_bad) {
        free(buf);
        if (!w_bad)
            cont_work_free(&w);
        snprintf(c->message, sizeof c->message, "out of memory");
        return -1;
    }
    k.J = buf;
    k.Gu = k.J + (size_t)(nu + 1) * (size_t)(nu + 1);
    k.zt = k.Gu + (size_t)nu * (size_t)nu;
    k.gp = k.zt + M;
    k.gm = k.gp + M;
    const int last = c->d->count;
    int rc = 0;
    for (int bi = first; rc != -1 && bi < last; bi++)
        for (long pk = 0; rc != -1 && pk < c->d->branches[bi].count; pk++) {
            const dyn_cont_label l = c->d->branches[bi].pts[pk].label;
            if ((l != DYN_LABEL_LP && l != DYN_LABEL_HB) || c->d->count >= max_branches)
                continue;
            k.hopf = l == DYN_LABEL_HB;
            k.ended = 0;
            k.kept = 0;
            rc = one_curve(&k, &w, o, bi, pk, max_branches);
            const size_t used = strlen(note);
            if ((k.ended || rc == -2) && used + 2 < notelen)
                snprintf(note + used, notelen - used, "%sthe %s curve through point %ld of "
                         "branch %d %s", used ? "; " : "", k.hopf ? "Hopf" : "fold", pk + 1,
                         c->d->branches[bi].id,
                         rc != -2  ? "ends where the model or the reduction fails (its stop says where)"
                         : k.kept ? "was followed one way only: the other could not be started"
                                  : "could not be started");
        }
    cont_work_free(&w);
    free(buf);
    return rc == -1 ? -1 : 0;
}
