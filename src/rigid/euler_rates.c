/* SPDX-License-Identifier: BSD-3-Clause */
/* euler_rates.c — kinematics of type I Euler angles: their rates from body rates
 * (Greenwood, "Advanced Dynamics", eq. (3.16), exactly as written in the homework's plane
 * model), the inverse map omega_B = R_phi R_theta (0, 0, dpsi) + R_phi (0, dtheta, 0) +
 * (dphi, 0, 0), and the distance of theta to the gimbal-lock values pi/2 + k pi where
 * sec(theta) is unbounded.
 */
#include "dynkit/mech.h"

#include <math.h>

int dyn_euler_rates(const double e[3], const double omega_B[3], double de[3])
{
    double theta = e[1], phi = e[2];
    double wx = omega_B[0], wy = omega_B[1], wz = omega_B[2];
    double cth = cos(theta);
    double sph = sin(phi), cph = cos(phi);
    double dpsi = (1.0 / cth) * (wy * sph + wz * cph); /* sec(theta)*(...) as in (3.16) */
    double dtheta = wy * cph - wz * sph;
    double dphi = wx + dpsi * sin(theta);
    de[0] = dpsi;
    de[1] = dtheta;
    de[2] = dphi;
    return fabs(cth) <= DYN_EULER_RATES_COS_MIN ? 1 : 0;
}

void dyn_euler_body_rates(const double e[3], const double de[3], double omega_B[3])
{
    double theta = e[1], phi = e[2];
    double dpsi = de[0], dtheta = de[1], dphi = de[2];
    double sth = sin(theta), cth = cos(theta);
    double sph = sin(phi), cph = cos(phi);
    double wx = dphi - dpsi * sth;
    double wy = dtheta * cph + dpsi * cth * sph;
    double wz = dpsi * cth * cph - dtheta * sph;
    omega_B[0] = wx;
    omega_B[1] = wy;
    omega_B[2] = wz;
}

double dyn_euler_singularity_distance(double theta)
{
    /* theta = pi/2 + k pi - d has |cos(theta)| = sin(|d|) for |d| <= pi/2. */
    double c = fabs(cos(theta));
    return asin(c < 1.0 ? c : 1.0);
}
