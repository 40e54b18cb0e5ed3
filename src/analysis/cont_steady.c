/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady.c — a branch of steady motions (relative equilibria) in one parameter
 * (dynkit/steady.h, dyn_steady_continue): the start solved by dyn_steady_solve, the steady
 * equations used chosen among the derivatives of the non-cyclic kept states E (as many as
 * there are unknowns, by complete pivoting), the branch followed by the pseudo-arclength loop
 * of cont_core.c on the system of cont_steady_system.c, then the branches from its branch
 * points (cont_steady_switch.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h"
#include "cont_steady_switch.h"
#include "cont_steady_system.h"

/* The nu equations among E's ne whose rows of G_U (ne x nu, row-major) are independent:
 * Gaussian elimination with complete pivoting on the rows scaled to a largest entry of 1
 * (those below 1e-8 of the largest entry of all by that entry), pivots below 1e-10 of the
 * largest entry refused. Of pivots equal within 1e-9 the earlier
 * equation's is taken: a mechanism's coordinates come before its speeds, and their
 * equations q' = u keep their rows whatever the state, where a speed's equation that
 * holds with them at the start can lose its row along the branch (a body's turning
 * rate psi'' = -(dI/dtheta / I) psi' theta', whose row vanishes where the cone closes,
 * theta = 0: chosen, it makes the branch's equations singular there and a pitchfork
 * a fold). Positions into sel; 0, or -1 when G_U's rank is below nu. */
static int select_equations(int ne, int nu, double *G, int *sel)
{
    double big0 = 0.0;
    for (int i = 0; i < ne * nu; i++)
        big0 = fmax(big0, fabs(G[i]));
    for (int i = 0; i < ne; i++) {
        double s = 0.0;
        for (int j = 0; j < nu; j++)
            s = fmax(s, fabs(G[i * nu + j]));
        if (!(s > 1e-8 * big0))
            s = big0; /* a row of differencing noise (an equation that holds by itself)
                       * is not raised to the others' size */
        for (int j = 0; j < nu && s > 0.0; j++)
            G[i * nu + j] /= s;
    }
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
                if (!row_used[i] && !col_used[j] && fabs(G[i * nu + j]) > best * (1.0 + 1e-9)) {
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
                 "no steady motion found near the start at %.40s = %s: %.120s",
                 m->params[o->ip].name, dyn_shortest(cm->p_set[0]).s, si.message);
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
        rc = sc_state_at(c, c->H);
        for (int e = 0; e < ne && !rc; e++)
            ut[e] = c->f[sp->equations[e]];
        c->H[j] = z[j] - h;
        rc = rc ? rc : sc_state_at(c, c->H);
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
    if (o->ip2 >= m->n_params || o->ip2 == o->ip)
        return fail(info, "the second parameter must be another one");
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
    c.p2 = NAN;
    int *ints = malloc((4 * N + 3 * NE + NU) * sizeof *ints);
    const size_t nd = 4 * N + 1 + 5 * N * N + dyn_linearize_work_size(n) + NE * NE + NU * NE +
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
    c.piv = c.epos + NE;
    c.y = mem;
    c.f = c.y + N;
    double *z = c.f + N; /* (N + 1 values: nu + 1 used, nu <= n) */
    c.A = z + N + 1;
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
                 "the start %.40s = %s is outside [parmin, parmax] = [%s, %s]",
                 m->params[o->ip].name, dyn_shortest(z[nu]).s, dyn_shortest(o->parmin).s,
                 dyn_shortest(o->parmax).s);
        rc = DYN_ERR_ARG;
    }
    cont_system s;
    sc_system(&s, &c);
    /* the residual at its rounding, as dyn_steady_solve's: 1e-12 max(||f||_inf, 1) */
    if (rc == 0 && sc_state_at(&c, z))
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
    const int first = d->count;
    if (rc == 0 && sc_follow(&c, &s, &w, o, NULL, z, t, DYN_LABEL_EP, 0, -1))
        rc = fail(info, c.message[0] ? c.message : "the right-hand side failed at the start");
    /* the other branches at the branch points */
    char note[sizeof info->message] = "";
    if (rc == 0 && !o->no_switch && sc_switch_all(&c, &s, &w, o, first, note, sizeof note))
        rc = fail(info, c.message[0] ? c.message : "out of memory");
    /* the curves of folds and Hopf points in two parameters */
    if (rc == 0 && o->ip2 >= 0 && sc_curves_all(&c, &s, o, first, note, sizeof note))
        rc = fail(info, c.message[0] ? c.message : "out of memory");
    if (rc == 0 && cm.missed.count > 0) {
        const size_t used = strlen(note);
        if (used > 0 && used + 2 < sizeof note)
            memcpy(note + used, "; ", 3);
        cont_missed_text(&cm.missed, m->params[o->ip].name, note + strlen(note),
                         sizeof note - strlen(note));
    }
    if (rc == 0 && c.dropped > 1e-8)
        snprintf(info->message, sizeof info->message,
                 "the steady equations not used hold only to %.3g relative%s%.400s", c.dropped,
                 note[0] ? "; " : "", note);
    else if (rc == 0)
        snprintf(info->message, sizeof info->message, "%s", note);
    for (int bi = first; rc == 0 && bi < d->count; bi++)
        info->points += d->branches[bi].count;
    info->newton_steps = w.newton;
    info->rhs_calls = cm.rhs_calls;
    free(t);
    free(ints);
    free(mem);
    cont_work_free(&w);
    cont_model_free(&cm);
    return rc;
}
