/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/brusselator.h — the 1-D Brusselator with diffusion, a model whose size is chosen
 * by its user: the stiff test problem BRUSS of Hairer & Wanner, "Solving ODEs II",
 * sec. IV.10 (method of lines on N interior points x_i = i/(N+1)):
 *   u_i' = A + u_i^2 v_i - (B + 1) u_i + alpha (N+1)^2 (u_{i-1} - 2 u_i + u_{i+1})
 *   v_i' = B u_i - u_i^2 v_i           + alpha (N+1)^2 (v_{i-1} - 2 v_i + v_{i+1})
 * A = 1, B = 3, alpha = 1/50, boundaries u_0 = u_{N+1} = 1, v_0 = v_{N+1} = 3,
 * u_i(0) = 1 + sin(2 pi x_i), v_i(0) = 3, t in [0, 10]. The states are interleaved
 * (u1, v1, u2, v2, ...), so the Jacobian is banded with lower = upper = 2; the model
 * declares that band and gives the band analytically (and the full matrix, for small N).
 *
 * A dyn_model has a fixed number of states, so the library builds one model per N
 * (dyn_brusselator_new) instead of registering a single one: the command line spells it
 * `brusselator` (N = DYN_BRUSSELATOR_DEFAULT_N) or `brusselator:N`.
 */
#ifndef DYNKIT_BRUSSELATOR_H
#define DYNKIT_BRUSSELATOR_H

#include <stddef.h>

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DYN_BRUSSELATOR_DEFAULT_N 500 /* HNW II's BRUSS: 1000 states */
#define DYN_BRUSSELATOR_MAX_N 1000000

/* Parameters. N is the size the model was built with (dyn_model_default_params sets it);
 * it must not be changed afterwards. */
typedef struct dyn_brusselator_par {
    double A, B;   /* [1] feed and conversion rates */
    double alpha;  /* [1] diffusion coefficient */
    double N;      /* interior grid points (an integer, the model's size / 2) */
} dyn_brusselator_par;

/* The model for N interior points (2N states), allocated; NULL with a message in err when
 * N is not in [1, DYN_BRUSSELATOR_MAX_N] or memory runs out. Free with
 * dyn_brusselator_free. */
dyn_model *dyn_brusselator_new(int N, char *err, size_t errlen);
void dyn_brusselator_free(dyn_model *m);
/* The model a name "brusselator:N" (or "brusselator", the default N) stands for, allocated
 * as by dyn_brusselator_new; NULL when name is not such a name or N is out of range. The
 * references and the verification problems name their model this way. */
dyn_model *dyn_brusselator_for_name(const char *name);

/* The right-hand side, the band of its Jacobian (DYN_BAND_AT storage, lower = upper = 2)
 * and the full Jacobian (2N x 2N, row-major). */
int dyn_brusselator_rhs(double t, const double *y, double *dydt, void *par);
int dyn_brusselator_jac_band(double t, const double *y, double *J, void *par);
int dyn_brusselator_jac(double t, const double *y, double *J, void *par);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_BRUSSELATOR_H */
