/* SPDX-License-Identifier: BSD-3-Clause */
/* step_control.h — step-size selection of the general driver (private): the initial step
 * (HNW I sec. II.4, "Starting step size") and the PI controller of DOPRI5 (Gustafsson,
 * ACM TOMS 17 (1991); HNW I sec. II.4 and IV.2, eq. (2.43c) of vol. II).
 */
#ifndef DYN_ODE_STEP_CONTROL_H
#define DYN_ODE_STEP_CONTROL_H

#include "ode/stepper.h"

/* The controller's constants and memory. */
typedef struct dyn_controller {
    double safety;   /* 0.9 */
    double beta;     /* PI term (0.04); 0: the classical I controller */
    double fac_min;  /* smallest h_new / h (0.2) */
    double fac_max;  /* largest h_new / h (10) */
    double expo;     /* 1/(q + 1) - 0.75 beta, q = the error order */
    double err_old;  /* error of the last accepted step (1e-4 at the start) */
    double err_old_pow; /* err_old^beta, computed when err_old is stored (1 when beta == 0) */
} dyn_controller;

/* The controller's exponent 1/(q + 1) - 0.75 beta: dyn_solve refuses a beta that makes it
 * <= 0 (the step would shrink as the error falls). */
double dyn_controller_exponent(int q, double beta);
/* Set up the controller for error order q (the estimate behaves like h^(q+1)); zeros in
 * safety, fac_min, fac_max mean the defaults, beta < 0 means 0 and beta == 0 the default. */
void dyn_controller_init(dyn_controller *c, int q, double safety, double beta, double fac_min,
                         double fac_max);
/* Next step after an accepted step of size h with error norm err (<= 1); rejected_before
 * keeps the step from growing right after a rejection. */
double dyn_controller_accept(dyn_controller *c, double h, double err, int rejected_before);
/* Next try after a rejected step of size h with error norm err (> 1, or NaN/Inf: a quarter). */
double dyn_controller_reject(const dyn_controller *c, double h, double err);

/* Initial step for the stepper at (t0, y0) with tolerances tol (HNW I sec. II.4): from
 * d0 = |y0|, d1 = |f0| and d2 ~ |f'| (one extra evaluation of f at t0 + h0, counted in
 * st->rhs_calls), h = min(100 h0, (0.01 / max(d1, d2))^(1/(q+1)), hmax). ytmp, ftmp are
 * (n) scratch. Returns 0 and *h, or the non-zero value of f (st->fail_t set). */
int dyn_initial_step(dyn_stepper *st, double t0, const double *y0, int q, double hmax,
                     double *ytmp, double *ftmp, double *h);

#endif /* DYN_ODE_STEP_CONTROL_H */
