/* SPDX-License-Identifier: BSD-3-Clause */
/* quat.c — quaternion algebra on double[4] = (w, x, y, z), scalar first: Hamilton product,
 * conjugate, normalisation, rotating vectors, axis-angle form and the kinematic equation
 * dq/dt = 1/2 q (x) (0, omega_B) for body rates (Markley & Crassidis, "Fundamentals of
 * Spacecraft Attitude Determination and Control", 2014, ch. 2-3, read with the Hamilton
 * product; Sola, "Quaternion kinematics for the error-state Kalman filter", 2017).
 * Meaning of q (see dynkit/mech.h): the rotation carrying the N axes onto the B axes, so
 * q (x) v (x) q* maps B coordinates to N and q* (x) v (x) q maps N coordinates to B.
 */
#include "dynkit/mech.h"

#include <math.h>

void dyn_quat_mul(const double p[4], const double q[4], double out[4])
{
    double w = p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3];
    double x = p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2];
    double y = p[0] * q[2] + p[2] * q[0] + p[3] * q[1] - p[1] * q[3];
    double z = p[0] * q[3] + p[3] * q[0] + p[1] * q[2] - p[2] * q[1];
    out[0] = w;
    out[1] = x;
    out[2] = y;
    out[3] = z;
}

void dyn_quat_conj(const double q[4], double out[4])
{
    out[0] = q[0];
    out[1] = -q[1];
    out[2] = -q[2];
    out[3] = -q[3];
}

double dyn_quat_normalize(const double q[4], double out[4])
{
    double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (n > 0.0 && isfinite(n)) {
        double s = 1.0 / n;
        out[0] = q[0] * s;
        out[1] = q[1] * s;
        out[2] = q[2] * s;
        out[3] = q[3] * s;
    } else {
        out[0] = 1.0;
        out[1] = out[2] = out[3] = 0.0;
    }
    return n;
}

/* v' = v + 2 w (u x v) + 2 u x (u x v) with u = sign * (x, y, z): the expanded
 * q (x) (0, v) (x) q* (sign = +1) or q* (x) (0, v) (x) q (sign = -1) for unit q. */
static void rotate(const double q[4], double sign, const double v[3], double out[3])
{
    double u[3] = {sign * q[1], sign * q[2], sign * q[3]};
    double t[3], t2[3];
    dyn_vec3_cross(u, v, t);
    dyn_vec3_scale(t, 2.0, t);
    dyn_vec3_cross(u, t, t2);
    out[0] = v[0] + q[0] * t[0] + t2[0];
    out[1] = v[1] + q[0] * t[1] + t2[1];
    out[2] = v[2] + q[0] * t[2] + t2[2];
}

void dyn_quat_rotate(const double q[4], const double v[3], double out[3])
{
    rotate(q, 1.0, v, out);
}

void dyn_quat_rotate_inv(const double q[4], const double v[3], double out[3])
{
    rotate(q, -1.0, v, out);
}

void dyn_quat_from_axis_angle(const double axis[3], double angle, double q[4])
{
    double n[3];
    double len = dyn_vec3_normalize(axis, n);
    if (!(len > 0.0 && isfinite(len))) {
        q[0] = 1.0;
        q[1] = q[2] = q[3] = 0.0;
        return;
    }
    double s = sin(0.5 * angle);
    q[0] = cos(0.5 * angle);
    q[1] = s * n[0];
    q[2] = s * n[1];
    q[3] = s * n[2];
}

double dyn_quat_to_axis_angle(const double q[4], double axis[3])
{
    double v[3] = {q[1], q[2], q[3]};
    double vn = dyn_vec3_norm(v);
    double angle = 2.0 * atan2(vn, fabs(q[0]));
    if (axis) {
        if (vn > 0.0) {
            double s = (q[0] < 0.0 ? -1.0 : 1.0) / vn;
            axis[0] = v[0] * s;
            axis[1] = v[1] * s;
            axis[2] = v[2] * s;
        } else {
            axis[0] = 1.0;
            axis[1] = axis[2] = 0.0;
        }
    }
    return angle;
}

void dyn_quat_derivative(const double q[4], const double omega_B[3], double dq[4])
{
    double wx = omega_B[0], wy = omega_B[1], wz = omega_B[2];
    double d0 = -0.5 * (q[1] * wx + q[2] * wy + q[3] * wz);
    double d1 = 0.5 * (q[0] * wx + q[2] * wz - q[3] * wy);
    double d2 = 0.5 * (q[0] * wy + q[3] * wx - q[1] * wz);
    double d3 = 0.5 * (q[0] * wz + q[1] * wy - q[2] * wx);
    dq[0] = d0;
    dq[1] = d1;
    dq[2] = d2;
    dq[3] = d3;
}
