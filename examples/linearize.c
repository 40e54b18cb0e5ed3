/* SPDX-License-Identifier: BSD-3-Clause */
/* The analysis API (dynkit/analysis.h) on a built-in model: the pendulum's equilibria found
 * from guesses (dyn_equilibrium), linearized there by extrapolated differences (the
 * pendulum has no analytic Jacobian: dyn_linearize), the eigenvalues by LAPACK's dgeev
 * (dynkit/lapack.h, the optional backend dynkit_lapack) and the stability, for a rod of
 * l = 2 m. At the bottom the eigenvalues are +-i sqrt(g/l), at the top +-sqrt(g/l); the
 * program prints both and exits
 * 1 when either differs from the closed form by more than 1e-12 relative.
 * Build: cc linearize.c -ldynkit_lapack -ldynkit -llapack -lm (or CMake's dynkit::lapack). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/analysis.h"
#include "dynkit/lapack.h"
#include "dynkit/models.h"

/* Equilibrium near guess y, linearization and eigenvalues; 0 or 1 (message printed). */
static int analyse(const dyn_model *m, void *par, double *y, double *re, double *im,
                   dyn_stability *s)
{
    double A[4], B[4], work[64];
    char err[256];
    dyn_equilibrium_info eq;
    dyn_linearize_info li;
    if (dyn_equilibrium(m, 0.0, y, par, NULL, work, &eq)) {
        fprintf(stderr, "equilibrium: %s\n", eq.message);
        return 1;
    }
    if (dyn_linearize(m, 0.0, y, par, NULL, A, work, &li)) {
        fprintf(stderr, "linearize: %s\n", li.message);
        return 1;
    }
    memcpy(B, A, sizeof A); /* dgeev overwrites its matrix */
    if (dyn_eig_solver_lapack.eigenvalues(2, B, re, im, err, sizeof err)) {
        fprintf(stderr, "eigenvalues: %s\n", err);
        return 1;
    }
    dyn_eig_sort(2, re, im);
    *s = dyn_classify(2, re, dyn_stability_tol(2, A, 0.0));
    printf("phi = %.15f rad after %d iterations: eigenvalues %.15g %+.15gi, %.15g %+.15gi: "
           "%s\n",
           y[0], eq.iterations, re[0], im[0], re[1], im[1], dyn_stability_name(*s));
    return 0;
}

int main(void)
{
    const dyn_model *m = &dyn_model_pendulum;
    char par[256], err[256];
    if (m->par_size > sizeof par || dyn_model_default_params(m, par, err, sizeof err)) {
        fprintf(stderr, "pendulum: %s\n", err);
        return 1;
    }
    dyn_model_set_param(m, par, dyn_model_param_index(m, "l"), 2.0); /* a 2 m rod */
    if (m->prepare && m->prepare(par, err, sizeof err)) {
        fprintf(stderr, "pendulum: %s\n", err);
        return 1;
    }
    const double w = sqrt(9.81 / 2.0); /* sqrt(g/l) */
    double bottom[2] = {0.5, 0.2}, top[2] = {2.8, 0.0}, re[2], im[2];
    dyn_stability s;
    int bad = analyse(m, par, bottom, re, im, &s);
    bad |= s != DYN_MARGINAL || fabs(im[1] - w) > 1e-12 * w || fabs(im[0] + w) > 1e-12 * w;
    bad |= analyse(m, par, top, re, im, &s);
    bad |= s != DYN_UNSTABLE || fabs(re[1] - w) > 1e-12 * w || fabs(re[0] + w) > 1e-12 * w;
    printf("closed form: +-i %.15g at the bottom, +-%.15g at the top%s\n", w, w,
           bad ? ": DIFFERENT" : "");
    return bad;
}
