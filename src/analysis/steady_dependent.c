/* SPDX-License-Identifier: BSD-3-Clause */
/* steady_dependent.c — a mechanism's dependent states (those its constraints determine)
 * solved from the others: Newton's method on the constraints' values (the values on the
 * speeds h of every constraint and the positions f of the holonomic ones, from
 * dyn_constraint_values), the Jacobian with respect to the dependent states by central
 * differences of steps 2^-20 max(|y|, 1), the square system by Cholesky's factorization
 * of the normal equations; until the values stop decreasing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ode/cholesky.h"
#include "dynkit/analysis.h"
#include "dynkit/steady.h"

/* The constraints' values: h of every constraint then f of the holonomic ones, into c;
 * how many, or -1. */
static int values(const dyn_model *cm, const void *par, double t, const double *y, double *h,
                  double *f, int *hol, double *c)
{
    const int m = dyn_constraint_values(cm, par, t, y, h, f, hol);
    if (m < 0)
        return -1;
    int k = 0;
    for (int r = 0; r < m; r++)
        c[k++] = h[r];
    for (int r = 0; r < m; r++)
        if (hol[r])
            c[k++] = f[r];
    return k;
}

int dyn_steady_dependent(const dyn_model *cm, const void *par, double t, double *y, int nd,
                         const int *dep, char *err, size_t errlen)
{
    if (nd == 0)
        return 0;
    const size_t mo = (size_t)cm->n_outputs + 1, ND = (size_t)nd;
    double *mem = malloc((2 * mo + 3 * 2 * mo + 2 * ND * 2 * mo + ND * ND + ND) * sizeof *mem);
    int *hol = malloc(mo * sizeof *hol);
    if (!mem || !hol) {
        free(mem);
        free(hol);
        snprintf(err, errlen, "out of memory");
        return DYN_ERR_ARG;
    }
    double *h = mem, *f = h + mo, *c = f + mo, *cp = c + 2 * mo, *cm2 = cp + 2 * mo,
           *J = cm2 + 2 * mo, *H = J + ND * 2 * mo, *d = H + ND * ND;
    int rc = 0, k = values(cm, par, t, y, h, f, hol, c);
    if (k != nd) {
        snprintf(err, errlen, "%d constraint values for %d dependent states", k, nd);
        rc = DYN_ERR_ARG;
    }
    double cn = INFINITY;
    for (int it = 0; it < 50 && !rc; it++) {
        double now = 0.0;
        for (int i = 0; i < nd; i++)
            now = fmax(now, fabs(c[i]));
        if (!(now < cn) || now == 0.0)
            break; /* stopped decreasing: at its rounding */
        cn = now;
        for (int j = 0; j < nd && !rc; j++) {
            const double yj = y[dep[j]];
            int ex;
            frexp(fmax(fabs(yj), 1.0), &ex);
            const double step = ldexp(1.0, ex - 21);
            y[dep[j]] = yj + step;
            const int a = values(cm, par, t, y, h, f, hol, cp);
            y[dep[j]] = yj - step;
            const int b = values(cm, par, t, y, h, f, hol, cm2);
            y[dep[j]] = yj;
            if (a != nd || b != nd)
                rc = DYN_ERR_ARG;
            for (int i = 0; i < nd && !rc; i++)
                J[(size_t)i * ND + (size_t)j] = (cp[i] - cm2[i]) / (2.0 * step);
        }
        if (rc) {
            snprintf(err, errlen, "the constraints' values fail");
            break;
        }
        for (int a = 0; a < nd; a++) {
            double g = 0.0;
            for (int l = 0; l < nd; l++)
                g += J[(size_t)l * ND + (size_t)a] * c[l];
            d[a] = -g;
            for (int b = 0; b <= a; b++) {
                double s = 0.0;
                for (int l = 0; l < nd; l++)
                    s += J[(size_t)l * ND + (size_t)a] * J[(size_t)l * ND + (size_t)b];
                H[(size_t)a * ND + (size_t)b] = H[(size_t)b * ND + (size_t)a] = s;
            }
        }
        if (dyn_cholesky_factor(nd, H)) {
            snprintf(err, errlen, "the constraints do not determine the dependent states");
            rc = DYN_ERR_ARG;
            break;
        }
        dyn_cholesky_solve(nd, H, d);
        for (int j = 0; j < nd; j++)
            y[dep[j]] += d[j];
        values(cm, par, t, y, h, f, hol, c);
    }
    free(mem);
    free(hol);
    return rc;
}
