/* SPDX-License-Identifier: BSD-3-Clause */
/* peer_gsl.c — GSL's odeiv2 as a peer in the benchmark suite (suite.h).
 *
 * Measures, on the same right-hand sides as every other solver:
 * - fixed step: gsl_odeiv2_step_rk4 through gsl_odeiv2_step_apply. It is not plain RK4: it
 *   takes one step of h and two of h/2, returns the two half steps and estimates the error
 *   from the difference (11 right-hand-side calls per step). So it is timed twice: at the
 *   suite's step h (equal step), and at 2h, where its result is RK4's at h (equal accuracy).
 *   GSL has no explicit Euler or Heun method (its rk2 is an embedded 2(3) pair).
 * - adaptive: rk2 (Kutta's 3rd-order formula with a 2nd-order estimate), rkf45, rkck and
 *   rk8pd through gsl_odeiv2_driver (standard control, epsabs = epsrel = tol: the error of
 *   every component against tol (1 + |y_i|), maximum norm), first step BENCH_GSL_H0.
 * - stiff: msbdf (variable-order BDF with the analytic Jacobian) through the driver.
 * GSL is GPL-3: it is linked into the benchmark program only, never into the library.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_version.h>

#include "suite.h"

typedef struct gsl_ctx {
    const bench_sys *sys;
    gsl_odeiv2_system gs;
    const gsl_odeiv2_step_type *type;
    gsl_odeiv2_step *step;     /* fixed step */
    double *yerr;              /* (n) fixed step */
    gsl_odeiv2_driver *driver; /* adaptive, for tolerance tol */
    double tol, h0;
    long calls, jac_calls;
} gsl_ctx;

/* Right-hand sides: plain ones for the fixed-step timing, counting ones (params = ctx) for
 * the adaptive runs. */
#define GSL_RHS(NAME, EVAL, PAR_T)                                                                 \
    static int NAME(double t, const double y[], double dydt[], void *params)                       \
    {                                                                                              \
        (void)t;                                                                                   \
        EVAL(y, dydt, (const PAR_T *)params);                                                      \
        return GSL_SUCCESS;                                                                        \
    }                                                                                              \
    static int NAME##_counted(double t, const double y[], double dydt[], void *params)             \
    {                                                                                              \
        gsl_ctx *x = params;                                                                       \
        (void)t;                                                                                   \
        x->calls++;                                                                                \
        EVAL(y, dydt, (const PAR_T *)x->sys->par);                                                 \
        return GSL_SUCCESS;                                                                        \
    }
GSL_RHS(gsl_vdp, bench_vdp_eval, bench_vdp_par)
GSL_RHS(gsl_plane, bench_plane_eval, bench_plane_par)
GSL_RHS(gsl_arenstorf, bench_arenstorf_eval, bench_arenstorf_par)

static int gsl_vdp_jac(double t, const double y[], double *dfdy, double dfdt[], void *params)
{
    gsl_ctx *x = params;
    (void)t;
    x->jac_calls++;
    bench_vdp_jac(y, dfdy, x->sys->par);
    dfdt[0] = dfdt[1] = 0.0;
    return GSL_SUCCESS;
}

static void gsl_destroy(void *vctx)
{
    gsl_ctx *x = vctx;
    if (!x)
        return;
    if (x->step)
        gsl_odeiv2_step_free(x->step);
    if (x->driver)
        gsl_odeiv2_driver_free(x->driver);
    free(x->yerr);
    free(x);
}

static int gsl_fixed_run(void *vctx, double h, long steps, double *y, bench_counts *counts)
{
    gsl_ctx *x = vctx;
    const int n = x->sys->n;
    memcpy(y, x->sys->y0, (size_t)n * sizeof *y);
    gsl_odeiv2_step_reset(x->step);
    double t = x->sys->t0;
    for (long k = 0; k < steps; k++) {
        if (gsl_odeiv2_step_apply(x->step, t, h, y, x->yerr, NULL, NULL, &x->gs) != GSL_SUCCESS)
            return 1;
        t = x->sys->t0 + (double)(k + 1) * h;
    }
    if (counts) {
        counts->rhs = 11 * steps;
        counts->jac = 0;
        counts->steps = steps;
    }
    return 0;
}

static int gsl_adaptive_run(void *vctx, double tol, long steps, double *y, bench_counts *counts)
{
    gsl_ctx *x = vctx;
    (void)steps;
    if (!x->driver || x->tol != tol) { /* allocated at the untimed first run of a tolerance */
        if (x->driver)
            gsl_odeiv2_driver_free(x->driver);
        x->driver = gsl_odeiv2_driver_alloc_y_new(&x->gs, x->type, x->h0, tol, tol);
        if (!x->driver)
            return 1;
        x->tol = tol;
    } else {
        gsl_odeiv2_driver_reset_hstart(x->driver, x->h0);
    }
    x->calls = x->jac_calls = 0;
    memcpy(y, x->sys->y0, (size_t)x->sys->n * sizeof *y);
    double t = x->sys->t0;
    const int rc = gsl_odeiv2_driver_apply(x->driver, &t, x->sys->t1, y);
    if (counts) {
        counts->rhs = x->calls;
        counts->jac = x->jac_calls;
        counts->steps = (long)(x->driver->e->count - x->driver->e->failed_steps);
    }
    return rc != GSL_SUCCESS || t != x->sys->t1;
}

static gsl_ctx *gsl_new(const bench_sys *sys, const gsl_odeiv2_step_type *type, int counted)
{
    gsl_ctx *x = calloc(1, sizeof *x);
    if (!x)
        return NULL;
    x->sys = sys;
    x->type = type;
    x->gs.dimension = (size_t)sys->n;
    x->gs.params = counted ? (void *)x : (void *)sys->par;
    switch (sys->id) {
    case BENCH_VDP: x->gs.function = counted ? gsl_vdp_counted : gsl_vdp; break;
    case BENCH_VDP_STIFF:
        x->gs.function = counted ? gsl_vdp_counted : gsl_vdp;
        x->gs.jacobian = counted ? gsl_vdp_jac : NULL;
        break;
    case BENCH_PLANE: x->gs.function = counted ? gsl_plane_counted : gsl_plane; break;
    case BENCH_ARENSTORF: x->gs.function = counted ? gsl_arenstorf_counted : gsl_arenstorf; break;
    case BENCH_KEPLER: free(x); return NULL; /* dynkit's controllers only: no peer runs it */
    }
    x->h0 = sys->id == BENCH_VDP_STIFF ? 1e-6 : 1e-3;
    return x;
}

static int add(bench_solver *out, int *count, int max, gsl_ctx *x, const char *label, int flags,
               int order, double factor, double calls_per_step, const char *note,
               int (*run)(void *, double, long, double *, bench_counts *))
{
    if (!x)
        return 1;
    if (*count >= max) {
        gsl_destroy(x);
        return 1;
    }
    bench_solver *s = &out[(*count)++];
    memset(s, 0, sizeof *s);
    snprintf(s->label, sizeof s->label, "%s", label);
    snprintf(s->note, sizeof s->note, "%s", note ? note : "");
    s->peer = "GSL";
    s->flags = flags;
    s->order = order;
    s->step_factor = factor;
    s->calls_per_step = calls_per_step;
    s->ctx = x;
    s->run = run;
    s->destroy = gsl_destroy;
    return 0;
}

static int gsl_solvers(const bench_sys *sys, bench_task task, bench_method m, bench_solver *out,
                       int max)
{
    int count = 0;
    gsl_set_error_handler_off();
    if (task == BENCH_TASK_FIXED) {
        if (m != BENCH_RK4)
            return 0;
        for (int twice = 0; twice < 2; twice++) {
            gsl_ctx *x = gsl_new(sys, gsl_odeiv2_step_rk4, 0);
            if (x) {
                x->step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk4, (size_t)sys->n);
                x->yerr = malloc((size_t)sys->n * sizeof *x->yerr);
                if (!x->step || !x->yerr) {
                    gsl_destroy(x);
                    x = NULL;
                }
            }
            if (add(out, &count, max, x,
                    twice ? "GSL rk4 at 2h (equal accuracy)" : "GSL rk4 at h (equal step)",
                    twice ? BENCH_ACCURACY : 0, 4, twice ? 2.0 : 1.0, 11.0,
                    twice ? NULL
                          : "gsl_odeiv2_step_rk4 takes a step of h and two of h/2 and returns "
                            "the two half steps (11 calls per step, the accuracy of RK4 at h/2); "
                            "at 2h it computes RK4's result at h",
                    gsl_fixed_run))
                break;
        }
        return count;
    }
    if (task == BENCH_TASK_ADAPTIVE) {
        const struct {
            const char *label;
            const gsl_odeiv2_step_type *const *type;
            int order;
        } list[] = {{"GSL rk2 (3rd order)", &gsl_odeiv2_step_rk2, 3},
                    {"GSL rkf45", &gsl_odeiv2_step_rkf45, 5},
                    {"GSL rkck", &gsl_odeiv2_step_rkck, 5},
                    {"GSL rk8pd", &gsl_odeiv2_step_rk8pd, 8}};
        for (size_t i = 0; i < sizeof list / sizeof list[0]; i++)
            if (add(out, &count, max, gsl_new(sys, *list[i].type, 1), list[i].label, 0,
                    list[i].order, 1.0, 0.0, NULL, gsl_adaptive_run))
                break;
        return count;
    }
    if (task == BENCH_TASK_STIFF && sys->id == BENCH_VDP_STIFF)
        add(out, &count, max, gsl_new(sys, gsl_odeiv2_step_msbdf, 1),
            "GSL msbdf (BDF, analytic Jacobian)", 0, 5, 1.0, 0.0, NULL, gsl_adaptive_run);
    return count;
}

static const char *peer_version(void) { return "GSL " GSL_VERSION " (odeiv2)"; }

const bench_peer bench_peer_gsl = {"gsl", peer_version, gsl_solvers};
