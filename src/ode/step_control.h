/* SPDX-License-Identifier: BSD-3-Clause */
/* step_control.h — step-size selection of the general driver (private): the initial step
 * (HNW I sec. II.4, "Starting step size"). The PI controller of DOPRI5 (Gustafsson, ACM
 * TOMS 17 (1991); HNW I sec. II.4 and IV.2, eq. (2.43c) of vol. II) is dyn_sinl_ctl_* in
 * dynkit/solve_inline.h, shared with the fast path.
 */
#ifndef DYN_ODE_STEP_CONTROL_H
#define DYN_ODE_STEP_CONTROL_H

#include "ode/stepper.h"

/* Initial step for the stepper at (t0, y0) with tolerances tol (HNW I sec. II.4): from
 * d0 = |y0|, d1 = |f0| and d2 ~ |f'| (one extra evaluation of f at t0 + h0, counted in
 * st->rhs_calls), h = min(100 h0, (0.01 / max(d1, d2))^(1/(q+1)), hmax). ytmp, ftmp are
 * (n) scratch. Returns 0 and *h, or the non-zero value of f (st->fail_t set). */
int dyn_initial_step(dyn_stepper *st, double t0, const double *y0, int q, double hmax,
                     double *ytmp, double *ftmp, double *h);

#endif /* DYN_ODE_STEP_CONTROL_H */
