/* SPDX-License-Identifier: BSD-3-Clause */
/* events.h — finding and locating events on one step's dense output (private to the
 * library; used by solve.c). See events.c for the method.
 */
#ifndef DYN_ODE_EVENTS_H
#define DYN_ODE_EVENTS_H

#include "dynkit/solve.h"

/* Memory between steps and results live in the caller's workspace of doubles:
 * memo (2 x ne): g at the end of the last step, then the sign of the last non-zero value
 * seen (-1, 0: none yet, +1), as doubles;
 * hits (3 per hit): the time, the index into the event array, the direction (+1 rising,
 * -1 falling), as doubles. */
#define DYN_HIT_T(h, k) ((h)[3 * (k)])
#define DYN_HIT_INDEX(h, k) ((int)(h)[3 * (k) + 1])
#define DYN_HIT_DIR(h, k) ((int)(h)[3 * (k) + 2])

/* Doubles of scratch dyn_events_step needs. */
size_t dyn_events_work(int n, int n_events, int samples);
/* Largest number of hits one step can give. */
int dyn_events_max_hits(int n_events, int samples);

/* Start: g of every event at (t0, y0) into memo (2 x ne). */
void dyn_events_start(const dyn_event *ev, int ne, void *par, double t0, const double *y0,
                      double *memo);

/* Find the crossings of every event in (d->t0, t1] of the step d (t1 = the step's end, whose
 * state y1 is exact), sampling g at samples + 1 points and checking parabolas through
 * neighbouring samples for hidden pairs of roots; locate each by Brent's method on the
 * interpolant. Hits (sorted by time, then index) go to hits; memo is updated to the step's
 * end. Returns the number of hits. work has dyn_events_work doubles. Events whose direction
 * does not match are followed (their sign) but not reported. restart = 1 in the first step
 * after a reset: an event that starts on its zero (memo 0, no sign) is also checked for an
 * excursion to the other side before the first sample (the vertex of the parabola through
 * the zero and the next two samples). */
int dyn_events_step(const dyn_event *ev, int ne, void *par, const dyn_dense *d, double t1,
                    const double *y1, int samples, double *memo, double *work, double *hits,
                    long *g_calls, int restart);

/* XPPAUT's numbers at an instant (flags.c): the move of an instant past the crossing, a
 * relative 1e-10 of the step's part before it (its STOL); the least change of a condition
 * that fires a global in a cascade (its tolmin); a sign 0 condition within DYN_EVENTS_ZERO
 * of zero at the step's end counts as hit there, so that no reset fires it (its
 * MY_DBL_EPS). */
#define DYN_EVENTS_STOL 1e-10
#define DYN_EVENTS_TOL 1e-10
#define DYN_EVENTS_ZERO 5e-16

/* The instant of a reset whose crossing is at te in the step from ta to tb: ta + h s with
 * s = (te - ta)/h moved to s (1 + DYN_EVENTS_STOL), at least DYN_EVENTS_STOL, at most tb
 * (te itself when te = tb). Every event crossing at or before it fires at it. */
double dyn_events_instant(double ta, double te, double tb);

/* One cycle of a cascade at time t (solve.h, "Cascades"): every event not yet fired at t
 * (fired[i] == 0) whose g went from g0[i] (at the instant before any reset) to g at the
 * state y by more than tol (XPPAUT: DYN_EVENTS_TOL), onto or across zero, in its direction (rising: from
 * <= 0 to >= 0, falling: from >= 0 to <= 0; DYN_EVENT_JUMPS: g0 and g of opposite signs
 * or one of them zero, unless g_end[i], g at the step's end (may be NULL), is within
 * DYN_EVENTS_ZERO of zero), gets fired[i] = cycle when rising, -cycle when falling.
 * Returns how many. */
int dyn_events_cascade(const dyn_event *ev, int ne, void *par, double t, const double *y,
                       const double *g0, const double *g_end, double tol, double *fired,
                       int cycle);

/* An event handed to the driver (index, time, state, direction); 1 stops the run. */
typedef int (*dyn_events_report_fn)(int index, double t, const double *y, int direction,
                                     void *ctx);

/* Where the drivers' events go: counted in res, handed to on_event. */
typedef struct dyn_event_sink {
    const dyn_event *events;
    dyn_event_fn on_event; /* may be NULL */
    void *event_ctx;
    dyn_result *res;
} dyn_event_sink;

/* A dyn_events_report_fn on a dyn_event_sink (ctx): the event counted and handed to
 * on_event; 1 when it ends the run (terminal, or on_event asked to stop), with
 * res->stopped_by_event and res->event_index set. */
int dyn_events_report(int index, double t, const double *y, int direction, void *ctx);

/* What dyn_events_cascades ended with. */
enum { DYN_CASCADES_DONE = 0, DYN_CASCADES_STOPPED = 1, DYN_CASCADES_RESET_FAILED = 2 };

/* The cascades of the instant t (solve.h, "Cascades"), after the resets of the step's hits
 * at or before t (hits sorted, nh of them; t from dyn_events_instant): y_before is the
 * state at the instant before its resets, y the state after them, which the cascades'
 * resets change in place; g_end: g at the step's end (dyn_events_step's memo, may be NULL),
 * tol: dyn_events_cascade's.
 * Cycles of dyn_events_cascade, each event reported and reset in index order, until none
 * fires. casc has 2 ne doubles; *count counts the events fired. Returns
 * DYN_CASCADES_STOPPED when report asked to stop (*which: the event),
 * DYN_CASCADES_RESET_FAILED when a reset returned *status != 0 (*which: the event), else
 * DYN_CASCADES_DONE. */
int dyn_events_cascades(const dyn_event *ev, int ne, void *par, double t,
                        const double *y_before, double *y, const double *hits, int nh,
                        const double *g_end, double tol, double *casc,
                        dyn_events_report_fn report,
                        void *ctx, long *count, int *which, int *status);

/* Restart after the resets at t, from y (y_before: the state before them) as from a new
 * initial value: memo from g at y; an event that fired at t (a hit at or before t) and whose
 * g the resets left unchanged sits on its own zero (a ball's velocity reversed at y = 0, a
 * counter raised at a crossing): like a zero at the start it is no event, and the side the
 * solution leaves to decides its sign. */
void dyn_events_restart(const dyn_event *ev, int ne, void *par, double t,
                        const double *y_before, const double *y, const double *hits, int nh,
                        double *memo);

#endif /* DYN_ODE_EVENTS_H */
