/* SPDX-License-Identifier: BSD-3-Clause */
/* euler_angles.c — type I Euler angles (psi about Z, theta about Y', phi about x; Greenwood,
 * "Advanced Dynamics", ch. 3) to and from rotation matrices and quaternions.
 *
 * Forward: R = (R_phi R_theta) R_psi, evaluated in the same order as the homework's
 * R_total = R_phi*R_theta*R_psi. Expanded, with c. = cos, s. = sin:
 *   R = [ cth cps,                   cth sps,                   -sth    ;
 *         sph sth cps - cph sps,     sph sth sps + cph cps,     sph cth ;
 *         cph sth cps + sph sps,     cph sth sps - sph cps,     cph cth ].
 * Inverse: theta = atan2(-R13, cos(theta)) with cos(theta) from the two pairs
 * hypot(R11, R12) and hypot(R23, R33) (accurate at every theta, never asin), phi =
 * atan2(R23, R33), and psi from a combination that stays well conditioned at gimbal lock:
 *   R21 - R32 = (1 + sth) sin(phi - psi),  R22 + R31 = (1 + sth) cos(phi - psi),
 *   R21 + R32 = -(1 - sth) sin(phi + psi), R22 - R31 = (1 - sth) cos(phi + psi),
 * using the first pair when sin(theta) >= 0 and the second otherwise (the factor is >= 1).
 * Near theta = +-pi/2 phi alone is ill-conditioned (R23, R33 are O(cos theta)), but the
 * rebuilt R stays accurate because phi -+ psi is exact. At the singularity itself phi = 0.
 * Quaternion: q = q_Z(psi) (x) q_Y(theta) (x) q_X(phi) (the standard Z-Y-X aerospace
 * sequence, e.g. Diebel, "Representing Attitude", 2006), with our N->B reading of R(q).
 */
#include "dynkit/mech.h"

#include <float.h>
#include <math.h>

void dyn_euler_to_mat(const double e[3], double R[9])
{
    double Rpsi[9], Rtheta[9], Rphi[9], P[9];
    dyn_rot_z(e[0], Rpsi);
    dyn_rot_y(e[1], Rtheta);
    dyn_rot_x(e[2], Rphi);
    dyn_mat3_mul(Rphi, Rtheta, P);
    dyn_mat3_mul(P, Rpsi, R);
}

/* Wrap an angle known to lie in (-3 pi, 3 pi) into (-pi, pi]. */
static double wrap_pi(double a)
{
    if (a > DYN_PI) {
        a -= 2.0 * DYN_PI;
    } else if (a <= -DYN_PI) {
        a += 2.0 * DYN_PI;
    }
    return a;
}

int dyn_mat_to_euler(const double R[9], double e[3])
{
    double cth = 0.5 * (hypot(R[0], R[1]) + hypot(R[5], R[8]));
    double theta = atan2(-R[2], cth);
    int singular = !(cth > 4.0 * DBL_EPSILON);
    double phi = singular ? 0.0 : atan2(R[5], R[8]);
    double psi;
    if (-R[2] >= 0.0) { /* sin(theta) >= 0: phi - psi is well defined */
        double d = atan2(R[3] - R[7], R[4] + R[6]);
        psi = wrap_pi(phi - d);
    } else { /* sin(theta) < 0: phi + psi is well defined */
        double s = atan2(-(R[3] + R[7]), R[4] - R[6]);
        psi = wrap_pi(s - phi);
    }
    e[0] = psi;
    e[1] = theta;
    e[2] = phi;
    return singular;
}

void dyn_euler_to_quat(const double e[3], double q[4])
{
    double cps = cos(0.5 * e[0]), sps = sin(0.5 * e[0]);
    double cth = cos(0.5 * e[1]), sth = sin(0.5 * e[1]);
    double cph = cos(0.5 * e[2]), sph = sin(0.5 * e[2]);
    q[0] = cps * cth * cph + sps * sth * sph;
    q[1] = cps * cth * sph - sps * sth * cph;
    q[2] = cps * sth * cph + sps * cth * sph;
    q[3] = sps * cth * cph - cps * sth * sph;
}

int dyn_quat_to_euler(const double q[4], double e[3])
{
    double R[9];
    if (dyn_quat_to_mat(q, R) != 0) {
        e[0] = e[1] = e[2] = NAN;
        return -1;
    }
    return dyn_mat_to_euler(R, e);
}
