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

/* One cycle of a cascade at time t (solve.h, "Cascades"): every event not yet fired at t
 * (fired[i] == 0) whose g went from g0[i] (before the instant's resets) onto or across zero
 * at the state y, in its direction (DYN_EVENT_JUMPS: either), gets fired[i] = cycle when
 * rising, -cycle when falling. Returns how many. */
int dyn_events_cascade(const dyn_event *ev, int ne, void *par, double t, const double *y,
                       const double *g0, double *fired, int cycle);

#endif /* DYN_ODE_EVENTS_H */
