/* SPDX-License-Identifier: BSD-3-Clause */
/* Example: the homework's van der Pol run with RK4 through the C API. */
#include <stdio.h>

#include <dynkit/dynkit.h>

int main(void)
{
    dyn_vanderpol_par par = {.mu = 1.0};
    const double y0[2] = {2.0, 0.0};
    double y[2], work[16];
    const dyn_tableau *rk4 = dyn_method_find("rk4");
    dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
    dyn_result res;
    if (dyn_fixed_solve(rk4, &sys, 0.0, 15.0, 0.01, y0, y, work, NULL, &res) != DYN_OK) {
        fprintf(stderr, "solve failed: %s\n", res.message);
        return 1;
    }
    printf("y(15) = (%.15g, %.15g) after %ld steps, %ld rhs calls\n", y[0], y[1],
           res.stats.steps, res.stats.rhs_calls);
    return 0;
}
