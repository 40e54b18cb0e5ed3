/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_cont.c — the periodic branches of a bifurcation diagram (dynkit/continuation.h's
 * dyn_cont_periodic_fn): from a Hopf point of an equilibrium branch, the branch of periodic
 * orbits by collocation (colloc_po.c) with the diagram's settings (ntst, ncol, ds, dsmin,
 * dsmax, nmax, parmin, parmax), stored as a DYN_BRANCH_PERIODIC branch (each state's
 * maximum and minimum over the orbit, the period, the Floquet multipliers, stability and
 * the labels LPC, PD, TR, UZ, EP; on request each point's orbit at its collocation nodes);
 * then from each period doubling the period-doubled branch, and so on down the cascade,
 * and from each branch point of cycles (BP) not met before the other family both ways,
 * while the diagram has room for branches. A branch that ends on another Hopf point
 * records it (end_branch, end_point), and that point starts no branch: its cycles are
 * these. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/colloc.h"
#include "dynkit/continuation.h"

static dyn_cont_label label_of(const char *s)
{
    if (strcmp(s, "LPC") == 0)
        return DYN_LABEL_LPC;
    if (strcmp(s, "PD") == 0)
        return DYN_LABEL_PD;
    if (strcmp(s, "TR") == 0)
        return DYN_LABEL_TR;
    if (strcmp(s, "BP") == 0)
        return DYN_LABEL_BP;
    if (strcmp(s, "EP") == 0)
        return DYN_LABEL_EP;
    if (strcmp(s, "UZ") == 0)
        return DYN_LABEL_UZ;
    return DYN_LABEL_NONE;
}

/* each point's orbit at its nodes (time over the period, then the states) into b->orbit;
 * NAN for a point that kept none. 0, or -1 when out of memory. */
static int keep_profiles(dyn_branch *b, const dyn_po_branch *pb)
{
    long nodes = 0;
    for (int k = 0; k < pb->npoints; k++)
        if (pb->pts[k].orbit.u)
            nodes = dyn_colloc_nodes(&pb->pts[k].orbit);
    if (nodes == 0)
        return 0;
    const size_t row = (size_t)nodes * (size_t)(1 + b->n);
    b->orbit = malloc((size_t)pb->npoints * row * sizeof *b->orbit);
    if (!b->orbit)
        return -1;
    b->orbit_nodes = (int)nodes;
    for (int k = 0; k < pb->npoints; k++) {
        const dyn_colloc_sol *s = &pb->pts[k].orbit;
        double *out = b->orbit + (size_t)k * row;
        const int have = s->u && dyn_colloc_nodes(s) == nodes;
        for (long g = 0; g < nodes; g++) {
            double *o = out + (size_t)g * (size_t)(1 + b->n);
            o[0] = have ? dyn_colloc_node_time(s, g) : NAN;
            for (int i = 0; i < b->n; i++)
                o[1 + i] = have ? s->u[(size_t)g * (size_t)b->n + (size_t)i] : NAN;
        }
    }
    return 0;
}

/* the Hopf point of an equilibrium branch of d where branch pb ended, its orbits shrunk
 * onto an equilibrium: of the HB points other than (parent, parent_point) whose state lies
 * within the last orbit's range of each state widened by that range, and whose parameter
 * is within twice the last step's change of the parameter from the end (the end is located
 * where the oscillation vanishes, to about a step), the nearest in the parameter. Its
 * branch's id into *eb and index into *ep; 0, or -1 when none. */
static int hopf_at_end(const dyn_diagram *d, const dyn_po_branch *pb, int parent,
                       long parent_point, int *eb, long *ep)
{
    if (!pb->hopf_end || pb->npoints < 2)
        return -1;
    const dyn_po_point *e = &pb->pts[pb->npoints - 1], *q = &pb->pts[pb->npoints - 2];
    const double reach = 2.0 * fabs(e->par - q->par) + 1e-9 * (1.0 + fabs(e->par));
    double best = INFINITY;
    for (int bi = 0; bi < d->count; bi++) {
        const dyn_branch *b = &d->branches[bi];
        if (b->kind != DYN_BRANCH_EQUILIBRIUM || b->n != pb->n)
            continue;
        for (long k = 0; k < b->count; k++) {
            const double dp = fabs(b->pts[k].par[0] - e->par);
            if (b->pts[k].label != DYN_LABEL_HB || (b->id == parent && k == parent_point) ||
                !(dp <= reach) || !(dp < best))
                continue;
            int inside = 1;
            for (int i = 0; i < b->n && inside; i++) {
                const double x = b->x[(size_t)k * (size_t)b->n + (size_t)i];
                const double w = e->xmax[i] - e->xmin[i] + 1e-9 * (1.0 + fabs(x));
                inside = x >= e->xmin[i] - w && x <= e->xmax[i] + w;
            }
            if (inside) {
                best = dp;
                *eb = b->id;
                *ep = k;
            }
        }
    }
    return isfinite(best) ? 0 : -1;
}

/* pb appended to d as a periodic branch (with its orbits when keep_orbits); its id, or -1
 * when out of memory */
static int store(dyn_diagram *d, const dyn_po_branch *pb, int ip, int parent, long parent_point,
                 int keep_orbits)
{
    dyn_branch *b = dyn_diagram_add(d, DYN_BRANCH_PERIODIC, pb->n, pb->n, ip, -1);
    if (!b)
        return -1;
    b->parent = parent;
    b->parent_point = parent_point;
    /* the diagram's progress callback once, with the whole branch, rather than at each
     * point of a burst of appends (a rate-limited display would show its first) */
    void (*progress)(const dyn_branch *, void *) = b->progress;
    b->progress = NULL;
    for (int k = 0; k < pb->npoints; k++) {
        const dyn_po_point *q = &pb->pts[k];
        dyn_branch_point p;
        memset(&p, 0, sizeof p);
        p.label = k == 0 && !q->label[0] ? DYN_LABEL_EP : label_of(q->label);
        p.par[0] = q->par;
        p.par[1] = NAN;
        p.period = q->period;
        p.stable = q->stable;
        p.l1 = NAN;
        p.omega = NAN;
        if (dyn_branch_append(b, &p, q->xmax, q->xmin, q->mult_re, q->mult_im) < 0) {
            b->progress = progress;
            return -1;
        }
    }
    b->progress = progress;
    if (progress && b->count > 0)
        progress(b, b->progress_ctx);
    snprintf(b->stop, sizeof b->stop, "%.150s", pb->message);
    int eb = 0;
    long ep = -1;
    if (parent > 0 && d->branches[parent - 1].kind == DYN_BRANCH_EQUILIBRIUM &&
        hopf_at_end(d, pb, parent, parent_point, &eb, &ep) == 0) {
        b->end_branch = eb;
        b->end_point = ep;
        const dyn_branch *pa = &d->branches[parent - 1];
        const double p_end = d->branches[eb - 1].pts[ep].par[0];
        char msg[320];
        snprintf(msg, sizeof msg,
                 "the orbit shrank to the HB at %.10g (point %ld of branch %d): the cycles "
                 "from HB at %.10g are those from HB at %.10g", p_end, ep + 1, eb, p_end,
                 pa->pts[parent_point].par[0]);
        snprintf(b->stop, sizeof b->stop, "%.159s", msg);
    }
    if (keep_orbits && pb->npoints > 0 && keep_profiles(b, pb))
        return -1;
    return b->id;
}

/* whether a BP at parameter par and period T is a BP point of a periodic branch of d
 * other than point self_point of branch self (within 1e-6 relative in both) */
static int bp_known(const dyn_diagram *d, int self, long self_point, double par, double T)
{
    for (int bi = 0; bi < d->count; bi++) {
        const dyn_branch *b = &d->branches[bi];
        if (b->kind != DYN_BRANCH_PERIODIC)
            continue;
        for (long k = 0; k < b->count; k++)
            if (b->pts[k].label == DYN_LABEL_BP && !(b->id == self && k == self_point) &&
                fabs(b->pts[k].par[0] - par) <= 1e-6 * (1.0 + fabs(par)) &&
                fabs(b->pts[k].period - T) <= 1e-6 * (1.0 + fabs(T)))
                return 1;
    }
    return 0;
}

typedef struct po_follow {
    const dyn_po_system *sys;
    const dyn_po_opts *po;
    const dyn_cont_opts *o;
    dyn_diagram *d;
    int max_branches;
} po_follow;

/* the branches switched to from pb (stored in d as branch id), depth first: at its first
 * PD the period-doubled branch, at each BP that no other branch of d has the other family
 * (its direction's sign, then the opposite; none with o->no_switch), each followed in turn, while d has fewer
 * than max_branches branches; a switch that fails is left out. id, or -1 when out of
 * memory. */
static int follow(po_follow *f, const dyn_po_branch *pb, int id)
{
    int pd = -1;
    for (int k = 0; k < pb->npoints && pd < 0; k++)
        if (strcmp(pb->pts[k].label, "PD") == 0)
            pd = k;
    for (int k = 0; k < pb->npoints && id > 0; k++) {
        const int is_pd = k == pd, is_bp = strcmp(pb->pts[k].label, "BP") == 0;
        if (!is_pd && !(is_bp && !f->o->no_switch &&
                        !bp_known(f->d, id, k, pb->pts[k].par, pb->pts[k].period)))
            continue;
        for (int dir = 1; dir >= (is_pd ? 1 : -1) && id > 0; dir -= 2) {
            if (f->d->count >= f->max_branches)
                return id;
            dyn_po_branch next;
            const int st = is_pd ? dyn_po_from_pd(f->sys, &pb->pts[k], f->po, &next)
                                 : dyn_po_from_bp(f->sys, &pb->pts[k], dir, f->po, &next);
            if (st) {
                dyn_po_branch_free(&next);
                if (is_pd)
                    return id; /* the cascade stops there */
                continue;
            }
            const int nid = store(f->d, &next, f->o->ip, id, k, f->o->orbits);
            if (nid < 0 || follow(f, &next, nid) < 0)
                id = -1;
            dyn_po_branch_free(&next);
        }
    }
    return id;
}

static int hqr_eig(int n, double *a, double *re, double *im, char *err, size_t errlen)
{
    return dyn_eig_hqr(n, a, re, im, err, errlen);
}

int dyn_po_continue_hopf(const dyn_model *m, const void *par, const dyn_cont_opts *o,
                         dyn_diagram *d, int branch, long point, void *ctx, char *err,
                         size_t errlen)
{
    static const dyn_eig_solver hqr = {"hqr", hqr_eig};
    /* the cycles from this Hopf point are already there when a branch ended on it */
    for (int j = 0; j < d->count; j++)
        if (d->branches[j].kind == DYN_BRANCH_PERIODIC && d->branches[j].end_branch == branch &&
            d->branches[j].end_point == point)
            return 0;
    const dyn_branch *eb = &d->branches[branch - 1];
    const int n = m->n_states;
    double *x0 = malloc((size_t)n * sizeof *x0);
    if (!x0) {
        snprintf(err, errlen, "out of memory");
        return DYN_COLLOC_ERR_NOMEM;
    }
    memcpy(x0, eb->x + (size_t)point * (size_t)n, (size_t)n * sizeof *x0);
    const double p0 = eb->pts[point].par[0], omega = eb->pts[point].omega;
    dyn_po_model pm;
    dyn_po_system sys;
    int st = dyn_po_model_init(&pm, m, par, o->ip, &sys);
    if (st) {
        free(x0);
        snprintf(err, errlen, "out of memory");
        return st;
    }
    dyn_po_opts po;
    memset(&po, 0, sizeof po);
    po.ntst = o->ntst;
    po.ncol = o->ncol;
    po.ds = fabs(o->ds) > 0 ? fabs(o->ds) : DYN_CONT_DS;
    po.dsmin = o->dsmin;
    po.dsmax = o->dsmax;
    po.nmax = (int)(o->nmax > 0 ? o->nmax : DYN_CONT_NMAX);
    po.par_min = o->parmin;
    po.par_max = o->parmax;
    po.eig = ctx ? (const dyn_eig_solver *)ctx : &hqr;
    po.keep_orbits = o->orbits;
    po.at = o->at;
    po.n_at = o->n_at;
    dyn_po_branch pb;
    st = dyn_po_from_hopf(&sys, x0, p0, omega, &po, &pb);
    free(x0);
    if (st) {
        snprintf(err, errlen, "%s", pb.message);
        dyn_po_branch_free(&pb);
        dyn_po_model_free(&pm);
        return st;
    }
    po_follow f = {&sys, &po, o, d, o->max_branches > 0 ? o->max_branches : 16};
    int id = store(d, &pb, o->ip, branch, point, o->orbits);
    if (id > 0)
        id = follow(&f, &pb, id);
    dyn_po_branch_free(&pb);
    dyn_po_model_free(&pm);
    if (id < 0) {
        snprintf(err, errlen, "out of memory");
        return DYN_COLLOC_ERR_NOMEM;
    }
    return 0;
}
