/* SPDX-License-Identifier: BSD-3-Clause */
/* map_steps.h — the steps of a discrete map for dyn_fixed_solve (private; map_steps.c). */
#ifndef DYNKIT_SRC_ODE_MAP_STEPS_H
#define DYNKIT_SRC_ODE_MAP_STEPS_H

#include "dynkit/ode.h"

/* Iterate y_{k+1} = f(t_k, y_k) over the whole steps of grid g (no partial step), y holding
 * y_0 (finite, sample 0 already output) and spare n more doubles; res has been initialised
 * by dyn_fixed_solve (samples counts sample 0). Returns res->status. */
int dyn_map_steps(const dyn_tableau *m, const dyn_system *sys, const dyn_grid *g, double *y,
                  double *spare, const dyn_fixed_opts *o, dyn_result *res);

#endif /* DYNKIT_SRC_ODE_MAP_STEPS_H */
