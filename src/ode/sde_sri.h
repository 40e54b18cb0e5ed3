/* SPDX-License-Identifier: BSD-3-Clause */
/* sde_sri.h — Rößler's stochastic Runge–Kutta methods of the SRI family (private; sde.c).
 *
 * A. Rößler, "Runge–Kutta methods for the strong approximation of solutions of stochastic
 * differential equations", SIAM J. Numer. Anal. 48 (2010) 922–952: for dX = a dt + b dW
 * with one noise, or several whose coefficients do not read the states that the others
 * move (dyn_noise_class DYN_NOISE_COMMUTATIVE or ADDITIVE), one step is
 *   H0_i = X + sum_j A0_ij a(H0_j) h + sum_j B0_ij sum_k b_k(H1k_j) I_(k,0)/h,
 *   H1k_i = X + sum_j A1_ij a(H0_j) h + sum_j B1_ij b_k(H1k_j) sqrt(h),
 *   X+ = X + sum_i alpha_i a(H0_i) h
 *          + sum_k sum_i (beta1_i I_(k) + beta2_i I_(k,k)/sqrt(h)) b_k(H1k_i)
 *          + sum_k sum_i (beta3_i I_(k,0)/h + beta4_i I_(k,k,k)/h) b_k(H1k_i),
 * with I_(k) = dW_k, I_(k,k) = (dW_k^2 - h)/2, I_(k,k,k) = (dW_k^3 - 3 h dW_k)/6 and
 * I_(k,0) the time integral of W_k - W_k(t) over the step. The stages H0_i take the time
 * t + c0_i h, the H1k_i t + c1_i h. The last sum is the embedded error estimate's noise part
 * E2 (Rackauckas and Nie 2017), its drift part E1 = h (a(H0_1) + ... + a(H0_e)), e = the
 * tableau's error_terms. */
#ifndef DYNKIT_SRC_ODE_SDE_SRI_H
#define DYNKIT_SRC_ODE_SDE_SRI_H

#define DYN_SRI_STAGES 4

typedef struct dyn_sri_tableau {
    const char *name;
    int stages, error_terms;
    double c0[DYN_SRI_STAGES], c1[DYN_SRI_STAGES];
    double A0[DYN_SRI_STAGES][DYN_SRI_STAGES], A1[DYN_SRI_STAGES][DYN_SRI_STAGES];
    double B0[DYN_SRI_STAGES][DYN_SRI_STAGES], B1[DYN_SRI_STAGES][DYN_SRI_STAGES];
    double alpha[DYN_SRI_STAGES], beta1[DYN_SRI_STAGES], beta2[DYN_SRI_STAGES];
    double beta3[DYN_SRI_STAGES], beta4[DYN_SRI_STAGES];
} dyn_sri_tableau;

/* SRIW1: strong order 1.5, weak order 2 (Rößler 2010, section 5; DifferentialEquations.jl's
 * SRIW1), with error_terms 2; its order conditions are checked in tests/test_sde.c. */
extern const dyn_sri_tableau dyn_sriw1;

/* The drift (unit -1) or the noise column unit (b_unit = f(w = e_unit) - f(w = 0)) at (t, y)
 * into out; non-zero when the right-hand side failed. */
typedef int (*dyn_sri_eval_fn)(void *ctx, double t, const double *y, int unit, double *out);

/* Doubles of workspace dyn_sri_step needs for n states and m noises. */
#define DYN_SRI_WORK(n, m)                                                                   \
    ((size_t)(DYN_SRI_STAGES * (1 + (m)) + 1) * (size_t)(n) + 3 * (size_t)(m))

/* One step of tab from (t, y) over h with increments dw and time integrals i10 (m each), the
 * drift a0 and the columns b0 (m x n) at (t, y) given; additive: the columns do not depend
 * on the state (evaluated at y). The new state into out, the error estimate's parts into
 * e1 and e2 (n each). Returns non-zero when an evaluation failed. */
int dyn_sri_step(const dyn_sri_tableau *tab, int n, int m, int additive, double t, double h,
                 const double *y, const double *dw, const double *i10, const double *a0,
                 const double *b0, dyn_sri_eval_fn eval, void *ctx, double *work, double *out,
                 double *e1, double *e2);

#endif /* DYNKIT_SRC_ODE_SDE_SRI_H */
