/* SPDX-License-Identifier: BSD-3-Clause */
/* Van der Pol oscillator of homework problem 2 (the homework's vanderpoldemo):
 *   y1' = y2,  y2' = mu (1 - y1^2) y2 - y1,
 * with mu = 1, y0 = (2, 0), tspan [0, 15], step 0.01 s.
 * Reference: B. van der Pol, Phil. Mag. 2 (1926); Hairer, Nørsett & Wanner I, sec. I.16.
 * Analytic Jacobian [[0, 1], [-2 mu y1 y2 - 1, mu (1 - y1^2)]] for the stiff methods
 * (mu = 1000 is the classic stiff test, HNW II sec. IV.1).
 */
#include <stddef.h>

#include "dynkit/models.h"

int dyn_vanderpol_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_vanderpol_par *p = par;
    (void)t;
    dydt[0] = y[1];
    dydt[1] = p->mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
    return 0;
}

int dyn_vanderpol_jac(double t, const double *y, double *J, void *par)
{
    const dyn_vanderpol_par *p = par;
    (void)t;
    J[0] = 0.0;
    J[1] = 1.0;
    J[2] = -2.0 * p->mu * y[0] * y[1] - 1.0;
    J[3] = p->mu * (1.0 - y[0] * y[0]);
    return 0;
}

static const dyn_var states[] = {
    {"y1", "1", "position-like state"},
    {"y2", "1/s", "its time derivative"},
};
static const double y0[] = {2.0, 0.0};
static const dyn_param params[] = {
    {"mu", "1", "nonlinear damping parameter", offsetof(dyn_vanderpol_par, mu), 1.0},
};

const dyn_model dyn_model_vanderpol = {
    .name = "vanderpol",
    .title = "van der Pol oscillator (homework problem 2)",
    .description = "Self-excited oscillator with nonlinear damping, the homework's vanderpoldemo.\n"
                   "  y1' = y2\n"
                   "  y2' = mu (1 - y1^2) y2 - y1",
    .n_states = 2,
    .states = states,
    .y0 = y0,
    .n_params = 1,
    .params = params,
    .par_size = sizeof(dyn_vanderpol_par),
    .n_outputs = 0,
    .outputs = NULL,
    .rhs = dyn_vanderpol_rhs,
    .compute_outputs = NULL,
    .prepare = NULL,
    .t0 = 0.0,
    .t1 = 15.0,
    .step = 0.01, /* the homework's step: the sample grid, and fixed-step methods' step */
    .method = "dp45", /* adaptive whatever the span and mu; the homework's RK4: --method rk4 */
    .rtol = 1e-8,
    .atol = 1e-10,
    .jacobian = dyn_vanderpol_jac,
};
