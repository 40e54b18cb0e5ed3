/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/phase_plane.h — a model's phase plane in two of its states (the others held at
 * given values): the rates f_x, f_y at a point, the nullclines f_x = 0 and f_y = 0 by
 * marching squares with each vertex located on its grid edge to rounding, and the
 * equilibria of the plane by Newton's method with their type from the 2x2 Jacobian
 * (trace and determinant: Strogatz, "Nonlinear Dynamics and Chaos", sec. 5.2 and 6.3).
 * XPPAUT draws the same pictures (its nullclines on a grid of NMESH cells, its
 * "Sing pts"). Part of the core library: C11 + libm, re-entrant, never prints. */
#ifndef DYNKIT_PHASE_PLANE_H
#define DYNKIT_PHASE_PLANE_H

#include <stddef.h>

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The plane: states ix (abscissa) and iy (ordinate) of model over [xlo, xhi] x [ylo, yhi],
 * the other states at y[] (n_states values) and the time t; par is the model's prepared
 * parameter struct. */
typedef struct dyn_plane {
    const dyn_model *model;
    const void *par;
    double t;
    const double *y;
    int ix, iy;
    double xlo, xhi, ylo, yhi;
} dyn_plane;

/* Doubles of workspace the functions below need for a grid of nx x ny cells
 * (dyn_plane_rates and dyn_plane_equilibrium: nx = ny = 0). */
size_t dyn_plane_work_size(int n_states, int nx, int ny);

/* f_ix and f_iy at (x, y) into *fx, *fy: 0, or the right-hand side's non-zero status. */
int dyn_plane_rates(const dyn_plane *p, double x, double y, double *work, double *fx,
                    double *fy);

/* A piece of a nullcline: which 0 for f_ix = 0, 1 for f_iy = 0; from (x0, y0) to (x1, y1). */
typedef void (*dyn_segment_fn)(int which, double x0, double y0, double x1, double y1,
                               void *ctx);
/* The nullclines on nx x ny cells of the window (marching squares): each cell edge whose
 * ends differ in sign holds a vertex, located on the edge by the Illinois method to
 * rounding (so each vertex lies on the curve, not only near it); a cell with four vertices
 * joins them by the sign at its centre. Returns 0, or -1 with the reason in err (a bad
 * window or grid, a right-hand side that failed or is not finite: that grid point counts
 * as having no sign, and no segment touches it). */
int dyn_plane_nullclines(const dyn_plane *p, int nx, int ny, double *work, dyn_segment_fn emit,
                         void *ctx, char *err, size_t errlen);

/* The type of an equilibrium of the plane, from the trace and determinant of its 2x2
 * Jacobian. */
typedef enum dyn_plane_point_type {
    DYN_PLANE_SADDLE = 0,
    DYN_PLANE_STABLE_NODE = 1,
    DYN_PLANE_UNSTABLE_NODE = 2,
    DYN_PLANE_STABLE_FOCUS = 3,
    DYN_PLANE_UNSTABLE_FOCUS = 4,
    DYN_PLANE_CENTER = 5,      /* trace 0 (within rounding), determinant > 0 */
    DYN_PLANE_DEGENERATE = 6   /* determinant 0 (within rounding) */
} dyn_plane_point_type;
/* "saddle", "stable node", ... */
const char *dyn_plane_point_name(dyn_plane_point_type type);

typedef struct dyn_plane_point {
    double x, y;
    double jac[4];            /* d(f_x, f_y)/d(x, y), row-major */
    double re[2], im[2];      /* its eigenvalues, re[0] <= re[1] */
    dyn_plane_point_type type;
} dyn_plane_point;

/* Newton's method for f_ix = f_iy = 0 from (x, y), with the model's Jacobian when it has
 * one, else central differences; 0 with *pt when it converged (|f| at most 1e-10 times the
 * rates' scale) inside the window enlarged by a cell, -1 otherwise. */
int dyn_plane_equilibrium(const dyn_plane *p, double x, double y, double *work,
                          dyn_plane_point *pt);
/* The equilibria in the window: Newton from the centre of every cell of an nx x ny grid
 * that both nullclines cross (a sign change of f_ix and of f_iy at its corners), duplicates
 * (within 1e-7 of the window's size) merged; at most max into pts, sorted by x then y.
 * Returns how many, or -1 with the reason in err. */
int dyn_plane_equilibria(const dyn_plane *p, int nx, int ny, double *work, dyn_plane_point *pts,
                         int max, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_PHASE_PLANE_H */
