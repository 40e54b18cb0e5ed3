/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/lyapunov.h — Lyapunov exponents of a model along a trajectory by Benettin's method
 * (G. Benettin, L. Galgani, A. Giorgilli, J.-M. Strelcyn, Meccanica 15 (1980) 9-20 and
 * 21-30): the variational equations Q' = J(t, y) Q integrated with the trajectory (for a
 * map Q <- dF/dy Q at each iteration), Q re-orthonormalized by QR (Gram-Schmidt) at fixed
 * intervals, the logarithms of R's diagonal summed; the exponents are those sums over the
 * time after a transient, largest first. The averaging time is cut into blocks, and the
 * spread of the block means estimates the error. J Q comes from the model's exact Jacobian,
 * or from central differences along each column of Q. C11 + libm; the workspace is
 * allocated once per call. docs/analysis.md, "Lyapunov exponents". */
#ifndef DYNKIT_LYAPUNOV_H
#define DYNKIT_LYAPUNOV_H

#include "dynkit/analysis.h"
#include "dynkit/model.h"
#include "dynkit/solve.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DYN_LYAPUNOV_BLOCKS 10 /* blocks of the error estimate when blocks is 0 */

typedef struct dyn_lyapunov_opts {
    int k;             /* exponents: 1 (the largest, the default for 0) to n (the spectrum) */
    int map;           /* 1: m is a discrete map y_{k+1} = F(t_k, y_k) */
    double t_trans;    /* the transient before averaging (a map: iterations), >= 0 */
    double t_avg;      /* the averaging time after it (a map: iterations), > 0 */
    double tau;        /* a flow's interval between orthonormalizations (> 0; a map:
                        * every iteration); also the step of a map's time (0: 1) */
    const dyn_tableau *method; /* a flow's adaptive method; NULL: dop853 */
    double rtol, atol; /* 0: 1e-10 and 1e-10 */
    dyn_jac_scheme scheme; /* AUTO or ANALYTIC: the model's exact Jacobian when it has one
                            * (ANALYTIC: required); CENTRAL/RICHARDSON: differences along Q */
    int blocks;        /* blocks of the averaging time: 0 means DYN_LYAPUNOV_BLOCKS (>= 2) */
} dyn_lyapunov_opts;

typedef struct dyn_lyapunov_info {
    double t_end;          /* the time reached */
    long orthonormalizations;
    long rhs_calls;        /* a flow's integrator's calls of the extended system */
    int exact_jacobian;    /* 1: the model's Jacobian; 0: differences */
    char message[256];
} dyn_lyapunov_info;

/* The k largest Lyapunov exponents of model m (prepared parameters par) from (t0, y0) into
 * exponents (k values, largest first) and an error estimate of each into err (k values or
 * NULL): the standard deviation of the block means over sqrt(blocks). Returns 0;
 * DYN_ERR_ARG (bad options, a delay, Volterra or Markov model; a model's other noise
 * terms are 0, as its parameter struct holds them outside a solve) or the integrator's status
 * when the trajectory fails, with the message in info (may be NULL). */
int dyn_lyapunov(const dyn_model *m, void *par, double t0, const double *y0,
                 const dyn_lyapunov_opts *opts, double *exponents, double *err,
                 dyn_lyapunov_info *info);

/* Orthonormalize the k columns of Q (n x k, row-major) by modified Gram-Schmidt, applied
 * twice ("twice is enough": Giraud, Langou, Rozloznik 2005); the logarithms of the
 * diagonal of R into logr (k values). Returns 0, or -1 when a column vanishes or is not
 * finite. */
int dyn_qr_log_diag(int n, int k, double *Q, double *logr);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_LYAPUNOV_H */
