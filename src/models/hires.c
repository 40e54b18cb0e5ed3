/* SPDX-License-Identifier: BSD-3-Clause */
/* HIRES: "High Irradiance RESponse" of photomorphogenesis (Schäfer 1975), 8 species,
 * linear kinetics plus one bilinear reaction, as in Hairer & Wanner, "Solving ODEs II",
 * sec. IV.10, and the Test Set for IVP Solvers (Mazzia & Magherini, Univ. Bari), problem
 * HIRES, whose rate constants and interval [0, 321.8122] are used:
 *   y1' = -k1 y1 + k2 y2 + k6 y3 + oks
 *   y2' =  k1 y1 - (k2 + k3) y2
 *   y3' = -(k6 + k1) y3 + k2 y4 + k5 y5
 *   y4' =  k3 y2 + k1 y3 - (k4 + k2) y4
 *   y5' = -(k5 + k1) y5 + k2 (y6 + y7)
 *   y6' = -k7 y6 y8 + k8 y4 + k1 y5 - k2 y6 + k8 y7
 *   y7' =  k7 y6 y8 - (k2 + k8 + k9) y7
 *   y8' = -k7 y6 y8 + (k2 + k8 + k9) y7
 * k1 = 1.71, k2 = 0.43, k3 = 8.32, k4 = 0.69, k5 = 0.035, k6 = 8.32, k7 = 280,
 * k8 = 0.69, k9 = 0.69, oks = 0.0007; y(0) = (1, 0, 0, 0, 0, 0, 0, 0.0057).
 * y7 + y8 is conserved.
 */
#include <stddef.h>
#include <string.h>

#include "dynkit/problems.h"

int dyn_hires_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_hires_par *p = par;
    (void)t;
    const double r7 = p->k7 * y[5] * y[7];
    const double k289 = p->k2 + p->k8 + p->k9;
    dydt[0] = -p->k1 * y[0] + p->k2 * y[1] + p->k6 * y[2] + p->oks;
    dydt[1] = p->k1 * y[0] - (p->k2 + p->k3) * y[1];
    dydt[2] = -(p->k6 + p->k1) * y[2] + p->k2 * y[3] + p->k5 * y[4];
    dydt[3] = p->k3 * y[1] + p->k1 * y[2] - (p->k4 + p->k2) * y[3];
    dydt[4] = -(p->k5 + p->k1) * y[4] + p->k2 * (y[5] + y[6]);
    dydt[5] = -r7 + p->k8 * y[3] + p->k1 * y[4] - p->k2 * y[5] + p->k8 * y[6];
    dydt[6] = r7 - k289 * y[6];
    dydt[7] = -r7 + k289 * y[6];
    return 0;
}

int dyn_hires_jac(double t, const double *y, double *J, void *par)
{
    const dyn_hires_par *p = par;
    (void)t;
    const double k289 = p->k2 + p->k8 + p->k9;
    memset(J, 0, 64 * sizeof *J);
#define JJ(i, j) J[((i)-1) * 8 + ((j)-1)]
    JJ(1, 1) = -p->k1;
    JJ(1, 2) = p->k2;
    JJ(1, 3) = p->k6;
    JJ(2, 1) = p->k1;
    JJ(2, 2) = -(p->k2 + p->k3);
    JJ(3, 3) = -(p->k6 + p->k1);
    JJ(3, 4) = p->k2;
    JJ(3, 5) = p->k5;
    JJ(4, 2) = p->k3;
    JJ(4, 3) = p->k1;
    JJ(4, 4) = -(p->k4 + p->k2);
    JJ(5, 5) = -(p->k5 + p->k1);
    JJ(5, 6) = p->k2;
    JJ(5, 7) = p->k2;
    JJ(6, 4) = p->k8;
    JJ(6, 5) = p->k1;
    JJ(6, 6) = -p->k7 * y[7] - p->k2;
    JJ(6, 7) = p->k8;
    JJ(6, 8) = -p->k7 * y[5];
    JJ(7, 6) = p->k7 * y[7];
    JJ(7, 7) = -k289;
    JJ(7, 8) = p->k7 * y[5];
    JJ(8, 6) = -p->k7 * y[7];
    JJ(8, 7) = k289;
    JJ(8, 8) = -p->k7 * y[5];
#undef JJ
    return 0;
}

static int hires_outputs(double t, const double *y, const void *par, double *out)
{
    (void)t;
    (void)par;
    out[0] = y[6] + y[7];
    return 0;
}

/* The model's domain: concentrations are >= 0. A value below -1e-6 (of a total of 1) is
 * no rounding: the tolerances let the solution leave the domain. */
static const char *hires_warn(double t, const double *y, const void *par)
{
    (void)t;
    (void)par;
    for (int i = 0; i < 8; i++)
        if (y[i] < -1e-6)
            return "a concentration is negative: the run left the model's domain "
                   "(concentrations >= 0); give a smaller --atol (and --rtol), with a fixed-step "
                   "method a smaller --step, or a stiff method (rodas4)";
    return NULL;
}

static const dyn_var states[] = {
    {"y1", "1", "Pr"},     {"y2", "1", "Pfr"},   {"y3", "1", "PrX"},    {"y4", "1", "PfrX"},
    {"y5", "1", "PrX2"},   {"y6", "1", "PfrX2"}, {"y7", "1", "PfrX2E"}, {"y8", "1", "E"},
};
static const double y0[] = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057};
#define P(name, desc, v) {#name, "1/s", desc, offsetof(dyn_hires_par, name), v}
static const dyn_param params[] = {
    P(k1, "rate constant k1", 1.71),  P(k2, "rate constant k2", 0.43),
    P(k3, "rate constant k3", 8.32),  P(k4, "rate constant k4", 0.69),
    P(k5, "rate constant k5", 0.035), P(k6, "rate constant k6", 8.32),
    P(k7, "rate constant k7 of the bilinear reaction y6 + y8 -> y7", 280.0),
    P(k8, "rate constant k8", 0.69),  P(k9, "rate constant k9", 0.69),
    {"oks", "1/s", "constant source of y1", offsetof(dyn_hires_par, oks), 0.0007},
};
#undef P
static const dyn_var outputs[] = {
    {"y7_plus_y8", "1", "y7 + y8 (conserved, 0.0057)"},
};

const dyn_model dyn_model_hires = {
    .name = "hires",
    .title = "HIRES photomorphogenesis kinetics, 8 states (stiff; HNW II sec. IV.10, Test Set)",
    .description = "Schafer's 'High Irradiance RESponse' model, 8 species.\n"
                   "  y1' = -k1 y1 + k2 y2 + k6 y3 + oks\n"
                   "  y2' =  k1 y1 - (k2 + k3) y2\n"
                   "  y3' = -(k6 + k1) y3 + k2 y4 + k5 y5\n"
                   "  y4' =  k3 y2 + k1 y3 - (k4 + k2) y4\n"
                   "  y5' = -(k5 + k1) y5 + k2 (y6 + y7)\n"
                   "  y6' = -k7 y6 y8 + k8 y4 + k1 y5 - k2 y6 + k8 y7\n"
                   "  y7' =  k7 y6 y8 - (k2 + k8 + k9) y7\n"
                   "  y8' = -k7 y6 y8 + (k2 + k8 + k9) y7\n"
                   "Rate constants and the interval [0, 321.8122] of the Test Set for IVP\n"
                   "Solvers (Bari). Default run: rodas4 with a sample at every accepted step.",
    .n_states = 8,
    .states = states,
    .y0 = y0,
    .n_params = 10,
    .params = params,
    .par_size = sizeof(dyn_hires_par),
    .n_outputs = 1,
    .outputs = outputs,
    .rhs = dyn_hires_rhs,
    .compute_outputs = hires_outputs,
    .prepare = NULL,
    .warn = hires_warn,
    .t0 = 0.0,
    .t1 = 321.8122,
    .step = 0.01, /* fixed-step methods (RK4 is stable at this step) */
    .method = "rodas4",
    .jacobian = dyn_hires_jac,
    .samples = DYN_SAMPLES_STEPS, /* rodas4: 44 steps over the span */
    .rtol = 1e-6, /* every method, cvode too: concentrations down to 1e-5 */
    .atol = 1e-10,
};
