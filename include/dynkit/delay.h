/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/delay.h — delay differential equations by the method of steps.
 *
 * A delay equation y'(t) = f(t, y(t), y(t - tau_1), ...) reads its own past. The past is
 * the dense output of the accepted steps (dyn_dense, solve.h): every method's own
 * interpolant, of the order of the method (DOPRI5's and DOP853's, or the cubic Hermite
 * interpolant of fixed-step tables), kept in a dyn_history fed by dyn_solve's step
 * callback (dyn_history_push). Before t0 the past is the history function (XPPAUT: a
 * formula of t given as `x(0)=...`, or the initial value). A lag shorter than the step
 * being tried reads the last accepted step's polynomial extrapolated (as RADAR5 and
 * Shampine's ddesd do when a lag vanishes).
 *
 * Breaking points (Bellen & Zennaro, "Numerical Methods for Delay Differential Equations",
 * Oxford 2003, sec. 3.1): where the history meets the solution at t0, y' jumps; the jump
 * reaches y'' at t0 + tau, y''' at t0 + 2 tau, ... A step that crosses such a point loses
 * the method's order, so the adaptive steps land on them (dyn_solve_opts.stops):
 * dyn_delay_breaks lists t0 + k_1 tau_1 + ... + k_m tau_m up to the order that matters.
 *
 * The history is bounded: with max_delay > 0 (XPPAUT's `@ delay=`) steps that end before
 * t - max_delay are dropped, and a lag longer than max_delay (or negative) is an error
 * that stops the run (XPPAUT stops there too). The caller owns the memory: when the store
 * is full and no old step can be dropped, grow is called between steps, as for
 * dyn_dense_record. Never allocates, never prints.
 */
#ifndef DYNKIT_DELAY_H
#define DYNKIT_DELAY_H

#include <stddef.h>

#include "dynkit/solve.h"

#ifdef __cplusplus
extern "C" {
#endif

/* State i before t0 (at t < t0), given the initial state y0 (what it returns for a state
 * without a history of its own); NULL: y0[i]. */
typedef double (*dyn_history_fn)(int i, double t, const void *par, const double *y0);

typedef struct dyn_history dyn_history;
typedef int (*dyn_history_grow_fn)(dyn_history *h, void *ctx); /* 0: grown */

struct dyn_history {
    int n, degree;          /* states, degree of the steps' dense output */
    double t0;              /* the start: before it, before() or y0 */
    const double *y0;       /* (n) the initial state (borrowed) */
    dyn_history_fn before;  /* may be NULL */
    const void *par;        /* passed to before */
    double max_delay;       /* > 0: the longest lag allowed; 0: no bound */
    /* the steps: blocks of dyn_dense_record_block(n, degree) doubles, first..first+count */
    double *data;
    long capacity, first, count;
    double t_last;          /* the end of the last step (t0 before the first) */
    dyn_history_grow_fn grow; /* may be NULL */
    void *grow_ctx;
    /* the latest lag that was refused (dyn_history_value gave NaN, which stops the run
     * unless a smaller step avoids it) */
    int failed;             /* 0, or 1: lag > max_delay, 2: negative lag, 3: a lag that is
                             * not a number, 4: out of memory for the steps (push) */
    double fail_t, fail_lag;
    int fail_state;
};

/* Start an empty history over data (capacity blocks; may be NULL with capacity 0 when
 * grow provides the memory). */
void dyn_history_init(dyn_history *h, int n, int degree, double t0, const double *y0,
                      dyn_history_fn before, const void *par, double max_delay, double *data,
                      long capacity);

/* Add an accepted step (a dyn_step_fn: ctx is the history). Returns 0, or DYN_ERR_CAPACITY
 * when the store is full and could not grow. A step that starts before the last one ends
 * (a restart after a reset) replaces the later part. */
int dyn_history_push(const dyn_dense *step, void *ctx);

/* State i at time t, read at the time now (t = now - lag): before t0 the history function,
 * then the steps (the last extrapolated past its end). A lag above max_delay or below 0
 * records the failure (the first one) and gives NaN. */
double dyn_history_value(dyn_history *h, int i, double now, double t);

/* The failure as a sentence ("delay(STATE, ...) ..."), with names[i] the state names (may
 * be NULL); returns buf. */
char *dyn_history_message(const dyn_history *h, const char *const *names, char *buf,
                          size_t size);

/* Breaking points of constant lags (lags[0..n_lags), each > 0; equal ones count once, the
 * first DYN_DELAY_MAX_LAGS distinct ones) in (t0, t1]: the sums t0 + k_1 tau_1 + ... with
 * k_1 + ... + k_m <= levels, sorted, duplicates (within 1e-12 relative) merged, at most cap
 * of them into out. Returns their number (0 when a lag is not a finite number > 0).
 * levels = order of the method + 1 covers every derivative that limits it. */
#define DYN_DELAY_MAX_LAGS 8
long dyn_delay_breaks(double t0, double t1, const double *lags, int n_lags, int levels,
                      double *out, long cap);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_DELAY_H */
