/* SPDX-License-Identifier: BSD-3-Clause */
/* rosenbrock_tables.c — coefficients of the Rosenbrock methods, as data.
 *
 * RODAS (order 4(3), stiffly accurate, L-stable, dense output of order 3):
 * E. Hairer & G. Wanner, "Solving Ordinary Differential Equations II. Stiff and
 * Differential-Algebraic Problems", 2nd ed., Springer 1996, sec. IV.7 (Table 7.2 ff.),
 * transcribed from their Fortran code rodas.f, subroutine ROCOE, METH = 1
 * (http://www.unige.ch/~hairer/prog/stiff/rodas.f, version of the stiff codes of
 * Hairer & Wanner; 2-clause BSD). The coefficient names there map here as
 *   C2, C3, C4 -> alpha;  D1..D4 -> gam;  Aij -> a;  Cij -> c;  D2j, D3j -> dense;
 * the code forms stage 5 at y0 + sum_j A5j u_j, the embedded solution as that plus u5 and
 * the solution as that plus u6, so a_6j = A5j (j < 5), a_65 = 1, m = (A51..A54, 1, 1) and
 * the error estimate is u6 itself (e = (0, 0, 0, 0, 0, 1)); stages 5 and 6 sit at t + h
 * and have no df/dt term. The dense output is rodas.f's CONT/CONTRO.
 * tests/test_rosenbrock.c checks the order conditions of HNW II Table IV.7.1 on these
 * numbers (order 4; embedded order 3) besides the observed orders.
 */
#include <stddef.h>
#include <string.h>

#include "ode/rosenbrock.h"

/* clang-format off */
static const double rodas4_alpha[6] = {0.0, 0.386, 0.21, 0.63, 1.0, 1.0};
static const double rodas4_gam[6] = {
    0.25, -0.1043, 0.1035, -0.3620000000000023e-01, 0.0, 0.0};
static const double rodas4_a[36] = {
    0, 0, 0, 0, 0, 0,
    1.544, 0, 0, 0, 0, 0,
    0.9466785280815826, 0.2557011698983284, 0, 0, 0, 0,
    3.314825187068521, 2.896124015972201, 0.9986419139977817, 0, 0, 0,
    1.221224509226641, 6.019134481288629, 12.53708332932087, -0.6878860361058950, 0, 0,
    1.221224509226641, 6.019134481288629, 12.53708332932087, -0.6878860361058950, 1.0, 0,
};
static const double rodas4_c[36] = {
    0, 0, 0, 0, 0, 0,
    -5.6688, 0, 0, 0, 0, 0,
    -2.430093356833875, -0.2063599157091915, 0, 0, 0, 0,
    -0.1073529058151375, -9.594562251023355, -20.47028614809616, 0, 0, 0,
    7.496443313967647, -10.24680431464352, -33.99990352819905, 11.70890893206160, 0, 0,
    8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136,
    -6.058818238834054, 0,
};
static const double rodas4_m[6] = {
    1.221224509226641, 6.019134481288629, 12.53708332932087, -0.6878860361058950, 1.0, 1.0};
static const double rodas4_e[6] = {0, 0, 0, 0, 0, 1.0};
static const double rodas4_dense[12] = {
    10.12623508344586, -7.487995877610167, -34.80091861555747, -7.992771707568823,
    1.025137723295662, 0,
    -0.6762803392801253, 6.087714651680015, 16.43084320892478, 24.76722511418386,
    -6.594389125716872, 0,
};
/* clang-format on */

const dyn_ros_method dyn_ros_rodas4 = {
    .name = "rodas4",
    .title = "RODAS 4(3): Rosenbrock, stiffly accurate, L-stable, dense output of order 3",
    .reference = "Hairer & Wanner, Solving ODEs II, sec. IV.7; rodas.f (ROCOE, METH=1)",
    .stages = 6,
    .order = 4,
    .order_embedded = 3,
    .dense_order = 3,
    .gamma = 0.25,
    .alpha = rodas4_alpha,
    .gam = rodas4_gam,
    .a = rodas4_a,
    .c = rodas4_c,
    .m = rodas4_m,
    .e = rodas4_e,
    .dense_rows = 2,
    .dense = rodas4_dense,
};

const dyn_ros_method *dyn_ros_find(const char *name)
{
    if (name && strcmp(name, dyn_ros_rodas4.name) == 0)
        return &dyn_ros_rodas4;
    return NULL;
}
