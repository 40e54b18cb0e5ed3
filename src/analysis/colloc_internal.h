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

/* The collocation Jacobian at x (phase condition against ref) bordered by the arclength row
 * of t, [G_X; t^T]: the sign of its determinant into *det_sign and log |det| into *det_log
 * (up to a sign that depends only on the sizes: compare points of one mesh size); with rhs
 * (the collocation rows interval by interval, then the boundary, phase and arclength rows,
 * as many as unknowns) the solution into sol (the nodes' states, then the free scalars).
 * colloc_newton.c; 0 or DYN_COLLOC_*. */
int dyn_colloc_bordered(const dyn_colloc_problem *p, const dyn_colloc_sol *x,
                        const dyn_colloc_sol *ref, const dyn_colloc_sol *t, const double *rhs,
                        double *sol, int *det_sign, double *det_log);

/* Branch points of periodic orbits (colloc_bp.c). Keller's test at the point x of a branch
 * with tangent t: the sign of det [G_X; t^T] and its log |det|; 0 or DYN_COLLOC_*. */
int colloc_bp_test(const dyn_colloc_problem *p, const dyn_colloc_sol *x,
                   const dyn_colloc_sol *t, int *sign, double *logabs);
/* A point at arclength s along a step (a corrector's solution, allocated into y) and its
 * branch-point test's value into g (relative to the step's start); 0 or DYN_COLLOC_*. */
typedef int (*colloc_bp_eval)(void *ctx, double s, dyn_colloc_sol *y, double *g);
/* The branch point between the step's start x0 (arclength 0, test psi0) and ds (psi1, of
 * the other sign), from eval's points: the point into x (allocated like x0), its arclength
 * into *s_at; 0 or DYN_COLLOC_* (no point found beyond it). */
int colloc_bp_locate(colloc_bp_eval eval, void *ctx, const dyn_colloc_sol *x0, double ds,
                     double psi0, double psi1, dyn_colloc_sol *x, double *s_at);
/* At a branch point x with the known branch's tangent t: the direction of the other branch,
 * the null vector of [G_X; t^T] (orthogonal to t in the collocation inner product, of unit
 * length, its largest state component positive) into v (allocated like x). */
int colloc_bp_direction(const dyn_colloc_problem *p, const dyn_colloc_sol *x,
                        const dyn_colloc_sol *t, dyn_colloc_sol *v);

#endif /* DYN_COLLOC_INTERNAL_H */
