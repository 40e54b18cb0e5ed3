/* SPDX-License-Identifier: BSD-3-Clause */
/* Private to the library: the parts shared by the two plane models (plane.c, plane_quat.c):
 * the Newton–Euler accelerations for a given orientation matrix, the energy, the parameter
 * table and its checks, and the default initial state of simulate_plane.m.
 */
#ifndef DYNKIT_SRC_MODELS_PLANE_COMMON_H
#define DYNKIT_SRC_MODELS_PLANE_COMMON_H

#include <stddef.h>

#include "dynkit/plane.h"

/* The initial state of simulate_plane.m for the default parameters: sX = -px, sY = 0.2,
 * sZ = l0 + m g / k, level attitude, dsX = 2 m/s, omegaz = pi/4/10 rad/s. */
#define DYN_PLANE_SX0 (-0.1)
#define DYN_PLANE_SY0 0.2
#define DYN_PLANE_SZ0 (1.0 + 1.0 * 9.81 / 20.0)
#define DYN_PLANE_DSX0 2.0
#define DYN_PLANE_OMEGAZ0 (DYN_PI / 4.0 / 10.0)

/* simulate_plane.m's initial state for the parameters p, in the 12-state layout:
 * sX = -px, sY = 0.2, sZ = l0 + m g/k, level attitude, dsX = 2, omegaz = pi/40. */
void dyn_plane_seed_state(const void *par, double *y12);

/* Parameter table shared by both models (dyn_plane_par members). */
#define DYN_PLANE_N_PARAMS 16
extern const dyn_param dyn_plane_params[DYN_PLANE_N_PARAMS];
/* Check a dyn_plane_par: m, inertias and k > 0 ... (see plane_common.c). */
int dyn_plane_prepare(void *par, char *err, size_t errlen);

/* Position of the spring point P in N: rp_N = rs_N + R^T rp_B. */
void dyn_plane_spring_point(const dyn_plane_par *p, const double rs_N[3], const double R[9],
                            double rp_N[3]);
/* Newton–Euler for the plane at position rs_N, orientation R (N->B) and body rates omega_B:
 * dds_N = (Fspring_N + Fg_N) / m, domega_B from Euler's equations with the spring moment
 * rp_B x (R Fspring_N). Returns 0, DYN_PLANE_ERR_SPRING or DYN_PLANE_ERR_PARAM. */
int dyn_plane_accel(const dyn_plane_par *p, const double rs_N[3], const double R[9],
                    const double omega_B[3], double dds_N[3], double domega_B[3]);
/* Energy of the plane at rs_N, R, velocity v_N and body rates omega_B (see plane.h). */
double dyn_plane_energy_at(const dyn_plane_par *p, const double rs_N[3], const double R[9],
                           const double v_N[3], const double omega_B[3]);

#endif /* DYNKIT_SRC_MODELS_PLANE_COMMON_H */
