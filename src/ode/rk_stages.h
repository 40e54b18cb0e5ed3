/* The one stage loop of every explicit Runge–Kutta method (private to the library).
 *
 * For stage i: Y_i = y_n + h * sum_{j<i} a_ij k_j, k_i = f(t_n + c_i h, Y_i);
 * then y_{n+1} = y_n + h * sum_i b_i k_i (Hairer, Nørsett & Wanner I, eq. II.1.8).
 * Zero coefficients are skipped, so the sums are exactly the textbook formulas: Euler is
 * y + h*k1 and Heun y + h*(k1 + k2)/2 bit for bit, as in the homework's MATLAB code.
 * Static inline so that the driver gets a trace-free copy with the trace branch removed.
 */
#ifndef DYNKIT_SRC_ODE_RK_STAGES_H
#define DYNKIT_SRC_ODE_RK_STAGES_H

#include "dynkit/ode.h"

/* Workspace layout (doubles): k (stages x n) | Y (n) | two spare states (n each). */
#define DYN_RK_WORK(stages, n) ((size_t)((stages) + 3) * (size_t)(n))

/* Take one step from (t, y) of size h into ynew (distinct from y). Returns 0, or the
 * non-zero value of f with the failing stage index in *fail_stage. */
static inline int dyn_rk_stages(const dyn_tableau *m, dyn_rhs_fn f, void *par, int n,
                                double t, double h, const double *restrict y,
                                double *restrict ynew, double *restrict k,
                                double *restrict Y, int *fail_stage, dyn_trace_fn trace,
                                void *trace_ctx, long step_index)
{
    const int s = m->stages;
    const double *a = m->a, *b = m->b, *c = m->c;
    dyn_trace_stage ts;
    if (trace) {
        ts.method = m;
        ts.step = step_index;
        ts.t_n = t;
        ts.h = h;
        ts.n = n;
        ts.y_n = y;
    }
    for (int i = 0; i < s; i++) {
        const double *ai = a + (size_t)i * (size_t)s;
        const double *Yi = y;
        if (i > 0) {
            for (int q = 0; q < n; q++) {
                double acc = 0.0;
                for (int j = 0; j < i; j++)
                    if (ai[j] != 0.0)
                        acc += ai[j] * k[(size_t)j * (size_t)n + (size_t)q];
                Y[q] = y[q] + h * acc;
            }
            Yi = Y;
        }
        double *ki = k + (size_t)i * (size_t)n;
        int rc = f(t + c[i] * h, Yi, ki, par);
        if (rc) {
            *fail_stage = i;
            return rc;
        }
        if (trace) {
            ts.stage = i;
            ts.t_stage = t + c[i] * h;
            ts.Y = Yi;
            ts.k = ki;
            trace(&ts, trace_ctx);
        }
    }
    for (int q = 0; q < n; q++) {
        double acc = 0.0;
        for (int j = 0; j < s; j++)
            if (b[j] != 0.0)
                acc += b[j] * k[(size_t)j * (size_t)n + (size_t)q];
        ynew[q] = y[q] + h * acc;
    }
    if (trace) {
        ts.stage = s;
        ts.t_stage = t + h;
        ts.Y = ynew;
        ts.k = NULL;
        trace(&ts, trace_ctx);
    }
    return 0;
}

#endif
