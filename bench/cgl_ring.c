/* SPDX-License-Identifier: BSD-3-Clause */
/* The complex Ginzburg-Landau ring of bench/cgl.ode as a C model for dynkit: 128 sites,
 * 256 states u0, v0, u1, v1, ... (A = u + i v), A_t = A + (1 + i a) A_xx - (1 + i b) |A|^2 A,
 * the second difference with d = 1/dx^2, the same parameters and initial state. It has no
 * Jacobian, so stiff methods form it by differences: n = 256 calls of f a Jacobian with
 * dense matrices, or, with a pattern, one call per group of columns
 * (docs/stiff.md, "Sparse Jacobians"):
 *     dynkit run bench/cgl_ring.c --method rodas4 --final --stats
 *     dynkit run bench/cgl_ring.c --method rodas4 --final --stats --jac-pattern probe
 * With CGL_DECLARE_PATTERN defined at the top of the file (a copy of it), the model declares
 * its pattern (dyn_model.jac_pattern) without values, as a C model can.
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include <dynkit/model.h>

#define SITES 128
#define STATES (2 * SITES)

typedef struct cgl_par {
    double a, b, d;
} cgl_par;

static int rhs(double t, const double *y, double *f, void *par)
{
    const cgl_par *c = par;
    (void)t;
    for (int j = 0; j < SITES; j++) {
        const int jp = (j + 1) % SITES, jm = (j + SITES - 1) % SITES;
        const double u = y[2 * j], v = y[2 * j + 1];
        const double lu = y[2 * jp] - 2.0 * u + y[2 * jm];
        const double lv = y[2 * jp + 1] - 2.0 * v + y[2 * jm + 1];
        const double r = u * u + v * v;
        f[2 * j] = u + c->d * lu - c->a * c->d * lv - r * (u - c->b * v);
        f[2 * j + 1] = v + c->d * lv + c->a * c->d * lu - r * (v + c->b * u);
    }
    return 0;
}

static char names[STATES][8];
static dyn_var states[STATES];
static double initial[STATES];
static const dyn_param params[] = {
    {"a", "1", "linear dispersion", offsetof(cgl_par, a), 1.0},
    {"b", "1", "nonlinear dispersion", offsetof(cgl_par, b), -0.5},
    {"d", "1", "1/dx^2 of the second difference", offsetof(cgl_par, d), 64.0},
};

static dyn_model model = {
    .name = "cgl_ring",
    .title = "complex Ginzburg-Landau ring, 128 sites",
    .description = "A_t = A + (1 + i a) A_xx - (1 + i b) |A|^2 A on a ring, A = u + i v.",
    .n_states = STATES,
    .states = states,
    .y0 = initial,
    .n_params = 3,
    .params = params,
    .par_size = sizeof(cgl_par),
    .rhs = rhs,
    .t0 = 0.0,
    .t1 = 10.0,
    .step = 0.1,
    .method = "rodas4",
};

#ifdef CGL_DECLARE_PATTERN
/* column 2m + s holds the rows of sites m - 1, m, m + 1 (sorted) */
static int colptr[STATES + 1], rowind[6 * STATES];

static void declare_pattern(void)
{
    int k = 0;
    for (int col = 0; col < STATES; col++) {
        const int m = col / 2;
        int sites[3] = {(m + SITES - 1) % SITES, m, (m + 1) % SITES};
        for (int p = 0; p < 3; p++) /* sorted */
            for (int q = p + 1; q < 3; q++)
                if (sites[q] < sites[p]) {
                    const int keep = sites[p];
                    sites[p] = sites[q];
                    sites[q] = keep;
                }
        colptr[col] = k;
        for (int q = 0; q < 3; q++) {
            rowind[k++] = 2 * sites[q];
            rowind[k++] = 2 * sites[q] + 1;
        }
    }
    colptr[STATES] = k;
    model.jac_pattern = (dyn_sparse_pattern){STATES, k, colptr, rowind};
}
#endif

const dyn_model *dynkit_model(void)
{
    if (!states[0].name) {
        for (int j = 0; j < SITES; j++) {
            const double x = 2.0 * 3.14159265358979323846 * j / SITES;
            snprintf(names[2 * j], sizeof names[0], "u%d", j);
            snprintf(names[2 * j + 1], sizeof names[0], "v%d", j);
            states[2 * j] = (dyn_var){names[2 * j], "1", "real part of A"};
            states[2 * j + 1] = (dyn_var){names[2 * j + 1], "1", "imaginary part of A"};
            initial[2 * j] = 0.9 * cos(2.0 * x) + 0.1 * cos(5.0 * x);
            initial[2 * j + 1] = 0.9 * sin(2.0 * x);
        }
#ifdef CGL_DECLARE_PATTERN
        declare_pattern();
#endif
    }
    return &model;
}
