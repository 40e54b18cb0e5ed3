/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_equilibrium.c — branches of equilibria f(x, p) = 0 in one parameter and the
 * diagram they make (dynkit/continuation.h, dyn_continue). The unknowns are z = (x, p); the
 * test functions are those of AUTO-07p (Doedel et al., AUTO-07p manual, ch. 5 and 12):
 * the parameter's component of the unit tangent changes sign at a fold (LP); the scaled
 * det [f_x f_p; t^T] at a branch point (BP); the real part of the complex eigenvalue nearest
 * the imaginary axis at a Hopf point (HB), counted only when the number of complex
 * eigenvalues in the right half-plane changes. At a BP the other branch leaves along the root
 * of the algebraic branching equation (cont_branching.c; Keller 1977) and is followed both
 * ways; a branch that comes back to its start or a labelled point (a closed loop, as the
 * asymmetric equilibria of AUTO-07p's demo enz) ends there. */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h"
#include "cont_equilibrium.h"


typedef struct eq_ctx {
    cont_model *cm;
    dyn_diagram *d;
    int bi;               /* the branch's index in d */
    int store_failed;
} eq_ctx;

static int eq_residual(void *ctx, const double *z, double *g)
{
    cont_model *cm = ((eq_ctx *)ctx)->cm;
    if (cont_model_set(cm, z[cm->n], NAN))
        return -1;
    return cont_model_f(cm, z, g);
}

static int eq_jacobian(void *ctx, const double *z, double *J)
{
    cont_model *cm = ((eq_ctx *)ctx)->cm;
    const int n = cm->n;
    if (cont_model_set(cm, z[n], NAN) || cont_model_jx(cm, z, J, n + 1))
        return -1;
    return cont_model_fp(cm, z, z[n], NAN, 0, J + n, n + 1);
}

static int eq_tests(void *ctx, const double *z, const double *t, double det, double *psi,
                    int *count)
{
    cont_model *cm = ((eq_ctx *)ctx)->cm;
    const int n = cm->n;
    if (cont_model_set(cm, z[n], NAN) || cont_model_jx(cm, z, cm->J, n) ||
        cont_model_eig(cm, cm->J))
        return -1;
    psi[0] = t[n];
    count[0] = -1;
    psi[1] = det;
    count[1] = -1;
    if (cm->map)
        cont_map_tests(cm, psi + 2, count + 2); /* PD and TR (cont_map.c) */
    else
        psi[2] = cont_hopf_test(cm->n, cm->re, cm->im, 0.0, &count[2], NULL);
    return 0;
}

/* omega of a Hopf point: the imaginary part of the complex pair nearest the axis */
static double hopf_omega(const cont_model *cm)
{
    double best = NAN, best_abs = INFINITY;
    for (int i = 0; i < cm->n; i++)
        if (cm->im[i] > 0.0 && fabs(cm->re[i]) < best_abs) {
            best_abs = fabs(cm->re[i]);
            best = cm->im[i];
        }
    return best;
}

/* a real eigenvalue zero beside the pair +-i omega (a fold-Hopf point, as where Roessler's
 * equilibria meet): Kuznetsov's l1 solves with the Jacobian, singular there, and is not
 * defined */
static int hopf_with_zero(const cont_model *cm, double omega)
{
    for (int i = 0; i < cm->n; i++)
        if (cm->im[i] == 0.0 && fabs(cm->re[i]) <= 1e-6 * omega)
            return 1;
    return 0;
}

static int eq_store(void *ctx, const double *z, const double *t, dyn_cont_label label)
{
    (void)t;
    eq_ctx *e = ctx;
    cont_model *cm = e->cm;
    const int n = cm->n;
    if (cont_model_set(cm, z[n], NAN) || cont_model_jx(cm, z, cm->J, n) ||
        cont_model_eig(cm, cm->J))
        return -1;
    double l1 = NAN, omega = NAN;
    if (label == DYN_LABEL_TR && cm->map)
        omega = cont_map_angle(cm);
    if (label == DYN_LABEL_HB) {
        omega = hopf_omega(cm);
        char err[256];
        if (isfinite(omega) && !hopf_with_zero(cm, omega) &&
            dyn_first_lyapunov(cm->m, cm->t, z, cm->par, cm->jac, cm->J, omega, &l1, err,
                               sizeof err))
            l1 = NAN;
        /* dyn_first_lyapunov leaves par as it was; the eigenvalues are still cm's */
    }
    if (cont_model_store(cm, &e->d->branches[e->bi], z, z[n], NAN, 1, label, l1, omega)) {
        e->store_failed = 1;
        return -1;
    }
    return 0;
}

static void eq_system(cont_system *s, eq_ctx *e)
{
    memset(s, 0, sizeof *s);
    s->N = e->cm->n;
    s->ip = e->cm->n;
    s->ip2 = -1;
    s->ctx = e;
    s->residual = eq_residual;
    s->jacobian = eq_jacobian;
    s->n_tests = e->cm->map ? 4 : 3;
    s->test_label[0] = DYN_LABEL_LP;
    s->test_label[1] = DYN_LABEL_BP;
    s->test_label[2] = e->cm->map ? DYN_LABEL_PD : DYN_LABEL_HB;
    s->test_label[3] = DYN_LABEL_TR;
    s->tests = eq_tests;
    s->store = eq_store;
}

/* one branch from z along t into a new branch of d */
static int follow_branch(cont_model *cm, const dyn_cont_opts *o, dyn_diagram *d, const double *z,
                         const double *t, dyn_cont_label start, int parent, long parent_point,
                         cont_work *w)
{
    dyn_branch *b = dyn_diagram_add(d, DYN_BRANCH_EQUILIBRIUM, cm->n, cm->n, o->ip, -1);
    if (!b)
        return -1;
    b->parent = parent;
    b->parent_point = parent_point;
    eq_ctx e = {cm, d, d->count - 1, 0};
    cont_system s;
    eq_system(&s, &e);
    cont_loop L;
    cont_loop_from_opts(o, &L, start);
    L.stop_closed = 1;
    L.missed = &cm->missed;
    char stop[160];
    const int rc = cont_follow(&s, w, &L, z, t, stop, sizeof stop);
    snprintf(d->branches[e.bi].stop, sizeof d->branches[e.bi].stop, "%s", stop);
    if (rc == -2 && d->branches[e.bi].count == 0) {
        /* nothing to keep: the branch is dropped */
        cont_diagram_drop_last(d);
        return parent ? 0 : -1;
    }
    return rc == -1 ? -1 : rc == 1 ? 1 : 0;
}

static double dist_inf(const double *a, const double *b, int n)
{
    double m = 0.0;
    for (int i = 0; i < n; i++)
        m = fmax(m, fabs(a[i] - b[i]) / (1.0 + fabs(a[i])));
    return m;
}

/* point k of branch b as z = (x, p) */
static void branch_point(const dyn_branch *b, long k, double *z)
{
    const size_t n = (size_t)b->n;
    memcpy(z, b->x + (size_t)k * n, n * sizeof *z);
    z[n] = b->pts[k].par[0];
}

/* Whether a branch of d other than bi, or bi away from its point kb, passes through z (a
 * point of it, or within a tenth of a chord's length of the chord between two of its
 * points): both branches through the BP z are computed then (the one switched to from
 * there, one that crossed it, or bi itself crossing there again, as a figure eight does),
 * and it is not switched at again. za, zb: workspace of n + 1. */
static int passed_elsewhere(const dyn_diagram *d, int bi, long kb, const double *z, double *za,
                            double *zb)
{
    for (int j = 0; j < d->count; j++) {
        const dyn_branch *b = &d->branches[j];
        if (b->kind != DYN_BRANCH_EQUILIBRIUM)
            continue;
        const int M = b->n + 1;
        double scale = 1.0;
        for (int i = 0; i < M; i++)
            scale = fmax(scale, fabs(z[i]));
        for (long k = 0; k < b->count; k++) {
            /* the branch's own steps next to the BP are where it is, not where it passes */
            if (j == bi && k >= kb - 1 && k <= kb + 2)
                continue;
            branch_point(b, k, zb);
            if (dist_inf(zb, z, M) < 1e-6)
                return 1;
            if (k == 0)
                continue;
            branch_point(b, k - 1, za);
            double u, length;
            const double dist = cont_chord_distance(M, za, zb, z, &u, &length);
            if (u > 0.0 && u < 1.0 && dist <= 0.1 * length + 1e-9 * scale)
                return 1;
        }
    }
    return 0;
}

/* The unit tangent of branch b at its point k from the point and its neighbours: the
 * derivative of the quadratic through the three in the arclength (second order), or the
 * secant of two at an end. 0 or non-zero. */
static int branch_tangent(const dyn_branch *b, long k, double *t, double *za, double *zb)
{
    const int M = b->n + 1;
    double *zk = t;
    const long ka = k > 0 ? k - 1 : k, kb = k + 1 < b->count ? k + 1 : k;
    if (ka == kb)
        return -1;
    branch_point(b, ka, za);
    branch_point(b, kb, zb);
    if (ka == k || kb == k) {
        for (int i = 0; i < M; i++)
            t[i] = zb[i] - za[i];
    } else {
        double ha = 0.0, hb = 0.0;
        branch_point(b, k, zk);
        for (int i = 0; i < M; i++) {
            ha += (zk[i] - za[i]) * (zk[i] - za[i]);
            hb += (zb[i] - zk[i]) * (zb[i] - zk[i]);
        }
        ha = sqrt(ha);
        hb = sqrt(hb);
        if (!(ha > 0.0) || !(hb > 0.0))
            return -1;
        for (int i = 0; i < M; i++)
            t[i] = hb / (ha * (ha + hb)) * (zk[i] - za[i]) + ha / (hb * (ha + hb)) * (zb[i] - zk[i]);
    }
    double nt = 0.0;
    for (int i = 0; i < M; i++)
        nt += t[i] * t[i];
    nt = sqrt(nt);
    if (!(nt > 0.0) || !isfinite(nt))
        return -1;
    for (int i = 0; i < M; i++)
        t[i] /= nt;
    return 0;
}

/* A note appended to note[0..len), after a "; " when it holds one already. */
static void add_note(char *note, size_t len, const char *fmt, ...)
{
    const size_t used = strlen(note);
    if (used + 3 >= len)
        return;
    if (used)
        memcpy(note + used, "; ", 3);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(note + strlen(note), len - strlen(note), fmt, ap);
    va_end(ap);
}

/* Switch at the BP `k` of branch bi: the other branch's direction by the algebraic
 * branching equation, followed both ways (one way when it comes back: a closed branch). */
static int switch_at(cont_model *cm, const dyn_cont_opts *o, dyn_diagram *d, int bi, long k,
                     cont_work *w, char *note, size_t note_len)
{
    const int n = cm->n, M = n + 1;
    double *buf = malloc(5 * (size_t)M * sizeof *buf);
    if (!buf)
        return -1;
    double *z = buf, *t = z + M, *v = t + M, *z2 = v + M, *z3 = z2 + M;
    const dyn_branch *b = &d->branches[bi];
    branch_point(b, k, z);
    if (passed_elsewhere(d, bi, k, z, z2, z3) || branch_tangent(b, k, t, z2, z3)) {
        free(buf);
        return 0;
    }
    eq_ctx e = {cm, d, bi, 0};
    cont_system s;
    eq_system(&s, &e);
    const int how = cont_branch_direction(&s, z, t, v);
    if (how < 0) {
        free(buf);
        return 0; /* no second direction: not switched */
    }
    if (how == 1)
        add_note(note, note_len,
                 "at the BP %.40s = %.12g of branch %d the branching equation is degenerate: "
                 "the other branch is followed from the direction orthogonal to the branch",
                 cm->m->params[o->ip].name, z[n], b->id);
    int rc = 0;
    const int parent = b->id;
    for (int dir = 1; dir >= -1 && rc == 0 && d->count < o->max_branches; dir -= 2) {
        for (int i = 0; i < M; i++)
            z2[i] = dir * v[i];
        rc = follow_branch(cm, o, d, z, z2, DYN_LABEL_BP, parent, k, w);
    }
    free(buf);
    return rc == 1 ? 0 : rc;
}

/* Switch at the PD `k` of branch bi of a map (points of period cm->period): the points of
 * twice the period leave the branch along the eigenvector of the multiplier -1 (Kuznetsov,
 * Elements, sec. 4.4), followed one way, as AUTO-07p's ISW = -1 does (the other way is the
 * other point of the same cycles); their first point is labelled PD. */
static int switch_pd(cont_model *cm, const dyn_cont_opts *o, dyn_diagram *d, int bi, long k,
                     cont_work *w, char *note, size_t note_len)
{
    const int n = cm->n, M = n + 1, period = cm->period;
    const dyn_branch *b = &d->branches[bi];
    if (2 * period > CONT_MAP_MAX_PERIOD) {
        add_note(note, note_len, "the points of period %d from the PD at %.40s = %.12g are not "
                 "followed (at most period %d)", 2 * period, cm->m->params[o->ip].name,
                 b->pts[k].par[0], CONT_MAP_MAX_PERIOD);
        return 0;
    }
    double *buf = malloc((2 * (size_t)M + 2 * (size_t)n * (size_t)n) * sizeof *buf);
    if (!buf)
        return -1;
    double *z = buf, *v = z + M, *J = v + M, *G = J + (size_t)n * (size_t)n;
    branch_point(b, k, z);
    const int parent = b->id;
    /* the null vector of dF^k/dy + I = (dF^k/dy - I) + 2 I */
    int rc = cont_model_set(cm, z[n], NAN) || cont_model_jx(cm, z, J, n);
    for (int i = 0; i < n && !rc; i++)
        J[(size_t)i * (size_t)n + (size_t)i] += 2.0;
    if (!rc)
        rc = cont_normal_factor(J, n, n, 0, G) || cont_inverse_iteration(G, n, 1, 4, v);
    if (rc) {
        add_note(note, note_len, "no branch of period %d from the PD at %.40s = %.12g: its "
                 "eigenvector was not found", 2 * period, cm->m->params[o->ip].name, z[n]);
        free(buf);
        return 0;
    }
    v[n] = 0.0;
    cm->period = 2 * period;
    const int first = d->count;
    rc = follow_branch(cm, o, d, z, v, DYN_LABEL_BP, parent, k, w);
    if (d->count > first && d->branches[first].count > 0)
        d->branches[first].pts[0].label = DYN_LABEL_PD;
    cm->period = period;
    free(buf);
    return rc == 1 ? 0 : rc;
}

static int fail(dyn_cont_info *info, int status, const char *fmt, const char *what)
{
    if (info)
        snprintf(info->message, sizeof info->message, fmt, what);
    return status;
}

/* The names of the states whose components of the unit vector v (n) are at least a tenth
 * of the largest, comma-separated into out. */
static void large_components(const dyn_model *m, const double *v, int n, char *out, size_t len)
{
    double vmax = 0.0;
    for (int i = 0; i < n; i++)
        vmax = fmax(vmax, fabs(v[i]));
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; i < n; i++) {
        if (!(fabs(v[i]) >= 0.1 * vmax))
            continue;
        const char *name = m->states[i].name;
        if (used + strlen(name) + 6 >= len) {
            snprintf(out + used, len - used, "%s...", used ? ", " : "");
            return;
        }
        used += (size_t)snprintf(out + used, len - used, "%s%s", used ? ", " : "", name);
    }
}

/* Newton's method alone from the guess x0 "converged" far away (its step is judged relative
 * to |z|, which grows without bound along a valley where f saturates: a published islet
 * model went from G6P = 196 to -8.5e18, where |f| = 4e-3): no start, with the reason in
 * ei. Far: |z - x0|_inf > 1e8 max(|x0|_inf, 1). */
static int start_ran_away(const dyn_model *m, const double *z, const double *x0, int n,
                          dyn_equilibrium_info *ei)
{
    double scale = 1.0, dist = 0.0;
    int far = 0;
    for (int i = 0; i < n; i++) {
        scale = fmax(scale, fabs(x0[i]));
        if (fabs(z[i] - x0[i]) > dist) {
            dist = fabs(z[i] - x0[i]);
            far = i;
        }
    }
    if (!(dist > 1e8 * scale))
        return 0;
    snprintf(ei->message, sizeof ei->message,
             "Newton's method ran away from the guess (%.40s to %.3g)",
             far < m->n_states ? m->states[far].name : "a state", z[far]);
    return 1;
}

/* Why the start z is singular ([f_x f_p] of rank below n): when f_x is singular to rounding
 * there, the states along its null vector and the states whose rates' rows are dependent
 * (its left null vector: a conserved combination), by inverse iteration on f_x^T f_x and
 * f_x f_x^T. There the equilibria are not isolated (a state conserved or absent from f:
 * every parameter value has a family of them), or the start is a fold or branch point. A
 * map's (map 1) are said of dF/dy - I and its fixed points. */
static void singular_start_message(const cont_system *s, const dyn_model *m, int map,
                                   const double *z, char *msg, size_t len)
{
    const int n = s->N, M = n + 1;
    const size_t nn = (size_t)n * (size_t)n;
    snprintf(msg, len, "the start is singular (a fold or a branch point): start elsewhere");
    double *J = malloc(((size_t)n * (size_t)M + 2 * nn + 2 * (size_t)n) * sizeof *J);
    if (!J)
        return;
    double *fx = J + (size_t)n * (size_t)M, *G = fx + nn, *v = G + nn, *u = v + n;
    double big = 0.0, res = INFINITY;
    if (s->jacobian(s->ctx, z, J) == 0) {
        for (int r = 0; r < n; r++)
            for (int c = 0; c < n; c++) {
                fx[(size_t)r * (size_t)n + (size_t)c] = J[(size_t)r * (size_t)M + (size_t)c];
                big = fmax(big, fabs(fx[(size_t)r * (size_t)n + (size_t)c]));
            }
        if (cont_normal_factor(fx, n, n, 0, G) == 0 && cont_inverse_iteration(G, n, 1, 8, v) == 0 &&
            cont_normal_factor(fx, n, n, 1, G) == 0 && cont_inverse_iteration(G, n, 1, 8, u) == 0) {
            /* |f_x v|: singular to rounding? */
            res = 0.0;
            for (int r = 0; r < n; r++) {
                double a = 0.0;
                for (int c = 0; c < n; c++)
                    a += fx[(size_t)r * (size_t)n + (size_t)c] * v[c];
                res = fmax(res, fabs(a));
            }
        }
    }
    if (res <= 1e-10 * fmax(big, 1e-300)) {
        char along[32], rows[32]; /* the message within info.message's 256 bytes */
        large_components(m, v, n, along, sizeof along);
        large_components(m, u, n, rows, sizeof rows);
        snprintf(msg, len,
                 "the start is singular: %s is singular (null vector along %s; rows of %s "
                 "dependent): a family of %s (a conserved quantity, a state not in %s) or a "
                 "branch point; start elsewhere",
                 map ? "dF/dy - I" : "f_x", along, rows, map ? "fixed points" : "equilibria",
                 map ? "F" : "f");
    }
    free(J);
}

/* 1 when a step h along t from the start z, corrected, has moved the parameter: z is a
 * fold, where p changes at second order, and not a family of equilibria at one parameter
 * value, along which t also lies where [f_x f_p] has full rank (z' = p - z, w' = z - 1 at
 * p = 1: every w) */
static int fold_start(const cont_system *s, cont_work *w, const double *z, const double *t,
                      double h, int n)
{
    const int M = n + 1;
    double *zp = malloc((size_t)M * sizeof *zp);
    if (!zp)
        return 0;
    for (int k = 0; k < M; k++)
        zp[k] = z[k] + h * t[k];
    const int moved = cont_correct(s, w, z, t, h, zp, NULL) == 0 &&
                      fabs(zp[n] - z[n]) > 1e-8 * h * h * (1.0 + fabs(z[n]));
    free(zp);
    return moved;
}

int dyn_continue(const dyn_model *m, const void *par, const double *x0, const dyn_cont_opts *o,
                 dyn_diagram *d, dyn_cont_info *info)
{
    dyn_cont_info local;
    if (!info)
        info = &local;
    memset(info, 0, sizeof *info);
    if (!m || !par || !x0 || !o || !d)
        return fail(info, DYN_ERR_ARG, "%s", "a NULL argument");
    if (o->ip < 0 || o->ip >= m->n_params)
        return fail(info, DYN_ERR_ARG, "%s", "the parameter's index is out of range");
    if (o->ip2 >= m->n_params || o->ip2 == o->ip)
        return fail(info, DYN_ERR_ARG, "%s", "the second parameter must be another one");
    if (!(o->ds != 0.0) || !(o->dsmin > 0.0) || !(o->dsmax >= o->dsmin) ||
        !(fabs(o->ds) >= o->dsmin) || !isfinite(o->dsmax))
        return fail(info, DYN_ERR_ARG, "%s",
                    "the steps must satisfy 0 < dsmin <= |ds| <= dsmax (finite)");
    if (o->nmax < 2)
        return fail(info, DYN_ERR_ARG, "%s", "nmax must be at least 2");
    if (m->n_states < 1)
        return fail(info, DYN_ERR_ARG, "%s", "the model has no states");
    cont_model cm;
    if (cont_model_init(&cm, m, par, o))
        return fail(info, DYN_ERR_ARG, "%s", "out of memory");
    const int n = m->n_states, M = n + 1;
    cont_work w;
    double *z = malloc(3 * (size_t)M * sizeof *z);
    if (cont_work_init(&w, n) || !z) {
        cont_model_free(&cm);
        cont_work_free(&w);
        free(z);
        return fail(info, DYN_ERR_ARG, "%s", "out of memory");
    }
    double *t = z + M, *e = t + M;
    memcpy(z, x0, (size_t)n * sizeof *z);
    z[n] = cm.p_set[0];
    int rc = 0;
    /* a forced model: its branch is that of the model frozen at o->t, with a note */
    char time_note[sizeof info->message] = "";
    const int forced = cont_time_dependent(&cm, z, time_note, sizeof time_note) == 1;
    eq_ctx ec = {&cm, d, -1, 0};
    cont_system s;
    eq_system(&s, &ec);
    /* the start: Newton's method at the fixed parameter (the arclength row is e_p) */
    for (int i = 0; i < M; i++)
        e[i] = i == n ? 1.0 : 0.0;
    /* Levenberg-Marquardt from the guess (dyn_equilibrium), then Newton's method; where
     * Levenberg-Marquardt stalls at a minimum of |f| that is not a zero (van der Pol from
     * its initial state (2, 0)), Newton's method alone from the guess */
    dyn_equilibrium_info ei;
    const dyn_equilibrium_opts eo = {{o->jac, NULL}, 0.0, 0};
    double *ework = malloc(dyn_equilibrium_work_size(n) * sizeof *ework);
    const int have_work = ework != NULL;
    /* a map's start: Newton's method on F(y) - y alone */
    int eq_rc = have_work && !o->map ? dyn_equilibrium(m, o->t, z, cm.par, &eo, ework, &ei) : -1;
    free(ework);
    if (o->map)
        snprintf(ei.message, sizeof ei.message, "Newton's method on F(y) - y diverged");
    if (eq_rc && have_work) {
        memcpy(z, x0, (size_t)n * sizeof *z);
        z[n] = cm.p_set[0];
        if (cont_correct(&s, &w, z, e, 0.0, z, NULL) == 0 && !start_ran_away(m, z, x0, n, &ei))
            eq_rc = 0;
    }
    if (eq_rc || cont_correct(&s, &w, z, e, 0.0, z, NULL)) {
        snprintf(info->message, sizeof info->message,
                 "no equilibrium found near the start at %.40s = %s: %.120s",
                 m->params[o->ip].name, dyn_shortest(cm.p_set[0]).s,
                 eq_rc ? ei.message : cm.message[0] ? cm.message : "Newton's method diverged");
        info->start_failed = 1;
        rc = DYN_ERR_ARG;
    }
    if (rc == 0 && !(z[n] >= o->parmin && z[n] <= o->parmax)) {
        snprintf(info->message, sizeof info->message,
                 "the start %.40s = %s is outside [parmin, parmax] = [%s, %s]",
                 m->params[o->ip].name, dyn_shortest(z[n]).s, dyn_shortest(o->parmin).s,
                 dyn_shortest(o->parmax).s);
        rc = DYN_ERR_ARG;
    }
    if (rc == 0) {
        e[n] = o->ds > 0.0 ? 1.0 : -1.0;
        double det;
        int tst = cont_tangent(&s, &w, z, e, t, &det);
        /* at a fold f_x is singular but [f_x f_p] is not (x' = p - x^2 from p = 0): the
         * tangent bordered by a state's unit vector instead, as AUTO-07p starts there */
        for (int i = 0; tst == 1 && i < n; i++) {
            for (int k = 0; k < M; k++)
                e[k] = k == i ? 1.0 : 0.0;
            tst = cont_tangent(&s, &w, z, e, t, &det);
            /* the way of ds in the parameter, or in that state where the branch turns */
            const double lead = fabs(t[n]) > 1e-8 ? t[n] : t[i];
            if (tst == 0 && lead * o->ds < 0.0)
                for (int k = 0; k < M; k++)
                    t[k] = -t[k];
            if (tst == 0 && !fold_start(&s, &w, z, t, fabs(o->ds), n))
                tst = 1;
        }
        if (tst) {
            singular_start_message(&s, m, o->map, z, info->message, sizeof info->message);
            rc = DYN_ERR_ARG;
        }
    }
    if (rc == 0 && follow_branch(&cm, o, d, z, t, DYN_LABEL_EP, 0, -1, &w) < 0)
        rc = DYN_ERR_ARG;
    char note[sizeof info->message] = "";
    /* branch switching at the BPs, breadth first over the branches found */
    for (int bi = 0; rc == 0 && !o->no_switch && bi < d->count; bi++) {
        if (d->branches[bi].kind != DYN_BRANCH_EQUILIBRIUM)
            continue;
        if (o->map && d->branches[bi].count > 0) /* a map's branch: its points' period */
            cm.period = (int)d->branches[bi].pts[0].period;
        for (long k = 0; rc == 0 && k < d->branches[bi].count; k++) {
            const dyn_cont_label l = d->branches[bi].pts[k].label;
            /* a branch's first point labelled PD is where it was born */
            if ((l != DYN_LABEL_BP && (l != DYN_LABEL_PD || !o->map ||
                                       (k == 0 && d->branches[bi].parent > 0))) ||
                d->count >= o->max_branches)
                continue;
            if (l == DYN_LABEL_BP ? switch_at(&cm, o, d, bi, k, &w, note, sizeof note)
                                  : switch_pd(&cm, o, d, bi, k, &w, note, sizeof note))
                rc = DYN_ERR_ARG;
        }
    }
    cm.period = 1;
    /* periodic orbits from the Hopf points, then the curves in two parameters */
    const int n_eq = d->count;
    for (int bi = 0; rc == 0 && bi < n_eq; bi++) {
        if (o->map && d->branches[bi].count > 0) /* a map's branch: its points' period */
            cm.period = (int)d->branches[bi].pts[0].period;
        for (long k = 0; rc == 0 && k < d->branches[bi].count; k++) {
            const dyn_cont_label l = d->branches[bi].pts[k].label;
            /* a map's flips in two parameters, not where a branch of cycles was born */
            const int flip = o->map && l == DYN_LABEL_PD &&
                             !(k == 0 && d->branches[bi].parent > 0);
            if (l == DYN_LABEL_HB && o->periodic) {
                char err[256] = "";
                if (o->periodic(m, par, o, d, d->branches[bi].id, k, o->periodic_ctx, err,
                                sizeof err))
                    add_note(note, sizeof note,
                             "periodic orbits from the Hopf point of branch %d: %.180s", bi + 1,
                             err);
            }
            const int ns = o->map && l == DYN_LABEL_TR;
            if ((l == DYN_LABEL_HB || l == DYN_LABEL_LP || flip || ns) && o->ip2 >= 0 &&
                cont_curves_from(&cm, o, d, bi, k, info))
                rc = DYN_ERR_ARG;
        }
    }
    cm.period = 1;
    if (cm.missed.count > 0) {
        char missed[sizeof note];
        cont_missed_text(&cm.missed, m->params[o->ip].name, missed, sizeof missed);
        add_note(note, sizeof note, "%s", missed);
    }
    if (rc && !info->message[0])
        snprintf(info->message, sizeof info->message, "%s",
                 cm.message[0] ? cm.message : "out of memory");
    else if (rc == 0 && note[0]) /* the notes of switching and periodic orbits, after others */
        add_note(info->message, sizeof info->message, "%s", note);
    if (rc == 0 && forced) { /* first: the other notes may fill the message */
        if (info->message[0])
            add_note(time_note, sizeof time_note, "%s", info->message);
        memcpy(info->message, time_note, sizeof time_note);
    }
    for (int bi = 0; bi < d->count; bi++)
        info->points += d->branches[bi].count;
    info->newton_steps = w.newton;
    info->rhs_calls = cm.rhs_calls;
    cont_model_free(&cm);
    cont_work_free(&w);
    free(z);
    return rc;
}
