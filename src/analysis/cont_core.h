/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_core.h — the generic part of continuation (private to the library): a system
 * G(z) = 0 of N equations in N + 1 unknowns z followed by pseudo-arclength continuation
 * (Keller 1977; Doedel, Keller & Kernevez 1991, "Numerical analysis and control of
 * bifurcation problems I", sec. 2), test functions whose sign changes mark special points,
 * located by the secant method along the arclength. Equilibria (cont_equilibrium.c) and the
 * curves of folds and Hopf points (cont_curves.c) are such systems. */
#ifndef DYN_ANALYSIS_CONT_CORE_H
#define DYN_ANALYSIS_CONT_CORE_H

#include "dynkit/continuation.h"

#define CONT_MAX_TESTS 5

typedef struct cont_system {
    int N;          /* equations; z has N + 1 unknowns */
    int ip;         /* the index in z of the parameter that has bounds and UZ values */
    int ip2;        /* the index of a second bounded parameter, or -1 */
    void *ctx;
    /* G(z) into g (N values): 0, or non-zero when f fails */
    int (*residual)(void *ctx, const double *z, double *g);
    /* DG(z) into J (N x (N + 1), row-major): 0 or non-zero */
    int (*jacobian)(void *ctx, const double *z, double *J);
    /* the test functions at a point (z, its unit tangent t, sign of det [DG; t^T]): psi
     * (n_tests values) and for each an integer count that must change too for a sign
     * change of psi to count (-1: any sign change counts); 0 or non-zero */
    int n_tests;
    dyn_cont_label test_label[CONT_MAX_TESTS];
    int (*tests)(void *ctx, const double *z, const double *t, double det_sign, double *psi,
                 int *count);
    /* store a computed point (label DYN_LABEL_NONE for a regular one): 0, or non-zero
     * when out of memory */
    int (*store)(void *ctx, const double *z, const double *t, dyn_cont_label label);
    /* > 0: Newton's method also ends when ||G||_inf <= gtol and the arclength condition
     * holds (a residual at its rounding: near a branch point the step would only amplify
     * it); 0: not used */
    double gtol;
} cont_system;

typedef struct cont_work {
    int N;
    double *A;   /* (N + 1) x (N + 1) */
    double *r, *dz, *g, *zp; /* N + 1 each */
    int *piv;
    long newton, fails;
} cont_work;

int cont_work_init(cont_work *w, int N);
void cont_work_free(cont_work *w);

/* Newton's method on G(z) = 0, t0 . (z - z0) = s from z (a guess, overwritten): 0 when
 * converged (*iters the iterations), non-zero when not. */
int cont_correct(const cont_system *s, cont_work *w, const double *z0, const double *t0,
                 double ds, double *z, int *iters);
/* The unit tangent t at z: DG t = 0, t . t_old > 0 (t_old a unit vector); *det_sign the sign
 * of det [DG; t_old^T] scaled by its rows. 0; 1 when the matrix is exactly singular (a
 * branch point); -1 when DG failed or is not finite. */
int cont_tangent(const cont_system *s, cont_work *w, const double *z, const double *t_old,
                 double *t, double *det_sign);
/* A unit null vector of [DG(z); t^T] by inverse iteration (at a branch point: the direction
 * of the other branch). 0 or non-zero. */
int cont_null_direction(const cont_system *s, cont_work *w, const double *z, const double *t,
                        double *v);

/* G = A^T A (right: A's columns, m x m) or A A^T (left: A's rows, r x r) for A (r x m,
 * row-major) with a ridge of 1e-13 of its largest diagonal entry (1 when that is 0),
 * factored by Cholesky (ode/cholesky.h) into G. 0 or non-zero (not finite, not factored). */
int cont_normal_factor(const double *A, int r, int m, int left, double *G);

/* q vectors (1 or 2, rows of V, each k long) of the smallest eigenvalues of the factored G
 * by `iterations` steps of inverse iteration from fixed starts, orthonormalized after each
 * solve: null vectors of A when G is cont_normal_factor's. 0 or non-zero. */
int cont_inverse_iteration(const double *G, int k, int q, int iterations, double *V);

/* The unit direction v of the other branch at a simple branch point z of G(z) = 0, t an
 * approximation of the known branch's unit tangent there, by the algebraic branching
 * equation (cont_branching.c). Returns 0; 1 when the equation is degenerate there and v is
 * the direction orthogonal to t in the null space of DG instead; -1 when DG failed. */
int cont_branch_direction(const cont_system *s, const double *z, const double *t, double *v);

/* A simple branch point z of G(z) = 0 near `guess`, solved for by Newton's method on Moore's
 * extended system (cont_bp_refine.c): 0; 1 when it converged to a branch point of an
 * unfolded problem (G != 0 there); -1 when it did not converge or DG failed. */
int cont_refine_branch_point(const cont_system *s, const double *guess, double *z);

/* The distance from zp to the chord from za to zb in R^M; *u in [0, 1] the place of the
 * chord's point nearest to zp, za + u (zb - za), *length the chord's length. */
double cont_chord_distance(int M, const double *za, const double *zb, const double *zp,
                           double *u, double *length);

/* Whether the step from za to zb of a curve in R^M passes the point zp (computed on the
 * same curve, tangent tp there) again going the same way (the chord within about 18 degrees
 * of tp: a curve that crosses itself at a branch point passes it another way): within a
 * tenth of the chord's length of the chord, after the curve went more than `away` from zp
 * (*far: the largest distance from zp so far, 0 at first, updated here). A curve that does
 * is closed. `scale` (at least |zp|_inf) sets the absolute part of the tolerance, 1e-9
 * scale. Periodic branches can call it on their own vectors. */
int cont_passes_point(int M, const double *za, const double *zb, const double *zp,
                      const double *tp, double scale, double away, double *far);

/* DG(z) into J (N x (N + 1), row-major) by central differences of residual (N values at
 * z, N + 1 unknowns; a cont_system's), column j with the step h_j: CONT_STEPS_POW2, 2^-20
 * max(|z_j|, 1) rounded down to a power of two, divided by 2 h_j; CONT_STEPS_CBRT,
 * eps^(1/3) max(|z_j|, 1), divided by the difference of the two arguments as rounded.
 * work: 3 N + 1 doubles. 0, or -1 when the residual failed (cont_jacobian.c). */
#define CONT_STEPS_POW2 0
#define CONT_STEPS_CBRT 1
int cont_central_jacobian(int (*residual)(void *ctx, const double *z, double *g), void *ctx,
                          int N, int steps, const double *z, double *J, double *work);

/* The settings of one run of the loop. */
typedef struct cont_loop {
    double ds, dsmin, dsmax;  /* ds > 0: the direction is the starting tangent's */
    long nmax;
    double pmin, pmax;        /* bounds of z[ip]; pmin >= pmax: none */
    double p2min, p2max;      /* bounds of z[ip2]; p2min >= p2max: none */
    const double *at;         /* UZ values of z[ip] */
    int n_at;
    dyn_cont_label start_label; /* the first point's label (EP, BP, LP, HB) */
    int stop_closed;          /* non-zero: end a curve that comes back to its start or to
                               * one of its labelled points */
    struct cont_missed *missed; /* NULL, or where the loop counts its unlocated points */
} cont_loop;

/* The special points whose test function changed sign over a step where none could be
 * located (the secant method did not converge) and no other special point was: they are
 * not stored, and the caller says so. */
typedef struct cont_missed {
    int count;
    dyn_cont_label label;     /* the first one's label */
    double p0, p1;            /* the parameter at the ends of its step */
} cont_missed;

/* What m holds, in words for a note ("2 special points detected but not located ..."), the
 * parameter named `par`, into buf (len bytes); "" when m counts none. */
void cont_missed_text(const cont_missed *m, const char *par, char *buf, size_t len);

/* L from the options of dyn_continue: |ds|, dsmin, dsmax, nmax, the bounds of the first
 * parameter, the UZ values, the first point's label; no bounds on a second parameter. */
void cont_loop_from_opts(const dyn_cont_opts *o, cont_loop *L, dyn_cont_label start);

/* The Hopf test on eigenvalues (re, im: n values): the real part of the complex eigenvalue
 * nearest the imaginary axis (+1 when none is complex: |im| <= 1e-8 of the largest
 * modulus), with *unstable the number of complex ones whose real part is above `above`
 * and *omega (NULL: not wanted) the nearest one's |im| (NAN when none). */
double cont_hopf_test(int n, const double *re, const double *im, double above, int *unstable,
                      double *omega);

/* Follow the branch from z (a point of it) along the unit tangent t for at most nmax
 * points, storing each (the first with start_label, the last with EP) with the special
 * points located between them. stop gets why it ended. Returns 0, -1 when storing
 * failed (out of memory), -2 when f failed at the first point (nothing stored), 1 when
 * (with L->stop_closed) the curve came back to its start or to one of its labelled points
 * going the same way: a closed curve, whose last point (labelled EP) is that point again.
 * A start labelled BP keeps the direction t given (the tangent is not defined there). */
int cont_follow(const cont_system *s, cont_work *w, const cont_loop *L, const double *z,
                const double *t, char *stop, size_t stoplen);

#endif /* DYN_ANALYSIS_CONT_CORE_H */
