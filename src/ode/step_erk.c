/* SPDX-License-Identifier: BSD-3-Clause */
/* The explicit Runge–Kutta stepper of the general driver: fixed-step tables and embedded
 * pairs through the one stage loop (rk_stages.h), with
 * - the local error estimate h sum e_i k_i in Hairer's norm, or DOP853's combination of its
 *   5th- and 3rd-order estimates (HNW I sec. II.10; dop853.f);
 * - FSAL: the last stage of bs23 and dp45 is f(t + h, y_{n+1}) and becomes the next step's
 *   first; tables without FSAL compute f(t + h, y_{n+1}) only when it is needed (dense
 *   output, stiffness test) and then reuse it as the next step's first stage, so no
 *   evaluation is wasted (the stage loop skips stage 0 when k[0] holds it already);
 * - dense output in Hairer's nested form (dyn_dense): the cubic Hermite interpolant of y_n,
 *   y_{n+1}, f_n, f_{n+1}, plus the table's corrections (dp45: one, DOP853: four, with its
 *   three extra stages) (HNW I sec. II.6; DOPRI5's and DOP853's dense output);
 * - stiffness: |h lambda| ~ h |f(Y_j) - f(y_{n+1})| / |Y_j - y_{n+1}| for a stage j at
 *   c = 1, as in DOPRI5 and DOP853 (HNW I sec. IV.2).
 */
#include <math.h>
#include <string.h>

#include "dynkit/solve_inline.h" /* dyn_sinl_stiffness, dyn_sinl_dense */
#include "ode/rosenbrock.h"
#include "ode/stepper.h"

/* Stage slots: the table's stages, f(t + h, ynew) at slot s for tables without FSAL, and
 * the extra stages of the dense output. */
static int kslots(const dyn_tableau *m)
{
    int k = m->fsal ? m->stages : m->stages + 1;
    return m->dense_stages > k ? m->dense_stages : k;
}

static size_t erk_work_size(const dyn_tableau *m, int n, const dyn_jac_shape *shape)
{
    (void)shape;
    return ((size_t)kslots(m) + 2) * (size_t)n;
}

static size_t erk_iwork_size(const dyn_tableau *m, int n)
{
    (void)m;
    (void)n;
    return 0;
}

static int erk_dense_degree(const dyn_tableau *m)
{
    return m->dense_degree > 3 && m->dense ? m->dense_degree : 3;
}

static int erk_start(dyn_stepper *st, double t0, const double *y0)
{
    (void)t0;
    (void)y0;
    dyn_erk_state *e = &st->u.erk;
    const dyn_tableau *m = st->m;
    const int n = st->n;
    e->kslots = kslots(m);
    e->k = st->work;
    e->Y = e->k + (size_t)e->kslots * (size_t)n;
    e->tmp = e->Y + n;
    e->planned = dyn_rk_plan_init(&e->plan, m, e->k, n);
    e->k0_valid = 0;
    e->fnew_valid = 0;
    e->ne = e->ne3 = 0;
    for (int i = 0; i < m->stages && i < DYN_RK_PLAN_MAX_STAGES; i++) {
        const double *ki = e->k + (size_t)i * (size_t)n;
        if (m->e && m->e[i] != 0.0) {
            e->ec[e->ne] = m->e[i];
            e->ekp[e->ne++] = ki;
        }
        if (m->e3 && m->e3[i] != 0.0) {
            e->e3c[e->ne3] = m->e3[i];
            e->e3kp[e->ne3++] = ki;
        }
    }
    return 0;
}

/* Evaluate f into dst, counting it. */
static int eval(dyn_stepper *st, double t, const double *y, double *dst)
{
    st->rhs_calls++;
    int rc = st->f(t, y, dst, st->par);
    if (rc)
        st->fail_t = t;
    return rc;
}

static int erk_deriv(dyn_stepper *st, double t, const double *y, const double **f)
{
    dyn_erk_state *e = &st->u.erk;
    if (!e->k0_valid) {
        int rc = eval(st, t, y, e->k);
        if (rc)
            return rc;
        e->k0_valid = 1;
    }
    *f = e->k;
    return 0;
}

/* Sum of (err_i / scale_i)^2 over the states, err_i = sum_q c[q] kp[q][i] summed in order,
 * and likewise *s3out for the terms c3, kp3 when n3 > 0. Every sum starts from -0.0, which
 * is the same as starting from its first term (-0.0 + x == x for every x, +0.0 included),
 * so the compiler drops the addition, one of the error's chain. Inlined with a constant
 * scalar: 1 (no per-state tolerances) takes dyn_tol_scale's per-state tests out of the
 * loop; the same numbers either way. */
DYN_RK_INLINE double err_sums(const dyn_tol *tol, int scalar, int n, const double *y,
                              const double *ynew, int ne, const double *c,
                              const double *const *kp, int n3, const double *c3,
                              const double *const *kp3, double *s3out)
{
    double s5 = -0.0, s3 = -0.0;
    for (int i = 0; i < n; i++) {
        double err = -0.0;
        for (int q = 0; q < ne; q++)
            err += c[q] * kp[q][i];
        const double sk = scalar ? tol->atol + tol->rtol * fmax(fabs(y[i]), fabs(ynew[i]))
                                 : dyn_tol_scale(tol, i, y[i], ynew[i]);
        const double r = err / sk;
        s5 += r * r;
        if (n3) {
            double err3 = -0.0;
            for (int q = 0; q < n3; q++)
                err3 += c3[q] * kp3[q][i];
            const double r3 = err3 / sk;
            s3 += r3 * r3;
        }
    }
    *s3out = s3;
    return s5;
}

/* The square of the error norm of the step from the stage derivatives (dyn_sinl_err of
 * dynkit/solve_inline.h computes the same, term for term). */
static double erk_error(dyn_stepper *st, double h, const double *y, const double *ynew)
{
    const dyn_erk_state *e = &st->u.erk;
    const int n = st->n;
    double s3 = 0.0, s5;
    if (!st->tol.rtolv && !st->tol.atolv)
        s5 = err_sums(&st->tol, 1, n, y, ynew, e->ne, e->ec, e->ekp, e->ne3, e->e3c, e->e3kp,
                      &s3);
    else
        s5 = err_sums(&st->tol, 0, n, y, ynew, e->ne, e->ec, e->ekp, e->ne3, e->e3c, e->e3kp,
                      &s3);
    if (!e->ne3)
        return h * h * (s5 / n); /* (|h| sqrt(s5 / n))^2 */
    /* DOP853: (|h| |E5|^2 / sqrt(n (|E5|^2 + 0.01 |E3|^2)))^2, h^2 |E5|^2 formed while the
     * denominator is (one division and one multiplication after it). A square that
     * overflows (a norm above 1e154) is rejected as a non-finite one is: h / 4. */
    if (s5 == 0.0 && s3 == 0.0)
        return 0.0;
    return h * h * s5 * (s5 / ((s5 + 0.01 * s3) * n));
}

static int erk_attempt(dyn_stepper *st, double t, double h, const double *y, double *ynew,
                       double *err, int retry)
{
    (void)retry; /* k[0] = f(t, y) stays valid after a rejection */
    dyn_erk_state *e = &st->u.erk;
    const dyn_tableau *m = st->m;
    const int n = st->n;
    int fail_stage = 0, rc;
    double finite = 0.0;
    const dyn_trace_fn trace = st->attempts < st->trace_steps ? st->trace : NULL;
    /* stage 0 is not evaluated when k[0] holds f(t, y) already (FSAL, or f(t + h, ynew)
     * computed for the dense output) */
    const int first = e->k0_valid && m->c[0] == 0.0;
    if (e->planned)
        rc = dyn_rk_stages_from(m, &e->plan, st->f, st->par, n, t, h, st->tend, y, ynew, e->k,
                                e->Y, &fail_stage, &finite, trace, st->trace_ctx, st->attempts,
                                first);
    else
        rc = dyn_rk_stages_scan_from(m, st->f, st->par, n, t, h, st->tend, y, ynew, e->k, e->Y,
                                     &fail_stage, &finite, trace, st->trace_ctx, st->attempts,
                                     first);
    st->attempts++;
    st->rhs_calls += (rc ? fail_stage + 1 : m->stages) - first; /* the calls made */
    e->fnew_valid = 0;
    if (rc) {
        st->fail_t = dyn_rk_stage_time(t, m->c[fail_stage], h, st->tend);
        e->k0_valid = fail_stage > 0; /* stage 0 was f(t, y) */
        return rc;
    }
    e->k0_valid = 1;
    if (finite != 0.0) {
        *err = INFINITY;
        return 0;
    }
    *err = m->e ? erk_error(st, h, y, ynew) : 0.0;
    return 0;
}

/* f(t + h, ynew) of the accepted step: the FSAL stage, or slot s evaluated once. */
static int fnew(dyn_stepper *st, double t, double h, const double *ynew, const double **out)
{
    dyn_erk_state *e = &st->u.erk;
    const dyn_tableau *m = st->m;
    const int n = st->n;
    if (m->fsal) {
        *out = e->k + (size_t)(m->stages - 1) * (size_t)n;
        return 0;
    }
    double *slot = e->k + (size_t)m->stages * (size_t)n;
    if (!e->fnew_valid) {
        const double t1 = t + h > st->tend ? st->tend : t + h;
        int rc = eval(st, t1, ynew, slot);
        if (rc)
            return rc;
        e->fnew_valid = 1;
    }
    *out = slot;
    return 0;
}

/* DOPRI5's |h lambda| (dyn_sinl_stiffness of dynkit/solve_inline.h: one copy for both
 * drivers), with f(t + h, ynew) from fnew. */
static double erk_stiffness(dyn_stepper *st, double t, double h, const double *y,
                            const double *ynew)
{
    dyn_erk_state *e = &st->u.erk;
    const dyn_tableau *m = st->m;
    const int j = m->stiff_stage;
    if (!(m->stiff_bound > 0.0) || j < 0 || j >= m->stages || m->c[j] != 1.0)
        return -1.0;
    const double *f1;
    if (fnew(st, t, h, ynew, &f1))
        return -1.0;
    return dyn_sinl_stiffness(m, st->n, h, e->k, f1, y, ynew, e->tmp);
}

/* The step's dense output (dyn_sinl_dense of dynkit/solve_inline.h: one copy for both
 * drivers): f(t + h, ynew) in slot s for a table without FSAL, then the extra stages. */
static int erk_dense(dyn_stepper *st, double t, double h, const double *y, const double *ynew,
                     double *coef)
{
    dyn_erk_state *e = &st->u.erk;
    return dyn_sinl_dense(st->m, erk_dense_degree(st->m), st->n, t, h, st->tend, st->f, st->par,
                          e->k, e->Y, &e->fnew_valid, y, ynew, coef, &st->rhs_calls,
                          &st->fail_t);
}

static void erk_accept(dyn_stepper *st, double t, double h, const double *ynew)
{
    (void)t;
    (void)h;
    (void)ynew;
    dyn_erk_state *e = &st->u.erk;
    const dyn_tableau *m = st->m;
    const size_t N = (size_t)st->n;
    if (m->fsal) {
        memcpy(e->k, e->k + (size_t)(m->stages - 1) * N, N * sizeof *e->k);
        e->k0_valid = 1;
    } else if (e->fnew_valid) {
        memcpy(e->k, e->k + (size_t)m->stages * N, N * sizeof *e->k);
        e->k0_valid = 1;
    } else {
        e->k0_valid = 0;
    }
    e->fnew_valid = 0;
}

static const dyn_stepper_ops erk_ops = {
    .work_size = erk_work_size,
    .iwork_size = erk_iwork_size,
    .dense_degree = erk_dense_degree,
    .start = erk_start,
    .deriv = erk_deriv,
    .attempt = erk_attempt,
    .stiffness = erk_stiffness,
    .dense = erk_dense,
    .accept = erk_accept,
    .err_squared = 1,
};

const dyn_stepper_ops *dyn_stepper_ops_for(const dyn_tableau *m)
{
    if (!m)
        return NULL;
    switch (m->kind) {
    case DYN_KIND_EXPLICIT_RK:
        return &erk_ops;
    case DYN_KIND_EMBEDDED_RK:
        return m->e ? &erk_ops : NULL;
    case DYN_KIND_ROSENBROCK:
        return m->impl ? &dyn_ros_stepper_ops : NULL;
    default:
        return NULL;
    }
}
