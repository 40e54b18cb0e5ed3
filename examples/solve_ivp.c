/* SPDX-License-Identifier: BSD-3-Clause */
/* Example: the Lorenz system solved with one call that returns the whole solution, like
 * SciPy's solve_ivp or MATLAB's ode45 (dynkit/ivp.h): samples at chosen times, the counters,
 * the dense output evaluated between them. */
#include <stdio.h>

#include <dynkit/dynkit.h>

typedef struct lorenz_par {
    double sigma, rho, beta;
} lorenz_par;

static int lorenz(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const lorenz_par *p = par;
    dydt[0] = p->sigma * (y[1] - y[0]);
    dydt[1] = y[0] * (p->rho - y[2]) - y[1];
    dydt[2] = y[0] * y[1] - p->beta * y[2];
    return 0;
}

int main(void)
{
    lorenz_par par = {10.0, 28.0, 8.0 / 3.0};
    const double y0[3] = {1.0, 1.0, 1.0};
    double times[9];
    for (int i = 0; i < 9; i++)
        times[i] = 0.25 * i;
    dyn_ivp_opts opts = {.method = "dop853", .rtol = 1e-10, .atol = 1e-12, .t_eval = times,
                         .n_eval = 9, .dense_output = 1};
    dyn_ivp_solution *sol = dyn_ivp_solve(lorenz, 3, &par, 0.0, 2.0, y0, &opts);
    if (!sol) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    if (sol->status != DYN_OK) {
        fprintf(stderr, "solve failed: %s\n", sol->message);
        dyn_ivp_free(sol);
        return 1;
    }
    printf("%6s %20s %20s %20s\n", "t", "x", "y", "z");
    for (long i = 0; i < sol->n_t; i++)
        printf("%6.2f %20.12f %20.12f %20.12f\n", sol->t[i], sol->y[3 * i], sol->y[3 * i + 1],
               sol->y[3 * i + 2]);
    double mid[3];
    dyn_ivp_eval(sol, 1.1, mid); /* anywhere in the span, from the kept dense output */
    printf("x(1.1) = %.12f from the dense output\n", mid[0]);
    printf("%ld steps (%ld rejected), %ld calls of f\n", sol->stats.accepted,
           sol->stats.rejected, sol->stats.rhs_calls);
    dyn_ivp_free(sol);
    return 0;
}
