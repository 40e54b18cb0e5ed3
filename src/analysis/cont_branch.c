/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_branch.c — the storage of a bifurcation diagram (dynkit/continuation.h): branches
 * that grow by doubling, the points' scalars beside row-major arrays of states and
 * eigenvalues, and the names of labels (AUTO-07p's) and kinds of branch. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/continuation.h"

const char *dyn_cont_label_name(dyn_cont_label l)
{
    static const char *const names[DYN_LABEL_COUNT] = {"",   "LP", "HB", "BP", "LPC", "PD", "TR",
                                                       "CP", "BT", "GH", "EP", "UZ",  "HH",
                                                       "ZH"};
    return (int)l >= 0 && l < DYN_LABEL_COUNT ? names[l] : "";
}

const char *dyn_branch_kind_name(dyn_branch_kind k)
{
    switch (k) {
    case DYN_BRANCH_EQUILIBRIUM: return "equilibrium";
    case DYN_BRANCH_PERIODIC: return "periodic";
    case DYN_BRANCH_FOLD: return "fold";
    case DYN_BRANCH_HOPF: return "hopf";
    case DYN_BRANCH_STEADY: return "steady";
    case DYN_BRANCH_FLIP: return "flip";
    case DYN_BRANCH_NEIMARK_SACKER: return "neimark-sacker";
    }
    return "";
}

dyn_branch *dyn_diagram_add(dyn_diagram *d, dyn_branch_kind kind, int n, int n_eig, int ip,
                            int ip2)
{
    if (d->count == d->capacity) {
        const int cap = d->capacity ? 2 * d->capacity : 4;
        dyn_branch *nb = realloc(d->branches, (size_t)cap * sizeof *nb);
        if (!nb)
            return NULL;
        d->branches = nb;
        d->capacity = cap;
    }
    dyn_branch *b = &d->branches[d->count];
    memset(b, 0, sizeof *b);
    b->id = d->count + 1;
    b->kind = kind;
    b->parent_point = -1;
    b->end_point = -1;
    b->n = n;
    b->n_eig = n_eig;
    b->n_par = ip2 >= 0 ? 2 : 1;
    b->par_index[0] = ip;
    b->par_index[1] = ip2;
    b->progress = d->progress;
    b->progress_ctx = d->progress_ctx;
    d->count++;
    return b;
}

static int grow(dyn_branch *b)
{
    const long cap = b->capacity ? 2 * b->capacity : 64;
    const size_t n = (size_t)b->n, ne = 2 * (size_t)b->n_eig;
    dyn_branch_point *pts = realloc(b->pts, (size_t)cap * sizeof *pts);
    if (!pts)
        return -1;
    b->pts = pts;
    double *x = realloc(b->x, (size_t)cap * (n ? n : 1) * sizeof *x);
    if (!x)
        return -1;
    b->x = x;
    if (b->kind == DYN_BRANCH_PERIODIC) {
        double *xm = realloc(b->xmin, (size_t)cap * (n ? n : 1) * sizeof *xm);
        if (!xm)
            return -1;
        b->xmin = xm;
    }
    double *e = realloc(b->eig, (size_t)cap * (ne ? ne : 1) * sizeof *e);
    if (!e)
        return -1;
    b->eig = e;
    b->capacity = cap;
    return 0;
}

long dyn_branch_append(dyn_branch *b, const dyn_branch_point *p, const double *x,
                       const double *xmin, const double *eig_re, const double *eig_im)
{
    if (b->count == b->capacity && grow(b))
        return -1;
    const long k = b->count++;
    const size_t n = (size_t)b->n, ne = (size_t)b->n_eig;
    b->pts[k] = *p;
    memcpy(b->x + (size_t)k * n, x, n * sizeof *x);
    if (b->xmin)
        memcpy(b->xmin + (size_t)k * n, xmin ? xmin : x, n * sizeof *x);
    double *e = b->eig + (size_t)k * 2 * ne;
    for (size_t i = 0; i < ne; i++) {
        e[2 * i] = eig_re ? eig_re[i] : NAN;
        e[2 * i + 1] = eig_im ? eig_im[i] : NAN;
    }
    if (b->progress)
        b->progress(b, b->progress_ctx);
    return k;
}

void dyn_diagram_free(dyn_diagram *d)
{
    for (int i = 0; i < d->count; i++) {
        free(d->branches[i].pts);
        free(d->branches[i].x);
        free(d->branches[i].xmin);
        free(d->branches[i].eig);
        free(d->branches[i].orbit);
    }
    free(d->branches);
    d->branches = NULL;
    d->count = d->capacity = 0;
}

void dyn_cont_opts_default(dyn_cont_opts *o, int ip)
{
    memset(o, 0, sizeof *o);
    o->ip = ip;
    o->ip2 = -1;
    o->ds = DYN_CONT_DS;
    o->dsmin = DYN_CONT_DSMIN;
    o->dsmax = DYN_CONT_DSMAX;
    o->nmax = DYN_CONT_NMAX;
    o->npr = DYN_CONT_NPR;
    o->parmin = DYN_CONT_PARMIN;
    o->parmax = DYN_CONT_PARMAX;
    o->ntst = DYN_CONT_NTST;
    o->ncol = DYN_CONT_NCOL;
    o->max_branches = 16;
    o->jac = DYN_JAC_AUTO;
}
