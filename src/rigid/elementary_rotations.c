/* SPDX-License-Identifier: BSD-3-Clause */
/* elementary_rotations.c — the three elementary rotation matrices of the homework's plane
 * model in Greenwood's convention ("Advanced Dynamics", ch. 3): each maps coordinates
 * in the old frame to coordinates in the frame turned by the angle about one axis
 * (N->B, "passive"), so a positive psi turns N's X axis towards +Y and X_N has B
 * coordinates (cos psi, -sin psi, 0).
 */
#include "dynkit/mech.h"

#include <math.h>

void dyn_rot_z(double psi, double R[9])
{
    double c = cos(psi), s = sin(psi);
    R[0] = c;    R[1] = s;   R[2] = 0.0;
    R[3] = -s;   R[4] = c;   R[5] = 0.0;
    R[6] = 0.0;  R[7] = 0.0; R[8] = 1.0;
}

void dyn_rot_y(double theta, double R[9])
{
    double c = cos(theta), s = sin(theta);
    R[0] = c;    R[1] = 0.0; R[2] = -s;
    R[3] = 0.0;  R[4] = 1.0; R[5] = 0.0;
    R[6] = s;    R[7] = 0.0; R[8] = c;
}

void dyn_rot_x(double phi, double R[9])
{
    double c = cos(phi), s = sin(phi);
    R[0] = 1.0;  R[1] = 0.0; R[2] = 0.0;
    R[3] = 0.0;  R[4] = c;   R[5] = s;
    R[6] = 0.0;  R[7] = -s;  R[8] = c;
}
