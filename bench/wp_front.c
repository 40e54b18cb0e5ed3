/* SPDX-License-Identifier: BSD-3-Clause */
/* wp_front.c — cost at an error level on a solver's work-precision front (wp_front.h). */
#include "wp_front.h"

#include <math.h>

double wp_front_cost_at(int n, const double *err, const double *cost, const int *ok, double e)
{
    int idx[WP_FRONT_MAX], k = 0;
    for (int i = 0; i < n && i < WP_FRONT_MAX; i++)
        if ((!ok || ok[i]) && err[i] > 0 && cost[i] > 0)
            idx[k++] = i;
    for (int a = 1; a < k; a++) /* insertion sort by cost */
        for (int b = a; b > 0 && cost[idx[b]] < cost[idx[b - 1]]; b--) {
            const int t = idx[b];
            idx[b] = idx[b - 1];
            idx[b - 1] = t;
        }
    double fe[WP_FRONT_MAX], fc[WP_FRONT_MAX];
    int nf = 0;
    for (int a = 0; a < k; a++)
        if (nf == 0 || err[idx[a]] < fe[nf - 1]) {
            fe[nf] = err[idx[a]];
            fc[nf] = cost[idx[a]];
            nf++;
        }
    for (int a = 0; a + 1 < nf; a++)
        if (e <= fe[a] && e >= fe[a + 1]) {
            const double w = (log(e) - log(fe[a])) / (log(fe[a + 1]) - log(fe[a]));
            return exp(log(fc[a]) + w * (log(fc[a + 1]) - log(fc[a])));
        }
    if (nf == 1 && e == fe[0])
        return fc[0];
    return NAN;
}
