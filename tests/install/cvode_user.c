/* SPDX-License-Identifier: BSD-3-Clause */
/* A user's program on the installed CVODE backend: y' = -y from y(0) = 1 to t = 1. */
#include <math.h>
#include <stdio.h>

#include <dynkit/cvode.h>

static int decay(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)par;
    dydt[0] = -y[0];
    return 0;
}

int main(void)
{
    dyn_system sys = {decay, 1, NULL};
    const double y0 = 1.0, tout = 1.0;
    double y;
    dyn_result res;
    dyn_cvode_opts opts = {.rtol = 1e-8, .atol = 1e-10};
    if (dyn_cvode_solve(&sys, 0.0, &y0, &tout, 1, &opts, NULL, NULL, &y, &res) != DYN_OK ||
        fabs(y - exp(-1.0)) > 1e-6) {
        fprintf(stderr, "cvode: %s (y = %.17g)\n", res.message, y);
        return 1;
    }
    printf("CVODE %s: y(1) = %.10f in %ld steps\n", dyn_cvode_version(), y, res.stats.accepted);
    return 0;
}
