/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/solve.h — the general driver: adaptive step-size control, dense output, events.
 *
 * dyn_solve integrates a system with any registered method. Adaptive pairs (bs23 = ode23,
 * dp45 = ode45, dop853) choose their steps from the local error estimate: Hairer's norm
 *     err = sqrt(1/n sum_i (e_i / (atol_i + rtol_i max(|y_i|, |ynew_i|)))^2),
 * a step is accepted when err <= 1, and the next step comes from a PI controller
 * (Gustafsson; HNW I sec. II.4 and IV.2, the controller of DOPRI5). Fixed-step tables take
 * steps t0 + k*h exactly as dyn_fixed_solve does (same numbers, bit for bit).
 *
 * Output never forces a step: values at requested times (a grid t0 + k*h, computed, or a
 * list) are interpolated on the step's dense output (a polynomial in the step: the method's
 * own interpolant, or the cubic Hermite interpolant of the step's end values and
 * derivatives for tables without one). Each accepted step can be handed to the caller as a
 * dense-output view (dyn_dense), and a caller-owned recorder (dyn_dense_record) can keep
 * every step so that the whole solution can be evaluated after the solve.
 *
 * Events (dyn_event, ode.h) are sign changes of g(t, y) along the dense output: g is
 * sampled at event_samples + 1 points of every step (and a parabola through three samples
 * is checked for a dip across zero between them), so two crossings inside one step are
 * seen; each crossing is then located by Brent's method on the interpolant to a few ulps
 * of t (Shampine & Thompson, "Event location for ordinary differential equations",
 * Comput. Math. Appl. 39 (2000)). A terminal event ends the solve with the state at the
 * event.
 *
 * Resets (dyn_event.reset, XPPAUT's `global`): at a non-terminal event with a reset, on_event
 * sees the state at the event, the reset changes it, and the integration restarts from the
 * event's time and the new state as from a new initial value: f evaluated anew (no FSAL
 * stage carried over), the step-size controller's history cleared, the next step the
 * smaller of the controller's and the starting-step estimate at the new state (fixed-step
 * tables: a partial step from the event to the next grid point t0 + k*h, then whole steps
 * again). Crossings found later in the step belong to the old trajectory and are dropped;
 * events at the same time are all reported (with the state before the resets) and their
 * resets applied in time-then-index order. XPPAUT's instants (xppaut_globals = 1): the
 * instant of a reset is the crossing moved past it by a relative 1e-10 of the step's part
 * before it (XPPAUT's STOL), so that g is already just past zero there, and every event
 * crossing at or before that moved instant fires in it, with the state there. Cascades
 * (XPPAUT's globals): after those resets, every event that has not fired at this instant
 * and whose g the resets carried onto or across zero in its direction (from <= 0 to >= 0
 * rising, from >= 0 to <= 0 falling, g compared between the state at the instant before any
 * reset and after the resets so far; with xppaut_globals only a change of more than 1e-10;
 * a DYN_EVENT_JUMPS event when the two have opposite signs or one is zero, unless its g is
 * within 5e-16 of zero at the step's end) fires at the same instant: these
 * are reported (with the state after the resets so far), then their resets applied in
 * index order, and so on in cycles; each event fires at most once per instant
 * (dyn_result.cascades counts them; a terminal one stops the solve with the state after the
 * resets). Samples after the event (grid, out_times) come
 * from the new trajectory; with a sample at every step, the state after the reset is
 * written at the event's time. The event that fired is not found again leaving its own
 * zero in the other direction within DYN_RESET_ULPS ulps of the restart (rounding left
 * the state a few ulps on the far side), and more than DYN_ZENO_RESETS resets, each within
 * DYN_RESET_ULPS ulps of the one before, stop the solve with DYN_ERR_ZENO (a bouncing ball
 * at the time its bounces accumulate). The step callback and the recorder get the whole
 * step that holds a reset (the next one starts at the event; dyn_dense_record_eval takes
 * the later step where two overlap).
 *
 * Memory: the caller owns everything (workspace of dyn_solve_work_size doubles, outputs,
 * recorder); the step loop never allocates and nothing prints. Integration runs forward
 * (t1 > t0).
 */
#ifndef DYNKIT_SOLVE_H
#define DYNKIT_SOLVE_H

#include <stddef.h>

#include "dynkit/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Resets (see above): a solve stops with DYN_ERR_ZENO at the DYN_ZENO_RESETS-th reset in a
 * row that comes less than DYN_ZENO_WINDOW max(|t|, t1 - t0) after the one before (2^-32,
 * about 2.3e-10: time no longer advances at the resolution of the solution). */
#define DYN_ZENO_RESETS 8
#define DYN_ZENO_WINDOW 0x1p-32

/* Defaults of the tolerances (MATLAB's ode45 and SciPy's solve_ivp). */
#define DYN_DEFAULT_RTOL 1e-3
#define DYN_DEFAULT_ATOL 1e-6
/* The smallest relative tolerance (MATLAB's 100 eps): a smaller non-zero rtol asks for less
 * than rounding and is raised to it (dyn_result.rtol_raised says so). */
#define DYN_MIN_RTOL (100.0 * 2.220446049250313e-16)

/* The dense output of one step, a polynomial of degree `degree` in theta = (t - t0)/h in
 * Hairer's nested form (HNW I sec. II.6; DOPRI5's CONTD5, DOP853's CONTD8):
 *     y = c0 + theta (c1 + (1-theta) (c2 + theta (c3 + (1-theta) (c4 + theta (...))))),
 * c_j = coef[j*n .. j*n + n), the factors alternating theta, (1-theta) inward. c0 = y(t0),
 * c1 = y(t0 + h) - y(t0), so both ends are exact; c2 = h f(t0) - c1 and
 * c3 = 2 c1 - h (f(t0) + f(t0 + h)) make it the cubic Hermite interpolant, and higher c_j
 * (multiplied by theta^2 (1-theta)^2 and more) are the method's corrections. Any polynomial
 * with that degree can be written so. A view: coef belongs to whoever made it (the
 * solver's workspace during a callback). */
typedef struct dyn_dense {
    double t0, h;          /* the step covers [t0, t0 + h] */
    int n;                 /* states */
    int degree;            /* polynomial degree (dp45: 4, dop853: 7, Hermite: 3) */
    const double *coef;    /* ((degree + 1) x n) */
} dyn_dense;

/* y(t) (n values) of a step's dense output; t outside the step extrapolates. */
void dyn_dense_eval(const dyn_dense *d, double t, double *y);
/* dy/dt (n values) of the dense output at t. */
void dyn_dense_deriv(const dyn_dense *d, double t, double *dydt);

/* Degree of the dense output dyn_solve gives for method m (3 for tables without their own
 * interpolant: cubic Hermite), or 0 for NULL. */
int dyn_method_dense_degree(const dyn_tableau *m);

/* A caller-owned store of the dense output of every accepted step, so the solution can be
 * evaluated anywhere in the span after the solve. Step i is a block of
 * dyn_dense_record_block(n, degree) doubles at data + i*block: t0, h, then the coefficients.
 * Choice: the library never allocates. When the record is full the solver calls grow (the
 * caller's code, which may reallocate data and raise capacity; it runs between steps, not
 * inside the library's arithmetic); without grow, or if grow fails, the solve stops with
 * DYN_ERR_CAPACITY and what was recorded stays valid. */
typedef struct dyn_dense_record dyn_dense_record;
typedef int (*dyn_record_grow_fn)(dyn_dense_record *rec, void *ctx); /* 0: grown */
struct dyn_dense_record {
    int n, degree;         /* set by dyn_dense_record_init */
    long capacity;         /* steps data can hold */
    long count;            /* steps recorded */
    double *data;          /* (capacity x block) */
    dyn_record_grow_fn grow; /* may be NULL */
    void *grow_ctx;
};
/* Doubles per recorded step: 2 + (degree + 1) * n. */
size_t dyn_dense_record_block(int n, int degree);
/* Start an empty record for n states and the given degree (dyn_method_dense_degree) over
 * data (capacity blocks; may be NULL with capacity 0 when grow provides the memory). */
void dyn_dense_record_init(dyn_dense_record *rec, int n, int degree, double *data,
                           long capacity);
/* View of recorded step i (0 <= i < count) into d; returns 0, or DYN_ERR_ARG. */
int dyn_dense_record_step(const dyn_dense_record *rec, long i, dyn_dense *d);
/* y(t) (n values) from the recorded step that contains t (binary search). Returns 0, or
 * DYN_ERR_ARG when the record is empty or t lies outside [first t0, last t0 + h]. */
int dyn_dense_record_eval(const dyn_dense_record *rec, double t, double *y);

/* Called after each accepted step with its dense output; non-zero stops the solve
 * (DYN_STOPPED). */
typedef int (*dyn_step_fn)(const dyn_dense *step, void *ctx);

/* Called for each event in time order: index into dyn_solve_opts.events, its time, the
 * state there (n) and the direction of the crossing (+1 rising, -1 falling). Return
 * non-zero to make it terminal (stop the solve there). */
typedef int (*dyn_event_fn)(int index, double t, const double *y, int direction, void *ctx);

/* Options of dyn_solve; zero-initialise, then set what you need. */
typedef struct dyn_solve_opts {
    /* accuracy (adaptive methods): scalar tolerances, or per-state ones when rtolv/atolv
     * are not NULL. rtol 0 and atol 0 mean the defaults DYN_DEFAULT_RTOL, DYN_DEFAULT_ATOL
     * (give rtolv/atolv with zeros for a purely absolute or relative control). A scalar
     * rtol below DYN_MIN_RTOL is raised to it; per-state ones below it (but > 0) are
     * refused. */
    double rtol, atol;
    const double *rtolv;   /* (n) or NULL */
    const double *atolv;   /* (n) or NULL */
    /* steps */
    double h;              /* fixed-step methods: the step (required); adaptive: unused */
    dyn_end_policy end;    /* fixed-step grid and output grid: see dyn_grid_plan */
    double initial_step;   /* adaptive: first step; 0: chosen automatically (HNW I II.4) */
    double max_step;       /* adaptive: largest step; 0: t1 - t0 */
    /* adaptive: times the steps land on (a step that would pass one ends there), sorted;
     * e.g. the breaking points of a delay equation (dynkit/delay.h). The step after a stop
     * evaluates f anew (no FSAL stage carried over: f may jump there). Fixed-step tables
     * keep their grid: a stop on it (within 1e-12 relative) is such a restart, others are
     * stepped over. */
    const double *stops;   /* (n_stops) or NULL */
    long n_stops;
    long max_steps;        /* attempted steps at most; 0: no limit (DYN_ERR_MAX_STEPS) */
    /* step-size controller (0: the defaults below) */
    double safety;         /* the pair's own: 0.8 for bs23 and dp45 (MATLAB's ode23 and
                            * ode45), 0.85 for dop853 */
    double beta;           /* PI term 0.04; negative: 0 (pure I controller); must keep
                            * 1/(q+1) - 0.75 beta > 0 (q: the error order) */
    double fac_min;        /* smallest step ratio h_new/h, 0.2 */
    double fac_max;        /* largest step ratio, 10 */
    long stiff_check;      /* test stiffness every this many accepted steps (1000) */
    /* output: samples at t0 + k*out_step (with `end`), or at out_times, or (neither) at
     * every step's end; sample 0 is the initial state except with out_times not starting
     * at t0. With a terminal event the event is the last sample. */
    double out_step;
    const double *out_times; /* (n_out_times) non-decreasing, in [t0, t1] */
    long n_out_times;
    dyn_output_fn output;  /* may be NULL */
    void *output_ctx;
    dyn_step_fn step;      /* may be NULL: each accepted step's dense output */
    void *step_ctx;
    dyn_dense_record *record; /* may be NULL */
    /* events */
    const dyn_event *events; /* (n_events) */
    int n_events;
    dyn_event_fn on_event; /* may be NULL */
    void *event_ctx;
    int event_samples;     /* sub-intervals per step where g is sampled; 0: 8 */
    /* 1: the events are XPPAUT's globals (dyn_model.xppaut_globals): a reset's instant is
     * moved past its crossing and cascades ignore changes of 1e-10 or less ("XPPAUT's
     * instants" above) */
    int xppaut_globals;
    /* stiff methods (ignored by explicit ones) */
    dyn_jac_fn jacobian;   /* analytic df/dy or NULL (finite differences) */
    int *iwork;            /* dyn_solve_iwork_size ints, or NULL when that is 0 */
    /* A banded Jacobian (jac_banded = 1; lower/upper bandwidths, 0 <= jac_lower,
     * jac_upper < n): J comes from jacobian_band (DYN_BAND_AT storage) or, when that is
     * NULL, from banded differences (jac_lower + jac_upper + 1 calls of f, columns in
     * groups); `jacobian` is then unused, and the iteration matrix is factored by
     * band_solver (NULL: dyn_band_solver_builtin). Work and cost grow like n, not n^2. */
    int jac_banded;
    int jac_lower, jac_upper;
    dyn_jac_fn jacobian_band;
    const dyn_band_solver *band_solver;
    /* A sparse Jacobian (jac_sparse.nnz > 0 and sparse_solver not NULL; jac_banded 0): J from
     * jacobian_sparse (the values in the order of the pattern, which must hold every
     * diagonal entry), the iteration matrix I/(h gamma) - J factored by sparse_solver.
     * `jacobian` is then unused. Without jacobian_sparse, J comes from forward differences
     * with the pattern's columns in jac_n_groups groups (jac_groups, n entries: see
     * dyn_sparse_groups), jac_n_groups calls of f a Jacobian. Without sparse_solver, or
     * without both jacobian_sparse and jac_groups, the pattern is not used (dense
     * matrices). */
    dyn_sparse_pattern jac_sparse;
    dyn_jac_fn jacobian_sparse;
    const dyn_sparse_solver *sparse_solver;
    const int *jac_groups;
    int jac_n_groups;
    /* diagnostics */
    dyn_trace_fn trace;    /* stages of the first trace_steps attempted steps */
    void *trace_ctx;
    long trace_steps;
    dyn_progress_fn progress;
    void *progress_ctx;
    long progress_steps;   /* accepted steps between calls; 0: 4096 */
} dyn_solve_opts;

/* Doubles of workspace dyn_solve needs for method m, n states and the options (the
 * number of events and event_samples enter); 0 for a bad method or n. */
size_t dyn_solve_work_size(const dyn_tableau *m, int n, const dyn_solve_opts *opts);
/* Ints of integer workspace (opts->iwork) for method m and n states; 0 for explicit ones. */
size_t dyn_solve_iwork_size(const dyn_tableau *m, int n);

/* Integrate sys from (t0, y0) to t1 > t0 with method m. y (n) receives the final state (the
 * last good one on failure, the event's state after a terminal event); it may equal y0 or be
 * NULL. work has dyn_solve_work_size doubles. Samples stream through opts->output, steps
 * through opts->step and opts->record, events through opts->on_event. Never allocates.
 * Returns res->status: DYN_OK (also when a terminal event ended the run, see
 * res->stopped_by_event), DYN_ERR_ARG, DYN_ERR_RHS, DYN_ERR_NONFINITE (a state stays NaN or
 * Inf however small the step), DYN_ERR_STEP_SIZE, DYN_ERR_MAX_STEPS, DYN_ERR_CAPACITY,
 * DYN_STOPPED or DYN_CANCELLED; res->t is the time reached. opts may be NULL only for
 * adaptive methods. */
int dyn_solve(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
              const double *y0, double *y, double *work, const dyn_solve_opts *opts,
              dyn_result *res);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_SOLVE_H */
