/* Order conditions of Runge–Kutta tables up to order 4 (the 8 rooted trees).
 *
 * Reference: Butcher, "Numerical Methods for Ordinary Differential Equations", 3rd ed.,
 * sec. 31 (rooted trees); Hairer, Nørsett & Wanner I, table II.2.2. Also checks the
 * row-sum condition c_i = sum_j a_ij that the conditions assume.
 */
#include <math.h>

#include "dynkit/ode.h"

static double max_abs(double a, double b) { return fabs(a) > fabs(b) ? fabs(a) : fabs(b); }

double dyn_tableau_order_residual(const dyn_tableau *tab, int p)
{
    const int s = tab->stages;
    const double *a = tab->a, *b = tab->b, *c = tab->c;
    double worst = 0.0;
    double ac[64], ac2[64], aac[64]; /* (A c)_i, (A c^2)_i, (A A c)_i */
    if (s > 64)
        return INFINITY;
    for (int i = 0; i < s; i++) {
        double row = 0.0;
        ac[i] = ac2[i] = 0.0;
        for (int j = 0; j < s; j++) {
            row += a[i * s + j];
            ac[i] += a[i * s + j] * c[j];
            ac2[i] += a[i * s + j] * c[j] * c[j];
        }
        worst = max_abs(worst, row - c[i]);
    }
    for (int i = 0; i < s; i++) {
        aac[i] = 0.0;
        for (int j = 0; j < s; j++)
            aac[i] += a[i * s + j] * ac[j];
    }
    double t1 = 0, t2 = 0, t3a = 0, t3b = 0, t4a = 0, t4b = 0, t4c = 0, t4d = 0;
    for (int i = 0; i < s; i++) {
        t1 += b[i];
        t2 += b[i] * c[i];
        t3a += b[i] * c[i] * c[i];
        t3b += b[i] * ac[i];
        t4a += b[i] * c[i] * c[i] * c[i];
        t4b += b[i] * c[i] * ac[i];
        t4c += b[i] * ac2[i];
        t4d += b[i] * aac[i];
    }
    if (p >= 1)
        worst = max_abs(worst, t1 - 1.0);
    if (p >= 2)
        worst = max_abs(worst, t2 - 0.5);
    if (p >= 3) {
        worst = max_abs(worst, t3a - 1.0 / 3.0);
        worst = max_abs(worst, t3b - 1.0 / 6.0);
    }
    if (p >= 4) {
        worst = max_abs(worst, t4a - 0.25);
        worst = max_abs(worst, t4b - 0.125);
        worst = max_abs(worst, t4c - 1.0 / 12.0);
        worst = max_abs(worst, t4d - 1.0 / 24.0);
    }
    return worst;
}
