/* SPDX-License-Identifier: BSD-3-Clause */
/* vec3.c — 3-vector algebra on double[3]: sums, scaling, dot and cross products, norms,
 * distances. Plain component formulas in a right-handed Cartesian basis; outputs are
 * computed into locals first so they may alias the inputs.
 */
#include "dynkit/mech.h"

#include <math.h>

void dyn_vec3_add(const double a[3], const double b[3], double out[3])
{
    out[0] = a[0] + b[0];
    out[1] = a[1] + b[1];
    out[2] = a[2] + b[2];
}

void dyn_vec3_sub(const double a[3], const double b[3], double out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

void dyn_vec3_scale(const double a[3], double s, double out[3])
{
    out[0] = s * a[0];
    out[1] = s * a[1];
    out[2] = s * a[2];
}

double dyn_vec3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void dyn_vec3_cross(const double a[3], const double b[3], double out[3])
{
    double c0 = a[1] * b[2] - a[2] * b[1];
    double c1 = a[2] * b[0] - a[0] * b[2];
    double c2 = a[0] * b[1] - a[1] * b[0];
    out[0] = c0;
    out[1] = c1;
    out[2] = c2;
}

double dyn_vec3_norm(const double a[3])
{
    return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

double dyn_vec3_normalize(const double a[3], double out[3])
{
    double n = dyn_vec3_norm(a);
    if (n > 0.0 && isfinite(n)) {
        double s = 1.0 / n;
        out[0] = a[0] * s;
        out[1] = a[1] * s;
        out[2] = a[2] * s;
    } else {
        out[0] = out[1] = out[2] = 0.0;
    }
    return n;
}

double dyn_vec3_distance(const double a[3], const double b[3])
{
    double d[3];
    dyn_vec3_sub(a, b, d);
    return dyn_vec3_norm(d);
}
