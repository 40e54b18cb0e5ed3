/* SPDX-License-Identifier: BSD-3-Clause */
/* Homework problem 1 (pendulum): 1a maximum height from energy, 1c small-angle solution,
 * 1e one Euler step against the nonlinear solution, 1f the two measures, each measured.
 * The nonlinear reference is RK4 at a step small enough that halving it changes nothing
 * visible (its error estimate is reported with it). */
#include <math.h>
#include <string.h>

#include "dynkit/models.h"
#include "dynkit/report.h"
#include "report/hw_common.h"


int dyn_hw_pendulum_compute(dyn_hw_pendulum *r, char *err, size_t errlen)
{
    const dyn_model *model = &dyn_model_pendulum;
    dyn_pendulum_par p;
    dyn_model_default_params(model, &p, err, errlen);
    memset(r, 0, sizeof *r);
    r->m = p.m;
    r->l = p.l;
    r->g = p.g;
    memcpy(r->y0, model->y0, sizeof r->y0);
    r->te = 0.2;
    r->max_height_m = dyn_pendulum_max_height(&p, r->y0);
    r->goes_over_top = dyn_pendulum_energy(&p, r->y0) >= 2.0 * p.m * p.g * p.l;
    r->phi_small_angle_rad = dyn_pendulum_small_angle(&p, r->y0, r->te);

    double y[2], y_coarse[2];
    int rc = hw_final_state("euler", dyn_pendulum_rhs, &p, 2, 0.0, r->te, r->te, r->y0, y, err,
                            errlen);
    r->phi_euler_rad = y[0];
    r->dphi_euler = y[1];
    r->ref_step = r->te / 2000.0;
    rc = rc ? rc
            : hw_final_state("rk4", dyn_pendulum_rhs, &p, 2, 0.0, r->te, r->ref_step, r->y0, y,
                             err, errlen);
    rc = rc ? rc
            : hw_final_state("rk4", dyn_pendulum_rhs, &p, 2, 0.0, r->te, 2.0 * r->ref_step,
                             r->y0, y_coarse, err, errlen);
    r->phi_nonlinear_rad = y[0];
    r->ref_error_estimate = fabs(y[0] - y_coarse[0]);
    r->error_small_angle = r->phi_small_angle_rad - r->phi_nonlinear_rad;
    r->error_euler = r->phi_euler_rad - r->phi_nonlinear_rad;

    rc = rc ? rc
            : hw_final_state("euler", dyn_pendulum_rhs, &p, 2, 0.0, r->te, r->te / 10.0, r->y0,
                             y, err, errlen);
    r->euler_10_steps_error = y[0] - r->phi_nonlinear_rad;
    rc = rc ? rc
            : hw_final_state("rk4", dyn_pendulum_rhs, &p, 2, 0.0, r->te, r->te, r->y0, y, err,
                             errlen);
    r->rk4_one_step_error = y[0] - r->phi_nonlinear_rad;
    return rc;
}
