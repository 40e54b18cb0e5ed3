/* SPDX-License-Identifier: BSD-3-Clause */
/* Homework problem 3 (model plane on a spring): Euler and RK4 at the homework's step over
 * its end time, the distance between the final centres of mass and the principal angle
 * between the final orientations (the rotation R_euler R_rk4^T, dynkit/mech.h).
 * Because the Euler run passes close to the Euler-angle singularity, its answer is chaotic
 * with respect to rounding: the analysis compares both runs with a converged RK4 reference
 * at a 100 times smaller step (the spread over 1,000 perturbed starts is a study of many
 * runs: src/studies/study_plane.c). */
#include <math.h>
#include <string.h>

#include "dynkit/mech.h"
#include "dynkit/plane.h"
#include "report/hw_common.h"

typedef struct plane_watch {
    double min_margin; /* smallest distance of theta to +-pi/2 seen */
} plane_watch;

static int watch_theta(long k, double t, const double *y, void *ctx)
{
    plane_watch *w = ctx;
    double d = dyn_euler_singularity_distance(y[4]);
    (void)k;
    (void)t;
    if (d < w->min_margin)
        w->min_margin = d;
    return 0;
}

/* Euler and RK4 runs from y0; the final states and the closest approaches to the
 * singularity (may be NULL). */
static int euler_and_rk4(dyn_plane_par *p, const double *y0, double h, double t1,
                         double *euler, double *rk4, double *margins, char *err, size_t errlen)
{
    plane_watch we = {INFINITY}, wr = {INFINITY};
    int rc = hw_run("euler", dyn_plane_rhs, p, 12, 0.0, t1, h, y0, euler, watch_theta, &we, err,
                    errlen);
    rc = rc ? rc
            : hw_run("rk4", dyn_plane_rhs, p, 12, 0.0, t1, h, y0, rk4, watch_theta, &wr, err,
                     errlen);
    if (margins) {
        margins[0] = we.min_margin;
        margins[1] = wr.min_margin;
    }
    return rc;
}

int dyn_hw_plane_compute(dyn_hw_plane *r, char *err, size_t errlen)
{
    const dyn_model *model = &dyn_model_plane;
    dyn_plane_par p;
    double y0[12], margins[2];
    memset(r, 0, sizeof *r);
    if (dyn_model_default_params(model, &p, err, errlen))
        return 1;
    dyn_model_initial_state(model, &p, y0);
    r->step_s = model->step;
    r->end_time_s = model->t1;
    int rc = euler_and_rk4(&p, y0, r->step_s, r->end_time_s, r->final_euler, r->final_rk4,
                           margins, err, errlen);
    if (rc)
        return rc;
    r->euler_min_theta_margin_rad = margins[0];
    r->rk4_min_theta_margin_rad = margins[1];
    hw_plane_compare(r->final_euler, r->final_rk4, &r->distance_m, &r->principal_angle_rad);

    /* converged reference */
    double coarse[12], dummy;
    r->ref_step = r->step_s / 100.0;
    rc = rc ? rc
            : hw_final_state("rk4", dyn_plane_rhs, &p, 12, 0.0, r->end_time_s, r->ref_step, y0,
                             r->reference, err, errlen);
    rc = rc ? rc
            : hw_final_state("rk4", dyn_plane_rhs, &p, 12, 0.0, r->end_time_s,
                             2.0 * r->ref_step, y0, coarse, err, errlen);
    hw_plane_compare(r->reference, coarse, &r->ref_error_estimate_m, &dummy);
    hw_plane_compare(r->final_rk4, r->reference, &r->rk4_distance_to_reference_m,
            &r->rk4_angle_to_reference_rad);
    hw_plane_compare(r->final_euler, r->reference, &r->euler_distance_to_reference_m,
            &r->euler_angle_to_reference_rad);
    const double e0 = dyn_plane_energy(&p, y0);
    r->energy_drift_euler = (dyn_plane_energy(&p, r->final_euler) - e0) / fabs(e0);
    r->energy_drift_rk4 = (dyn_plane_energy(&p, r->final_rk4) - e0) / fabs(e0);
    return rc;
}
