/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/mech.h — mechanics: 3-vectors, 3x3 matrices, rotations, Euler angles, quaternions,
 * principal angle, Newton–Euler for a rigid body.
 *
 * Conventions (Greenwood, "Advanced Dynamics", ch. 3; the homework's plane model):
 * - Vectors are double[3]; 3x3 matrices are double[9], row-major: M[3*i + j] is row i, col j.
 * - A rotation matrix R maps N-frame (space-fixed) coordinates to B-frame (body) coordinates:
 *   v_B = R v_N. Its rows are the B axes written in N coordinates.
 * - Type I Euler angles e = (psi, theta, phi): psi about Z, theta about the new Y', phi about
 *   the new x, and R = R_phi * R_theta * R_psi with
 *   R_psi = [c s 0; -s c 0; 0 0 1], R_theta = [c 0 -s; 0 1 0; s 0 c],
 *   R_phi = [1 0 0; 0 c s; 0 -s c].
 * - Quaternions are double[4] = (w, x, y, z), scalar first, Hamilton product. A unit q is the
 *   rotation that carries the N axes onto the B axes: b_i = q (x) n_i (x) q* in N coordinates.
 *   Coordinates then transform as v_B = q* (x) v_N (x) q, so the matrix of q is the same
 *   N->B matrix as above: R(q) = (w^2 - |v|^2) I + 2 v v^T - 2 w [v x], and
 *   q(psi, theta, phi) = q_Z(psi) (x) q_Y(theta) (x) q_X(phi) gives R(q) = R_phi R_theta R_psi.
 *   q and -q are the same rotation.
 * - Body rates omega_B are the angular velocity of B relative to N, in B coordinates.
 *
 * Every function is pure: inputs are const, outputs are caller-owned arrays, and an output
 * may be the same array as an input of the same shape (aliasing is allowed). Nothing here
 * allocates, prints or keeps state. Functions that can fail return an int status: 0 on
 * success, non-zero as documented at the declaration.
 */
#ifndef DYNKIT_MECH_H
#define DYNKIT_MECH_H

#ifdef __cplusplus
extern "C" {
#endif

#ifndef DYN_PI
#define DYN_PI 3.14159265358979323846 /* pi (strict C11 has no M_PI) */
#endif

/* |cos(theta)| at or below which dyn_euler_rates reports the Euler-angle rates singular. */
#define DYN_EULER_RATES_COS_MIN 1e-12

/* ---- 3-vectors (double[3]) ---- */

/* out = a + b. */
void dyn_vec3_add(const double a[3], const double b[3], double out[3]);
/* out = a - b. */
void dyn_vec3_sub(const double a[3], const double b[3], double out[3]);
/* out = s * a. */
void dyn_vec3_scale(const double a[3], double s, double out[3]);
/* Dot product a . b. */
double dyn_vec3_dot(const double a[3], const double b[3]);
/* out = a x b (right-handed); out may alias a or b. */
void dyn_vec3_cross(const double a[3], const double b[3], double out[3]);
/* Euclidean norm |a|. */
double dyn_vec3_norm(const double a[3]);
/* out = a / |a|; returns |a|. When |a| == 0 (or is not finite) out is set to (0, 0, 0). */
double dyn_vec3_normalize(const double a[3], double out[3]);
/* Distance |a - b| between the points a and b. */
double dyn_vec3_distance(const double a[3], const double b[3]);

/* ---- 3x3 matrices (double[9], row-major) ---- */

/* out = A B; out may alias A or B. */
void dyn_mat3_mul(const double A[9], const double B[9], double out[9]);
/* out = A B^T; out may alias A or B. */
void dyn_mat3_mul_bt(const double A[9], const double B[9], double out[9]);
/* out = A^T; out may alias A. */
void dyn_mat3_transpose(const double A[9], double out[9]);
/* out = A v (e.g. v_B = R v_N); out may alias v. */
void dyn_mat3_mul_vec(const double A[9], const double v[3], double out[3]);
/* out = A^T v (e.g. v_N = R^T v_B); out may alias v. */
void dyn_mat3_tmul_vec(const double A[9], const double v[3], double out[3]);
/* out = I. */
void dyn_mat3_identity(double out[9]);
/* Determinant of A (+1 for a proper rotation). */
double dyn_mat3_det(const double A[9]);
/* Orthonormality error max_ij |(R R^T - I)_ij|; 0 for an exact rotation or reflection. */
double dyn_mat3_orthonormality_error(const double R[9]);

/* ---- elementary rotations (N->B convention: the frame turned by the angle) ---- */

/* R_psi: frame turned by psi about Z: [c s 0; -s c 0; 0 0 1]. */
void dyn_rot_z(double psi, double R[9]);
/* R_theta: frame turned by theta about Y: [c 0 -s; 0 1 0; s 0 c]. */
void dyn_rot_y(double theta, double R[9]);
/* R_phi: frame turned by phi about X: [1 0 0; 0 c s; 0 -s c]. */
void dyn_rot_x(double phi, double R[9]);

/* ---- type I Euler angles e = (psi, theta, phi) ---- */

/* R = (R_phi R_theta) R_psi, the N->B matrix of the Euler angles (the seed's R_total). */
void dyn_euler_to_mat(const double e[3], double R[9]);
/* Euler angles of the rotation R: theta in [-pi/2, pi/2], psi and phi in (-pi, pi].
 * Robust at every theta: R rebuilt from e matches R to rounding. When |theta| = pi/2 to
 * working precision (cos(theta) <= 4 DBL_EPSILON) only phi - psi (theta = pi/2) or
 * phi + psi (theta = -pi/2) is defined: phi is set to 0 and the whole rotation about the
 * vertical goes into psi; returns 1 then, else 0. R should be a rotation (not checked). */
int dyn_mat_to_euler(const double R[9], double e[3]);
/* Unit quaternion q_Z(psi) (x) q_Y(theta) (x) q_X(phi) with R(q) = dyn_euler_to_mat(e);
 * continuous in e, so w may be negative. */
void dyn_euler_to_quat(const double e[3], double q[4]);
/* Euler angles of the rotation of q (need not be unit), as dyn_mat_to_euler: returns 1 at
 * |theta| = pi/2 (phi set to 0), 0 otherwise, or -1 when |q| is 0 or not finite (e = NaN). */
int dyn_quat_to_euler(const double q[4], double e[3]);

/* ---- Euler-angle kinematics (Greenwood (3.16)) ---- */

/* Euler-angle rates de = (dpsi, dtheta, dphi) from body rates omega_B:
 * dpsi = sec(theta) (wy sin(phi) + wz cos(phi)), dtheta = wy cos(phi) - wz sin(phi),
 * dphi = wx + dpsi sin(theta). Returns 0, or 1 when |cos(theta)| <= DYN_EULER_RATES_COS_MIN
 * (singular): de is still written, dtheta is exact, dpsi and dphi are huge or not finite. */
int dyn_euler_rates(const double e[3], const double omega_B[3], double de[3]);
/* Body rates omega_B from Euler angles e and their rates de (the inverse of
 * dyn_euler_rates; defined at every theta): wx = dphi - dpsi sin(theta),
 * wy = dtheta cos(phi) + dpsi cos(theta) sin(phi),
 * wz = dpsi cos(theta) cos(phi) - dtheta sin(phi). */
void dyn_euler_body_rates(const double e[3], const double de[3], double omega_B[3]);
/* Distance in radians (in [0, pi/2]) from theta to the nearest singular value pi/2 + k pi,
 * for warnings when a model nears gimbal lock. */
double dyn_euler_singularity_distance(double theta);

/* ---- quaternions (double[4] = (w, x, y, z)) ---- */

/* out = p (x) q (Hamilton); R(p (x) q) = R(q) R(p): first p, then q about the turned axes.
 * out may alias p or q. */
void dyn_quat_mul(const double p[4], const double q[4], double out[4]);
/* out = q* = (w, -x, -y, -z), the inverse rotation of a unit q. */
void dyn_quat_conj(const double q[4], double out[4]);
/* out = q / |q|; returns |q|. When |q| == 0 (or is not finite) out = (1, 0, 0, 0). */
double dyn_quat_normalize(const double q[4], double out[4]);
/* out = q (x) v (x) q* for unit q: turns v actively; maps B coordinates to N (= R(q)^T v). */
void dyn_quat_rotate(const double q[4], const double v[3], double out[3]);
/* out = q* (x) v (x) q for unit q: maps N coordinates to B (= R(q) v). */
void dyn_quat_rotate_inv(const double q[4], const double v[3], double out[3]);
/* N->B matrix R(q) of the rotation of q; q need not be unit (divided by |q|^2).
 * Returns 0, or 1 when |q| is 0 or not finite (R is then filled with NaN). */
int dyn_quat_to_mat(const double q[4], double R[9]);
/* Unit quaternion of the rotation matrix R (Shepperd's method: the best-conditioned of the
 * four component formulas), with w >= 0. R should be a rotation (the result is normalised). */
void dyn_mat_to_quat(const double R[9], double q[4]);
/* Unit quaternion of the rotation by angle (radians, right-handed) about axis (need not be
 * unit). A zero or non-finite axis gives the identity (1, 0, 0, 0). */
void dyn_quat_from_axis_angle(const double axis[3], double angle, double q[4]);
/* Rotation angle in [0, pi] of q, 2 atan2(|v|, |w|) (accurate near 0 and pi; q need not be
 * unit), and its unit axis (sign chosen so the angle is in [0, pi]) into axis (may be NULL);
 * axis = (1, 0, 0) when the angle is 0. */
double dyn_quat_to_axis_angle(const double q[4], double axis[3]);
/* Quaternion kinematics dq = 1/2 q (x) (0, omega_B) for body rates omega_B (in B).
 * Keeps |q| constant to first order; the caller renormalises when integrating. */
void dyn_quat_derivative(const double q[4], const double omega_B[3], double dq[4]);

/* ---- principal angle between two orientations ---- */

/* Principal angle in [0, pi] of the rotation R1 R2^T (the matrix mapping B2 coordinates to
 * B1 coordinates: it turns the B2 axes onto the B1 axes), computed through Shepperd's
 * quaternion and 2 atan2(|v|, |w|), never acos of the trace: accurate near 0 and pi,
 * exactly 0 for R1 == R2. axis (may be NULL) receives the unit axis of that rotation
 * (the same in B1 and B2 coordinates); (1, 0, 0) when the angle is 0. */
double dyn_principal_angle(const double R1[9], const double R2[9], double axis[3]);
/* As dyn_principal_angle for the orientations of two type I Euler-angle triples, computed
 * with their quaternions by dyn_principal_angle_quat. */
double dyn_principal_angle_euler(const double e1[3], const double e2[3], double axis[3]);
/* As dyn_principal_angle for two quaternions (need not be unit; a zero one counts as the
 * identity): angle 4 atan2(|q1 - q2|, |q1 + q2|) with q2's sign making q1 . q2 >= 0, exactly 0
 * for q1 == +-q2; axis from q2* (x) q1, the rotation R(q1) R(q2)^T. */
double dyn_principal_angle_quat(const double q1[4], const double q2[4], double axis[3]);

/* ---- Newton–Euler for a rigid body with diagonal inertia about its centre of mass ---- */

/* Linear acceleration a = F / m (F and a in the same frame). Returns 0, or 1 when m is not
 * positive and finite (a is then filled with NaN). */
int dyn_rigid_linear_accel(double m, const double F[3], double a[3]);
/* Euler's equations in B with inertia = (Ixx, Iyy, Izz):
 * Ixx dwx = Mx + (Iyy - Izz) wy wz, Iyy dwy = My + (Izz - Ixx) wz wx,
 * Izz dwz = Mz + (Ixx - Iyy) wx wy. omega_B, moment_B (about the centre of mass) and
 * domega_B in B. Returns 0, or 1 when an inertia is not positive and finite (NaN written). */
int dyn_rigid_euler_accel(const double inertia[3], const double omega_B[3],
                          const double moment_B[3], double domega_B[3]);
/* Angular momentum about the centre of mass in B: L_B = diag(inertia) omega_B. */
void dyn_rigid_angular_momentum(const double inertia[3], const double omega_B[3],
                                double L_B[3]);
/* Rotational kinetic energy 1/2 (Ixx wx^2 + Iyy wy^2 + Izz wz^2). */
double dyn_rigid_rotational_energy(const double inertia[3], const double omega_B[3]);
/* Translational kinetic energy 1/2 m |v|^2 of the centre of mass. */
double dyn_rigid_translational_energy(double m, const double v[3]);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_MECH_H */
