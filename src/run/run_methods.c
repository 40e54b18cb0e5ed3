/* SPDX-License-Identifier: BSD-3-Clause */
/* The methods of dyn_run (dynkit/run.h): the library's registry of Butcher tables and
 * Rosenbrock methods (dyn_method_find), and descriptors for the solver families that are not
 * tables: rkmil and sriw1 (dyn_sde_solve), volterra (dyn_volterra_solve) and cvode (the
 * optional SUNDIALS backend). A descriptor has no coefficients; its kind only makes
 * dyn_method_is_adaptive and dyn_method_is_stiff answer for it as for the method it runs. */
#include <string.h>

#include "dynkit/run.h"

static const dyn_tableau rkmil_method = {
    .name = "rkmil",
    .title = "Runge-Kutta Milstein for models with noise: strong order 1, adaptive steps by "
             "step doubling on one Brownian path",
    .reference = "Kloeden and Platen, Numerical Solution of SDEs (1992), eq. 11.1.5; "
                 "dynkit/sde.h",
    .kind = DYN_KIND_EMBEDDED_RK,
    .order = 1,
};

static const dyn_tableau sriw1_method = {
    .name = "sriw1",
    .title = "Roessler's SRIW1 for models with noise: strong order 1.5, weak order 2, adaptive "
             "steps by its embedded estimate on one Brownian path",
    .reference = "Roessler, SIAM J. Numer. Anal. 48 (2010) 922-952; Rackauckas and Nie (2017); "
                 "dynkit/sde.h",
    .kind = DYN_KIND_EMBEDDED_RK,
    .order = 1,
};

/* kind explicit RK: it counts as a fixed-step method on the grid of the step */
static const dyn_tableau volterra_method = {
    .name = "volterra",
    .title = "XPPAUT's method for Volterra integrals: product trapezoid rule on the grid, "
             "implicit, Newton's method at each step",
    .reference = "Linz, Analytical and Numerical Methods for Volterra Equations (1985), "
                 "ch. 7-8; dynkit/volterra.h",
    .kind = DYN_KIND_EXPLICIT_RK,
    .order = 2,
};

/* kind stiff: adaptive and stiff */
static const dyn_tableau cvode_method = {
    .name = "cvode",
    .title = "SUNDIALS CVODE: BDF, variable order 1-5 and step, Newton iteration with a dense "
             "LU (optional backend)",
    .reference = "Hindmarsh et al., ACM TOMS 31 (2005) 363-396; CVODE user guide",
    .kind = DYN_KIND_ROSENBROCK,
    .order = 5,
};

const dyn_tableau *dyn_run_method_rkmil(void) { return &rkmil_method; }
const dyn_tableau *dyn_run_method_sriw1(void) { return &sriw1_method; }
const dyn_tableau *dyn_run_method_volterra(void) { return &volterra_method; }
const dyn_tableau *dyn_run_method_cvode(void) { return &cvode_method; }

const dyn_tableau *dyn_run_method_find(const char *name)
{
    const dyn_tableau *m = dyn_method_find(name);
    if (m || !name)
        return m;
    static const dyn_tableau *const others[] = {&rkmil_method, &sriw1_method,
                                                &volterra_method, &cvode_method};
    for (size_t i = 0; i < sizeof others / sizeof others[0]; i++)
        if (strcmp(name, others[i]->name) == 0)
            return others[i];
    return NULL;
}

int dyn_run_sde_method(const dyn_tableau *m)
{
    return m == &rkmil_method          ? DYN_SDE_RKMIL
           : m == &sriw1_method        ? DYN_SDE_SRIW1
           : m && dyn_method_is_map(m) ? DYN_SDE_MAP
                                       : DYN_SDE_EM;
}

int dyn_run_resets(const dyn_model *m)
{
    int count = 0;
    for (int i = 0; i < m->n_events; i++)
        count += m->events[i].reset != NULL;
    return count;
}
