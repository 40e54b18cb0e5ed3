/* SPDX-License-Identifier: BSD-3-Clause */
/* principal_angle.c — principal (Euler) angle and axis of the rotation between two
 * orientations: the rotation R1 R2^T that maps B2 coordinates to B1 coordinates (by Euler's
 * theorem a single rotation about a fixed axis). Never acos((tr - 1)/2), which loses half
 * the digits near 0 and pi (Markley & Crassidis, 2014, ch. 2):
 * - matrices: Shepperd's quaternion (w, v) of R1 R2^T, angle 2 atan2(|v|, |w|);
 * - unit quaternions: twice their angle on the unit 3-sphere, 4 atan2(|q1 - q2|, |q1 + q2|)
 *   after choosing the sign of q2 with q1 . q2 >= 0 (Kahan's angle between vectors), exactly
 *   0 for equal inputs whatever the compiler does with fused multiply-adds; the axis is that
 *   of q2* (x) q1, since R(q2* (x) q1) = R(q1) R(q2)^T.
 * Both are accurate to rounding near 0 and near pi. */
#include "dynkit/mech.h"

#include <math.h>

double dyn_principal_angle(const double R1[9], const double R2[9], double axis[3])
{
    double C[9], q[4];
    dyn_mat3_mul_bt(R1, R2, C);
    dyn_mat_to_quat(C, q);
    return dyn_quat_to_axis_angle(q, axis);
}

double dyn_principal_angle_quat(const double q1[4], const double q2[4], double axis[3])
{
    double a[4], b[4], d[4], p[4];
    dyn_quat_normalize(q1, a);
    dyn_quat_normalize(q2, b);
    double s = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] < 0.0 ? -1.0 : 1.0;
    for (int i = 0; i < 4; i++) {
        d[i] = a[i] - s * b[i];
        p[i] = a[i] + s * b[i];
    }
    double dn = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + d[3] * d[3]);
    double pn = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
    double angle = 4.0 * atan2(dn, pn); /* dn <= pn, so angle <= pi */
    if (axis) {
        if (angle > 0.0) {
            double c2[4], q[4];
            dyn_quat_conj(b, c2);
            dyn_quat_mul(c2, a, q);
            dyn_quat_to_axis_angle(q, axis);
        } else {
            axis[0] = 1.0;
            axis[1] = axis[2] = 0.0;
        }
    }
    return angle;
}

double dyn_principal_angle_euler(const double e1[3], const double e2[3], double axis[3])
{
    double q1[4], q2[4];
    dyn_euler_to_quat(e1, q1);
    dyn_euler_to_quat(e2, q2);
    return dyn_principal_angle_quat(q1, q2, axis);
}
