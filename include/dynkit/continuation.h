/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/continuation.h — bifurcation diagrams: branches of equilibria f(x, p) = 0 of a
 * model followed in a parameter p by pseudo-arclength continuation (Keller; Doedel, Keller &
 * Kernevez 1991), with folds (LP), Hopf points (HB, with the first Lyapunov coefficient),
 * branch points (BP, with branch switching), end points (EP) and user points (UZ) located;
 * curves of folds and of Hopf points in two parameters, with cusps (CP), Bogdanov-Takens
 * (BT) and generalized Hopf (GH) points located (Kuznetsov, "Elements of Applied Bifurcation
 * Theory", 3rd ed., ch. 8 and 10; Govaerts 2000). The same branch type holds periodic
 * orbits, whose continuation by collocation plugs in through dyn_cont_opts.periodic.
 * Over the public model API only; C11 + libm; never prints. docs/analysis.md. */
#ifndef DYNKIT_CONTINUATION_H
#define DYNKIT_CONTINUATION_H

#include <stddef.h>

#include "dynkit/analysis.h"
#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The label of a point of a branch (AUTO-07p's names). */
typedef enum dyn_cont_label {
    DYN_LABEL_NONE = 0,
    DYN_LABEL_LP,  /* fold (limit point) of equilibria */
    DYN_LABEL_HB,  /* Hopf bifurcation */
    DYN_LABEL_BP,  /* branch point (where two branches cross) */
    DYN_LABEL_LPC, /* fold of periodic orbits */
    DYN_LABEL_PD,  /* period doubling */
    DYN_LABEL_TR,  /* torus (Neimark-Sacker) bifurcation */
    DYN_LABEL_CP,  /* cusp (on a curve of folds) */
    DYN_LABEL_BT,  /* Bogdanov-Takens (on a curve of folds or of Hopf points) */
    DYN_LABEL_GH,  /* generalized Hopf (first Lyapunov coefficient zero on a Hopf curve) */
    DYN_LABEL_EP,  /* end point: a branch's first and last point */
    DYN_LABEL_UZ,  /* a user point: a parameter value asked for (dyn_cont_opts.at) */
    DYN_LABEL_HH,  /* Hamiltonian Hopf: two imaginary pairs collide and leave the axis (a
                    * conservative steady motion's loss of stability) */
    DYN_LABEL_ZH,  /* zero-Hopf (fold-Hopf): eigenvalues 0 and +-i omega (on a curve of folds
                    * or of Hopf points) */
    DYN_LABEL_COUNT
} dyn_cont_label;

/* "LP", "HB", ..., "" for DYN_LABEL_NONE. */
const char *dyn_cont_label_name(dyn_cont_label l);

/* What a branch's points are. */
typedef enum dyn_branch_kind {
    DYN_BRANCH_EQUILIBRIUM = 0, /* equilibria in one parameter */
    DYN_BRANCH_PERIODIC = 1,    /* periodic orbits in one parameter */
    DYN_BRANCH_FOLD = 2,        /* folds of equilibria in two parameters */
    DYN_BRANCH_HOPF = 3,        /* Hopf points in two parameters */
    DYN_BRANCH_STEADY = 4,      /* steady motions in one parameter (dynkit/steady.h) */
    DYN_BRANCH_FLIP = 5,        /* a map's period doublings (flips) in two parameters */
    DYN_BRANCH_NEIMARK_SACKER = 6 /* a map's Neimark-Sacker points (TR) in two parameters */
} dyn_branch_kind;

/* "equilibrium", "periodic", "fold", "hopf", "steady", "flip", "neimark-sacker". */
const char *dyn_branch_kind_name(dyn_branch_kind k);

/* The scalars of one point of a branch. The vectors are in the branch's arrays, row k. */
typedef struct dyn_branch_point {
    dyn_cont_label label;
    double par[2];  /* the parameter(s): par[1] is NAN on a one-parameter branch */
    double period;  /* periodic orbits: the period; NAN for equilibria */
    int stable;     /* 1 asymptotically stable, 0 not, -1 not known (curves, failures) */
    /* HB: the first Lyapunov coefficient l1 (< 0 supercritical, > 0 subcritical) and the
     * frequency omega; on a Hopf curve omega^2 for every point (negative past a BT: a
     * neutral saddle); HH: the frequency where the two pairs meet; NAN where not defined */
    double l1;
    double omega;
} dyn_branch_point;

/* A branch: count points of n states each, in the order computed. For equilibria x holds
 * the state and xmin is NULL; for periodic orbits x holds each state's maximum over the
 * orbit and xmin its minimum. eig holds n_eig complex numbers per point as (re, im) pairs:
 * the eigenvalues of the Jacobian (equilibria, fold and Hopf curves) or the Floquet
 * multipliers (periodic orbits), sorted as dyn_eig_sort does. */
typedef struct dyn_branch {
    int id;             /* 1, 2, ... in the order branches were started */
    dyn_branch_kind kind;
    int parent;         /* the id of the branch it was started from (a BP, HB, LP), 0: none */
    long parent_point;  /* the index of that point on the parent, -1: none */
    /* periodic branches: the Hopf point where the orbits shrank to an equilibrium again (the
     * id of its branch and its index there; the cycles from that point are these, and are
     * not computed again), 0 and -1: none */
    int end_branch;
    long end_point;
    int n;              /* states */
    int n_eig;          /* eigenvalues or multipliers per point (n, or 0 when not stored) */
    int n_par;          /* 1 or 2 */
    int par_index[2];   /* the parameters' indices in the model (par_index[1] = -1: none) */
    long count, capacity;
    dyn_branch_point *pts; /* (count) */
    double *x;          /* (count x n) */
    double *xmin;       /* (count x n), periodic orbits only, else NULL */
    double *eig;        /* (count x 2 n_eig) */
    /* Periodic branches computed with dyn_cont_opts.orbits: each point's orbit at the
     * orbit_nodes nodes of its collocation mesh, row k holding per node its time as a
     * fraction of the period (0 to 1) and the n states, (count x orbit_nodes x (1 + n));
     * a point without one holds NAN. Else orbit_nodes = 0 and orbit NULL. */
    int orbit_nodes;
    double *orbit;
    /* why the branch stopped, in words ("reached parmax = 2", "nmax = 200 points", ...) */
    char stop[160];
    /* the diagram's progress callback and its context (set by dyn_diagram_add) */
    void (*progress)(const struct dyn_branch *b, void *ctx);
    void *progress_ctx;
} dyn_branch;

/* A diagram: the branches of one computation. */
typedef struct dyn_diagram {
    int count, capacity;
    dyn_branch *branches; /* (count) */
    /* NULL, or called after each point appended to a branch (progress on long runs: the
     * branch with its new last point; a periodic branch, computed apart, once when it is
     * stored whole); set before the computation */
    void (*progress)(const dyn_branch *b, void *ctx);
    void *progress_ctx;
} dyn_diagram;

/* A new, empty branch appended to d (id = its position + 1): kind, n states, n_eig
 * eigenvalues or multipliers per point, the parameter indices (ip2 = -1: one parameter).
 * xmin is allocated for DYN_BRANCH_PERIODIC. Returns the branch (valid until the next
 * append to d), or NULL when out of memory. */
dyn_branch *dyn_diagram_add(dyn_diagram *d, dyn_branch_kind kind, int n, int n_eig, int ip,
                            int ip2);
/* Append a point to b: p's scalars, x (n values), xmin (n values, periodic branches; NULL
 * otherwise), eig_re/eig_im (n_eig values each, or NULL: NAN). Returns the point's index,
 * or -1 when out of memory. */
long dyn_branch_append(dyn_branch *b, const dyn_branch_point *p, const double *x,
                       const double *xmin, const double *eig_re, const double *eig_im);
/* Free every branch of d and reset it to empty (its progress callback kept). */
void dyn_diagram_free(dyn_diagram *d);

/* ---- settings (AUTO-07p's constants, XPPAUT's @ names) ---- */

/* Defaults (XPPAUT's AUTO window): */
#define DYN_CONT_DS 0.02
#define DYN_CONT_DSMIN 0.001
#define DYN_CONT_DSMAX 0.5
#define DYN_CONT_NMAX 200
#define DYN_CONT_NPR 50
#define DYN_CONT_PARMIN 0.0
#define DYN_CONT_PARMAX 2.0
#define DYN_CONT_NTST 15
#define DYN_CONT_NCOL 4
/* Newton's corrections end when the step is below DYN_CONT_TOL (1 + ||z||_inf); special
 * points are located until the parameter moves less than DYN_CONT_TOL_LOCATE relative. */
#define DYN_CONT_TOL 1e-11
#define DYN_CONT_TOL_LOCATE 1e-12
/* A fold's test function, the unit tangent's parameter component, changing sign while at
 * most DYN_CONT_FOLD_NOISE on both sides is rounding on a vertical branch (a family of
 * solutions at one parameter value, as from a linear centre's Hopf point): no LP or LPC. */
#define DYN_CONT_FOLD_NOISE 1e-9

struct dyn_cont_opts;

/* Continuation of periodic orbits from a Hopf point (given by the collocation part): from
 * the point `point` (labelled HB) of the equilibrium branch with id `branch` in d, append
 * the periodic branch(es) to d (dyn_diagram_add with DYN_BRANCH_PERIODIC; parent and
 * parent_point set). m, par (prepared, the parameters' base values), o as given to
 * dyn_continue; ctx is o->periodic_ctx. Returns 0, or non-zero with a message in err (the
 * diagram keeps what was appended). */
typedef int (*dyn_cont_periodic_fn)(const dyn_model *m, const void *par,
                                    const struct dyn_cont_opts *o, dyn_diagram *d, int branch,
                                    long point, void *ctx, char *err, size_t errlen);

typedef struct dyn_cont_opts {
    int ip;            /* the parameter continued (index in the model) */
    int ip2;           /* the second parameter of fold and Hopf curves, -1: none */
    double ds;         /* the first step, signed: its sign is the direction in ip (0: DS) */
    double dsmin, dsmax; /* step limits (> 0; 0: defaults) */
    long nmax;         /* points per branch at most (0: NMAX) */
    long npr;          /* AUTO's NPR (kept for the periodic part; every point is stored) */
    double parmin, parmax;   /* the range of ip: a branch ends (EP) on its bounds */
    double par2min, par2max; /* the range of ip2 on curves (equal: unbounded) */
    int ntst, ncol;    /* collocation: mesh intervals and points (0: defaults) */
    const double *at;  /* values of ip where a point labelled UZ is computed (n_at) */
    int n_at;
    int no_switch;     /* 1: do not follow the other branch at a BP (of cycles too) */
    int max_branches;  /* branches of the diagram at most (0: 16) */
    dyn_jac_scheme jac; /* the Jacobian in the states (dynkit/analysis.h) */
    double t;          /* the time at which f is evaluated (non-autonomous models) */
    dyn_cont_periodic_fn periodic; /* NULL: no periodic orbits from Hopf points */
    void *periodic_ctx;
    int orbits;        /* 1: periodic branches keep each point's orbit (dyn_branch.orbit) */
    /* 1: m is a discrete map y_{k+1} = F(t, y_k): the branches are of fixed points
     * F(y, p) = y, eig holds the multipliers (the eigenvalues of dF/dy), stable when every
     * |mu| < 1; labels LP (mu = 1), BP, PD (mu = -1) and TR (a complex pair crosses the
     * unit circle: Neimark-Sacker, AUTO-07p's name for maps, with omega the pair's angle
     * arg mu in (0, pi)); from each PD the points of twice the period (fixed points of
     * F o F), up to period 16 (dyn_branch_point.period: the points' period). With ip2 >= 0
     * the curves of folds, flips (DYN_BRANCH_FLIP) and Neimark-Sacker points
     * (DYN_BRANCH_NEIMARK_SACKER, omega the angle) in two parameters, with the cusp points
     * of the fold curves only (cont_map.c, cont_curves.c) */
    int map;
    /* a map's first branch: 0 or 1 its fixed points, k > 1 its points of period k (the
     * fixed points of F^k, multipliers those of F^k: XPPAUT's NJMP for AUTO) */
    int map_period;
} dyn_cont_opts;

/* o filled with the defaults above for parameter ip (ip2 = -1, parmin/parmax as defined,
 * par2min = par2max = 0: unbounded). */
void dyn_cont_opts_default(dyn_cont_opts *o, int ip);

/* What dyn_continue did. */
typedef struct dyn_cont_info {
    long points;        /* points computed over all branches */
    long newton_steps;  /* Newton iterations (each one Jacobian and one LU) */
    long rhs_calls;     /* evaluations of f (the Jacobians' differences included) */
    char message[512];  /* why it failed, when it did; else notes ("a branch stopped...") */
    int start_failed;   /* 1: it failed because no equilibrium was found near x0 */
} dyn_cont_info;

/* The bifurcation diagram of model m from x0 (n states: an equilibrium guess, refined by
 * Newton's method at the parameter value in par) in parameter o->ip: the branch through it
 * in the direction of o->ds, the branches from its branch points (both directions, unless
 * o->no_switch), the periodic branches from its Hopf points (o->periodic), and with o->ip2
 * >= 0 the curves of folds and Hopf points in (ip, ip2) from each LP and HB found, both
 * directions. par: the prepared parameter struct (not changed). Branches are appended to d
 * (which the caller frees with dyn_diagram_free). Returns 0; DYN_ERR_ARG (bad options, no
 * equilibrium near x0: message says which); DYN_ERR_RHS when f fails at the start. A branch
 * that cannot go on ends with an EP and says why in its stop text. info may be NULL. */
int dyn_continue(const dyn_model *m, const void *par, const double *x0, const dyn_cont_opts *o,
                 dyn_diagram *d, dyn_cont_info *info);

/* The first Lyapunov coefficient of model m at a Hopf point (x, with the parameters par)
 * with eigenvalues +-i omega (omega > 0) of the Jacobian A (n x n): Kuznetsov's formula
 * (eq. 3.20 of "Elements", ch. 3.5) l1 = Re[<p, C(q,q,q~)> - 2 <p, B(q, A^-1 B(q,q~))>
 * + <p, B(q~, (2 i omega - A)^-1 B(q,q))>] / (2 omega), A q = i omega q, A^T p = -i omega p,
 * <p, q> = 1, with B and C the second and third derivatives of f along the vectors by
 * differences of the Jacobian. Returns 0 with *l1, or DYN_ERR_ARG with a message. */
int dyn_first_lyapunov(const dyn_model *m, double t, const double *x, void *par,
                       dyn_jac_scheme jac, const double *A, double omega, double *l1,
                       char *err, size_t errlen);

/* Eigenvalues of a real n x n matrix a (row-major, overwritten) into re, im (n values; a
 * complex pair as consecutive entries, positive imaginary part first), by balancing,
 * reduction to Hessenberg form and Francis' double-shift QR (the EISPACK routines balanc,
 * elmhes, hqr; Wilkinson & Reinsch 1971). Returns 0, or DYN_ERR_MAX_STEPS (no convergence
 * after 30 n sweeps) with a message in err. The same contract as dyn_eig_solver. */
int dyn_eig_hqr(int n, double *a, double *re, double *im, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_CONTINUATION_H */
