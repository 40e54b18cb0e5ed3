/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/models.h — the built-in models of the homework, usable directly from C.
 *
 * Each model is a dyn_model (see model.h) plus its parameter struct, so a program can
 * call the right-hand side itself or hand the model to the generic tools.
 */
#ifndef DYNKIT_MODELS_H
#define DYNKIT_MODELS_H

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- pendulum (problem 1): point mass m on a massless rod of length l ----
 * states phi [rad] (0 at the bottom), dphi [rad/s]; ddphi = -(g/l) sin(phi). */
typedef struct dyn_pendulum_par {
    double m; /* [kg] mass */
    double l; /* [m] rod length */
    double g; /* [m/s^2] gravity */
} dyn_pendulum_par;
extern const dyn_model dyn_model_pendulum;
int dyn_pendulum_rhs(double t, const double *y, double *dydt, void *par);
/* Total energy [J] (zero at rest at the bottom) of state y = (phi, dphi). */
double dyn_pendulum_energy(const dyn_pendulum_par *p, const double *y);
/* Highest point [m] above the bottom reached from state y (problem 1a), from energy
 * conservation: E / (m g), or 2 l when the energy carries the mass over the top. */
double dyn_pendulum_max_height(const dyn_pendulum_par *p, const double *y);
/* Small-angle solution phi(t) [rad] (problem 1c): sin(phi) ~ phi gives harmonic motion
 * phi0 cos(w t) + dphi0/w sin(w t) with w = sqrt(g/l); y0 = (phi0, dphi0) at t = 0. */
double dyn_pendulum_small_angle(const dyn_pendulum_par *p, const double *y0, double t);

/* ---- van der Pol oscillator (problem 2): y1' = y2, y2' = mu (1 - y1^2) y2 - y1 ---- */
typedef struct dyn_vanderpol_par {
    double mu; /* [1] damping parameter */
} dyn_vanderpol_par;
extern const dyn_model dyn_model_vanderpol;
int dyn_vanderpol_rhs(double t, const double *y, double *dydt, void *par);
/* Jacobian [[0, 1], [-2 mu y1 y2 - 1, mu (1 - y1^2)]] (row-major 2 x 2). */
int dyn_vanderpol_jac(double t, const double *y, double *J, void *par);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_MODELS_H */
