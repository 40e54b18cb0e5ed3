/* SPDX-License-Identifier: BSD-3-Clause */
/* Robertson's chemical kinetics: three species A, B, C with the reactions
 *   A -> B (k1 = 0.04),  B + B -> C + B (k2 = 3e7),  B + C -> A + C (k3 = 1e4),
 *   y1' = -k1 y1 + k3 y2 y3
 *   y2' =  k1 y1 - k3 y2 y3 - k2 y2^2
 *   y3' =  k2 y2^2,        y(0) = (1, 0, 0).
 * The classic stiff test: H. H. Robertson (1966); Hairer & Wanner, "Solving ODEs II",
 * sec. IV.1; Test Set for IVP Solvers (Mazzia & Magherini, Univ. Bari), problem ROBER,
 * integrated there to t = 1e11. y1 + y2 + y3 is conserved (the rows of the right-hand side
 * sum to zero). The concentration y2 stays below 4e-5: give it its own absolute tolerance.
 */
#include <stddef.h>

#include "dynkit/problems.h"

int dyn_robertson_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_robertson_par *p = par;
    (void)t;
    const double r1 = p->k1 * y[0], r2 = p->k2 * y[1] * y[1], r3 = p->k3 * y[1] * y[2];
    dydt[0] = -r1 + r3;
    dydt[1] = r1 - r3 - r2;
    dydt[2] = r2;
    return 0;
}

int dyn_robertson_jac(double t, const double *y, double *J, void *par)
{
    const dyn_robertson_par *p = par;
    (void)t;
    J[0] = -p->k1;
    J[1] = p->k3 * y[2];
    J[2] = p->k3 * y[1];
    J[3] = p->k1;
    J[4] = -p->k3 * y[2] - 2.0 * p->k2 * y[1];
    J[5] = -p->k3 * y[1];
    J[6] = 0.0;
    J[7] = 2.0 * p->k2 * y[1];
    J[8] = 0.0;
    return 0;
}

static int robertson_outputs(double t, const double *y, const void *par, double *out)
{
    (void)t;
    (void)par;
    out[0] = y[0] + y[1] + y[2];
    return 0;
}

/* The model's domain: concentrations are >= 0. A value below -1e-6 (of a total of 1) is
 * no rounding: the tolerances let the solution leave the domain. */
static const char *robertson_warn(double t, const double *y, const void *par)
{
    (void)t;
    (void)par;
    for (int i = 0; i < 3; i++)
        if (y[i] < -1e-6)
            return "a concentration is negative: the run left the model's domain "
                   "(concentrations >= 0); give a smaller --atol (and --rtol), with a fixed-step "
                   "method a smaller --step, or a stiff method (rodas4)";
    return NULL;
}

static int robertson_prepare(void *par, char *err, size_t errlen)
{
    const dyn_robertson_par *p = par;
    return dyn_check_positive("k1", p->k1, err, errlen) ||
           dyn_check_positive("k2", p->k2, err, errlen) ||
           dyn_check_positive("k3", p->k3, err, errlen);
}

static const dyn_var states[] = {
    {"y1", "1", "concentration of A"},
    {"y2", "1", "concentration of B (the fast intermediate, below 4e-5)"},
    {"y3", "1", "concentration of C"},
};
static const double y0[] = {1.0, 0.0, 0.0};
static const dyn_param params[] = {
    {"k1", "1/s", "rate of A -> B", offsetof(dyn_robertson_par, k1), 0.04},
    {"k2", "1/s", "rate of B + B -> C + B", offsetof(dyn_robertson_par, k2), 3e7},
    {"k3", "1/s", "rate of B + C -> A + C", offsetof(dyn_robertson_par, k3), 1e4},
};
static const dyn_var outputs[] = {
    {"total", "1", "y1 + y2 + y3 (conserved, 1)"},
};

const dyn_model dyn_model_robertson = {
    .name = "robertson",
    .title = "Robertson's chemical kinetics (stiff; HNW II sec. IV.1, Test Set ROBER)",
    .description = "Three species, the classic stiff test (Robertson 1966).\n"
                   "  y1' = -k1 y1 + k3 y2 y3\n"
                   "  y2' =  k1 y1 - k3 y2 y3 - k2 y2^2\n"
                   "  y3' =  k2 y2^2\n"
                   "k1 = 0.04, k2 = 3e7, k3 = 1e4; y1 + y2 + y3 = 1 is conserved.\n"
                   "Explicit methods need steps below about 1e-3 here; the Test Set\n"
                   "integrates to t = 1e11 with a stiff solver. Default run: rodas4 with a\n"
                   "sample at every accepted step (the steps grow with the time scale).",
    .n_states = 3,
    .states = states,
    .y0 = y0,
    .n_params = 3,
    .params = params,
    .par_size = sizeof(dyn_robertson_par),
    .n_outputs = 1,
    .outputs = outputs,
    .rhs = dyn_robertson_rhs,
    .compute_outputs = robertson_outputs,
    .prepare = robertson_prepare,
    .warn = robertson_warn,
    .t0 = 0.0,
    .t1 = 40.0,
    .step = 5e-4, /* fixed-step methods: RK4 is stable here for h < 2.78 / 3400 = 8e-4 */
    .method = "rodas4",
    .jacobian = dyn_robertson_jac,
    .samples = DYN_SAMPLES_STEPS, /* rodas4: 20 steps from 1e-4 s to 40 s */
    /* every method, cvode too: y2 stays below 4e-5, and over 0:1e11 y1 and y2 fall far
     * below 1e-6 (the default atol would let them go negative) */
    .rtol = 1e-6,
    .atol = 1e-10,
};
