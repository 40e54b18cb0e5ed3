/* SPDX-License-Identifier: BSD-3-Clause */
/* quat_mat.c — conversions between quaternions and N->B rotation matrices.
 * R(q) = ((w^2 - |v|^2) I + 2 v v^T - 2 w [v x]) / |q|^2, the transpose of the usual active
 * matrix, because q carries the N axes onto the B axes while R maps N coordinates to B
 * (the attitude matrix of Shuster, "A Survey of Attitude Representations", J. Astronaut.
 * Sci. 41(4), 1993, with the scalar part written first). Matrix to quaternion follows Shepperd,
 * "Quaternion from rotation matrix", J. Guidance Control 1(3), 1978 (as in Markley,
 * J. Guidance 31(2), 2008): among 4w^2 = 1 + tr, 4x^2 = 1 + 2 R11 - tr, ... the largest
 * is taken by square root and the other three components follow from the off-diagonal sums
 * and differences divided by it, so no component is computed from a difference of nearly
 * equal numbers; then the result is normalised and given w >= 0.
 */
#include "dynkit/mech.h"

#include <math.h>

int dyn_quat_to_mat(const double q[4], double R[9])
{
    double w = q[0], x = q[1], y = q[2], z = q[3];
    double n2 = w * w + x * x + y * y + z * z;
    if (!(n2 > 0.0 && isfinite(n2))) {
        for (int i = 0; i < 9; i++) {
            R[i] = NAN;
        }
        return 1;
    }
    double s = 2.0 / n2;
    double xx = s * x * x, yy = s * y * y, zz = s * z * z;
    double xy = s * x * y, xz = s * x * z, yz = s * y * z;
    double wx = s * w * x, wy = s * w * y, wz = s * w * z;
    R[0] = 1.0 - (yy + zz);
    R[1] = xy + wz;
    R[2] = xz - wy;
    R[3] = xy - wz;
    R[4] = 1.0 - (xx + zz);
    R[5] = yz + wx;
    R[6] = xz + wy;
    R[7] = yz - wx;
    R[8] = 1.0 - (xx + yy);
    return 0;
}

void dyn_mat_to_quat(const double R[9], double q[4])
{
    double tr = R[0] + R[4] + R[8];
    double c[4];
    /* 4*(component)^2 for w, x, y, z; pick the largest. */
    double d[4] = {1.0 + tr, 1.0 + 2.0 * R[0] - tr, 1.0 + 2.0 * R[4] - tr,
                   1.0 + 2.0 * R[8] - tr};
    int k = 0;
    for (int i = 1; i < 4; i++) {
        if (d[i] > d[k]) {
            k = i;
        }
    }
    double r = sqrt(d[k] > 0.0 ? d[k] : 0.0); /* = 2 |component k| */
    double f = r > 0.0 ? 0.5 / r : 0.0;       /* 1 / (4 |component k|) */
    switch (k) {
    case 0:
        c[0] = 0.5 * r;
        c[1] = (R[5] - R[7]) * f;
        c[2] = (R[6] - R[2]) * f;
        c[3] = (R[1] - R[3]) * f;
        break;
    case 1:
        c[1] = 0.5 * r;
        c[0] = (R[5] - R[7]) * f;
        c[2] = (R[1] + R[3]) * f;
        c[3] = (R[2] + R[6]) * f;
        break;
    case 2:
        c[2] = 0.5 * r;
        c[0] = (R[6] - R[2]) * f;
        c[1] = (R[1] + R[3]) * f;
        c[3] = (R[5] + R[7]) * f;
        break;
    default:
        c[3] = 0.5 * r;
        c[0] = (R[1] - R[3]) * f;
        c[1] = (R[2] + R[6]) * f;
        c[2] = (R[5] + R[7]) * f;
        break;
    }
    if (c[0] < 0.0) {
        c[0] = -c[0];
        c[1] = -c[1];
        c[2] = -c[2];
        c[3] = -c[3];
    }
    dyn_quat_normalize(c, q);
}
