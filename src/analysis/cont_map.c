/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_map.c — the fixed points of a discrete map y_{k+1} = F(y_k, p) as a branch of
 * continuation (cont_equilibrium.h): the zeros of F(y) - y, whose multipliers mu are the
 * eigenvalues of dF/dy. Besides the fold (LP, mu = 1) and the branch point (BP), found by
 * the same test functions as for flows applied to F(y) - y, the test functions of the
 * map's own bifurcations (Kuznetsov, "Elements of Applied Bifurcation Theory", 3rd ed.,
 * ch. 4; AUTO-07p manual, IPS = -1): a period doubling (flip, PD) where a real multiplier
 * crosses -1, psi = det(I + dF/dy) = prod (1 + mu), with the number of real multipliers
 * below -1; a Neimark-Sacker point (labelled TR, as AUTO-07p labels it for maps) where a
 * complex pair crosses the unit circle, psi = |mu| - 1 of the complex pair nearest the
 * circle, with the number of complex multipliers outside it. The points of period k born at
 * period doublings are the fixed points of F^k, its Jacobian the product of dF/dy along the
 * orbit. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cont_equilibrium.h"

/* whether multiplier i is real: |im| within 1e-8 of the largest modulus, as the Hopf test
 * judges eigenvalues (cont_hopf_test) */
static int is_real(const cont_model *cm, int i, double small)
{
    return !(fabs(cm->im[i]) > small);
}

static double small_of(const cont_model *cm)
{
    double scale = 0.0;
    for (int i = 0; i < cm->n; i++)
        scale = fmax(scale, hypot(cm->re[i], cm->im[i]));
    return 1e-8 * fmax(scale, DBL_MIN);
}

void cont_map_tests(const cont_model *cm, double *psi, int *count)
{
    const double small = small_of(cm);
    /* period doubling: det(I + dF/dy), the complex pairs' factors |1 + mu|^2 > 0 */
    double det = 1.0;
    count[0] = 0;
    for (int i = 0; i < cm->n; i++) {
        if (is_real(cm, i, small)) {
            det *= 1.0 + cm->re[i];
            if (cm->re[i] < -1.0)
                count[0]++;
        } else if (cm->im[i] > 0.0) {
            det *= (1.0 + cm->re[i]) * (1.0 + cm->re[i]) + cm->im[i] * cm->im[i];
        }
    }
    psi[0] = det;
    /* Neimark-Sacker: |mu| - 1 of the complex pair nearest the unit circle (+1 when none) */
    double best = 1.0;
    count[1] = 0;
    for (int i = 0; i < cm->n; i++) {
        if (is_real(cm, i, small))
            continue;
        const double d = hypot(cm->re[i], cm->im[i]) - 1.0;
        if (d > 0.0)
            count[1]++;
        if (fabs(d) < fabs(best))
            best = d;
    }
    psi[1] = best;
}

int cont_map_iterate(cont_model *cm, const double *x, double *y)
{
    const size_t n = (size_t)cm->n;
    const double *from = x;
    for (int j = 0; j < cm->period; j++) {
        double *to = j == cm->period - 1 ? y : cm->map_work + (size_t)(j % 2) * n;
        cm->rhs_calls++;
        if (cm->m->rhs(cm->t, from, to, cm->par)) {
            snprintf(cm->message, sizeof cm->message, "the right-hand side failed");
            return -1;
        }
        from = to;
    }
    return 0;
}

int cont_map_jacobian(cont_model *cm, const double *x, double *A)
{
    const int n = cm->n;
    const size_t N = (size_t)n;
    double *y = cm->map_work, *P = y + 2 * N, *B = P + N * N, *T = B + N * N;
    const dyn_linearize_opts lo = {cm->jac, NULL};
    dyn_linearize_info info;
    memcpy(y, x, N * sizeof *y);
    for (int j = 0; j < cm->period; j++) {
        if (dyn_linearize(cm->m, cm->t, y, cm->par, &lo, j ? B : P, cm->lin_work, &info)) {
            snprintf(cm->message, sizeof cm->message, "%s", info.message);
            return -1;
        }
        cm->rhs_calls += info.rhs_calls;
        if (j) { /* P <- dF(y_j) P */
            for (size_t r = 0; r < N; r++)
                for (size_t c = 0; c < N; c++) {
                    double sum = 0.0;
                    for (size_t q = 0; q < N; q++)
                        sum += B[r * N + q] * P[q * N + c];
                    T[r * N + c] = sum;
                }
            memcpy(P, T, N * N * sizeof *P);
        }
        if (j + 1 < cm->period) { /* the next iterate, in place through y + N */
            cm->rhs_calls++;
            if (cm->m->rhs(cm->t, y, y + N, cm->par)) {
                snprintf(cm->message, sizeof cm->message, "the right-hand side failed");
                return -1;
            }
            memcpy(y, y + N, N * sizeof *y);
        }
    }
    memcpy(A, P, N * N * sizeof *A);
    return 0;
}

int cont_map_stable(const cont_model *cm, double tol)
{
    tol = fmax(tol, 1e-8);
    for (int i = 0; i < cm->n; i++)
        if (!(hypot(cm->re[i], cm->im[i]) < 1.0 - tol))
            return 0;
    return 1;
}

double cont_map_angle(const cont_model *cm)
{
    const double small = small_of(cm);
    double best = NAN, best_abs = INFINITY;
    for (int i = 0; i < cm->n; i++) {
        if (is_real(cm, i, small) || !(cm->im[i] > 0.0))
            continue;
        const double d = fabs(hypot(cm->re[i], cm->im[i]) - 1.0);
        if (d < best_abs) {
            best_abs = d;
            best = atan2(cm->im[i], cm->re[i]);
        }
    }
    return best;
}
