/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_bp_refine.c — a simple branch point of G(z) = 0 (G: R^(N+1) -> R^N, cont_core.h)
 * solved for directly, by Newton's method on Moore's extended system (Moore 1980; Keller
 * 1977; Govaerts, "Numerical methods for bifurcations of dynamical equilibria", 2000,
 * sec. 6.3; MatCont's BP locator for equilibria):
 *     G(z) + beta psi = 0,   DG(z)^T psi = 0,   (psi . psi - 1) / 2 = 0
 * in z, the left null vector psi and an unfolding beta, 2N + 2 equations and unknowns. At a
 * simple branch point its Jacobian is regular and beta = 0, where the bordered matrix of
 * pseudo-arclength continuation is singular: a branch that turns in its parameter where it
 * meets another (a pitchfork seen from its bifurcating branch) has its point located here
 * when the secant method along the branch cannot approach it. The second derivatives
 * psi . D^2G[e_j, .] come from central differences of the exact Jacobian. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/lm_step.h"
#include "cont_core.h"
#include "ode/linalg.h"

/* the iterations allowed, and the Newton step's size (relative to max(1, |z|_inf)) that
 * ends them */
#define BP_REFINE_ITERATIONS 12
#define BP_REFINE_TOL 1e-13

/* H (M x M, row-major) with H[i][j] = psi . d(DG e_i)/dz_j: column j from central
 * differences of DG^T psi along e_j. J (N x M), zh (M), d (M): work. */
static int psi_hessian(const cont_system *s, const double *z, const double *psi, double *H,
                       double *J, double *zh, double *d)
{
    const int N = s->N, M = N + 1;
    memcpy(zh, z, (size_t)M * sizeof *zh);
    for (int j = 0; j < M; j++) {
        const double h = 6e-6 * fmax(1.0, fabs(z[j]));
        for (int sign = 1; sign >= -1; sign -= 2) {
            zh[j] = z[j] + sign * h;
            if (s->jacobian(s->ctx, zh, J))
                return -1;
            for (int i = 0; i < M; i++) {
                double v = 0.0;
                for (int q = 0; q < N; q++)
                    v += psi[q] * J[(size_t)q * (size_t)M + (size_t)i];
                d[i] = sign > 0 ? v : d[i] - v;
            }
        }
        /* divided by the difference of the two arguments as rounded */
        const double width = (z[j] + h) - (z[j] - h);
        for (int i = 0; i < M; i++)
            H[(size_t)i * (size_t)M + (size_t)j] = d[i] / width;
        zh[j] = z[j];
    }
    return 0;
}

int cont_refine_branch_point(const cont_system *s, const double *guess, double *z)
{
    const int N = s->N, M = N + 1, K = M + N + 1;
    const size_t MM = (size_t)M, KK = (size_t)K;
    double *buf = malloc((KK * KK + 2 * MM * MM + MM * (size_t)N + 3 * KK + MM) * sizeof *buf);
    int *piv = malloc(KK * sizeof *piv);
    if (!buf || !piv) {
        free(buf);
        free(piv);
        return -1;
    }
    double *A = buf, *H = A + KK * KK, *G = H + MM * MM, *J = G + MM * MM;
    double *u = J + MM * (size_t)N, *r = u + KK, *zh = r + KK, *d = zh + KK;
    double *psi = u + M;
    int rc = -1;
    memcpy(u, guess, MM * sizeof *u);
    /* psi: the left null vector of DG at the guess; beta = 0 */
    if (s->jacobian(s->ctx, u, J) || cont_normal_factor(J, N, M, 1, G) ||
        cont_inverse_iteration(G, N, 1, 6, psi))
        goto done;
    u[K - 1] = 0.0;
    for (int it = 0; it < BP_REFINE_ITERATIONS; it++) {
        const double beta = u[K - 1];
        if (s->residual(s->ctx, u, r) || s->jacobian(s->ctx, u, J) ||
            psi_hessian(s, u, psi, H, G, zh, d))
            goto done;
        memset(A, 0, KK * KK * sizeof *A);
        /* G + beta psi: [DG | beta I | psi] */
        for (int i = 0; i < N; i++) {
            r[i] = -(r[i] + beta * psi[i]);
            double *row = A + (size_t)i * KK;
            memcpy(row, J + (size_t)i * MM, MM * sizeof *row);
            row[M + i] = beta;
            row[K - 1] = psi[i];
        }
        /* DG^T psi: [H | DG^T | 0] */
        for (int i = 0; i < M; i++) {
            double *row = A + (size_t)(N + i) * KK;
            double dt = 0.0;
            for (int q = 0; q < N; q++) {
                const double jq = J[(size_t)q * MM + (size_t)i];
                dt += psi[q] * jq;
                row[M + q] = jq;
            }
            r[N + i] = -dt;
            memcpy(row, H + (size_t)i * MM, MM * sizeof *row);
        }
        /* (psi . psi - 1) / 2: [0 | psi^T | 0] */
        double pp = 0.0;
        for (int q = 0; q < N; q++) {
            pp += psi[q] * psi[q];
            A[(KK - 1) * KK + (size_t)(M + q)] = psi[q];
        }
        r[K - 1] = -0.5 * (pp - 1.0);
        if (dyn_lu_factor(K, A, piv))
            goto done;
        dyn_lu_solve(K, A, piv, r);
        for (int i = 0; i < K; i++)
            u[i] += r[i];
        for (int i = 0; i < K; i++)
            if (!isfinite(u[i]))
                goto done;
        if (lm_norm_inf(M, r) <= BP_REFINE_TOL * fmax(1.0, lm_norm_inf(M, u))) {
            rc = 0;
            break;
        }
    }
    if (rc == 0) {
        /* a branch point of G = 0 itself, not of a problem unfolded by beta: G's residual
         * at rounding level against DG's size */
        if (s->jacobian(s->ctx, u, J))
            rc = -1;
        else if (!(fabs(u[K - 1]) <= 1e-10 * fmax(1.0, lm_norm_inf(N * M, J)) *
                                          fmax(1.0, lm_norm_inf(M, u))))
            rc = 1;
    }
    if (rc == 0)
        memcpy(z, u, MM * sizeof *z);
done:
    free(buf);
    free(piv);
    return rc;
}
