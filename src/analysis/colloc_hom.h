/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_hom.h — the projection conditions of a connecting orbit (XPPAUT's hom_bcs(k),
 * dyn_hom_bcs in dynkit/model.h) for the boundary-value solver (colloc_bvp.c); written in
 * colloc_hom.c. */
#ifndef DYN_COLLOC_HOM_H
#define DYN_COLLOC_HOM_H

#include "dynkit/model.h"

typedef struct bvp_hom {
    const dyn_model *m;
    void *par;       /* the model's parameter struct (the caller's) */
    double t;        /* the time of the Jacobians (the interval's start) */
    int n, dim, left, right;
    int n_left;      /* conditions at the left end: its equilibrium's stable dimension */
    int n_right;     /* at the right end: its equilibrium's unstable dimension */
    double *basis_left, *basis_right; /* dim x n_left, dim x n_right (row-major): fixed
                                       * orthonormal bases of the projectors' ranges */
    double *work;
    int *piv;
} bvp_hom;

/* The settings of m->hom checked, the dimensions of the equilibria held in y0 (the first
 * guess) counted and the bases fixed there. Returns 0, or non-zero with a message. */
int bvp_hom_init(bvp_hom *h, const dyn_model *m, void *par, double t, const double *y0,
                 char *msg, size_t len);
/* The rows of the hom_bcs conditions of g (n_bdry values) at the ends u0, u1; the others
 * are left. Returns 0, or non-zero (the Jacobian failed or the equilibrium is not
 * hyperbolic). */
int bvp_hom_rows(bvp_hom *h, const double *u0, const double *u1, double *g);
void bvp_hom_free(bvp_hom *h);

#endif /* DYN_COLLOC_HOM_H */
