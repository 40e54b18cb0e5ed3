/* SPDX-License-Identifier: BSD-3-Clause */
/* Helpers shared by the homework analyses: fixed-step runs into a final state, the comparison
 * of two states of the plane. */
#include <math.h>
#include <stdio.h>

#include "dynkit/mech.h"
#include "report/hw_common.h"

int hw_run(const char *method, dyn_rhs_fn f, void *par, int n, double t0, double t1, double h,
           const double *y0, double *y, dyn_output_fn each, void *ctx, char *err,
           size_t errlen)
{
    const dyn_tableau *m = dyn_method_find(method);
    double work[(8 + 3) * HW_MAX_STATES];
    if (!m || n > HW_MAX_STATES || dyn_fixed_work_size(m, n) > sizeof work / sizeof *work) {
        snprintf(err, errlen, "internal: method %s or %d states not supported here", method, n);
        return DYN_ERR_ARG;
    }
    dyn_system sys = {f, n, par};
    dyn_fixed_opts opts = {0};
    opts.output = each;
    opts.output_ctx = ctx;
    dyn_result res;
    int status = dyn_fixed_solve(m, &sys, t0, t1, h, y0, y, work, &opts, &res);
    if (status != DYN_OK)
        snprintf(err, errlen, "%s run (step %g) failed: %s", method, h, res.message);
    return status;
}

int hw_final_state(const char *method, dyn_rhs_fn f, void *par, int n, double t0, double t1,
                   double h, const double *y0, double *y, char *err, size_t errlen)
{
    return hw_run(method, f, par, n, t0, t1, h, y0, y, NULL, NULL, err, errlen);
}

double hw_distance(const double *a, const double *b, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrt(s);
}

void hw_plane_compare(const double *a, const double *b, double *distance, double *angle)
{
    double Ra[9], Rb[9], axis[3];
    dyn_euler_to_mat(a + 3, Ra);
    dyn_euler_to_mat(b + 3, Rb);
    *distance = dyn_vec3_distance(a, b);
    *angle = dyn_principal_angle(Ra, Rb, axis);
}
