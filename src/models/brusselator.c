/* SPDX-License-Identifier: BSD-3-Clause */
/* The 1-D Brusselator with diffusion (dynkit/brusselator.h): Hairer & Wanner, "Solving
 * ODEs II", sec. IV.10, problem BRUSS, with interleaved states (u1, v1, u2, v2, ...).
 * One model per N, allocated in one block (model, names, states, parameters, y0). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/brusselator.h"
#include "dynkit/solve.h"

/* Boundary values of the reference problem. */
#define U_EDGE 1.0
#define V_EDGE 3.0

int dyn_brusselator_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_brusselator_par *p = par;
    (void)t;
    const int N = (int)p->N;
    const double c = p->alpha * (p->N + 1.0) * (p->N + 1.0), A = p->A, B = p->B;
    for (int i = 0; i < N; i++) {
        const double u = y[2 * i], v = y[2 * i + 1];
        const double ul = i > 0 ? y[2 * i - 2] : U_EDGE, ur = i < N - 1 ? y[2 * i + 2] : U_EDGE;
        const double vl = i > 0 ? y[2 * i - 1] : V_EDGE, vr = i < N - 1 ? y[2 * i + 3] : V_EDGE;
        const double uuv = u * u * v;
        dydt[2 * i] = A + uuv - (B + 1.0) * u + c * (ul - 2.0 * u + ur);
        dydt[2 * i + 1] = B * u - uuv + c * (vl - 2.0 * v + vr);
    }
    return 0;
}

/* Entry (r, s) of the Jacobian through put, for every non-zero of the band. */
#define BRUSS_JAC(put)                                                                       \
    do {                                                                                     \
        const dyn_brusselator_par *p = par;                                                  \
        const int N = (int)p->N;                                                             \
        const double c = p->alpha * (p->N + 1.0) * (p->N + 1.0), B = p->B;                   \
        for (int i = 0; i < N; i++) {                                                        \
            const double u = y[2 * i], v = y[2 * i + 1];                                     \
            const int r = 2 * i;                                                             \
            put(r, r, 2.0 * u * v - (B + 1.0) - 2.0 * c);                                    \
            put(r, r + 1, u * u);                                                            \
            put(r + 1, r, B - 2.0 * u * v);                                                  \
            put(r + 1, r + 1, -u * u - 2.0 * c);                                             \
            if (i > 0) {                                                                     \
                put(r, r - 2, c);                                                            \
                put(r + 1, r - 1, c);                                                        \
            }                                                                                \
            if (i < N - 1) {                                                                 \
                put(r, r + 2, c);                                                            \
                put(r + 1, r + 3, c);                                                        \
            }                                                                                \
        }                                                                                    \
    } while (0)

int dyn_brusselator_jac_band(double t, const double *y, double *J, void *par)
{
    (void)t;
    const size_t n = 2 * (size_t)((const dyn_brusselator_par *)par)->N;
    memset(J, 0, n * 5 * sizeof *J);
#define PUT_BAND(i, j, v) DYN_BAND_AT(J, 2, 2, i, j) = (v)
    BRUSS_JAC(PUT_BAND);
#undef PUT_BAND
    return 0;
}

int dyn_brusselator_jac(double t, const double *y, double *J, void *par)
{
    (void)t;
    const size_t n = 2 * (size_t)((const dyn_brusselator_par *)par)->N;
    memset(J, 0, n * n * sizeof *J);
#define PUT_DENSE(i, j, v) J[(size_t)(i) * n + (size_t)(j)] = (v)
    BRUSS_JAC(PUT_DENSE);
#undef PUT_DENSE
    return 0;
}

static int bruss_prepare(void *par, char *err, size_t errlen)
{
    const dyn_brusselator_par *p = par;
    if (!(p->N >= 1.0 && p->N <= DYN_BRUSSELATOR_MAX_N && p->N == floor(p->N))) {
        snprintf(err, errlen, "N must be an integer in [1, %d] (got %g)", DYN_BRUSSELATOR_MAX_N,
                 p->N);
        return 1;
    }
    return dyn_check_positive("B", p->B, err, errlen) ||
           dyn_check_positive("alpha", p->alpha, err, errlen) ||
           dyn_check_positive("A", p->A, err, errlen);
}

static void bruss_initial_state(const void *par, double *y0)
{
    const dyn_brusselator_par *p = par;
    const int N = (int)p->N;
    for (int i = 0; i < N; i++) {
        y0[2 * i] = 1.0 + sin(2.0 * DYN_PI * (i + 1) / (p->N + 1.0));
        y0[2 * i + 1] = 3.0;
    }
}

/* One allocation: the model, its states, parameters, y0 and the states' names. */
typedef struct bruss_block {
    dyn_model model;
    dyn_param params[4];
    char title[96];
} bruss_block;

enum { NAME_BYTES = 10 }; /* "u1000000" and its NUL */

dyn_model *dyn_brusselator_new(int N, char *err, size_t errlen)
{
    if (N < 1 || N > DYN_BRUSSELATOR_MAX_N) {
        if (err && errlen)
            snprintf(err, errlen, "the Brusselator's N must be an integer in [1, %d] (got %d)",
                     DYN_BRUSSELATOR_MAX_N, N);
        return NULL;
    }
    const size_t n = 2 * (size_t)N;
    const size_t bytes =
        sizeof(bruss_block) + n * (sizeof(dyn_var) + sizeof(double) + NAME_BYTES);
    bruss_block *b = calloc(1, bytes);
    if (!b) {
        if (err && errlen)
            snprintf(err, errlen, "out of memory for the Brusselator with N = %d", N);
        return NULL;
    }
    dyn_var *states = (dyn_var *)(b + 1);
    double *y0 = (double *)(states + n);
    char *names = (char *)(y0 + n);
    dyn_brusselator_par defaults = {1.0, 3.0, 1.0 / 50.0, (double)N};
    for (size_t k = 0; k < n; k++) {
        char *name = names + k * NAME_BYTES;
        snprintf(name, NAME_BYTES, "%c%zu", k % 2 ? 'v' : 'u', k / 2 + 1);
        states[k].name = name;
        states[k].unit = "1";
        states[k].description = k % 2 ? "concentration v at x_i = i/(N+1)"
                                       : "concentration u at x_i = i/(N+1)";
    }
    bruss_initial_state(&defaults, y0);
    const dyn_param params[4] = {
        {"A", "1", "feed rate", offsetof(dyn_brusselator_par, A), defaults.A},
        {"B", "1", "conversion rate", offsetof(dyn_brusselator_par, B), defaults.B},
        {"alpha", "1", "diffusion coefficient", offsetof(dyn_brusselator_par, alpha),
         defaults.alpha},
        {"N", "1", "interior grid points: the model's size (brusselator:N), fixed",
         offsetof(dyn_brusselator_par, N), defaults.N},
    };
    memcpy(b->params, params, sizeof params);
    snprintf(b->title, sizeof b->title,
             "1-D Brusselator with diffusion, N = %d (%zu states, banded Jacobian)", N, n);
    dyn_model *m = &b->model;
    m->name = "brusselator";
    m->title = b->title;
    m->description =
        "Hairer & Wanner's stiff test problem BRUSS (Solving ODEs II, sec. IV.10): the "
        "Brusselator reaction with diffusion on x in [0, 1], by the method of lines on N "
        "interior points x_i = i/(N+1): u_i' = A + u_i^2 v_i - (B+1) u_i + alpha (N+1)^2 "
        "(u_{i-1} - 2 u_i + u_{i+1}), v_i' = B u_i - u_i^2 v_i + alpha (N+1)^2 (v_{i-1} - "
        "2 v_i + v_{i+1}), u_0 = u_{N+1} = 1, v_0 = v_{N+1} = 3, u_i(0) = 1 + sin(2 pi x_i), "
        "v_i(0) = 3. States interleaved (u1, v1, u2, ...): the Jacobian is banded with two "
        "diagonals below and two above. Choose N with brusselator:N (default 500).";
    m->n_states = (int)n;
    m->states = states;
    m->y0 = y0;
    m->n_params = 4;
    m->params = b->params;
    m->par_size = sizeof(dyn_brusselator_par);
    m->rhs = dyn_brusselator_rhs;
    m->prepare = bruss_prepare;
    m->t0 = 0.0;
    m->t1 = 10.0;
    m->step = 0.1;
    m->method = "rodas4";
    /* dyn_solve's tolerances (MATLAB's ode15s defaults), those its tests were measured at */
    m->rtol = DYN_DEFAULT_RTOL;
    m->atol = DYN_DEFAULT_ATOL;
    m->jacobian = dyn_brusselator_jac;
    m->initial_state = bruss_initial_state;
    m->phase_x = "u1";
    m->phase_y = "v1";
    m->jac_banded = 1;
    m->jac_lower = 2;
    m->jac_upper = 2;
    m->jacobian_band = dyn_brusselator_jac_band;
    return m;
}

dyn_model *dyn_brusselator_for_name(const char *name)
{
    static const char prefix[] = "brusselator";
    const size_t len = sizeof prefix - 1;
    if (!name || strncmp(name, prefix, len) != 0)
        return NULL;
    if (name[len] == '\0')
        return dyn_brusselator_new(DYN_BRUSSELATOR_DEFAULT_N, NULL, 0);
    if (name[len] != ':' || name[len + 1] < '0' || name[len + 1] > '9')
        return NULL;
    char *end = NULL;
    const long N = strtol(name + len + 1, &end, 10);
    if (*end != '\0' || N < 1 || N > DYN_BRUSSELATOR_MAX_N)
        return NULL;
    return dyn_brusselator_new((int)N, NULL, 0);
}

void dyn_brusselator_free(dyn_model *m)
{
    free(m); /* the model is the first member of its block */
}
