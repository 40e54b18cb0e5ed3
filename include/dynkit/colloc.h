/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/colloc.h — orthogonal collocation for boundary-value problems and periodic orbits,
 * AUTO's method (E. J. Doedel, AUTO-07p manual, and Doedel, Keller & Kernevez, Int. J.
 * Bifurcation and Chaos 1 (1991) 493-520, 745-772).
 *
 * u' = F(t, u, par) on t in [0, 1] (a periodic orbit's time scaled by its period) is
 * approximated by a continuous piecewise polynomial of degree ncol on a mesh of ntst
 * intervals, kept by its values at ncol + 1 equally spaced nodes per interval (the
 * intervals share their end nodes: (ntst ncol + 1) nodes in all), satisfying the equation at
 * the ncol Gauss points of each interval. With nbc boundary conditions g(u(0), u(1), par)
 * = 0, optionally the integral phase condition of a periodic orbit and a pseudo-arclength
 * condition, the unknowns are the node values and npar free scalars. Newton's linear
 * systems are solved by condensation of each interval's interior nodes, then a banded LU of
 * the mesh-point blocks bordered by the boundary, integral and parameter rows and columns:
 * the work is linear in ntst.
 *
 * The library part is C11 + libm: it allocates with malloc, never prints or exits. */
#ifndef DYNKIT_COLLOC_H
#define DYNKIT_COLLOC_H

#include <stddef.h>

#include "dynkit/analysis.h"
#include "dynkit/continuation.h"
#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DYN_COLLOC_MAX_NCOL 7 /* Gauss points per interval, as AUTO: 2 to 7 */

/* F(t, u, par) into f (n); fu (n x n row-major, dF_i/du_j) when non-NULL. Return 0 or
 * non-zero to stop. */
typedef int (*dyn_colloc_fn)(double t, const double *u, const double *par, double *f,
                             double *fu, void *ctx);
/* the nbc boundary residuals g(u(0), u(1), par) into g. Return 0 or non-zero to stop. */
typedef int (*dyn_colloc_bc_fn)(const double *u0, const double *u1, const double *par,
                                double *g, void *ctx);

typedef struct dyn_colloc_problem {
    int n;        /* states */
    int npar;     /* free scalars solved for with the states (a period, a parameter) */
    int nbc;      /* boundary conditions */
    int phase;    /* 1: the integral phase condition int_0^1 u . ref' dt = 0; 2: AUTO's for
                   * a connecting orbit, int_0^1 (u - ref) . ref' dt = 0 (ref satisfies it) */
    dyn_colloc_fn f;
    dyn_colloc_bc_fn bc;
    void *ctx;
} dyn_colloc_problem;

/* A solution on its mesh. */
typedef struct dyn_colloc_sol {
    int n, ntst, ncol, npar;
    double *mesh; /* ntst + 1 points, 0 to 1 */
    double *u;    /* (ntst ncol + 1) x n node values, node j ncol + l in interval j */
    double *par;  /* npar */
} dyn_colloc_sol;

int dyn_colloc_sol_alloc(dyn_colloc_sol *s, int n, int ntst, int ncol, int npar);
void dyn_colloc_sol_free(dyn_colloc_sol *s);
int dyn_colloc_sol_copy(dyn_colloc_sol *dst, const dyn_colloc_sol *src); /* allocates dst */
/* a uniform mesh */
void dyn_colloc_uniform_mesh(dyn_colloc_sol *s);
/* the piecewise polynomial at t in [0, 1] into u (n) */
void dyn_colloc_eval(const dyn_colloc_sol *s, double t, double *u);
/* the number of nodes, ntst ncol + 1 */
static inline long dyn_colloc_nodes(const dyn_colloc_sol *s)
{
    return (long)s->ntst * s->ncol + 1;
}
/* the time of node g in [0, 1] */
double dyn_colloc_node_time(const dyn_colloc_sol *s, long g);
/* <a, b>: int_0^1 a . b dt by the nodes' quadrature, plus the parameters' products. */
double dyn_colloc_dot(const dyn_colloc_sol *a, const dyn_colloc_sol *b);

/* The pseudo-arclength condition <x - x0, tangent> = ds. */
typedef struct dyn_colloc_arc {
    const dyn_colloc_sol *x0, *tangent;
    double ds;
} dyn_colloc_arc;

typedef struct dyn_colloc_opts {
    double tol;   /* Newton: max |step| <= tol (1 + max |x|); 0: 1e-10 */
    int max_iter; /* 0: 20 */
} dyn_colloc_opts;

typedef struct dyn_colloc_info {
    int iterations;
    double step;     /* the last Newton step's largest component */
    double residual; /* max |residual| at the end */
} dyn_colloc_info;

enum {
    DYN_COLLOC_OK = 0,
    DYN_COLLOC_ERR_ARG = 1,      /* sizes that do not fit */
    DYN_COLLOC_ERR_NOMEM = 2,
    DYN_COLLOC_ERR_SINGULAR = 3, /* Newton's matrix is singular */
    DYN_COLLOC_ERR_NEWTON = 4,   /* no convergence within max_iter */
    DYN_COLLOC_ERR_FN = 5        /* F or g returned non-zero or gave NaN */
};

/* Newton's method on the collocation equations from x (the guess; the solution on return).
 * ref: the phase condition's reference (needed when p->phase), on x's mesh; arc: the
 * pseudo-arclength condition, or NULL. Returns DYN_COLLOC_*. */
int dyn_colloc_solve(const dyn_colloc_problem *p, dyn_colloc_sol *x, const dyn_colloc_sol *ref,
                     const dyn_colloc_arc *arc, const dyn_colloc_opts *o,
                     dyn_colloc_info *info);

/* The tangent of the solution curve at x (p has one free scalar more than its equations
 * fix): t solves J t = 0 with <t, told> = 1 (told NULL: the last free scalar's unit
 * vector), normalised to <t, t> = 1. t is allocated like x. */
int dyn_colloc_tangent(const dyn_colloc_problem *p, const dyn_colloc_sol *x,
                       const dyn_colloc_sol *ref, const dyn_colloc_sol *told,
                       dyn_colloc_sol *t);

/* The monodromy matrix (n x n row-major into M) of the linearized collocation equations at
 * x: the product over the intervals of the condensed maps u(t_j) -> u(t_j+1) with the free
 * scalars held (AUTO's Floquet multipliers come from the same product). */
int dyn_colloc_monodromy(const dyn_colloc_problem *p, const dyn_colloc_sol *x, double *M);

/* A new mesh of ntst intervals that equidistributes AUTO's error measure, the
 * (ncol+1)-th derivative estimated by differences of the ncol-th one, raised to 1/(ncol+1);
 * x is interpolated onto it (and each sol of extra[0..nextra-1], which share x's mesh).
 * periodic: the derivative wraps around at 0 = 1. */
int dyn_colloc_adapt(dyn_colloc_sol *x, int ntst, int periodic, dyn_colloc_sol **extra,
                     int nextra);

/* The same solution on a new mesh (ntst intervals, uniform, or newmesh when non-NULL). */
int dyn_colloc_remesh(dyn_colloc_sol *x, int ntst, const double *newmesh);


/* ---- periodic orbits in one parameter (colloc_po.c) ---- */

/* A system x' = f(x, lambda): f into fx (n); J (n x n row-major, df/dx) when non-NULL.
 * Return 0 or non-zero to stop. */
typedef struct dyn_po_system {
    int n;
    int (*f)(const double *x, double lambda, double *fx, double *J, void *ctx);
    void *ctx;
} dyn_po_system;

typedef struct dyn_po_opts {
    int ntst, ncol;          /* mesh intervals and Gauss points (0: AUTO's 20 and 4) */
    double ds, dsmin, dsmax; /* arclength steps (0: 0.01, 1e-5, 0.5); ds < 0 reverses */
    int nmax;                /* points of the branch (0: 100) */
    double par_min, par_max; /* the branch ends outside [par_min, par_max] (equal: no bound) */
    double period_max;       /* the branch ends above this period (0: no bound) */
    int adapt;               /* a new mesh every `adapt` points (0: 3, AUTO's IAD; < 0 never) */
    double tol;              /* Newton's tolerance (0: 1e-9) */
    const dyn_eig_solver *eig; /* Floquet multipliers; NULL: none, no LPC/PD/TR/stability */
    int keep_orbits;         /* 1: every point keeps its orbit (else the labelled ones and
                              * the first and last) */
    const double *at;        /* parameter values where a point labelled UZ is computed */
    int n_at;
} dyn_po_opts;

/* One point of a periodic branch. */
typedef struct dyn_po_point {
    double par, period;
    double l2norm;    /* (int_0^1 |u|^2 dt)^(1/2), AUTO's L2-NORM */
    double *xmax, *xmin; /* n each: the states' extremes over the orbit (at the nodes) */
    double *mult_re, *mult_im; /* n each: the Floquet multipliers, the trivial one first */
    int stable;       /* 1: the non-trivial multipliers inside the unit circle; 0: not;
                       * -1: unknown (no eigenvalue solver) */
    char label[4];    /* "", "LPC", "PD", "TR", "BP" (a branch point of cycles), "UZ" (a
                       * value of dyn_po_opts.at), "EP" (the branch's last point) */
    dyn_colloc_sol orbit; /* kept for labelled points and the first and last (every point
                           * with dyn_po_opts.keep_orbits; else empty): u(t) on [0, 1],
                           * par[0] the period, par[1] the parameter */
    dyn_colloc_sol tangent; /* a BP point's tangent of the branch (else empty) */
} dyn_po_point;

typedef struct dyn_po_branch {
    int n, npoints, cap;
    dyn_po_point *pts;
    int status;        /* 0: ended normally (nmax, a bound); else DYN_COLLOC_* */
    int hopf_end;      /* 1: it ended where its orbits shrank to an equilibrium */
    char message[200]; /* why the branch ended */
} dyn_po_branch;

void dyn_po_branch_free(dyn_po_branch *b);

/* The periodic branch born at a Hopf point: the equilibrium x0 at parameter p0 with the
 * eigenvalues +-i omega (omega > 0). The first orbit is x0 + eps Re(q e^(2 pi i t)) with the
 * eigenvector q of i omega and period 2 pi/omega, a pseudo-arclength step of opts->ds from
 * the Hopf point along that direction (AUTO's start from an HB point). Returns 0 when the
 * branch has at least one point, else DYN_COLLOC_* (b->message says why). */
int dyn_po_from_hopf(const dyn_po_system *sys, const double *x0, double p0, double omega,
                     const dyn_po_opts *o, dyn_po_branch *b);

/* The period-doubled branch at a PD point of a branch (its kept orbit): the orbit
 * traversed twice plus a step along the eigenfunction of the multiplier -1. */
int dyn_po_from_pd(const dyn_po_system *sys, const dyn_po_point *pd, const dyn_po_opts *o,
                   dyn_po_branch *b);

/* The other branch at a BP point of a branch (its kept orbit and tangent): a step along
 * the null vector of the collocation system's Jacobian bordered by the tangent, the
 * direction orthogonal to the branch in the two-dimensional null space (AUTO-07p's
 * ISW = -1), taken with its sign (direction > 0) or the opposite one (direction < 0). */
int dyn_po_from_bp(const dyn_po_system *sys, const dyn_po_point *bp, int direction,
                   const dyn_po_opts *o, dyn_po_branch *b);

/* The Floquet multipliers of an orbit (par[0] the period, par[1] the parameter) into re,
 * im (n each), the one nearest 1 first; 0 or DYN_COLLOC_*. */
int dyn_po_multipliers(const dyn_po_system *sys, const dyn_colloc_sol *orbit,
                       const dyn_eig_solver *eig, double *re, double *im);

/* A model as a dyn_po_system in its parameter `ipar` (colloc_model.c): f at the model's t0
 * with the parameter struct copied from par (prepared again when the parameter changes),
 * the model's analytic Jacobian or central differences. */
typedef struct dyn_po_model {
    const dyn_model *m;
    int ipar;
    double current;
    void *par;    /* the model's parameter struct, owned */
    double *work; /* 3 n */
} dyn_po_model;
int dyn_po_model_init(dyn_po_model *pm, const dyn_model *m, const void *par, int ipar,
                      dyn_po_system *sys);
void dyn_po_model_free(dyn_po_model *pm);

/* ---- two-point boundary-value problems of a model (colloc_bvp.c) ---- */

typedef struct dyn_bvp_opts {
    int ntst, ncol; /* 0: 40 intervals, 4 Gauss points */
    double tol;     /* Newton's tolerance (0: 1e-10) */
    /* a free parameter (XPPAUT's periodic option: a frequency or period), 1 + its index
     * (0: none), solved for with the states; its one more unknown is fixed by the section
     * condition u_i(t0) = section_value on the state i = section - 1 (section 0: the state
     * that moves fastest at y0, |f_i(t0, y0)| largest, at its value y0[i]) */
    int free_par;
    int section;
    double section_value;
    /* a first guess instead of the initial-value problem (guess_rows 0: none): guess_rows
     * rows of times guess_t (increasing) and states guess_u (guess_rows x n), its first to
     * last time mapped onto [t0, t1], linear between rows; Newton's method from it, which
     * is also the phase condition's reference with hom_bcs (AUTO's continuation step) */
    const double *guess_t, *guess_u;
    long guess_rows;
} dyn_bvp_opts;

typedef struct dyn_bvp_result {
    dyn_colloc_sol sol;  /* on [0, 1]: t = t0 + (t1 - t0) s */
    double t0, t1;
    int iterations;      /* Newton's, on the final mesh */
    double *residuals;   /* n_bdry: the conditions at the solution */
    double err_est;      /* max over the nodes of |u_ntst - u_2ntst|, the solution against
                          * one on a mesh of twice as many intervals (NAN: that solve
                          * failed) */
    int section;         /* with a free parameter: the section's state (its index) and */
    double section_value; /* value; the parameter's value is sol.par[0] (-1: none) */
    int hom_left, hom_right; /* hom_bcs: the projection conditions at each end (the left
                              * equilibrium's stable dimension, the right one's unstable) */
    char message[256];
} dyn_bvp_result;

/* The model's boundary conditions (m->bdry, m->n_bdry == n_states; with XPPAUT's hom_bcs
 * (m->hom) n_states - 1 and AUTO's integral phase condition against the first guess, the
 * projections computed as in src/analysis/colloc_hom.c) on [t0, t1] with the
 * prepared parameters par: the initial-value problem from y0 (classical Runge-Kutta, 8
 * steps per node) is the first guess, Newton's method on the collocation equations on a
 * uniform mesh, then on a mesh adapted to that solution, and once more on twice as many
 * intervals for the error estimate (of the states and the free parameter). Returns 0 or DYN_COLLOC_* (message says why); r is
 * released with dyn_bvp_result_free either way. */
int dyn_bvp_solve(const dyn_model *m, const void *par, const double *y0, double t0, double t1,
                  const dyn_bvp_opts *o, dyn_bvp_result *r);
void dyn_bvp_result_free(dyn_bvp_result *r);

/* ---- the periodic branches of a bifurcation diagram (colloc_cont.c) ---- */

/* dyn_cont_periodic_fn (dynkit/continuation.h) for dyn_cont_opts.periodic: from the Hopf
 * point `point` of branch `branch` of d, the periodic branch with o's ntst, ncol, ds, dsmin,
 * dsmax, nmax, parmin, parmax (each state's maximum in x, minimum in xmin, the Floquet
 * multipliers in eig, labels LPC, PD, TR, EP; with o->orbits each point's orbit at its
 * collocation nodes in the branch's orbit array), then from its first period doubling the
 * doubled branch, and so on while d has fewer than o->max_branches branches. ctx: a
 * dyn_eig_solver for the multipliers, or NULL for dyn_eig_hqr. */
int dyn_po_continue_hopf(const dyn_model *m, const void *par, const dyn_cont_opts *o,
                         dyn_diagram *d, int branch, long point, void *ctx, char *err,
                         size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* DYNKIT_COLLOC_H */
