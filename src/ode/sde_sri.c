/* SPDX-License-Identifier: BSD-3-Clause */
/* One step of a stochastic Runge–Kutta method of Rößler's SRI family (sde_sri.h; A. Rößler,
 * SIAM J. Numer. Anal. 48 (2010) 922–952), with the embedded error estimate of Rackauckas and
 * Nie (Discrete Contin. Dyn. Syst. B 22 (2017) 2731–2761), and the coefficients of SRIW1. The
 * noises are taken one by one: each has its own stages H1k, which is Rößler's scheme when no
 * noise's coefficient reads a state another noise moves (the terms with I_(l,k), l != k,
 * then change no b_k). A stage whose row is zero and whose time is t is the start point and
 * is not evaluated again. */
#include <math.h>
#include <string.h>

#include "sde_sri.h"

const dyn_sri_tableau dyn_sriw1 = {
    .name = "sriw1",
    .stages = 4,
    .error_terms = 2,
    .c0 = {0.0, 0.75, 0.0, 0.0},
    .c1 = {0.0, 0.25, 1.0, 0.25},
    .A0 = {{0}, {0.75}, {0}, {0}},
    .A1 = {{0}, {0.25}, {1.0}, {0.0, 0.0, 0.25}},
    .B0 = {{0}, {1.5}, {0}, {0}},
    .B1 = {{0}, {0.5}, {-1.0}, {-5.0, 3.0, 0.5}},
    .alpha = {1.0 / 3.0, 2.0 / 3.0, 0.0, 0.0},
    .beta1 = {-1.0, 4.0 / 3.0, 2.0 / 3.0, 0.0},
    .beta2 = {-1.0, 4.0 / 3.0, -1.0 / 3.0, 0.0},
    .beta3 = {2.0, -4.0 / 3.0, -2.0 / 3.0, 0.0},
    .beta4 = {-2.0, 5.0 / 3.0, -2.0 / 3.0, 1.0},
};

static int row_zero(const double A[DYN_SRI_STAGES][DYN_SRI_STAGES],
                    const double B[DYN_SRI_STAGES][DYN_SRI_STAGES], int i)
{
    for (int j = 0; j < i; j++)
        if (A[i][j] != 0.0 || B[i][j] != 0.0)
            return 0;
    return 1;
}

int dyn_sri_step(const dyn_sri_tableau *tab, int n, int m, int additive, double t, double h,
                 const double *y, const double *dw, const double *i10, const double *a0,
                 const double *b0, dyn_sri_eval_fn eval, void *ctx, double *work, double *out,
                 double *e1, double *e2)
{
    const int s = tab->stages;
    const size_t N = (size_t)n;
    double *fa = work;                                /* a(H0_i): s x n */
    double *g = fa + (size_t)DYN_SRI_STAGES * N;      /* b_k(H1k_i): (k s + i) x n */
    double *stage = g + (size_t)DYN_SRI_STAGES * (size_t)m * N;
    double *chi1 = stage + N, *chi2 = chi1 + m, *chi3 = chi2 + m;
    const double sq = sqrt(h);
    for (int k = 0; k < m; k++) {
        chi1[k] = (dw[k] * dw[k] - h) / (2.0 * sq);
        chi2[k] = i10[k] / h;
        chi3[k] = (dw[k] * dw[k] * dw[k] - 3.0 * h * dw[k]) / (6.0 * h);
    }
    memcpy(fa, a0, N * sizeof *fa);
    for (int k = 0; k < m; k++)
        memcpy(g + (size_t)k * (size_t)s * N, b0 + (size_t)k * N, N * sizeof *g);
    for (int i = 1; i < s; i++) {
        double *fi = fa + (size_t)i * N;
        if (row_zero(tab->A0, tab->B0, i) && tab->c0[i] == 0.0) {
            memcpy(fi, a0, N * sizeof *fi);
        } else {
            for (int l = 0; l < n; l++) {
                double v = y[l];
                for (int j = 0; j < i; j++) {
                    v += tab->A0[i][j] * h * fa[(size_t)j * N + (size_t)l];
                    if (tab->B0[i][j] != 0.0)
                        for (int k = 0; k < m; k++)
                            v += tab->B0[i][j] * chi2[k] *
                                 g[((size_t)k * (size_t)s + (size_t)j) * N + (size_t)l];
                }
                stage[l] = v;
            }
            if (eval(ctx, t + tab->c0[i] * h, stage, -1, fi))
                return 1;
        }
        for (int k = 0; k < m; k++) {
            double *gk = g + (size_t)k * (size_t)s * N, *gi = gk + (size_t)i * N;
            if (row_zero(tab->A1, tab->B1, i) && tab->c1[i] == 0.0) {
                memcpy(gi, gk, N * sizeof *gi);
                continue;
            }
            if (additive) {
                memcpy(stage, y, N * sizeof *stage);
            } else {
                for (int l = 0; l < n; l++) {
                    double v = y[l];
                    for (int j = 0; j < i; j++)
                        v += tab->A1[i][j] * h * fa[(size_t)j * N + (size_t)l] +
                             tab->B1[i][j] * sq * gk[(size_t)j * N + (size_t)l];
                    stage[l] = v;
                }
            }
            if (eval(ctx, t + tab->c1[i] * h, stage, k, gi))
                return 1;
        }
    }
    for (int l = 0; l < n; l++) {
        double drift = 0.0, noise = 0.0, err = 0.0, est = 0.0;
        for (int i = 0; i < s; i++) {
            drift += tab->alpha[i] * fa[(size_t)i * N + (size_t)l];
            if (i < tab->error_terms)
                est += fa[(size_t)i * N + (size_t)l];
        }
        for (int k = 0; k < m; k++)
            for (int i = 0; i < s; i++) {
                const double gv = g[((size_t)k * (size_t)s + (size_t)i) * N + (size_t)l];
                noise += (tab->beta1[i] * dw[k] + tab->beta2[i] * chi1[k]) * gv;
                err += (tab->beta3[i] * chi2[k] + tab->beta4[i] * chi3[k]) * gv;
            }
        out[l] = y[l] + h * drift + noise + err;
        e1[l] = h * est;
        e2[l] = err;
    }
    return 0;
}
