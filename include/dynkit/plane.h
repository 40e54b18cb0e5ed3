/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/plane.h — the model plane on a spring (homework problem 3), in two formulations.
 *
 * A rigid plane (mass m, principal inertia Ixx, Iyy, Izz about its centre of mass S) hangs
 * from the ceiling point A (the origin of the space-fixed frame N, Z pointing down, gravity
 * g along +Z) by a linear spring (stiffness k, rest length l0) attached at the body point P,
 * rp_B = (px, py, pz) in the body frame B. Newton's equation in N, Euler's equations in B.
 *
 * - dyn_model_plane ("plane"), 12 states
 *     sX, sY, sZ, psi, theta, phi, dsX, dsY, dsZ, omegax, omegay, omegaz
 *   (m, rad, m/s, rad/s): the homework's plane_equationsofmotion with type I Euler angles
 *   and their rates from Greenwood (3.16), singular at theta = +-pi/2.
 * - dyn_model_plane_quat ("plane-quat"), 13 states
 *     sX, sY, sZ, qw, qx, qy, qz, dsX, dsY, dsZ, omegax, omegay, omegaz:
 *   the same plane with a quaternion q for the orientation (see dynkit/mech.h: R(q) is the
 *   N->B matrix, equal to the Euler-angle R for q = dyn_euler_to_quat(psi, theta, phi)),
 *   dq/dt = 1/2 q (x) (0, omega_B); no singularity.
 *
 * Both share dyn_plane_par. Conventions are those of dynkit/mech.h.
 */
#ifndef DYNKIT_PLANE_H
#define DYNKIT_PLANE_H

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parameters of both plane models; defaults are the homework's simulate_plane.m values. */
typedef struct dyn_plane_par {
    double g;            /* [m/s^2] gravity, along +Z (down): 9.81 */
    double l0;           /* [m] rest length of the spring: 1 */
    double k;            /* [N/m] spring stiffness: 20 */
    double px, py, pz;   /* [m] spring attachment P in B: (0.1, 0, -0.1) */
    double m;            /* [kg] mass: 1 */
    double Ixx, Iyy, Izz; /* [kg m^2] principal inertia about S: Ip/2, Ip/2, Ip; Ip = 1*.1^2 */
    /* geometry for animations only (the dynamics do not use it) */
    double length_plane; /* [m] fuselage length: 2 */
    double wingspan;     /* [m] wingspan: 4 */
    double height_fin;   /* [m] height of the fin: 0.5 */
    double wing_x, wing_y, wing_z; /* [m] r_wingcenter, S to wing centre in B: (0.1, 0, -0.01) */
} dyn_plane_par;

/* Non-zero return values of the plane right-hand sides. */
#define DYN_PLANE_ERR_SPRING 1 /* spring length |rp_N| is 0: the force direction is undefined */
#define DYN_PLANE_ERR_GIMBAL 2 /* plane: cos(theta) == 0 exactly (sec(theta) undefined) */
#define DYN_PLANE_ERR_QUAT 3   /* plane-quat: |q| is 0 or not finite */
#define DYN_PLANE_ERR_PARAM 4  /* m or an inertia not > 0 (prepare rejects such parameters) */

extern const dyn_model dyn_model_plane;
extern const dyn_model dyn_model_plane_quat;

/* Right-hand side of "plane" (12 states), par = dyn_plane_par. Returns 0, or
 * DYN_PLANE_ERR_SPRING when P is at A, DYN_PLANE_ERR_GIMBAL when cos(theta) is exactly 0
 * (never for a finite double theta: near +-pi/2 the rates are huge but finite; see the
 * model's warn and the theta_margin output), DYN_PLANE_ERR_PARAM for bad m or inertia. */
int dyn_plane_rhs(double t, const double *y, double *dydt, void *par);
/* Right-hand side of "plane-quat" (13 states), par = dyn_plane_par; q need not be unit
 * (R(q) divides by |q|^2). Returns 0, DYN_PLANE_ERR_SPRING, DYN_PLANE_ERR_QUAT or
 * DYN_PLANE_ERR_PARAM. */
int dyn_plane_quat_rhs(double t, const double *y, double *dydt, void *par);

/* Total energy [J] of a 12-state y: 1/2 m |ds|^2 + 1/2 omega.I omega + k/2 (|rp_N| - l0)^2
 * - m g sZ (zero potential at spring rest length and Z = 0); conserved by the dynamics. */
double dyn_plane_energy(const dyn_plane_par *p, const double *y);
/* The same energy [J] of a 13-state (plane-quat) y. */
double dyn_plane_quat_energy(const dyn_plane_par *p, const double *y);
/* Angular momentum [kg m^2/s] about the vertical axis through A of a 12-state y:
 * m (r_S x v_S)_Z + (R^T diag(I) omega_B)_Z; conserved (gravity is along Z, the spring
 * force passes through A). */
double dyn_plane_vertical_angular_momentum(const dyn_plane_par *p, const double *y);
/* Spring length |rp_N| [m] of a 12-state y. */
double dyn_plane_spring_length(const dyn_plane_par *p, const double *y);

/* Convert a 12-state y12 to the same physical 13-state y13 (q = dyn_euler_to_quat).
 * y12 and y13 must not overlap. */
void dyn_plane_state_to_quat(const double *y12, double *y13);
/* Convert a 13-state y13 to a 12-state y12 (Euler angles by dyn_quat_to_euler: theta in
 * [-pi/2, pi/2], psi and phi in (-pi, pi]). Must not overlap. Returns 0, 1 at theta =
 * +-pi/2 (phi set to 0), or -1 when |q| is 0 or not finite (angles NaN). */
int dyn_plane_quat_to_state(const double *y13, double *y12);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_PLANE_H */
