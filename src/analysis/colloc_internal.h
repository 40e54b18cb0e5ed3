/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_internal.h — what the collocation files share (src/analysis/colloc_*.c): the
 * basis of one interval (Gauss points, Lagrange polynomials on equally spaced nodes, their
 * quadrature weights; AUTO-07p's wint/cpnts/cntdif) and the node layout of a solution. */
#ifndef DYN_COLLOC_INTERNAL_H
#define DYN_COLLOC_INTERNAL_H

#include "dynkit/colloc.h"

#define CB_MAX (DYN_COLLOC_MAX_NCOL + 1)

typedef struct colloc_basis {
    int ncol;
    double z[CB_MAX];         /* the ncol Gauss points on [0, 1] */
    double L[CB_MAX][CB_MAX]; /* L[k][l]: Lagrange polynomial l (node l/ncol) at z_k */
    double D[CB_MAX][CB_MAX]; /* D[k][l]: its derivative at z_k */
    double w[CB_MAX];         /* int_0^1 L_l */
    double dn[CB_MAX];        /* the ncol-th derivative of L_l (a constant) */
    double Dn[CB_MAX][CB_MAX]; /* Dn[k][l]: the derivative of L_l at node k/ncol */
} colloc_basis;

/* the basis of ncol (2..DYN_COLLOC_MAX_NCOL) points; 0, or non-zero for a bad ncol */
int colloc_basis_init(colloc_basis *b, int ncol);
/* the Lagrange polynomials of the ncol + 1 equally spaced nodes at z in [0, 1] */
void colloc_lagrange(int ncol, double z, double *L);
/* the interval of t and its local coordinate z in [0, 1] */
int colloc_locate(const dyn_colloc_sol *s, double t, double *z);

#endif /* DYN_COLLOC_INTERNAL_H */
