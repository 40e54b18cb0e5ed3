/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/steady.h — steady motions (relative equilibria): states in which the derivatives
 * of the non-cyclic states vanish while the cyclic ones (states that the right-hand side
 * does not depend on, a mechanism's ignorable coordinates) move at constant rates. Named
 * unknowns (states or parameters) are solved for by Gauss-Newton with Levenberg-Marquardt
 * damping on the derivatives that must vanish, the state completed after each change by a
 * caller's step (a mechanism's dependent states from its constraints:
 * dyn_steady_dependent). C11 + libm. docs/analysis.md, "Steady motions". */
#ifndef DYNKIT_STEADY_H
#define DYNKIT_STEADY_H

#include <stddef.h>

#include "dynkit/continuation.h"
#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An unknown: state index, or parameter index when is_param. */
typedef struct dyn_steady_unknown {
    int is_param;
    int index;
} dyn_steady_unknown;

/* Complete the state y after unknowns changed (e.g. a mechanism's dependent speeds from its
 * constraints); 0, or non-zero with a message in err. */
typedef int (*dyn_steady_complete_fn)(void *ctx, double t, double *y, void *par, char *err,
                                      size_t errlen);

typedef struct dyn_steady_opts {
    int n_unknowns;
    const dyn_steady_unknown *unknowns;
    int n_equations;
    const int *equations;           /* the states whose derivatives must vanish */
    dyn_steady_complete_fn complete; /* NULL: none */
    void *complete_ctx;
    double tol;   /* relative to max(||f||_inf, 1); 0: 1e-12 */
    int max_iter; /* 0: 100 */
} dyn_steady_opts;

typedef struct dyn_steady_info {
    int iterations;
    double residual; /* the largest |f_i| of the equations at the solution */
    double tol;      /* the absolute tolerance it was held to */
    char message[256];
} dyn_steady_info;

/* Solve for the unknowns from their values in y and par (par prepared; the model's
 * prepare is called after a parameter changes) so that f_i(t, y) = 0 for each equation i.
 * y and par receive the solution (the last iterate on failure). Returns 0; DYN_ERR_STEP_SIZE
 * (no step lowers the residual: no steady motion near, message with the residual),
 * DYN_ERR_MAX_STEPS, DYN_ERR_ARG (more unknowns than equations, a prepare or completion
 * that fails), DYN_ERR_RHS. */
int dyn_steady_solve(const dyn_model *m, double t, double *y, void *par,
                     const dyn_steady_opts *opts, dyn_steady_info *info);

/* The cyclic states among the k kept ones (indices kept[0..k), all n states when kept is
 * NULL and k = n) from AP (n x k, row-major): the linearization along the admissible
 * directions, column j the derivative along kept state j. A kept state is cyclic when its
 * column vanishes (|entry| <= rel times the largest |entry| considered) on the rows of the
 * kept states not yet cyclic; repeated until no more become cyclic. cyclic[j] (k values) is
 * set to 1 for those; returns how many. */
int dyn_steady_cyclic(int n, int k, const int *kept, const double *AP, double rel, int *cyclic);

/* The dependent states dep[0..nd) of a mechanism solved from its constraints, the others
 * fixed: Newton's method on the values of cm's constraint outputs (dyn_constraint_values,
 * dynkit/analysis.h: h of every constraint and f of the holonomic ones, nd of them in all),
 * the Jacobian by central differences. Returns 0, or DYN_ERR_ARG with a message when the
 * count does not match or they do not converge. */
int dyn_steady_dependent(const dyn_model *cm, const void *par, double t, double *y, int nd,
                         const int *dep, char *err, size_t errlen);

/* ---- a branch of steady motions in one parameter ---- */

/* The admissible directions at (t, y) of a mechanism with constraints: P (n x k,
 * row-major, n the states) and the k states kept (P's rows there are the identity);
 * 0, or non-zero with a message in err. */
typedef int (*dyn_steady_basis_fn)(void *ctx, double t, const double *y, const void *par,
                                   double *P, int *kept, int *k, char *err, size_t errlen);

/* A steady-motion problem: E, the states whose derivatives vanish (the kept states that
 * are not cyclic), and U, the unknowns among them (states); the states of E not in U are
 * held, as the family of steady motions they label (a bicycle's forward speed, a disk's
 * spin). The state at parameter value p: the model's initial state at p
 * (dyn_model_initial_state) for the states flagged in follow, the start's value for the
 * others, the unknowns set, the dependent states completed. */
typedef struct dyn_steady_problem {
    int n_unknowns;
    const int *unknowns;      /* U: state indices, each one of equations */
    int n_equations;
    const int *equations;     /* E: state indices */
    const int *follow;        /* (n_states) 1: from the initial state at p; NULL: none */
    dyn_steady_complete_fn complete; /* the dependent states (NULL: none) */
    void *complete_ctx;
    dyn_steady_basis_fn basis; /* NULL: every state kept, P = I */
    void *basis_ctx;
} dyn_steady_problem;

/* The branch of steady motions through y0 (its unknowns a first guess, solved at the
 * parameter value in par as dyn_steady_solve does) in parameter o->ip by pseudo-arclength
 * continuation (the loop of dyn_continue) on the equations of U's size chosen among E's at
 * the start (rows of full rank by complete pivoting; the others must keep holding, and a
 * note says by how much they do not), appended to d as a DYN_BRANCH_STEADY branch whose
 * points hold the whole state and the eigenvalues of the reduced linearization B
 * (n_unknowns of them): A_min on E with the family's zero eigenvalues removed,
 * B = A_UU + G_U^+ G_F A_FU, G = A_min's columns U and F = E \ U on E's rows. Labels: LP
 * (the parameter's tangent component), BP (a real eigenvalue of B through zero: det B times
 * the sign of that component changes sign), HB (a complex pair of B crosses the imaginary
 * axis; l1 is not computed: NAN), HH (on a spectrum symmetric under lambda -> -lambda, a
 * conservative steady motion's: two imaginary pairs collide and leave the axis; there the
 * HB test is off and BP's is det B alone), UZ, EP. At a BP where the continuation's equations are
 * singular (another family of steady motions crosses) the other branch is followed both
 * ways and appended as branches of their own (parent, parent_point set) unless
 * o->no_switch, while d has fewer than o->max_branches; a BP where they are regular gets a
 * note in info->message. With o->ip2 >= 0 the curves of folds and of Hopf
 * points through each LP and HB in the two parameters follow (DYN_BRANCH_FOLD and
 * DYN_BRANCH_HOPF branches: no points located on them). o->periodic is not used. Returns 0, or DYN_ERR_ARG with a message (bad options, no steady motion near y0,
 * unknowns that the equations do not determine). info may be NULL. */
int dyn_steady_continue(const dyn_model *m, const void *par, const double *y0,
                        const dyn_cont_opts *o, const dyn_steady_problem *sp, dyn_diagram *d,
                        dyn_cont_info *info);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_STEADY_H */
