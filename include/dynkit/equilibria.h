/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/equilibria.h — every equilibrium of a model in a box: f(t, y) = 0 solved by
 * dyn_equilibrium (Newton's method through Levenberg-Marquardt steps, the model's exact
 * Jacobian or differences, dynkit/analysis.h) from a deterministic set of starts (the
 * box's centre, then the points of Halton's sequence scaled to the box), the solutions
 * inside the box merged when they agree, each with the eigenvalues of its linearization
 * and its type (stable/unstable node or focus, saddle, saddle-focus, centre,
 * non-hyperbolic) and the dimensions of its stable, unstable and centre manifolds. For a
 * discrete map (y_{k+1} = F(t, y_k)) the fixed points F(y) = y and their multipliers
 * (the eigenvalues of dF/dy), judged against the unit circle. Over the public model API;
 * C11 + libm. Unlike most of the library these calls allocate the result (released by
 * dyn_equilibria_free). docs/analysis.md, "Equilibria". */
#ifndef DYNKIT_EQUILIBRIA_H
#define DYNKIT_EQUILIBRIA_H

#include <stddef.h>

#include "dynkit/analysis.h"
#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Starts when dyn_equilibria_opts.starts is 0: the box's centre and 255 Halton points. */
#define DYN_EQUILIBRIA_STARTS 256
/* Two solutions are one equilibrium when every state agrees within this much of the
 * larger of the box's width in that state, |y| and 1e-3. */
#define DYN_EQUILIBRIA_MERGE 1e-6

/* What an equilibrium (or a map's fixed point) is, from the eigenvalues (multipliers). */
typedef enum dyn_eq_type {
    DYN_EQ_UNCLASSIFIED = 0,  /* no eigenvalues (no solver given) */
    DYN_EQ_STABLE_NODE = 1,   /* all stable, all real */
    DYN_EQ_UNSTABLE_NODE = 2, /* all unstable, all real */
    DYN_EQ_STABLE_FOCUS = 3,  /* all stable, a complex pair among them */
    DYN_EQ_UNSTABLE_FOCUS = 4,
    DYN_EQ_SADDLE = 5,        /* stable and unstable ones, none central, all real */
    DYN_EQ_SADDLE_FOCUS = 6,  /* the same with a complex pair */
    DYN_EQ_CENTRE = 7,        /* every one central and in complex pairs */
    DYN_EQ_NONHYPERBOLIC = 8, /* some central, none of the others (a zero eigenvalue, ...) */
    DYN_EQ_SADDLE_CENTRE = 9  /* stable, unstable and central ones, the central ones in
                               * complex pairs (a conservative system's saddle x centre) */
} dyn_eq_type;

/* "stable node", "unstable node", "stable focus", "unstable focus", "saddle",
 * "saddle-focus", "centre", "saddle-centre", "non-hyperbolic", "unclassified". */
const char *dyn_eq_type_name(dyn_eq_type t);

/* The type of the k eigenvalues re + i im (a map's multipliers when map is 1) and the
 * dimensions of the manifolds into dims (may be NULL): dims[0] stable (re < -tol, or
 * |mu| < 1 - tol), dims[1] unstable (re > tol, |mu| > 1 + tol), dims[2] centre (the rest). */
dyn_eq_type dyn_eq_classify(int k, const double *re, const double *im, int map, double tol,
                            int dims[3]);

/* The reduction of a linearization to admissible directions (a mechanism's constraints,
 * as dynkit linearize does): from A (n x n) at (t, y) write A_min (k x k, k <= n) into Amin
 * and k into *k. 0, or non-zero with a message in err. */
typedef int (*dyn_equilibria_reduce_fn)(void *ctx, double t, const double *y, void *par,
                                        const double *A, double *Amin, int *k, char *err,
                                        size_t errlen);

typedef struct dyn_equilibria_opts {
    const double *lo, *hi; /* the box (n values each, lo <= hi; required) */
    const double *guess;   /* a first start besides the box's points (n values) or NULL */
    int starts;            /* starts from the box: 0 means DYN_EQUILIBRIA_STARTS */
    int map;               /* 1: m is a discrete map: fixed points F(y) = y, multipliers */
    dyn_jac_scheme scheme; /* the Jacobian (AUTO: the model's exact one when it has one) */
    double tol;            /* dyn_equilibrium's relative tolerance; 0: its default */
    int max_iter;          /* Jacobians per start; 0: 60 */
    double merge;          /* 0: DYN_EQUILIBRIA_MERGE */
    /* eigenvalues: NULL for none (types DYN_EQ_UNCLASSIFIED) */
    const dyn_eig_solver *eig;
    /* the stability tolerance: rtol * ||A||_inf (dyn_stability_tol; for a map rtol times
     * max(||dF/dy||_inf, 1)); 0 means DYN_STABILITY_RTOL */
    double stability_rtol;
    dyn_equilibria_reduce_fn reduce; /* NULL: the eigenvalues of the full linearization */
    void *reduce_ctx;
} dyn_equilibria_opts;

/* The equilibria found, sorted by their states (first state, then the second, ...). */
typedef struct dyn_equilibria {
    int n;            /* states */
    int count;        /* equilibria */
    double *y;        /* (count x n) the states */
    double *residual; /* (count) ||f||_inf (a map: ||F(y) - y||_inf) there */
    int *k;           /* (count) eigenvalues of each (n, or k of the reduction) */
    double *re, *im;  /* (count x n) eigenvalues (a map: multipliers), k of each, sorted as
                       * dyn_eig_sort does */
    dyn_eq_type *type; /* (count) */
    int *dims;        /* (count x 3) stable, unstable, centre manifolds' dimensions */
    double *tol;      /* (count) the stability tolerance used */
    int starts;       /* starts tried */
    int converged;    /* starts that converged (inside the box or not) */
    int outside;      /* of these, how many converged outside the box */
    long rhs_calls;   /* evaluations of f in all */
    char message[256]; /* why it failed, when it did */
} dyn_equilibria;

/* The equilibria of model m (or fixed points of a map) with prepared parameters par at
 * time t inside the box of opts. Returns 0 with out filled (count may be 0: none found);
 * DYN_ERR_ARG (bad box, a delay or Volterra model, the reduction failed), DYN_ERR_CAPACITY
 * (out of memory) or the eigenvalue solver's failure as DYN_ERR_RHS, with out->message.
 * out is always to be released by dyn_equilibria_free. */
int dyn_equilibria_find(const dyn_model *m, double t, void *par, const dyn_equilibria_opts *opts,
                        dyn_equilibria *out);
void dyn_equilibria_free(dyn_equilibria *e);

/* Point k of Halton's sequence in dimension j (the radical inverse of k in the j-th
 * prime's base; k >= 1), in (0, 1). */
double dyn_halton(long k, int j);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_EQUILIBRIA_H */
