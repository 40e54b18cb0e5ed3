/* SPDX-License-Identifier: BSD-3-Clause */
/* klu_solver.c — dyn_sparse_solver over SuiteSparse's KLU (dynkit/klu.h): klu_analyze once
 * per pattern (AMD ordering, block triangular form), klu_factor the first time and whenever
 * the pivots of the last factorisation have become poor, klu_refactor otherwise (the
 * numeric factorisation with the same pivot order, cheaper), klu_solve for each right-hand
 * side; dyn_klu_forget drops the numeric factors at the start of a solve and keeps the
 * analysis, which then serves every solve of one pattern. The rule for refactoring follows SUNDIALS' sunlinsol_klu.c: klu_rcond below
 * eps^(2/3) means a new factorisation with pivoting. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include <klu.h>

#include "dynkit/klu.h"

typedef struct klu_ctx {
    klu_common common;
    klu_symbolic *symbolic;
    klu_numeric *numeric;
    const int *colptr, *rowind; /* the pattern analysed */
} klu_ctx;

static int klu_status(const klu_ctx *k)
{
    return k->common.status == KLU_OUT_OF_MEMORY || k->common.status == KLU_TOO_LARGE ||
                   k->common.status == KLU_INVALID
               ? -1
               : 1; /* singular */
}

static int dyn_klu_factor(void *ctx, const dyn_sparse_pattern *p, const double *ax)
{
    klu_ctx *k = ctx;
    int *cp = (int *)p->colptr, *ri = (int *)p->rowind; /* KLU reads them only */
    if (k->symbolic && (k->colptr != p->colptr || k->rowind != p->rowind)) {
        klu_free_numeric(&k->numeric, &k->common);
        klu_free_symbolic(&k->symbolic, &k->common);
    }
    if (!k->symbolic) {
        k->symbolic = klu_analyze(p->n, cp, ri, &k->common);
        if (!k->symbolic)
            return klu_status(k);
        k->colptr = p->colptr;
        k->rowind = p->rowind;
    }
    if (k->numeric) {
        if (klu_refactor(cp, ri, (double *)ax, k->symbolic, k->numeric, &k->common) &&
            klu_rcond(k->symbolic, k->numeric, &k->common) &&
            k->common.rcond >= pow(DBL_EPSILON, 2.0 / 3.0))
            return 0;
        klu_free_numeric(&k->numeric, &k->common);
    }
    k->numeric = klu_factor(cp, ri, (double *)ax, k->symbolic, &k->common);
    return k->numeric ? 0 : klu_status(k);
}

static void dyn_klu_solve(void *ctx, int n, double *b)
{
    klu_ctx *k = ctx;
    klu_solve(k->symbolic, k->numeric, n, 1, b, &k->common);
}

/* A new solve: its first factorisation pivots anew; the analysis of the pattern stays. */
static void dyn_klu_forget(void *ctx)
{
    klu_ctx *k = ctx;
    klu_free_numeric(&k->numeric, &k->common);
}

int dyn_klu_init(dyn_sparse_solver *s)
{
    klu_ctx *k = calloc(1, sizeof *k);
    s->name = "klu";
    s->ctx = k;
    s->factor = dyn_klu_factor;
    s->solve = dyn_klu_solve;
    s->forget = dyn_klu_forget;
    if (!k)
        return 1;
    klu_defaults(&k->common);
    return 0;
}

void dyn_klu_release(dyn_sparse_solver *s)
{
    klu_ctx *k = s ? s->ctx : NULL;
    if (!k)
        return;
    klu_free_numeric(&k->numeric, &k->common);
    klu_free_symbolic(&k->symbolic, &k->common);
    free(k);
    s->ctx = NULL;
}
