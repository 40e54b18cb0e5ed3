/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady_switch.c — branch switching on a branch of steady motions (private;
 * cont_steady_system.h): at a point labelled BP where the continuation's own equations are
 * singular (the augmented Jacobian [G_z; t^T] has a null vector: another family of steady
 * motions crosses, as where a top's precessions meet its upright spin, or a bicycle's steady
 * turns its upright running), the other branch leaves along that null vector, orthogonal to
 * the branch (Keller 1977; AUTO-07p's default switching, Doedel et al., AUTO-07p manual,
 * ch. 5) and is followed both ways. At a BP where those equations stay regular (a real pair
 * of B meeting at zero while the steady motions through the point stay one smooth family,
 * the rolling disk's) no other branch exists and none is followed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cont_steady_system.h"
#include "cont_steady_switch.h"

#define MAX_SEEN 64

/* A unit null vector v of K = [G_z; t^T] ((N + 1) x (N + 1)) by 4 steps of inverse
 * iteration on K^T K (cont_normal_factor, cont_inverse_iteration), and *rel = ||K v||_inf over
 * K's largest entry: near 0 at a branch point, of order 1 where the equations are regular.
 * K^T K rather than K: a mechanism's G_z is nilpotent in part (q' = dq), so K's eigenvalues
 * nearest zero come in pairs +-sqrt(delta) and inverse iteration on K would not converge to
 * the null vector. */
static int null_vector(const cont_system *s, const double *z, const double *t, double *J,
                       double *G, double *v, double *rel)
{
    const int N = s->N, M = N + 1;
    const size_t MM = (size_t)M;
    if (s->jacobian(s->ctx, z, J))
        return -1;
    memcpy(J + (size_t)N * MM, t, MM * sizeof *t); /* K: J's N rows and t */
    double big = 0.0;
    for (size_t i = 0; i < MM * MM; i++)
        big = fmax(big, fabs(J[i]));
    /* K's last row is the unit t: K^T K is not zero */
    if (cont_normal_factor(J, M, M, 0, G) || cont_inverse_iteration(G, M, 1, 4, v))
        return -1;
    double worst = 0.0;
    for (int r = 0; r < M; r++) {
        double kv = 0.0;
        for (int j = 0; j < M; j++)
            kv += J[(size_t)r * MM + (size_t)j] * v[j];
        worst = fmax(worst, fabs(kv));
    }
    *rel = worst / (big > 0.0 ? big : 1.0);
    return 0;
}

/* the point k of branch bi as z = (u, p), its tangent by the secant of its neighbours */
static int point_and_secant(const sc_ctx *c, const dyn_branch *b, long k, double *z, double *t)
{
    const int nu = c->nu, M = nu + 1;
    const long ka = k > 0 ? k - 1 : k, kb = k + 1 < b->count ? k + 1 : k;
    double nt = 0.0;
    for (int i = 0; i < M; i++) {
        const size_t n = (size_t)b->n;
        const int s = i < nu ? c->sp->unknowns[i] : 0;
        z[i] = i < nu ? b->x[(size_t)k * n + (size_t)s] : b->pts[k].par[0];
        const double za = i < nu ? b->x[(size_t)ka * n + (size_t)s] : b->pts[ka].par[0];
        const double zb = i < nu ? b->x[(size_t)kb * n + (size_t)s] : b->pts[kb].par[0];
        t[i] = zb - za;
        nt += t[i] * t[i];
    }
    nt = sqrt(nt);
    if (!(nt > 0.0))
        return -1;
    for (int i = 0; i < M; i++)
        t[i] /= nt;
    return 0;
}

int sc_switch_all(sc_ctx *c, const cont_system *s, cont_work *w, const dyn_cont_opts *o,
                  int first, char *note, size_t notelen)
{
    const int M = c->nu + 1;
    const int max_branches = o->max_branches > 0 ? o->max_branches : 16;
    double *buf = malloc((6 * (size_t)M + 2 * (size_t)M * (size_t)M) * sizeof *buf);
    if (!buf) {
        snprintf(c->message, sizeof c->message, "out of memory");
        return -1;
    }
    double *z = buf, *t = z + M, *v = t + M, *tv = v + M, *z1 = tv + M, *t1 = z1 + M;
    double *J = t1 + M, *G = J + (size_t)M * (size_t)M;
    double *seen = malloc(MAX_SEEN * (size_t)M * sizeof *seen);
    int rc = seen ? 0 : -1, n_seen = 0;
    if (rc)
        snprintf(c->message, sizeof c->message, "out of memory");
    for (int bi = first; rc == 0 && bi < c->d->count; bi++)
        for (long k = 0; rc == 0 && k < c->d->branches[bi].count; k++) {
            const dyn_branch *b = &c->d->branches[bi];
            if (b->pts[k].label != DYN_LABEL_BP || (b->parent_point >= 0 && k == 0) ||
                c->d->count >= max_branches)
                continue;
            const double p = b->pts[k].par[0];
            const int parent = b->id;
            double rel = INFINITY;
            if (point_and_secant(c, b, k, z, t))
                continue;
            /* a point where branches were switched already (reached again by another) */
            int again = 0;
            for (int j = 0; j < n_seen && !again; j++) {
                double dmax = 0.0;
                for (int i = 0; i < M; i++)
                    dmax = fmax(dmax, fabs(seen[(size_t)j * (size_t)M + (size_t)i] - z[i]) /
                                          (1.0 + fabs(z[i])));
                again = dmax < 1e-6;
            }
            if (again)
                continue;
            if (n_seen < MAX_SEEN)
                memcpy(seen + (size_t)n_seen++ * (size_t)M, z, (size_t)M * sizeof *z);
            if (null_vector(s, z, t, J, G, v, &rel) || !(rel < 1e-6)) {
                /* the equations are regular there: no other branch */
                const size_t used = strlen(note);
                if (used + 2 < notelen)
                    snprintf(note + used, notelen - used,
                             "%sBP at %.40s = %.12g (branch %d): the steady equations are "
                             "regular there, no other branch (a real pair of eigenvalues "
                             "through 0)",
                             used ? "; " : "", c->cm->m->params[o->ip].name, p, parent);
                continue;
            }
            /* a first point of the other branch a step ds along v, then its tangent */
            const double ds = fmin(fabs(o->ds), o->dsmax);
            for (int dir = 1; dir >= -1 && rc == 0 && c->d->count < max_branches;
                 dir -= 2) {
                double det;
                for (int i = 0; i < M; i++) {
                    tv[i] = dir * v[i];
                    z1[i] = z[i] + ds * tv[i];
                }
                if (cont_correct(s, w, z, tv, ds, z1, NULL) ||
                    cont_tangent(s, w, z1, tv, t1, &det))
                    continue;
                const int fr = sc_follow(c, s, w, o, z, z1, t1, DYN_LABEL_NONE, parent, k);
                rc = fr == -1 ? -1 : 0;
            }
        }
    free(buf);
    free(seen);
    return rc;
}
