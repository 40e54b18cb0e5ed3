/* SPDX-License-Identifier: BSD-3-Clause */
/* mat3.c — 3x3 matrix algebra on row-major double[9]: products (A B, A B^T, A v, A^T v),
 * transpose, identity, determinant and the orthonormality error max |R R^T - I| used to
 * check rotation matrices. Plain component formulas; results are formed in locals first so
 * outputs may alias inputs.
 */
#include "dynkit/mech.h"

#include <math.h>
#include <string.h>

void dyn_mat3_mul(const double A[9], const double B[9], double out[9])
{
    double C[9];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
        }
    }
    memcpy(out, C, sizeof C);
}

void dyn_mat3_mul_bt(const double A[9], const double B[9], double out[9])
{
    double C[9];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            C[3 * i + j] = A[3 * i] * B[3 * j] + A[3 * i + 1] * B[3 * j + 1]
                           + A[3 * i + 2] * B[3 * j + 2];
        }
    }
    memcpy(out, C, sizeof C);
}

void dyn_mat3_transpose(const double A[9], double out[9])
{
    double T[9] = {A[0], A[3], A[6], A[1], A[4], A[7], A[2], A[5], A[8]};
    memcpy(out, T, sizeof T);
}

void dyn_mat3_mul_vec(const double A[9], const double v[3], double out[3])
{
    double r0 = A[0] * v[0] + A[1] * v[1] + A[2] * v[2];
    double r1 = A[3] * v[0] + A[4] * v[1] + A[5] * v[2];
    double r2 = A[6] * v[0] + A[7] * v[1] + A[8] * v[2];
    out[0] = r0;
    out[1] = r1;
    out[2] = r2;
}

void dyn_mat3_tmul_vec(const double A[9], const double v[3], double out[3])
{
    double r0 = A[0] * v[0] + A[3] * v[1] + A[6] * v[2];
    double r1 = A[1] * v[0] + A[4] * v[1] + A[7] * v[2];
    double r2 = A[2] * v[0] + A[5] * v[1] + A[8] * v[2];
    out[0] = r0;
    out[1] = r1;
    out[2] = r2;
}

void dyn_mat3_identity(double out[9])
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(out, I, sizeof I);
}

double dyn_mat3_det(const double A[9])
{
    return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6])
           + A[2] * (A[3] * A[7] - A[4] * A[6]);
}

double dyn_mat3_orthonormality_error(const double R[9])
{
    double P[9];
    double err = 0.0;
    dyn_mat3_mul_bt(R, R, P);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            double e = fabs(P[3 * i + j] - (i == j ? 1.0 : 0.0));
            if (!(e <= err)) { /* also propagates NaN */
                err = e;
            }
        }
    }
    return err;
}
