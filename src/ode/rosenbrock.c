/* SPDX-License-Identifier: BSD-3-Clause */
/* rosenbrock.c — one step of a linearly implicit Rosenbrock method in the transformed form
 * of Hairer & Wanner, "Solving ODEs II", sec. IV.7, eq. (7.4') (their code RODAS), with an
 * analytic (mended by differences where an entry is not finite) or forward-difference
 * Jacobian and a forward-difference df/dt; the dense output
 * of RODAS (CONTRO), with dense, band (band_lu.c, jacobian_band.c) or sparse matrices (a
 * dyn_sparse_solver: KLU in the backend dynkit_klu; their Jacobian exact or by differences in
 * groups of columns, jacobian_sparse_fd.c); and a simple adaptive loop with RODAS's
 * step-size control (sec. IV.8,
 * with Gustafsson's predictive controller) for tests and reference computations.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "ode/jacobian.h"
#include "ode/linalg.h"
#include "ode/rosenbrock.h"

/* Doubles of J and of W. */
static size_t jac_size(int n, int banded, int lower, int upper)
{
    const size_t N = (size_t)n;
    return banded ? N * (size_t)(lower + upper + 1) : N * N;
}

static size_t lu_size(int n, int banded, int lower, int upper)
{
    const size_t N = (size_t)n;
    return banded ? N * (size_t)(2 * lower + upper + 1) : N * N;
}

size_t dyn_ros_work_size_band(const dyn_ros_method *m, int n, int banded, int lower, int upper)
{
    if (!m || n <= 0 || (banded && (lower < 0 || upper < 0 || lower >= n || upper >= n)))
        return 0;
    const size_t N = (size_t)n;
    return jac_size(n, banded, lower, upper) + lu_size(n, banded, lower, upper) +
           ((size_t)m->stages + 6) * N;
}

size_t dyn_ros_work_size(const dyn_ros_method *m, int n)
{
    return dyn_ros_work_size_band(m, n, 0, 0, 0);
}

void dyn_ros_ws_init(dyn_ros_ws *ws, const dyn_ros_method *m, int n, double *work, int *piv)
{
    dyn_ros_ws_init_band(ws, m, n, 0, 0, 0, work, piv);
}

size_t dyn_ros_work_size_sparse(const dyn_ros_method *m, int n, int nnz)
{
    if (!m || n <= 0 || nnz < n)
        return 0;
    return 2 * (size_t)nnz + ((size_t)m->stages + 6) * (size_t)n;
}

void dyn_ros_ws_init_sparse(dyn_ros_ws *ws, const dyn_ros_method *m, int n,
                            const dyn_sparse_pattern *p, double *work, int *piv)
{
    const size_t N = (size_t)n, nnz = (size_t)p->nnz;
    memset(ws, 0, sizeof *ws);
    ws->n = n;
    ws->s = m->stages;
    ws->pattern = p;
    ws->f0 = work;
    ws->J = ws->f0 + N;
    ws->ft = ws->J + nnz;
    ws->W = ws->ft + N;
    ws->u = ws->W + nnz;
    ws->Y = ws->u + (size_t)m->stages * N;
    ws->fy = ws->Y + N;
    ws->scratch = ws->fy + N;
    ws->piv = piv;
    ws->h_lu = 0.0;
}

void dyn_ros_ws_init_band(dyn_ros_ws *ws, const dyn_ros_method *m, int n, int banded,
                          int lower, int upper, double *work, int *piv)
{
    const size_t N = (size_t)n;
    memset(ws, 0, sizeof *ws);
    ws->n = n;
    ws->s = m->stages;
    ws->banded = banded;
    ws->lower = banded ? lower : 0;
    ws->upper = banded ? upper : 0;
    ws->ldab = banded ? 2 * lower + upper + 1 : 0;
    ws->f0 = work;
    ws->J = ws->f0 + N;
    ws->ft = ws->J + jac_size(n, banded, lower, upper);
    ws->W = ws->ft + N;
    ws->u = ws->W + lu_size(n, banded, lower, upper);
    ws->Y = ws->u + (size_t)m->stages * N;
    ws->fy = ws->Y + N;
    ws->scratch = ws->fy + N;
    ws->piv = piv;
    ws->h_lu = 0.0;
}

int dyn_ros_linearize(const dyn_ros_problem *p, double t, double h, const double *y,
                      dyn_ros_ws *ws, dyn_ros_stats *st)
{
    const dyn_system *sys = &p->sys;
    const int n = sys->n;
    long calls = 0;
    ws->h_lu = 0.0;
    int rc = sys->f(t, y, ws->f0, sys->par);
    st->rhs_calls++;
    if (rc) {
        ws->rhs_status = rc;
        return DYN_ROS_RHS_FAIL;
    }
    st->jac_evals++;
    if (ws->pattern && !p->jac_sparse) {
        rc = dyn_fd_jacobian_sparse(sys, t, y, ws->f0, p->typ, ws->pattern, p->groups,
                                    p->n_groups, ws->J, ws->scratch, &calls);
    } else if (ws->pattern) {
        rc = p->jac_sparse(t, y, ws->J, sys->par);
        if (rc) {
            ws->rhs_status = rc;
            return DYN_ROS_JAC_FAIL;
        }
        rc = dyn_jacobian_sparse_mend(sys, t, y, ws->f0, p->typ, ws->pattern, ws->J,
                                      ws->scratch, &calls, &st->jac_fd_columns);
    } else if (ws->banded && p->jac_band) {
        rc = p->jac_band(t, y, ws->J, sys->par);
        if (rc) {
            ws->rhs_status = rc;
            return DYN_ROS_JAC_FAIL;
        }
        rc = dyn_jacobian_band_mend(sys, t, y, ws->f0, p->typ, ws->lower, ws->upper, ws->J,
                                    ws->scratch, &calls, &st->jac_fd_columns);
    } else if (ws->banded) {
        rc = dyn_fd_jacobian_band(sys, t, y, ws->f0, p->typ, ws->lower, ws->upper, ws->J,
                                  ws->scratch, &calls);
    } else if (p->jac) {
        rc = p->jac(t, y, ws->J, sys->par);
        if (rc) {
            ws->rhs_status = rc;
            return DYN_ROS_JAC_FAIL;
        }
        rc = dyn_jacobian_mend(sys, t, y, ws->f0, p->typ, ws->J, ws->scratch, &calls,
                               &st->jac_fd_columns);
    } else {
        rc = dyn_fd_jacobian(sys, t, y, ws->f0, p->typ, ws->J, ws->scratch, &calls);
    }
    if (!rc) {
        if (p->autonomous)
            memset(ws->ft, 0, (size_t)n * sizeof *ws->ft);
        else
            rc = dyn_fd_dfdt(sys, t, y, ws->f0, h, ws->ft, ws->scratch, &calls);
    }
    st->rhs_calls += calls;
    st->jac_rhs_calls += calls;
    if (rc) {
        ws->rhs_status = rc;
        return DYN_ROS_RHS_FAIL;
    }
    return DYN_ROS_OK;
}

/* The solver of band matrices. */
static const dyn_band_solver *band_solver(const dyn_ros_problem *p)
{
    return p->band_solver ? p->band_solver : &dyn_band_solver_builtin;
}

/* W = I/(h gamma) - J in band storage, factorised. */
static int factor_band(const dyn_ros_method *m, const dyn_ros_problem *p, double h,
                       dyn_ros_ws *ws, dyn_ros_stats *st)
{
    const int n = ws->n, kl = ws->lower, ku = ws->upper, ldab = ws->ldab;
    const double fac = 1.0 / (h * m->gamma);
    memset(ws->W, 0, (size_t)n * (size_t)ldab * sizeof *ws->W);
    for (int j = 0; j < n; j++) {
        const int i0 = j - ku > 0 ? j - ku : 0;
        const int i1 = j + kl < n - 1 ? j + kl : n - 1;
        double *wj = ws->W + (size_t)j * (size_t)ldab + (size_t)(kl + ku); /* wj[i - j] */
        for (int i = i0; i <= i1; i++)
            wj[i - j] = -DYN_BAND_AT(ws->J, kl, ku, i, j);
        wj[0] += fac;
    }
    st->lu_decomps++;
    if (band_solver(p)->factor(n, kl, ku, ws->W, ldab, ws->piv)) {
        ws->h_lu = 0.0;
        return DYN_ROS_SINGULAR;
    }
    ws->h_lu = h;
    return DYN_ROS_OK;
}

/* W = I/(h gamma) - J with J's sparse pattern (which holds the diagonal), factorised by the
 * sparse solver. A solver that fails otherwise than on a singular matrix (memory) is taken
 * as singular too: the driver shrinks the step until it gives up. */
static int factor_sparse(const dyn_ros_method *m, const dyn_ros_problem *p, double h,
                         dyn_ros_ws *ws, dyn_ros_stats *st)
{
    const dyn_sparse_pattern *pat = ws->pattern;
    const double fac = 1.0 / (h * m->gamma);
    for (int j = 0; j < ws->n; j++)
        for (int k = pat->colptr[j]; k < pat->colptr[j + 1]; k++)
            ws->W[k] = pat->rowind[k] == j ? fac - ws->J[k] : -ws->J[k];
    st->lu_decomps++;
    if (p->sparse_solver->factor(p->sparse_solver->ctx, pat, ws->W)) {
        ws->h_lu = 0.0;
        return DYN_ROS_SINGULAR;
    }
    ws->h_lu = h;
    return DYN_ROS_OK;
}

/* W = I/(h gamma) - J, factorised. */
static int factor(const dyn_ros_method *m, double h, dyn_ros_ws *ws, dyn_ros_stats *st)
{
    const int n = ws->n;
    const size_t nn = (size_t)n * (size_t)n;
    const double fac = 1.0 / (h * m->gamma);
    for (size_t k = 0; k < nn; k++)
        ws->W[k] = -ws->J[k];
    for (int i = 0; i < n; i++)
        ws->W[(size_t)i * (size_t)n + (size_t)i] += fac;
    st->lu_decomps++;
    if (dyn_lu_factor(n, ws->W, ws->piv)) {
        ws->h_lu = 0.0;
        return DYN_ROS_SINGULAR;
    }
    ws->h_lu = h;
    return DYN_ROS_OK;
}

int dyn_ros_step(const dyn_ros_method *m, const dyn_ros_problem *p, double t, double h,
                 const double *y, dyn_ros_ws *ws, double *y1, double *err, double *cont,
                 dyn_ros_stats *st)
{
    const dyn_system *sys = &p->sys;
    const int n = sys->n, s = m->stages;
    const size_t N = (size_t)n;
    if (ws->h_lu != h) {
        int rc = ws->pattern ? factor_sparse(m, p, h, ws, st)
                 : ws->banded ? factor_band(m, p, h, ws, st)
                              : factor(m, h, ws, st);
        if (rc)
            return rc;
    }
    const double inv_h = 1.0 / h;
    for (int i = 0; i < s; i++) {
        const double *ai = m->a + (size_t)i * (size_t)s;
        const double *ci = m->c + (size_t)i * (size_t)s;
        double *ui = ws->u + (size_t)i * N;
        /* stage derivative f(t + alpha_i h, y0 + sum a_ij u_j) */
        int any = 0;
        for (int j = 0; j < i; j++)
            any |= ai[j] != 0.0;
        if (!any && m->alpha[i] == 0.0) {
            memcpy(ui, ws->f0, N * sizeof *ui);
        } else {
            memcpy(ws->Y, y, N * sizeof *ws->Y);
            for (int j = 0; j < i; j++) {
                const double a = ai[j];
                if (a == 0.0)
                    continue;
                const double *uj = ws->u + (size_t)j * N;
                for (int k = 0; k < n; k++)
                    ws->Y[k] += a * uj[k];
            }
            const double ti = m->alpha[i] == 1.0 ? t + h : t + m->alpha[i] * h;
            int rc = sys->f(ti, ws->Y, ui, sys->par);
            st->rhs_calls++;
            if (rc) {
                ws->rhs_status = rc;
                return DYN_ROS_RHS_FAIL;
            }
        }
        /* + sum (c_ij / h) u_j + gam_i h df/dt */
        for (int j = 0; j < i; j++) {
            const double c = ci[j] * inv_h;
            if (c == 0.0)
                continue;
            const double *uj = ws->u + (size_t)j * N;
            for (int k = 0; k < n; k++)
                ui[k] += c * uj[k];
        }
        if (m->gam[i] != 0.0 && !p->autonomous) {
            const double g = m->gam[i] * h;
            for (int k = 0; k < n; k++)
                ui[k] += g * ws->ft[k];
        }
        if (ws->pattern)
            p->sparse_solver->solve(p->sparse_solver->ctx, n, ui);
        else if (ws->banded)
            band_solver(p)->solve(n, ws->lower, ws->upper, ws->W, ws->ldab, ws->piv, ui);
        else
            dyn_lu_solve(n, ws->W, ws->piv, ui);
        st->lin_solves++;
    }
    st->steps++;
    for (int k = 0; k < n; k++) {
        double v = y[k];
        for (int i = 0; i < s; i++)
            if (m->m[i] != 0.0)
                v += m->m[i] * ws->u[(size_t)i * N + (size_t)k];
        y1[k] = v;
    }
    if (err) {
        for (int k = 0; k < n; k++) {
            double v = 0.0;
            for (int i = 0; i < s; i++)
                if (m->e[i] != 0.0)
                    v += m->e[i] * ws->u[(size_t)i * N + (size_t)k];
            err[k] = v;
        }
    }
    if (cont) {
        memcpy(cont, y, N * sizeof *cont);
        memcpy(cont + N, y1, N * sizeof *cont);
        for (int r = 0; r < m->dense_rows; r++) {
            const double *d = m->dense + (size_t)r * (size_t)s;
            double *q = cont + (2 + (size_t)r) * N;
            for (int k = 0; k < n; k++) {
                double v = 0.0;
                for (int i = 0; i < s; i++)
                    if (d[i] != 0.0)
                        v += d[i] * ws->u[(size_t)i * N + (size_t)k];
                q[k] = v;
            }
        }
    }
    return DYN_ROS_OK;
}

void dyn_ros_dense(const dyn_ros_method *m, int n, const double *cont, double theta,
                   double *out)
{
    const size_t N = (size_t)n;
    const double s1 = 1.0 - theta;
    (void)m; /* every registered method has the two-row CONTRO form */
    for (int k = 0; k < n; k++) {
        const double y0 = cont[k], y1 = cont[N + (size_t)k];
        const double q1 = cont[2 * N + (size_t)k], q2 = cont[3 * N + (size_t)k];
        out[k] = s1 * y0 + theta * (y1 + s1 * (q1 + theta * q2));
    }
}

static void put_msg(char *msg, size_t msglen, const char *what, double t, double h)
{
    if (msg && msglen)
        snprintf(msg, msglen, "%s at t = %s (h = %.3g)", what, dyn_shortest(t).s, h);
}

int dyn_ros_integrate(const dyn_ros_method *m, const dyn_ros_problem *p, double t0, double t1,
                      double *y, const dyn_ros_opts *o, dyn_ros_ws *ws, double *y1buf,
                      double *errbuf, dyn_ros_stats *st, double *t_reached, char *msg,
                      size_t msglen)
{
    const int n = p->sys.n;
    const double span = t1 - t0, dir = span >= 0.0 ? 1.0 : -1.0;
    const double safe = 0.9, fac_min = 0.2, fac_max = 6.0;
    const double expo = 1.0 / (m->order_embedded + 1);
    double t = t0;
    if (t_reached)
        *t_reached = t0;
    if (msg && msglen)
        msg[0] = '\0';
    if (!(o->rtol > 0.0) || !(o->atolv || o->atol >= 0.0) || !isfinite(span)) {
        if (msg && msglen)
            snprintf(msg, msglen, "rtol must be > 0 and atol >= 0 (got %g, %g)", o->rtol,
                     o->atol);
        return DYN_ERR_ARG;
    }
    if (span == 0.0)
        return DYN_OK;
    const double hmax = o->hmax > 0.0 ? o->hmax : fabs(span);
    const long max_steps = o->max_steps > 0 ? o->max_steps : 1000000L;
    double h = o->h0 != 0.0 ? fabs(o->h0) : fabs(span) * 1e-6;
    h = dir * fmin(h, hmax);
    double h_acc = 0.0, err_acc = 1.0;
    int reject = 0, n_accept = 0, n_sing = 0;
    long attempts = 0;

    while (dir * (t1 - t) > 0.0) {
        if (fabs(h) <= 10.0 * DBL_EPSILON * fabs(t)) {
            put_msg(msg, msglen, "step size too small", t, h);
            return DYN_ERR_STEP_SIZE;
        }
        int last = 0;
        if (dir * (t + h * 1.0001 - t1) >= 0.0) {
            h = t1 - t;
            last = 1;
        }
        int rc = dyn_ros_linearize(p, t, h, y, ws, st);
        if (rc) {
            put_msg(msg, msglen, "the right-hand side or Jacobian failed", t, h);
            return DYN_ERR_RHS;
        }
        for (;;) { /* attempts from (t, y) with this linearisation */
            if (++attempts > max_steps) {
                put_msg(msg, msglen, "too many steps", t, h);
                return DYN_ERR_MAX_STEPS;
            }
            rc = dyn_ros_step(m, p, t, h, y, ws, y1buf, errbuf, o->on_step ? o->cont : NULL,
                              st);
            if (rc == DYN_ROS_SINGULAR) {
                if (++n_sing >= 5) {
                    put_msg(msg, msglen, "matrix I/(h gamma) - J repeatedly singular", t, h);
                    return DYN_ERR_STEP_SIZE;
                }
                h *= 0.5;
                reject = 1;
                last = 0;
                continue;
            }
            if (rc) {
                put_msg(msg, msglen, "the right-hand side failed", t, h);
                return DYN_ERR_RHS;
            }
            double sum = 0.0;
            int finite = 1;
            for (int k = 0; k < n; k++) {
                const double atol = o->atolv ? o->atolv[k] : o->atol;
                const double sk = atol + o->rtol * fmax(fabs(y[k]), fabs(y1buf[k]));
                const double r = errbuf[k] / sk;
                sum += r * r;
                finite &= isfinite(y1buf[k]);
            }
            double err = sqrt(sum / n);
            if (!finite || !isfinite(err))
                err = 1e10; /* treat as a failed step: shrink strongly */
            double fac = fmax(1.0 / fac_max, fmin(1.0 / fac_min, pow(err, expo) / safe));
            double hnew = h / fac;
            if (err <= 1.0) {
                n_accept++;
                if (n_accept > 1) { /* Gustafsson's predictive controller */
                    double facgus = (h_acc / h) * pow(err * err / err_acc, expo) / safe;
                    facgus = fmax(1.0 / fac_max, fmin(1.0 / fac_min, facgus));
                    fac = fmax(fac, facgus);
                    hnew = h / fac;
                }
                h_acc = h;
                err_acc = fmax(1e-2, err);
                const double t_old = t;
                t = last ? t1 : t + h;
                memcpy(y, y1buf, (size_t)n * sizeof *y);
                if (t_reached)
                    *t_reached = t;
                if (o->on_step && o->on_step(t_old, t, y, o->cont, o->ctx))
                    return DYN_STOPPED;
                if (fabs(hnew) > hmax)
                    hnew = dir * hmax;
                if (reject)
                    hnew = dir * fmin(fabs(hnew), fabs(h));
                reject = 0;
                h = hnew;
                break;
            }
            reject = 1;
            last = 0;
            h = hnew;
            if (fabs(h) <= 10.0 * DBL_EPSILON * fabs(t)) {
                put_msg(msg, msglen,
                        finite ? "step size too small" : "state not finite even for tiny steps",
                        t, h);
                return finite ? DYN_ERR_STEP_SIZE : DYN_ERR_NONFINITE;
            }
        }
    }
    return DYN_OK;
}
