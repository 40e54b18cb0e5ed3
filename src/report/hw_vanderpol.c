/* SPDX-License-Identifier: BSD-3-Clause */
/* Homework problem 2 (van der Pol, mu = 1, y0 = (2, 0), 15 s at step 0.01): the final
 * state of each fixed-step method, and each one's distance to a converged RK4 reference. */
#include <math.h>
#include <string.h>

#include "dynkit/models.h"
#include "dynkit/report.h"
#include "report/hw_common.h"


int dyn_hw_vanderpol_compute(dyn_hw_vanderpol *r, char *err, size_t errlen)
{
    const dyn_model *model = &dyn_model_vanderpol;
    dyn_vanderpol_par p;
    dyn_model_default_params(model, &p, err, errlen);
    memset(r, 0, sizeof *r);
    r->mu = p.mu;
    r->step = model->step;
    r->t1 = model->t1;
    memcpy(r->y0, model->y0, sizeof r->y0);
    const char *methods[4] = {"euler", "heun", "midpoint", "rk4"};
    double *finals[4] = {r->euler, r->modified_euler, r->midpoint, r->rk4};
    int rc = 0;
    for (int i = 0; i < 4 && !rc; i++)
        rc = hw_final_state(methods[i], dyn_vanderpol_rhs, &p, 2, 0.0, r->t1, r->step, r->y0,
                            finals[i], err, errlen);
    double coarse[2];
    r->ref_step = r->step / 100.0;
    rc = rc ? rc
            : hw_final_state("rk4", dyn_vanderpol_rhs, &p, 2, 0.0, r->t1, r->ref_step, r->y0,
                             r->reference, err, errlen);
    rc = rc ? rc
            : hw_final_state("rk4", dyn_vanderpol_rhs, &p, 2, 0.0, r->t1, 2.0 * r->ref_step,
                             r->y0, coarse, err, errlen);
    r->ref_error_estimate = hw_distance(r->reference, coarse, 2);
    for (int i = 0; i < 4; i++)
        r->error[i] = hw_distance(finals[i], r->reference, 2);
    return rc;
}
