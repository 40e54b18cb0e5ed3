/* SPDX-License-Identifier: BSD-3-Clause */
/* rigid_body.c — Newton–Euler equations of a rigid body whose inertia tensor about the
 * centre of mass is diagonal in the body frame B (principal axes): m a = F, and Euler's
 * equations Ixx dwx = Mx + (Iyy - Izz) wy wz (and cyclic), as in Greenwood, "Advanced
 * Dynamics" and the homework's plane model; plus the angular momentum and the kinetic
 * energies used as invariants.
 */
#include "dynkit/mech.h"

#include <math.h>

static int positive_finite(double x)
{
    return x > 0.0 && isfinite(x);
}

int dyn_rigid_linear_accel(double m, const double F[3], double a[3])
{
    if (!positive_finite(m)) {
        a[0] = a[1] = a[2] = NAN;
        return 1;
    }
    a[0] = F[0] / m;
    a[1] = F[1] / m;
    a[2] = F[2] / m;
    return 0;
}

int dyn_rigid_euler_accel(const double inertia[3], const double omega_B[3],
                          const double moment_B[3], double domega_B[3])
{
    double Ixx = inertia[0], Iyy = inertia[1], Izz = inertia[2];
    double wx = omega_B[0], wy = omega_B[1], wz = omega_B[2];
    if (!positive_finite(Ixx) || !positive_finite(Iyy) || !positive_finite(Izz)) {
        domega_B[0] = domega_B[1] = domega_B[2] = NAN;
        return 1;
    }
    double dwx = (moment_B[0] + (Iyy - Izz) * wy * wz) / Ixx;
    double dwy = (moment_B[1] + (Izz - Ixx) * wz * wx) / Iyy;
    double dwz = (moment_B[2] + (Ixx - Iyy) * wx * wy) / Izz;
    domega_B[0] = dwx;
    domega_B[1] = dwy;
    domega_B[2] = dwz;
    return 0;
}

void dyn_rigid_angular_momentum(const double inertia[3], const double omega_B[3],
                                double L_B[3])
{
    double L0 = inertia[0] * omega_B[0];
    double L1 = inertia[1] * omega_B[1];
    double L2 = inertia[2] * omega_B[2];
    L_B[0] = L0;
    L_B[1] = L1;
    L_B[2] = L2;
}

double dyn_rigid_rotational_energy(const double inertia[3], const double omega_B[3])
{
    return 0.5 * (inertia[0] * omega_B[0] * omega_B[0] + inertia[1] * omega_B[1] * omega_B[1]
                  + inertia[2] * omega_B[2] * omega_B[2]);
}

double dyn_rigid_translational_energy(double m, const double v[3])
{
    return 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
