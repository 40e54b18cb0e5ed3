/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/problems.h — verification problems with published or computed references.
 *
 * Three built-in models besides the homework's (registered like them, so every tool works on
 * them), each with an analytic Jacobian:
 *   arenstorf  restricted three-body orbit of Arenstorf, periodic (Hairer, Nørsett & Wanner,
 *              "Solving ODEs I", sec. II.0) — non-stiff, needs step control;
 *   robertson  Robertson's chemical kinetics (HNW II, sec. IV.1; Test Set for IVP Solvers,
 *              problem ROBER) — stiff, conserves y1 + y2 + y3;
 *   hires      "High Irradiance RESponse" photomorphogenesis kinetics, 8 states (HNW II,
 *              sec. IV.10; Test Set for IVP Solvers, problem HIRES) — stiff;
 * and the reference solutions of these and of van der Pol (mu = 1 and mu = 1000) as data,
 * with their sources: see dyn_reference below and src/problems/references.c.
 */
#ifndef DYNKIT_PROBLEMS_H
#define DYNKIT_PROBLEMS_H

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- arenstorf: states (y1, y2, y1', y2'), rotating frame of Earth and Moon ----
 *   y1'' = y1 + 2 y2' - mu' (y1 + mu) / D1 - mu (y1 - mu') / D2
 *   y2'' = y2 - 2 y1' - mu' y2 / D1 - mu y2 / D2
 *   D1 = ((y1 + mu)^2 + y2^2)^(3/2), D2 = ((y1 - mu')^2 + y2^2)^(3/2), mu' = 1 - mu.
 * The default initial state starts a periodic orbit of period DYN_ARENSTORF_PERIOD. */
#define DYN_ARENSTORF_MU 0.012277471
#define DYN_ARENSTORF_PERIOD 17.0652165601579625588917206249
#define DYN_ARENSTORF_Y2DOT0 (-2.00158510637908252240537862224)
typedef struct dyn_arenstorf_par {
    double mu; /* [1] mass ratio Moon / (Earth + Moon) */
} dyn_arenstorf_par;
extern const dyn_model dyn_model_arenstorf;
int dyn_arenstorf_rhs(double t, const double *y, double *dydt, void *par);
int dyn_arenstorf_jac(double t, const double *y, double *J, void *par);
/* Jacobi constant 2 Omega - (y1'^2 + y2'^2), Omega = (y1^2 + y2^2)/2 + mu'/r1 + mu/r2:
 * the invariant of the motion. */
double dyn_arenstorf_jacobi(const dyn_arenstorf_par *p, const double *y);

/* ---- robertson: y1' = -k1 y1 + k3 y2 y3, y2' = k1 y1 - k3 y2 y3 - k2 y2^2, y3' = k2 y2^2
 * with k1 = 0.04, k2 = 3e7, k3 = 1e4, y(0) = (1, 0, 0). */
typedef struct dyn_robertson_par {
    double k1, k2, k3; /* rate constants */
} dyn_robertson_par;
extern const dyn_model dyn_model_robertson;
int dyn_robertson_rhs(double t, const double *y, double *dydt, void *par);
int dyn_robertson_jac(double t, const double *y, double *J, void *par);

/* ---- hires: 8 linear and one bilinear reaction (Schäfer 1975), rates of the Test Set. */
typedef struct dyn_hires_par {
    double k1, k2, k3, k4, k5, k6, k7, k8, k9; /* rate constants */
    double oks;                                 /* constant source of y1 */
} dyn_hires_par;
extern const dyn_model dyn_model_hires;
int dyn_hires_rhs(double t, const double *y, double *dydt, void *par);
int dyn_hires_jac(double t, const double *y, double *J, void *par);

/* ---- references ---- */

/* A parameter value of a reference run that differs from the model's default. */
typedef struct dyn_ref_setting {
    const char *name;
    double value;
} dyn_ref_setting;

/* The state of a model at t1, from t0 and y0, with where it comes from and how good it is. */
typedef struct dyn_reference {
    const char *name;            /* e.g. "robertson-1e11" */
    const char *model;           /* built-in model name (dyn_model_find), or brusselator:N */
    int n_set;
    const dyn_ref_setting *set;  /* (n_set) parameters that differ from the defaults */
    const double *y0;            /* initial state, or NULL for the model's default */
    double t0, t1;
    int n;                       /* states */
    const double *y;             /* (n) the state at t1, rounded to double */
    double error;                /* estimated bound on |y_i - exact_i| / |y_i|, each
                                  * component, beyond the rounding of y_i to double */
    const char *source;          /* citation */
    const char *method;          /* how it was computed */
} dyn_reference;

/* Number of references; by index (NULL out of range); by name (NULL if unknown). */
int dyn_reference_count(void);
const dyn_reference *dyn_reference_at(int i);
const dyn_reference *dyn_reference_find(const char *name);

/* Fill a parameter struct for reference r (par_size bytes of its model, caller-owned):
 * the model's defaults, then r's settings, then the model's prepare. Copies the initial
 * state into y0 (n). Returns 0, or non-zero with a message in err (unknown model or
 * parameter, prepare failed). */
int dyn_reference_setup(const dyn_reference *r, void *par, double *y0, char *err,
                        size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_PROBLEMS_H */
