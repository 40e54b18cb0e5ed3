/* SPDX-License-Identifier: BSD-3-Clause */
/* Helpers shared by the homework analyses (private to the library). */
#ifndef DYNKIT_SRC_REPORT_HW_COMMON_H
#define DYNKIT_SRC_REPORT_HW_COMMON_H

#include <stddef.h>

#include "dynkit/ode.h"
#include "dynkit/report.h"

#define HW_MAX_STATES 16

/* Final state y (n <= HW_MAX_STATES) of a fixed-step run of method over [t0, t1] with step h.
 * Returns DYN_OK or the solve status with a message in err. */
int hw_final_state(const char *method, dyn_rhs_fn f, void *par, int n, double t0, double t1,
                   double h, const double *y0, double *y, char *err, size_t errlen);

/* Like hw_final_state, calling each(k, t, y, ctx) at every sample. */
int hw_run(const char *method, dyn_rhs_fn f, void *par, int n, double t0, double t1, double h,
           const double *y0, double *y, dyn_output_fn each, void *ctx, char *err,
           size_t errlen);

/* Euclidean distance between two n-vectors. */
double hw_distance(const double *a, const double *b, int n);

/* Distance between the centres of mass and principal angle between the orientations of two
 * states of the plane (12: s, Euler angles, ds, omega). */
void hw_plane_compare(const double *a, const double *b, double *distance, double *angle);

/* The four problems; each returns 0 or non-zero with a message in err. */
int dyn_hw_pendulum_compute(dyn_hw_pendulum *r, char *err, size_t errlen);
int dyn_hw_vanderpol_compute(dyn_hw_vanderpol *r, char *err, size_t errlen);
int dyn_hw_plane_compute(dyn_hw_plane *r, char *err, size_t errlen);
int dyn_hw_cart_compute(dyn_hw_cart *r, char *err, size_t errlen);

#endif
