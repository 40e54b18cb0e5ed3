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
 * circle, with the number of complex multipliers outside it. */
#include <float.h>
#include <math.h>

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
