/* SPDX-License-Identifier: BSD-3-Clause */
/* suite.h — what the benchmark suite (suite.c) shares with its peer modules (peer_gsl.c,
 * peer_sundials.c, peer_boost.cpp): the systems every solver integrates and the interface of
 * one solver under test.
 *
 * A peer module turns a system and a task (fixed step with one method, adaptive, stiff) into
 * solvers: each is created once, outside the timing, and then run many times. Every solver
 * integrates the same right-hand sides (bench_systems.h, inlined into each module's own
 * callback), so differences in time are the solvers', not the models'.
 */
#ifndef DYNKIT_BENCH_SUITE_H
#define DYNKIT_BENCH_SUITE_H

#include "bench_systems.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum bench_sys_id {
    BENCH_VDP,       /* van der Pol, mu = 1, 2 states (bench_vdp_par) */
    BENCH_PLANE,     /* model plane on a spring, 12 states (bench_plane_par) */
    BENCH_ARENSTORF, /* Arenstorf orbit, 4 states (bench_arenstorf_par) */
    BENCH_VDP_STIFF, /* van der Pol, mu = 1000 (bench_vdp_par), with its Jacobian */
    BENCH_KEPLER     /* Kepler's problem, e = 0.9, 4 states: dynkit's controllers only */
} bench_sys_id;

typedef struct bench_sys {
    bench_sys_id id;
    const char *name;
    int n;
    const void *par;
    const double *y0; /* (n) */
    double t0, t1;
} bench_sys;

typedef enum bench_task {
    BENCH_TASK_FIXED,    /* fixed steps with one method (bench_method) */
    BENCH_TASK_ADAPTIVE, /* non-stiff adaptive solve t0 -> t1, rtol = atol = tol */
    BENCH_TASK_STIFF     /* stiff adaptive solve t0 -> t1, rtol = atol = tol */
} bench_task;

typedef enum bench_method { BENCH_EULER, BENCH_HEUN, BENCH_RK4, BENCH_NMETHOD } bench_method;

typedef struct bench_counts {
    long rhs;   /* right-hand-side evaluations (including those of difference Jacobians) */
    long jac;   /* Jacobian evaluations */
    long steps; /* steps (adaptive: accepted) */
} bench_counts;

/* Fixed-step solvers: how a row relates to the others. */
enum {
    BENCH_SAME = 1,     /* computes the method itself: the final state must agree with the
                         * hand-written loop's to a relative 1e-12 */
    BENCH_WRONG = 2,    /* known to compute something else (a peer's bug): shown with its
                         * error, excluded from every comparison */
    BENCH_ACCURACY = 4, /* a different method run at another step so that its error matches
                         * the hand-written loop's: compared by time per solve */
    BENCH_DIAG = 8,     /* a diagnostic variant (e.g. a peer with the right-hand side called
                         * through a pointer): shown, never a target's comparison */
    BENCH_INLINE = 16   /* dynkit's header-only adaptive driver (dyn_solve_inline): compared
                         * in its own target row, against Boost, and as one of dynkit's
                         * pairs in the row of the fastest pair against every peer */
};

typedef struct bench_solver {
    char label[80];
    const char *peer; /* "hand", "dynkit", "Boost", "GSL", "ARKODE", "CVODE" */
    int is_dynkit;
    int flags;             /* BENCH_SAME, BENCH_WRONG, BENCH_ACCURACY, BENCH_DIAG */
    int order;             /* adaptive: order of the propagated solution */
    double step_factor;    /* fixed: steps of step_factor * h (steps / step_factor of them) */
    double calls_per_step; /* fixed: right-hand-side calls per step */
    char note[320];        /* caveat printed under the table, or "" */
    void *ctx;
    /* Fixed: `steps` steps of h from sys->y0. Adaptive and stiff: sys->t0 -> sys->t1 with
     * rtol = atol = arg (steps unused). y (n) receives the final state; counts may be NULL.
     * Returns 0, or non-zero on failure. */
    int (*run)(void *ctx, double arg, long steps, double *y, bench_counts *counts);
    void (*destroy)(void *ctx);
} bench_solver;

/* A peer module: appends its solvers for sys and task (method for fixed steps) to out (room
 * for max) and returns how many; 0 when it has nothing for this task. version: one line. */
typedef struct bench_peer {
    const char *name; /* "gsl", "boost", "sundials": the --peers names */
    const char *(*version)(void);
    int (*solvers)(const bench_sys *sys, bench_task task, bench_method m, bench_solver *out,
                   int max);
} bench_peer;

#ifdef BENCH_HAVE_GSL
extern const bench_peer bench_peer_gsl;
#endif
#ifdef BENCH_HAVE_SUNDIALS
extern const bench_peer bench_peer_sundials;
#endif
#ifdef BENCH_HAVE_BOOST
extern const bench_peer bench_peer_boost;
#endif

/* The classical tables (Butcher): a (s x s) row-major, b, c; for modules that build their
 * own fixed-step methods. */
typedef struct bench_table {
    const char *name;
    int s, order;
    const double *a, *b, *c;
} bench_table;
const bench_table *bench_fixed_table(bench_method m);

#ifdef __cplusplus
}
#endif
#endif
