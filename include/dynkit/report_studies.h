/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/report_studies.h — the homework, deeper: three studies of many runs for the report
 * (dynkit report and its page), each computed by the sweep library (dynkit/sweep.h) on all
 * cores. Part of the library dynkit_sweep (OpenMP); the results are plain data in
 * dynkit/report.h (dyn_hw_studies), printed by the report's writers.
 *
 * - period: the pendulum released at rest from 60 amplitudes (dop853, rtol = atol = 1e-12,
 *   each run stopped at its first bottom, a quarter period), against 4 K(k)/w with
 *   k = sin(a/2) and K by the arithmetic-geometric mean (Abramowitz and Stegun 17.6);
 * - plane: Euler and RK4 at the homework's step from 1,000 starts, each non-zero initial
 *   state changed by a relative normal amount of standard deviation 1e-14 (Philox4x32-10,
 *   seed 1), the distance and principal angle between each pair of final states;
 * - cart: max |lambda| / (mu (2/3) m g) along the prescribed motion (4d) over a grid of the
 *   speed v0 (0..30 m/s) and the steering frequency f (0..3 Hz), N = 500 samples at Ts =
 *   0.01 s (RK4 of the path, dyn_model_cart_path), and the fraction of the time the wheels
 *   would slip.
 * Every study gives the same bits for any number of threads (the sweep's guarantee).
 */
#ifndef DYNKIT_REPORT_STUDIES_H
#define DYNKIT_REPORT_STUDIES_H

#include <stddef.h>

#include "dynkit/cart.h"
#include "dynkit/model.h"
#include "dynkit/report.h"

#ifdef __cplusplus
extern "C" {
#endif

/* All three studies into hw->studies (computed = 1), on threads threads (0: all cores).
 * Returns 0, or non-zero with a message in err. */
int dyn_homework_studies(dyn_homework *hw, int threads, char *err, size_t errlen);

/* Each study alone. */
int dyn_study_period_compute(dyn_study_period *s, int threads, char *err, size_t errlen);
int dyn_study_plane_compute(dyn_study_plane *s, int threads, char *err, size_t errlen);
int dyn_study_cart_compute(dyn_study_cart *s, int threads, char *err, size_t errlen);

/* K(k), the complete elliptic integral of the first kind for 0 <= k < 1, by the
 * arithmetic-geometric mean: K = pi / (2 AGM(1, sqrt(1 - k^2))). */
double dyn_elliptic_k(double k);

/* The cart following the prescribed motion of problem 4a (sX = -v0 t, theta = pi/8
 * sin(2 pi f t)): states sX and theta integrated from their prescribed rates, parameters
 * v0, f and the cart's (m, length_cart, width_cart, mu, g), outputs lambda (the rear-axle
 * force of the inverse dynamics' forces, as in 4d), slip_ratio = |lambda| / (mu (2/3) m g)
 * and slipping (1 while slip_ratio >= 1, else 0), event slip (slip_ratio rises through 1). Not in
 * the registry: a model for sweeps over v0 and f. */
typedef struct dyn_cart_path_par {
    double v0, f;      /* [m/s], [Hz] */
    dyn_cart_par cart; /* m, length_cart, width_cart, mu, g (no force table) */
} dyn_cart_path_par;
extern const dyn_model dyn_model_cart_path;

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_REPORT_STUDIES_H */
