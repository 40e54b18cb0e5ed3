/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_core.c — pseudo-arclength continuation of G(z) = 0, G: R^(N+1) -> R^N (cont_core.h):
 * Euler predictor along the unit tangent, Newton corrector on G(z) = 0 with the
 * arclength condition t . (z - z0) = ds (Keller 1977), the tangent as the solution of
 * [DG; t_old^T] t = e_(N+1), step control between dsmin and dsmax from Newton's iterations
 * (Doedel, Keller & Kernevez 1991, sec. 2.2; AUTO-07p's manual, ch. 5), and special points
 * located where a test function changes sign by the Illinois variant of the secant method
 * on the arclength (Dowell & Jarratt 1971), each trial point corrected onto the branch.
 * The sign of det [DG; t^T] changes at branch points (Keller): its value scaled by the rows'
 * norms (|.| <= 1 by Hadamard's inequality) is the branch-point test. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h"
#include "cont_core.h"
#include "ode/linalg.h"

#define CONT_MAX_NEWTON 12

int cont_work_init(cont_work *w, int N)
{
    memset(w, 0, sizeof *w);
    w->N = N;
    const size_t M = (size_t)N + 1;
    w->A = malloc((M * M + 4 * M) * sizeof *w->A);
    w->piv = malloc(M * sizeof *w->piv);
    if (!w->A || !w->piv) {
        cont_work_free(w);
        return -1;
    }
    w->r = w->A + M * M;
    w->dz = w->r + M;
    w->g = w->dz + M;
    w->zp = w->g + M;
    return 0;
}

void cont_work_free(cont_work *w)
{
    free(w->A);
    free(w->piv);
    w->A = NULL;
    w->piv = NULL;
}

static double norm_inf(const double *v, int n)
{
    double b = 0.0;
    for (int i = 0; i < n; i++)
        b = fmax(b, fabs(v[i]));
    return b;
}

static double dot(const double *a, const double *b, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

/* A = [DG(z); c^T] in w->A */
static int bordered(const cont_system *s, cont_work *w, const double *z, const double *c)
{
    const int M = s->N + 1;
    if (s->jacobian(s->ctx, z, w->A))
        return -1;
    memcpy(w->A + (size_t)s->N * (size_t)M, c, (size_t)M * sizeof *c);
    for (size_t k = 0; k < (size_t)M * (size_t)M; k++)
        if (!isfinite(w->A[k]))
            return -1;
    return 0;
}

int cont_correct(const cont_system *s, cont_work *w, const double *z0, const double *t0,
                 double ds, double *z, int *iters)
{
    const int N = s->N, M = N + 1;
    for (int it = 0; it < CONT_MAX_NEWTON; it++) {
        w->newton++;
        if (s->residual(s->ctx, z, w->g))
            return -1;
        for (int i = 0; i < N; i++)
            w->r[i] = -w->g[i];
        double arc = -ds;
        for (int i = 0; i < M; i++)
            arc += t0[i] * (z[i] - z0[i]);
        w->r[N] = -arc;
        const double gnorm = norm_inf(w->g, N);
        const int at_rounding =
            s->gtol > 0.0 && gnorm <= s->gtol && fabs(arc) <= DYN_CONT_TOL * (1.0 + norm_inf(z, M));
        if (at_rounding) {
            /* G is as small as its rounding allows at the scale of the whole right-hand
             * side; a Newton step is still taken while it halves G (near a pitchfork G
             * is far smaller than that scale, and stopping there would leave the point
             * off the branch by gtol^(1/3)), but not where it would only amplify the
             * rounding (at a branch point the step is nearly singular) */
            if (bordered(s, w, z, t0) || dyn_lu_factor(M, w->A, w->piv) || gnorm == 0.0) {
                if (iters)
                    *iters = it + 1;
                return 0;
            }
            dyn_lu_solve(M, w->A, w->piv, w->r);
            for (int i = 0; i < M; i++)
                w->zp[i] = z[i] + w->r[i];
            if (s->residual(s->ctx, w->zp, w->g) || !(norm_inf(w->g, N) <= 0.5 * gnorm)) {
                if (s->residual(s->ctx, z, w->g)) /* the context back at z */
                    return -1;
                if (iters)
                    *iters = it + 1;
                return 0;
            }
            memcpy(z, w->zp, (size_t)M * sizeof *z);
            if (norm_inf(w->r, M) <= DYN_CONT_TOL * (1.0 + norm_inf(z, M))) {
                if (iters)
                    *iters = it + 1;
                return 0;
            }
            continue;
        }
        if (bordered(s, w, z, t0))
            return -1;
        if (dyn_lu_factor(M, w->A, w->piv)) {
            /* exactly singular (a branch point hit exactly): converged if it already
             * solves the equations */
            if (norm_inf(w->r, M) <= DYN_CONT_TOL * (1.0 + norm_inf(z, M))) {
                if (iters)
                    *iters = it + 1;
                return 0;
            }
            return -1;
        }
        dyn_lu_solve(M, w->A, w->piv, w->r);
        for (int i = 0; i < M; i++)
            z[i] += w->r[i];
        if (!isfinite(norm_inf(z, M)))
            return -1;
        if (norm_inf(w->r, M) <= DYN_CONT_TOL * (1.0 + norm_inf(z, M))) {
            if (iters)
                *iters = it + 1;
            return 0;
        }
    }
    w->fails++;
    return -1;
}

/* det of the LU factors in w->A (n x n) divided by the product of the rows' norms of the
 * matrix before factoring (rownorm), each at least 1e-3 of the largest: a row that
 * vanishes at the branch point (a state whose equation decouples on a trivial branch, as
 * u' = (p - p0) u) would make the quotient a step from -1 to 1, which the secant steps
 * do not converge on */
static double scaled_det(int n, const double *LU, const int *piv, const double *rownorm)
{
    double big = 0.0;
    for (int i = 0; i < n; i++)
        big = fmax(big, rownorm[i]);
    const double floor_norm = big > 0.0 ? 1e-3 * big : 1.0;
    double d = 1.0;
    for (int i = 0; i < n; i++) {
        d *= LU[(size_t)i * (size_t)n + (size_t)i] / fmax(rownorm[i], floor_norm);
        if (piv[i] != i)
            d = -d;
    }
    return d;
}

int cont_tangent(const cont_system *s, cont_work *w, const double *z, const double *t_old,
                 double *t, double *det)
{
    const int M = s->N + 1;
    if (bordered(s, w, z, t_old))
        return -1;
    for (int i = 0; i < M; i++)
        w->dz[i] = sqrt(dot(w->A + (size_t)i * (size_t)M, w->A + (size_t)i * (size_t)M, M));
    if (dyn_lu_factor(M, w->A, w->piv))
        return 1; /* exactly singular: a branch point itself */
    if (det)
        *det = scaled_det(M, w->A, w->piv, w->dz);
    for (int i = 0; i < M; i++)
        t[i] = i == s->N ? 1.0 : 0.0;
    dyn_lu_solve(M, w->A, w->piv, t);
    const double nt = sqrt(dot(t, t, M));
    if (!(nt > 0.0) || !isfinite(nt))
        return -1;
    for (int i = 0; i < M; i++)
        t[i] /= nt;
    return 0;
}

int cont_null_direction(const cont_system *s, cont_work *w, const double *z, const double *t,
                        double *v)
{
    const int M = s->N + 1;
    if (bordered(s, w, z, t))
        return -1;
    if (dyn_lu_factor(M, w->A, w->piv)) {
        /* exactly singular: 1e-14 of the largest entry on the diagonal (the null vector
         * moves by as little) */
        if (bordered(s, w, z, t))
            return -1;
        double big = 0.0;
        for (size_t k = 0; k < (size_t)M * (size_t)M; k++)
            big = fmax(big, fabs(w->A[k]));
        for (int i = 0; i < M; i++)
            w->A[(size_t)i * (size_t)M + (size_t)i] += 1e-14 * (big > 0.0 ? big : 1.0) * (1.0 + 0.1 * i);
        if (dyn_lu_factor(M, w->A, w->piv))
            return -1;
    }
    for (int i = 0; i < M; i++)
        v[i] = 1.0 / (1.0 + i) * (i % 2 ? -1.0 : 1.0) + 0.1;
    for (int it = 0; it < 4; it++) {
        dyn_lu_solve(M, w->A, w->piv, v);
        const double nv = sqrt(dot(v, v, M));
        if (!(nv > 0.0) || !isfinite(nv))
            return -1;
        for (int i = 0; i < M; i++)
            v[i] /= nv;
    }
    /* v orthogonal to t (it is, up to the location's error) */
    const double c = dot(v, t, M);
    for (int i = 0; i < M; i++)
        v[i] -= c * t[i];
    const double nv = sqrt(dot(v, v, M));
    if (!(nv > 0.0))
        return -1;
    for (int i = 0; i < M; i++)
        v[i] /= nv;
    return 0;
}

/* ---- the loop ---- */

void cont_missed_text(const cont_missed *m, const char *par, char *buf, size_t len)
{
    if (m->count == 0) {
        if (len > 0)
            buf[0] = '\0';
        return;
    }
    snprintf(buf, len,
             "%d special point%s detected but not located, not in the output (the first: %s "
             "between %.40s = %.10g and %.10g); smaller steps (dsmax, dsmin) may locate %s",
             m->count, m->count > 1 ? "s" : "", dyn_cont_label_name(m->label), par, m->p0,
             m->p1, m->count > 1 ? "them" : "it");
}

void cont_loop_from_opts(const dyn_cont_opts *o, cont_loop *L, dyn_cont_label start)
{
    memset(L, 0, sizeof *L);
    L->ds = fabs(o->ds);
    L->dsmin = o->dsmin;
    L->dsmax = o->dsmax;
    L->nmax = o->nmax;
    L->pmin = o->parmin;
    L->pmax = o->parmax;
    L->p2min = L->p2max = 0.0;
    L->at = o->at;
    L->n_at = o->n_at;
    L->start_label = start;
}

double cont_hopf_test(int n, const double *re, const double *im, double above, int *unstable,
                      double *omega)
{
    double scale = 0.0;
    for (int i = 0; i < n; i++)
        scale = fmax(scale, hypot(re[i], im[i]));
    const double small = 1e-8 * fmax(scale, DBL_MIN);
    double best = 1.0, best_abs = INFINITY;
    *unstable = 0;
    if (omega)
        *omega = NAN;
    for (int i = 0; i < n; i++) {
        if (!(fabs(im[i]) > small))
            continue;
        if (re[i] > above)
            (*unstable)++;
        if (fabs(re[i]) < best_abs) {
            best_abs = fabs(re[i]);
            best = re[i];
            if (omega)
                *omega = fabs(im[i]);
        }
    }
    return best;
}

typedef struct special {
    double s;
    dyn_cont_label label;
    double *z, *t;
} special;

/* Drop sp[k] of the *ns points of a step: swapped with the last, whose place it takes with
 * its buffers (each entry owns its z and t for the whole branch). */
static void drop_special(special *sp, int *ns, int k)
{
    const special tmp = sp[k];
    sp[k] = sp[--*ns];
    sp[*ns] = tmp;
}

/* what a located function is: test k, or z[index] - target */
typedef struct target {
    int test;     /* >= 0: the test function's index */
    int index;    /* else the component of z */
    double value;
} target;

static int psi_at(const cont_system *s, cont_work *w, const target *g, const double *z,
                  const double *t_old, double *t, double *psi)
{
    double det;
    const int tangent = cont_tangent(s, w, z, t_old, t, &det);
    if (tangent < 0)
        return -1;
    if (tangent > 0) {
        /* the bordered matrix is exactly singular: a secant step landed on the branch
         * point itself, where the determinant is 0 and the tangent is not defined */
        det = 0.0;
        memcpy(t, t_old, (size_t)(s->N + 1) * sizeof *t);
    }
    if (g->test < 0) {
        *psi = z[g->index] - g->value;
        return 0;
    }
    double all[CONT_MAX_TESTS];
    int count[CONT_MAX_TESTS];
    if (s->tests(s->ctx, z, t, det, all, count))
        return -1;
    *psi = all[g->test];
    return 0;
}

/* The guess for the trial point at arclength c of the plane ta . (z - za) = c: from the
 * bracket's end nearer to c (zn, tangent tn, at arclength sn) along its tangent onto the
 * plane. Near a branch point the plane meets both branches and the corrector's matrix is
 * nearly singular: Newton's method converges there only from a guess this close. */
static void trial_guess(int M, const double *ta, double c, const double *zn, const double *tn,
                        double sn, double *z)
{
    const double along = dot(ta, tn, M);
    const double h = fabs(along) > 0.1 ? (c - sn) / along : c - sn;
    for (int i = 0; i < M; i++)
        z[i] = zn[i] + h * tn[i];
}

/* How near zero |psi| must be at an end of a bracket taken as the point, relative to the
 * larger |psi| at the step's ends (locate) */
#define LOCATE_ZERO 1e-4

/* Whether an end of the bracket [a, b] (pa, pb the points at its ends) with |psi| = abs_f
 * there is the zero sought: psi is near zero there (abs_f <= zero), or the branch is one
 * piece across the bracket, its ends' points no farther apart than 10 |b - a| (about
 * |b - a| along it), as for a test that is a sign. Else psi jumped because the corrector
 * went over to another branch. */
static int end_is_zero(int M, double abs_f, double zero, const double *pa, const double *pb,
                       double a, double b)
{
    if (abs_f <= zero)
        return 1;
    double d = 0.0, scale = 1.0;
    for (int i = 0; i < M; i++) {
        d += (pb[i] - pa[i]) * (pb[i] - pa[i]);
        scale = fmax(scale, fabs(pa[i]));
    }
    return sqrt(d) <= 10.0 * fabs(b - a) + 1e-12 * scale;
}

/* Locate psi = 0 for s in (0, sb) along (za, ta) where psi(0) = fa and psi(sb) = fb have
 * opposite signs (zb, tb the point and tangent at sb): z, t the point found. A trial point
 * whose correction fails (near a branch point the corrector's matrix is nearly singular and
 * Newton's method converges only from close by) is moved halfway to the bracket's nearer
 * end. When no trial point inside the bracket can be corrected any more and the bracket is
 * narrower than 1e-8 of the step, its end of the smaller |psi| is the point. An end of a
 * bracket is taken only where end_is_zero says so; else nothing is located. 0 or
 * non-zero. */
static int locate(const cont_system *s, cont_work *w, const target *g, const double *za,
                  const double *ta, double fa, double sb, double fb, const double *zb,
                  const double *tb, double *z, double *t, double *s_found)
{
    const int M = s->N + 1;
    double a = 0.0, b = sb;
    double *zt = malloc(8 * (size_t)M * sizeof *zt);
    if (!zt)
        return -1;
    /* the trial point and its tangent; the points and tangents at a and b; the guess and
     * the coordinate row of the correction */
    double *tt = zt + M, *pa = tt + M, *qa = pa + M, *pb = qa + M, *qb = pb + M, *zg = qb + M;
    double *ei = zg + M;
    memcpy(pa, za, (size_t)M * sizeof *pa);
    memcpy(qa, ta, (size_t)M * sizeof *qa);
    memcpy(pb, zb, (size_t)M * sizeof *pb);
    memcpy(qb, tb, (size_t)M * sizeof *qb);
    memcpy(z, zb, (size_t)M * sizeof *z);
    double c = b, c_prev = a;
    double abs_fa = fabs(fa), abs_fb = fabs(fb); /* |psi| at the ends (fa is scaled) */
    const double zero = LOCATE_ZERO * fmax(abs_fa, abs_fb);
    int ok = -1;
    for (int it = 0; it < 80; it++) {
        c = fb != fa ? (a * fb - b * fa) / (fb - fa) : 0.5 * (a + b);
        /* keep inside the bracket, away from its ends by a sliver */
        const double lo = fmin(a, b), hi = fmax(a, b);
        if (!(c > lo && c < hi))
            c = 0.5 * (a + b);
        if (it > 0 && fmin(fabs(c - a), fabs(c - b)) <= 1e-12 * fabs(sb)) {
            /* converged on an end of the bracket: b is the last trial point, in z */
            const int end_a = fabs(c - a) < fabs(c - b) && a != 0.0;
            if (end_a) {
                memcpy(z, pa, (size_t)M * sizeof *z);
                memcpy(t, qa, (size_t)M * sizeof *t);
                *s_found = a;
            }
            ok = end_is_zero(M, end_a ? abs_fa : abs_fb, zero, pa, pb, a, b) ? 0 : -1;
            break;
        }
        double fc = 0.0;
        int failed = 1;
        for (int tries = 0; tries < 9 && failed; tries++) {
            const int near_a = fabs(c - a) < fabs(c - b);
            const double h = fabs(c - (near_a ? a : b));
            const double *tn = near_a ? qa : qb;
            /* the guess from the bracket's nearer end */
            trial_guess(M, ta, c, near_a ? pa : pb, tn, near_a ? a : b, zg);
            double cc = c;
            if (tries == 0) {
                /* first the point of the plane ta . (z - za) = c from za + c ta */
                for (int i = 0; i < M; i++)
                    zt[i] = za[i] + c * ta[i];
                failed = cont_correct(s, w, za, ta, c, zt, NULL);
            } else {
                /* then corrected in the coordinate the branch moves most in (ta's: the
                 * tangents of trial points near a branch point are ill-conditioned), not
                 * in the plane normal to it: at a branch point where the other branch
                 * crosses at right angles that plane contains the other branch's tangent,
                 * and Newton's method in it wanders between the two */
                memcpy(zt, zg, (size_t)M * sizeof *zt);
                int big = 0;
                for (int i = 1; i < M; i++)
                    if (fabs(ta[i]) > fabs(ta[big]))
                        big = i;
                for (int i = 0; i < M; i++)
                    ei[i] = i == big ? 1.0 : 0.0;
                failed = cont_correct(s, w, zg, ei, 0.0, zt, NULL);
                /* the point's arclength along (za, ta), which must stay inside the bracket */
                cc = failed ? c : dot(ta, zt, M) - dot(ta, za, M);
                if (!failed && !(cc > lo && cc < hi))
                    failed = 1;
            }
            /* a point farther than half the step from the guess is on another branch
             * (near a branch point the plane of the arclength meets both) */
            double moved = 0.0;
            for (int i = 0; i < M && !failed; i++)
                moved += (zt[i] - zg[i]) * (zt[i] - zg[i]);
            if (!failed && sqrt(moved) > 0.5 * h + 1e-12 * fabs(sb))
                failed = 1;
            if (!failed)
                failed = psi_at(s, w, g, zt, ta, tt, &fc);
            if (failed && tries > 0)
                c = 0.5 * (c + (near_a ? a : b));
            else if (!failed)
                c = cc;
        }
        if (failed)
            break;
        memcpy(z, zt, (size_t)M * sizeof *z);
        memcpy(t, tt, (size_t)M * sizeof *t);
        *s_found = c;
        if (fc == 0.0 || (it > 0 && fabs(c - c_prev) <= 1e-12 * fabs(sb))) {
            /* the secant method also settles where psi jumps (the corrector went over to
             * another branch there): a point only where psi is near zero or the branch is
             * one piece across the bracket */
            ok = fc == 0.0 || end_is_zero(M, fabs(fc), zero, pa, pb, a, b) ? 0 : -1;
            break;
        }
        c_prev = c;
        if ((fc < 0.0) != (fb < 0.0)) {
            a = b;
            fa = fb;
            abs_fa = abs_fb;
            memcpy(pa, pb, 2 * (size_t)M * sizeof *pa); /* pa, qa from pb, qb */
        } else {
            fa *= 0.5;
        }
        b = c;
        fb = fc;
        abs_fb = fabs(fc);
        memcpy(pb, zt, (size_t)M * sizeof *pb);
        memcpy(qb, tt, (size_t)M * sizeof *qb);
        if (fabs(b - a) <= 1e-14 * fabs(sb)) {
            ok = end_is_zero(M, abs_fb, zero, pa, pb, a, b) ? 0 : -1;
            break;
        }
    }
    if (ok && a != 0.0 && fabs(b - a) <= 1e-8 * fabs(sb) &&
        end_is_zero(M, fmin(abs_fa, abs_fb), zero, pa, pb, a, b)) {
        const int end_a = abs_fa < abs_fb;
        memcpy(z, end_a ? pa : pb, (size_t)M * sizeof *z);
        memcpy(t, end_a ? qa : qb, (size_t)M * sizeof *t);
        *s_found = end_a ? a : b;
        ok = 0;
    }
    free(zt);
    return ok;
}

/* Where the secant method cannot approach a branch point along the branch (the branch turns
 * in its parameter there: a pitchfork seen from its bifurcating branch, where the plane of
 * the arclength meets both branches), the branch point solved for directly from the
 * located trial point bp (a guess on input): 0 when it lies within the step from z to z1
 * (tangent t at z), bp and *s_found (its arclength along t) then set; non-zero when not. */
static int branch_point_in_step(const cont_system *s, const double *z, const double *t,
                                const double *z1, double *bp, double *s_found)
{
    const int M = s->N + 1;
    double *zr = malloc((size_t)M * sizeof *zr);
    if (!zr || cont_refine_branch_point(s, bp, zr)) {
        free(zr);
        return -1;
    }
    double u, length;
    const double off = cont_chord_distance(M, z, z1, zr, &u, &length);
    const int inside = u > 0.0 && u < 1.0 && off <= 0.5 * length;
    if (inside) {
        memcpy(bp, zr, (size_t)M * sizeof *bp);
        *s_found = dot(t, zr, M) - dot(t, z, M);
    }
    free(zr);
    return inside ? 0 : -1;
}

static int cmp_special(const void *x, const void *y)
{
    const special *a = x, *b = y;
    return (a->s > b->s) - (a->s < b->s);
}

double cont_chord_distance(int M, const double *za, const double *zb, const double *zp,
                           double *u, double *length)
{
    double dd = 0.0, dy = 0.0;
    for (int i = 0; i < M; i++) {
        dd += (zb[i] - za[i]) * (zb[i] - za[i]);
        dy += (zp[i] - za[i]) * (zb[i] - za[i]);
    }
    *u = dd > 0.0 ? fmin(1.0, fmax(0.0, dy / dd)) : 0.0;
    *length = sqrt(dd);
    double dist = 0.0;
    for (int i = 0; i < M; i++) {
        const double r = zp[i] - (za[i] + *u * (zb[i] - za[i]));
        dist += r * r;
    }
    return sqrt(dist);
}

int cont_passes_point(int M, const double *za, const double *zb, const double *zp,
                      const double *tp, double scale, double away, double *far)
{
    double dd = 0.0, d0 = 0.0, along = 0.0, tt = 0.0;
    for (int i = 0; i < M; i++) {
        dd += (zb[i] - za[i]) * (zb[i] - za[i]);
        d0 += (zb[i] - zp[i]) * (zb[i] - zp[i]);
        along += tp[i] * (zb[i] - za[i]);
        tt += tp[i] * tp[i];
    }
    const int was_far = *far > away;
    *far = fmax(*far, sqrt(d0));
    if (!was_far || !(along > 0.95 * sqrt(dd * tt)))
        return 0;
    /* the chord misses its arc by about kappa |zb - za|^2 / 8 */
    double u, length;
    return cont_chord_distance(M, za, zb, zp, &u, &length) <= 0.1 * length + 1e-9 * scale;
}

/* The points a closed curve can come back to: its start and its labelled points. */
#define CONT_MAX_MARKS 16

typedef struct mark {
    double *z, *t;
    double scale; /* max(1, |z|_inf) */
    double far;
    dyn_cont_label label;
} mark;

static void add_mark(mark *mk, int *n, int M, const double *z, const double *t,
                     dyn_cont_label label)
{
    if (*n >= CONT_MAX_MARKS)
        return;
    memcpy(mk[*n].z, z, (size_t)M * sizeof *z);
    memcpy(mk[*n].t, t, (size_t)M * sizeof *t);
    mk[*n].scale = 1.0;
    for (int i = 0; i < M; i++)
        mk[*n].scale = fmax(mk[*n].scale, fabs(z[i]));
    mk[*n].far = 0.0;
    mk[*n].label = label;
    (*n)++;
}

int cont_follow(const cont_system *s, cont_work *w, const cont_loop *L, const double *z_start,
                const double *t_start, char *stop, size_t stoplen)
{
    const int M = s->N + 1;
    const int n_spec = CONT_MAX_TESTS + 2 + L->n_at;
    const size_t need = (size_t)M * (6 + 2 * (size_t)n_spec + 2 * CONT_MAX_MARKS);
    double *buf = malloc(need * sizeof *buf);
    special *sp = malloc((size_t)n_spec * sizeof *sp);
    if (!buf || !sp) {
        free(buf);
        free(sp);
        snprintf(stop, stoplen, "out of memory");
        return -1;
    }
    double *z = buf, *t = z + M, *z1 = t + M, *t1 = z1 + M, *tl = t1 + M;
    for (int k = 0; k < n_spec; k++) {
        sp[k].z = tl + M + 2 * (size_t)k * (size_t)M;
        sp[k].t = sp[k].z + M;
    }
    mark mk[CONT_MAX_MARKS];
    int n_marks = 0;
    for (int k = 0; k < CONT_MAX_MARKS; k++) {
        mk[k].z = tl + M + 2 * ((size_t)n_spec + (size_t)k) * (size_t)M;
        mk[k].t = mk[k].z + M;
    }
    memcpy(z, z_start, (size_t)M * sizeof *z);
    memcpy(t, t_start, (size_t)M * sizeof *t);
    double psi[CONT_MAX_TESTS], psi1[CONT_MAX_TESTS], det;
    int cnt[CONT_MAX_TESTS], cnt1[CONT_MAX_TESTS];
    int rc = 0;
    /* at a branch point the tangent is not defined: the direction given is kept (the
     * bordered matrix [DG; t^T] is singular there, and its solution in rounding would be
     * the other branch's tangent) */
    if (L->start_label == DYN_LABEL_BP || cont_tangent(s, w, z, t, t1, &det)) {
        memcpy(t1, t, (size_t)M * sizeof *t);
        det = 0.0;
    }
    if (s->tests(s->ctx, z, t1, det, psi, cnt)) {
        snprintf(stop, stoplen, "f or its Jacobian failed at the first point");
        free(buf);
        free(sp);
        return -2;
    }
    memcpy(t, t1, (size_t)M * sizeof *t);
    if (s->store(s->ctx, z, t, L->start_label)) {
        free(buf);
        free(sp);
        snprintf(stop, stoplen, "out of memory");
        return -1;
    }
    const int at_start_special = L->start_label != DYN_LABEL_EP;
    double ds = fmin(fabs(L->ds), L->dsmax);
    long points = 1;
    int pending = 0; /* z is computed but not stored yet */
    add_mark(mk, &n_marks, M, z, t, L->start_label);
    snprintf(stop, stoplen, "nmax = %ld points", L->nmax);
    while (points < L->nmax) {
        int iters = 0;
        for (int i = 0; i < M; i++)
            z1[i] = z[i] + ds * t[i];
        int bad = cont_correct(s, w, z, t, ds, z1, &iters);
        if (!bad)
            bad = cont_tangent(s, w, z1, t, t1, &det);
        if (!bad && dot(t, t1, M) < 0.9 && ds > L->dsmin)
            bad = 1; /* the tangent turned too far: a smaller step */
        if (!bad)
            bad = s->tests(s->ctx, z1, t1, det, psi1, cnt1);
        if (bad) {
            if (ds <= L->dsmin) {
                snprintf(stop, stoplen, "no convergence with the smallest step dsmin = %g",
                         L->dsmin);
                break;
            }
            ds = fmax(0.5 * ds, L->dsmin);
            continue;
        }
        /* back at the start or at a labelled point: a closed curve, ended there */
        int back = -1;
        for (int k = 0; k < n_marks && L->stop_closed && back < 0; k++)
            if (cont_passes_point(M, z, z1, mk[k].z, mk[k].t, mk[k].scale, 2.0 * L->dsmax,
                                  &mk[k].far))
                back = k;
        if (back >= 0) {
            if ((pending && s->store(s->ctx, z, t, DYN_LABEL_NONE)) ||
                s->store(s->ctx, mk[back].z, mk[back].t, DYN_LABEL_EP)) {
                rc = -1;
                break;
            }
            pending = 0;
            if (back == 0)
                snprintf(stop, stoplen, "closed: back at its first point");
            else
                snprintf(stop, stoplen, "closed: back at its %s point",
                         dyn_cont_label_name(mk[back].label));
            rc = 1;
            break;
        }
        /* special points between z and z1 */
        int ns = 0, end_here = 0, unlocated = -1;
        for (int k = 0; k < s->n_tests; k++) {
            if (isnan(psi[k]) || isnan(psi1[k]) || !((psi[k] < 0.0) != (psi1[k] < 0.0)) ||
                psi[k] == 0.0)
                continue;
            if (cnt[k] >= 0 && cnt[k] == cnt1[k])
                continue;
            if (s->test_label[k] == DYN_LABEL_LP &&
                fmax(fabs(psi[k]), fabs(psi1[k])) <= DYN_CONT_FOLD_NOISE)
                continue;
            if (points == 1 && at_start_special && s->test_label[k] == L->start_label)
                continue; /* the start itself */
            if (points == 1 && L->start_label == DYN_LABEL_BP &&
                s->test_label[k] == DYN_LABEL_LP && fabs(psi[k]) <= 1e-6)
                continue; /* a pitchfork's branch leaves its BP with the parameter's
                           * tangent 0 in exact arithmetic: its sign there is rounding */
            const target g = {k, 0, 0.0};
            if (locate(s, w, &g, z, t, psi[k], ds, psi1[k], z1, t1, sp[ns].z, sp[ns].t,
                       &sp[ns].s) == 0 ||
                (s->test_label[k] == DYN_LABEL_BP &&
                 branch_point_in_step(s, z, t, z1, sp[ns].z, &sp[ns].s) == 0)) {
                sp[ns].label = s->test_label[k];
                ns++;
            } else if (unlocated < 0)
                unlocated = k;
        }
        /* a fold located at a branch point is that branch point (the pitchfork's branch
         * x^2 = p turns in p where it meets x = 0): AUTO-07p reports the BP alone */
        for (int a = 0; a < ns; a++)
            for (int b = 0; b < ns; b++)
                if (sp[a].label == DYN_LABEL_LP && sp[b].label == DYN_LABEL_BP &&
                    fabs(sp[a].s - sp[b].s) <= 1e-6 * ds) {
                    drop_special(sp, &ns, a);
                    a = -1;
                    break;
                }
        /* two tests of one label located at one point (a branch point seen by det B and
         * by the continuation's own equations) are one point */
        for (int a = 0; a < ns; a++)
            for (int b = a + 1; b < ns; b++)
                if (sp[a].label == sp[b].label && fabs(sp[a].s - sp[b].s) <= 1e-6 * ds) {
                    drop_special(sp, &ns, b);
                    b = a;
                }
        /* a test changed sign and nothing could be located: a step that jumped onto
         * another branch, or one too long for the secant method; shorter, or noted */
        if (ns == 0 && unlocated >= 0 && ds > L->dsmin) {
            ds = fmax(0.5 * ds, L->dsmin);
            continue;
        }
        if (ns == 0 && unlocated >= 0 && L->missed) {
            if (L->missed->count++ == 0) {
                L->missed->label = s->test_label[unlocated];
                L->missed->p0 = z[s->ip];
                L->missed->p1 = z1[s->ip];
            }
        }
        for (int u = 0; u < L->n_at; u++) {
            const double a = z[s->ip] - L->at[u], b = z1[s->ip] - L->at[u];
            if ((a < 0.0) == (b < 0.0) || a == 0.0)
                continue;
            const target g = {-1, s->ip, L->at[u]};
            if (locate(s, w, &g, z, t, a, ds, b, z1, t1, sp[ns].z, sp[ns].t, &sp[ns].s) == 0) {
                sp[ns].label = DYN_LABEL_UZ;
                ns++;
            }
        }
        /* the bounds of the parameters */
        for (int q = 0; q < 2 && !end_here; q++) {
            const int ix = q == 0 ? s->ip : s->ip2;
            const double lo = q == 0 ? L->pmin : L->p2min, hi = q == 0 ? L->pmax : L->p2max;
            if (ix < 0 || !(lo < hi))
                continue;
            const double bound = z1[ix] > hi ? hi : z1[ix] < lo ? lo : NAN;
            if (isnan(bound))
                continue;
            const target g = {-1, ix, bound};
            if (locate(s, w, &g, z, t, z[ix] - bound, ds, z1[ix] - bound, z1, t1, sp[ns].z,
                       sp[ns].t, &sp[ns].s) == 0) {
                sp[ns].label = DYN_LABEL_EP;
                ns++;
            }
            snprintf(stop, stoplen, "reached %s = %s",
                     q == 0 ? (bound == hi ? "parmax" : "parmin")
                            : (bound == hi ? "par2max" : "par2min"),
                     dyn_shortest(bound).s);
            end_here = 1;
        }
        /* on the step that leaves the window, the special points beyond its bounds are
         * dropped (they would follow the bound's EP, or stand in its place where the bound
         * could not be located) */
        for (int a = 0; end_here && a < ns; a++) {
            const int out =
                sp[a].z[s->ip] < L->pmin - 1e-12 * fabs(L->pmin) ||
                sp[a].z[s->ip] > L->pmax + 1e-12 * fabs(L->pmax) ||
                (s->ip2 >= 0 && L->p2min < L->p2max &&
                 (sp[a].z[s->ip2] < L->p2min - 1e-12 * fabs(L->p2min) ||
                  sp[a].z[s->ip2] > L->p2max + 1e-12 * fabs(L->p2max)));
            if (out && sp[a].label != DYN_LABEL_EP)
                drop_special(sp, &ns, a--);
        }
        qsort(sp, (size_t)ns, sizeof *sp, cmp_special);
        if (pending && s->store(s->ctx, z, t, DYN_LABEL_NONE)) {
            rc = -1;
            break;
        }
        pending = 0;
        int stored_end = 0;
        for (int k = 0; k < ns && !stored_end; k++) {
            if (s->store(s->ctx, sp[k].z, sp[k].t, sp[k].label)) {
                rc = -1;
                break;
            }
            points++;
            stored_end = sp[k].label == DYN_LABEL_EP;
            if (!stored_end)
                add_mark(mk, &n_marks, M, sp[k].z, sp[k].t, sp[k].label);
        }
        if (rc || end_here)
            break;
        memcpy(z, z1, (size_t)M * sizeof *z);
        memcpy(t, t1, (size_t)M * sizeof *t);
        memcpy(psi, psi1, sizeof psi);
        memcpy(cnt, cnt1, sizeof cnt);
        pending = 1;
        points++;
        if (iters <= 3)
            ds = fmin(1.5 * ds, L->dsmax);
        else if (iters >= 7)
            ds = fmax(0.5 * ds, L->dsmin);
    }
    if (!rc && pending && s->store(s->ctx, z, t, DYN_LABEL_EP))
        rc = -1;
    free(buf);
    free(sp);
    return rc;
}
