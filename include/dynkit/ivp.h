/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/ivp.h — one call that solves an initial value problem and returns the whole
 * solution in arrays the library allocates: times, states, events, counters, and
 * optionally the dense output to evaluate anywhere. It follows SciPy's
 * scipy.integrate.solve_ivp (its OdeResult: t, y, t_events, y_events, status, message,
 * sol) and MATLAB's [t, y] = ode45(f, tspan, y0), with dyn_solve (solve.h) underneath.
 *
 *     dyn_ivp_solution *sol = dyn_ivp_solve(f, 2, &par, 0.0, 10.0, y0, NULL);
 *     if (!sol) ... out of memory
 *     if (sol->status != DYN_OK) fprintf(stderr, "%s\n", sol->message);
 *     for (long i = 0; i < sol->n_t; i++) printf("%g %g\n", sol->t[i], sol->y[i * 2]);
 *     dyn_ivp_free(sol);
 *
 * Memory: unlike the rest of the library these calls allocate: the solution's arrays grow
 * (doubling) from the solver's output and event callbacks, between steps; dyn_solve's step
 * loop itself stays allocation-free. Everything belongs to the solution and is released by
 * dyn_ivp_free. Nothing prints.
 */
#ifndef DYNKIT_IVP_H
#define DYNKIT_IVP_H

#include "dynkit/model.h"
#include "dynkit/solve.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Options; zero-initialise (or pass NULL) and set what you need. Zero means the default. */
typedef struct dyn_ivp_opts {
    const char *method;      /* a registered method (dyn_method_find); NULL: "dp45" */
    double rtol, atol;       /* 0: DYN_DEFAULT_RTOL 1e-3, DYN_DEFAULT_ATOL 1e-6 */
    const double *rtolv;     /* (n) per-state tolerances, or NULL */
    const double *atolv;     /* (n) or NULL */
    double h;                /* fixed-step methods (euler, rk4, ...): the step, required */
    const double *t_eval;    /* (n_eval) times in [t0, t1], non-decreasing: the solution
                              * there (by dense output); NULL: every step's end, from t0 */
    long n_eval;
    double first_step;       /* adaptive: 0 = automatic */
    double max_step;         /* adaptive: 0 = no limit but the span */
    long max_steps;          /* 0: no limit (else DYN_ERR_MAX_STEPS) */
    const dyn_event *events; /* (n_events) located on the solution; terminal ones end it */
    int n_events;
    dyn_jac_fn jacobian;     /* stiff methods: analytic df/dy, NULL: finite differences */
    int dense_output;        /* 1: keep every step's dense output for dyn_ivp_eval */
    /* stiff methods: a banded Jacobian (see dyn_solve_opts; the model's band when solving
     * a model and jac_banded is 0) */
    int jac_banded, jac_lower, jac_upper;
    dyn_jac_fn jacobian_band;
    int xppaut_globals;      /* see dyn_solve_opts; a model's own when solving a model */
} dyn_ivp_opts;

/* The solution. On failure everything up to the failure is kept (status says why). */
typedef struct dyn_ivp_solution {
    int status;              /* DYN_OK (also after a terminal event), or a dyn_status */
    char message[256];       /* why it stopped, when status != DYN_OK; "" otherwise */
    int n;                   /* states */
    long n_t;                /* samples */
    double *t;               /* (n_t) times */
    double *y;               /* (n_t x n) row-major: y[i * n + j] is state j at t[i] */
    long n_events;           /* events found, in time order */
    int *event_index;        /* (n_events) index into the events given */
    int *event_direction;    /* (n_events) +1 rising, -1 falling */
    double *t_events;        /* (n_events) */
    double *y_events;        /* (n_events x n) the state at each event (before a reset) */
    int terminated;          /* 1: a terminal event ended the solve at t[n_t - 1] */
    dyn_stats stats;         /* steps, rhs_calls, jac_calls, accepted, rejected, samples */
    dyn_result result;       /* dyn_solve's full result (time reached, stiffness, ...) */
    dyn_dense_record dense;  /* every step's dense output when opts.dense_output, else
                              * empty (count 0) */
} dyn_ivp_solution;

/* Solve dy/dt = f(t, y; par), y(t0) = y0 (n states), from t0 to t1 > t0 with the options
 * (NULL: dp45, rtol 1e-3, atol 1e-6, a sample at every accepted step). Returns a solution
 * to release with dyn_ivp_free, or NULL only when the solution itself cannot be allocated.
 * Bad arguments give status DYN_ERR_ARG and a message (no samples); running out of memory
 * during the solve gives DYN_ERR_CAPACITY with the samples stored so far. */
dyn_ivp_solution *dyn_ivp_solve(dyn_rhs_fn f, int n, void *par, double t0, double t1,
                                 const double *y0, const dyn_ivp_opts *opts);

/* The same for a model with its defaults where the arguments and options leave them open:
 * par (the model's parameter struct) NULL: its default parameters; y0 NULL:
 * dyn_model_initial_state; tspan NULL: [m->t0, m->t1]; the method m->method, the step
 * m->step of fixed-step methods, the tolerances m->rtol, m->atol and the Jacobian
 * m->jacobian unless opts gives them. Events: opts->events, or all of the model's events
 * when opts gives none; the model's events that reset the state always take part (after
 * those of opts when it lacks them, by name). */
dyn_ivp_solution *dyn_ivp_solve_model(const dyn_model *m, const void *par, const double *y0,
                                       const double *tspan, const dyn_ivp_opts *opts);

/* y(t) (sol->n values) from the dense output kept with opts.dense_output; returns 0, or
 * DYN_ERR_ARG when none was kept or t is outside the solved span. */
int dyn_ivp_eval(const dyn_ivp_solution *sol, double t, double *y);

/* Release a solution and all its arrays; NULL is ignored. */
void dyn_ivp_free(dyn_ivp_solution *sol);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_IVP_H */
