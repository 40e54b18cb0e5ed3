/* SPDX-License-Identifier: BSD-3-Clause */
/* cvode.c — the SUNDIALS CVODE backend (dynkit/cvode.h): a dyn_system solved by CVODE's
 * variable-order BDF (or Adams) method with Newton iteration and the dense direct linear
 * solver (the band matrix and solver when the Jacobian is banded, the sparse matrix and
 * SUNDIALS' KLU solver for a sparse pattern when built with them), the model's Jacobian when
 * it has one, its columns with an entry that is not finite formed by differences
 * (dyn_jacobian_mend) (Hindmarsh et al., ACM TOMS 31 (2005);
 * CVODE user guide v6). Works with SUNDIALS 6 and 7 (the context and error-handler calls
 * differ and are selected by SUNDIALS_VERSION_MAJOR).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>

#ifdef DYNKIT_CVODE_KLU
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "dynkit/cvode.h"

#if SUNDIALS_VERSION_MAJOR >= 7
#define DYN_SUN_COMM SUN_COMM_NULL
#else
#define DYN_SUN_COMM NULL
#endif

/* What CVODE's callbacks see. */
typedef struct cv_user {
    const dyn_system *sys;
    dyn_jac_fn jac;
    double *jbuf;      /* (n x n) row-major Jacobian from the user's function, or its band */
    double *jwork;     /* (2 n) for the columns mended by differences (dyn_jacobian_mend) */
    int lower, upper;  /* the band, when jbuf holds one */
    const dyn_sparse_pattern *pattern; /* sparse: jbuf holds the pattern's values */
    long jac_rhs_calls; /* calls of f for those columns (CVODE does not count them) */
    long jac_fd_columns; /* columns mended */
    const double *rtolv, *atolv; /* per-state tolerances (cv_ewt), or NULL */
    double atol;       /* scalar absolute tolerance when atolv is NULL */
    int rhs_status;    /* non-zero value f or jac returned */
    double fail_t;
    char msg[200];     /* CVODE's last error or warning message */
} cv_user;

static int cv_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *user_data)
{
    cv_user *u = user_data;
    int rc = u->sys->f(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), u->sys->par);
    if (rc) {
        u->rhs_status = rc;
        u->fail_t = t;
        return -1; /* unrecoverable: the system asked to stop */
    }
    return 0;
}

/* The model's Jacobian at (t, y) into u->jbuf (dense or band storage, as the model gives
 * it), its columns with an entry that is not finite formed by differences where f(t, y) =
 * fy is finite (dyn_jacobian_mend); non-zero when it failed, with the failure recorded as
 * a right-hand side's. */
static int jac_into_buffer(cv_user *u, sunrealtype t, N_Vector y, N_Vector fy, int banded)
{
    const double *yv = N_VGetArrayPointer(y), *f0 = N_VGetArrayPointer(fy);
    int rc = u->jac(t, yv, u->jbuf, u->sys->par);
    if (!rc && u->pattern)
        rc = dyn_jacobian_sparse_mend(u->sys, t, yv, f0, NULL, u->pattern, u->jbuf, u->jwork,
                                      &u->jac_rhs_calls, &u->jac_fd_columns);
    else if (!rc && banded)
        rc = dyn_jacobian_band_mend(u->sys, t, yv, f0, NULL, u->lower, u->upper, u->jbuf,
                                    u->jwork, &u->jac_rhs_calls, &u->jac_fd_columns);
    else if (!rc)
        rc = dyn_jacobian_mend(u->sys, t, yv, f0, NULL, u->jbuf, u->jwork, &u->jac_rhs_calls,
                               &u->jac_fd_columns);
    if (rc) {
        u->rhs_status = rc;
        u->fail_t = t;
    }
    return rc;
}

static int cv_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *user_data,
                  N_Vector tmp1, N_Vector tmp2, N_Vector tmp3)
{
    cv_user *u = user_data;
    (void)tmp1;
    (void)tmp2;
    (void)tmp3;
    const int n = u->sys->n;
    if (jac_into_buffer(u, t, y, fy, 0))
        return -1;
    for (int j = 0; j < n; j++) {
        sunrealtype *col = SUNDenseMatrix_Column(J, j); /* column-major */
        for (int i = 0; i < n; i++)
            col[i] = u->jbuf[(size_t)i * (size_t)n + (size_t)j];
    }
    return 0;
}

/* The band of the Jacobian (DYN_BAND_AT storage) into CVODE's band matrix, whose column j
 * points at the diagonal: element (i, j) is col[i - j]. */
static int cv_jac_band(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *user_data,
                       N_Vector tmp1, N_Vector tmp2, N_Vector tmp3)
{
    cv_user *u = user_data;
    (void)tmp1;
    (void)tmp2;
    (void)tmp3;
    const int n = u->sys->n, kl = u->lower, ku = u->upper;
    if (jac_into_buffer(u, t, y, fy, 1))
        return -1;
    for (int j = 0; j < n; j++) {
        sunrealtype *col = SUNBandMatrix_Column(J, j);
        const int i0 = j - ku > 0 ? j - ku : 0, i1 = j + kl < n - 1 ? j + kl : n - 1;
        for (int i = i0; i <= i1; i++)
            col[i - j] = DYN_BAND_AT(u->jbuf, kl, ku, i, j);
    }
    return 0;
}

int dyn_cvode_has_klu(void)
{
#ifdef DYNKIT_CVODE_KLU
    return 1;
#else
    return 0;
#endif
}

#ifdef DYNKIT_CVODE_KLU
/* The sparse Jacobian into CVODE's compressed-column matrix: the pattern (CVODE's KLU
 * solver forms I - gamma J in place, which keeps it, since it holds the diagonal) and the
 * values in its order. */
static int cv_jac_sparse(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *user_data,
                         N_Vector tmp1, N_Vector tmp2, N_Vector tmp3)
{
    cv_user *u = user_data;
    (void)tmp1;
    (void)tmp2;
    (void)tmp3;
    const dyn_sparse_pattern *p = u->pattern;
    if (jac_into_buffer(u, t, y, fy, 0))
        return -1;
    sunindextype *colptr = SUNSparseMatrix_IndexPointers(J);
    sunindextype *rowind = SUNSparseMatrix_IndexValues(J);
    sunrealtype *data = SUNSparseMatrix_Data(J);
    for (int j = 0; j <= p->n; j++)
        colptr[j] = (sunindextype)p->colptr[j];
    for (int k = 0; k < p->nnz; k++) {
        rowind[k] = (sunindextype)p->rowind[k];
        data[k] = u->jbuf[k];
    }
    return 0;
}
#endif

#if SUNDIALS_VERSION_MAJOR >= 7
static void cv_err(int line, const char *func, const char *file, const char *msg,
                   SUNErrCode code, void *data, SUNContext ctx)
{
    cv_user *u = data;
    (void)line;
    (void)file;
    (void)code;
    (void)ctx;
    snprintf(u->msg, sizeof u->msg, "%s: %s", func ? func : "CVODE", msg ? msg : "");
}
#else
static void cv_err(int code, const char *module, const char *function, char *msg, void *data)
{
    cv_user *u = data;
    (void)code;
    (void)module;
    snprintf(u->msg, sizeof u->msg, "%s: %s", function ? function : "CVODE", msg ? msg : "");
}
#endif

static int fail(dyn_result *res, int status, const char *what, const cv_user *u)
{
    const size_t size = sizeof res->message;
    res->status = status;
    int w = snprintf(res->message, size, "%s", what);
    if (u && u->msg[0] && w >= 0 && (size_t)w + 4 < size) /* CVODE's message, cut to fit */
        snprintf(res->message + w, size - (size_t)w, " (%.*s)", (int)(size - (size_t)w - 4),
                 u->msg);
    return status;
}

/* Per-state relative tolerances: CVODE's error weights 1 / (rtol_i |y_i| + atol_i)
 * (CVodeWFtolerances), the weights of CVodeSVtolerances with a vector rtol. */
static int cv_ewt(N_Vector y, N_Vector ewt, void *user_data)
{
    cv_user *u = user_data;
    const sunrealtype *yv = N_VGetArrayPointer(y);
    sunrealtype *w = N_VGetArrayPointer(ewt);
    for (int i = 0; i < u->sys->n; i++) {
        const double d = u->rtolv[i] * fabs(yv[i]) + (u->atolv ? u->atolv[i] : u->atol);
        if (!(d > 0.0))
            return -1;
        w[i] = 1.0 / d;
    }
    return 0;
}

const char *dyn_cvode_version(void) { return SUNDIALS_VERSION; }

/* One CVODE solver: what dyn_cvode_solve and dyn_cvode_solve_steps share. */
typedef struct cv_solver {
    cv_user u;
    SUNContext sctx;
    void *mem;
    N_Vector yv, av;
    SUNMatrix A;
    SUNLinearSolver LS;
    double *ycur; /* (n) the last state reached */
} cv_solver;

static void cv_result_init(dyn_result *res, double t0)
{
    memset(res, 0, sizeof *res);
    res->t = t0;
    res->fail_t = NAN;
    res->fail_index = -1;
    res->event_index = -1;
    res->stiff_t = NAN;
}

/* Create and set up CVODE for sys from (t0, y0), never past tstop (> t0; or no stop time
 * when tstop <= t0). Returns DYN_OK or a status with res filled. */
static int cv_open(cv_solver *cs, const dyn_system *sys, double t0, const double *y0,
                   double tstop, const dyn_cvode_opts *opts, dyn_result *res)
{
    const double rtol = opts->rtol > 0.0 ? opts->rtol : 1e-3;
    const double atol = opts->atol > 0.0 ? opts->atol : 1e-6;
    const int n = sys->n;
    const size_t N = (size_t)n;
    memset(cs, 0, sizeof *cs);
    cs->u.sys = sys;
    const int banded = opts->jac_banded != 0;
    if (banded && (opts->jac_lower < 0 || opts->jac_upper < 0 || opts->jac_lower >= n ||
                   opts->jac_upper >= n))
        return fail(res, DYN_ERR_ARG, "the band of the Jacobian must have 0 <= lower, upper < n",
                    NULL);
    const int sparse = !banded && dyn_cvode_has_klu() && opts->jac_sparse.nnz > 0 &&
                       opts->jacobian_sparse;
    char why[160];
    if (sparse && dyn_sparse_pattern_check(&opts->jac_sparse, n, why, sizeof why))
        return fail(res, DYN_ERR_ARG, why, NULL);
    const dyn_jac_fn jac = sparse   ? opts->jacobian_sparse
                           : banded ? opts->jacobian_band
                                    : opts->jacobian;
    cs->u.jac = jac;
    cs->u.pattern = sparse ? &opts->jac_sparse : NULL;
    cs->u.lower = banded ? opts->jac_lower : 0;
    cs->u.upper = banded ? opts->jac_upper : 0;
    cs->u.rtolv = opts->rtolv;
    cs->u.atolv = opts->atolv;
    cs->u.atol = atol;
    cs->ycur = malloc(N * sizeof *cs->ycur);
    if (jac) {
        cs->u.jbuf = malloc((sparse   ? (size_t)opts->jac_sparse.nnz
                             : banded ? N * (size_t)(cs->u.lower + cs->u.upper + 1)
                                      : N * N) *
                            sizeof *cs->u.jbuf);
        cs->u.jwork = malloc(2 * N * sizeof *cs->u.jwork);
    }
    if (!cs->ycur || (jac && (!cs->u.jbuf || !cs->u.jwork)))
        return fail(res, DYN_ERR_ARG, "out of memory", NULL);
    memcpy(cs->ycur, y0, N * sizeof *cs->ycur);

    if (SUNContext_Create(DYN_SUN_COMM, &cs->sctx) != 0) {
        cs->sctx = NULL;
        return fail(res, DYN_ERR_ARG, "SUNContext_Create failed", NULL);
    }
#if SUNDIALS_VERSION_MAJOR >= 7
    SUNContext_ClearErrHandlers(cs->sctx);
    SUNContext_PushErrHandler(cs->sctx, cv_err, &cs->u);
#endif
    cs->yv = N_VNew_Serial((sunindextype)n, cs->sctx);
    if (!cs->yv)
        return fail(res, DYN_ERR_ARG, "N_VNew_Serial failed", NULL);
    memcpy(N_VGetArrayPointer(cs->yv), y0, N * sizeof *cs->ycur);
    cs->mem = CVodeCreate(opts->adams ? CV_ADAMS : CV_BDF, cs->sctx);
    if (!cs->mem)
        return fail(res, DYN_ERR_ARG, "CVodeCreate failed", NULL);
#if SUNDIALS_VERSION_MAJOR < 7
    CVodeSetErrHandlerFn(cs->mem, cv_err, &cs->u);
#endif
    void *mem = cs->mem;
    int flag = CVodeInit(mem, cv_rhs, t0, cs->yv);
    if (flag == CV_SUCCESS)
        flag = CVodeSetUserData(mem, &cs->u);
    if (flag == CV_SUCCESS) {
        if (opts->rtolv) {
            flag = CVodeWFtolerances(mem, cv_ewt);
        } else if (opts->atolv) {
            cs->av = N_VNew_Serial((sunindextype)n, cs->sctx);
            if (!cs->av)
                return fail(res, DYN_ERR_ARG, "N_VNew_Serial failed", NULL);
            memcpy(N_VGetArrayPointer(cs->av), opts->atolv, N * sizeof *cs->ycur);
            flag = CVodeSVtolerances(mem, rtol, cs->av);
        } else {
            flag = CVodeSStolerances(mem, rtol, atol);
        }
    }
    if (flag == CV_SUCCESS) {
        if (sparse) {
#ifdef DYNKIT_CVODE_KLU
            cs->A = SUNSparseMatrix((sunindextype)n, (sunindextype)n,
                                    (sunindextype)opts->jac_sparse.nnz, CSC_MAT, cs->sctx);
            cs->LS = cs->A ? SUNLinSol_KLU(cs->yv, cs->A, cs->sctx) : NULL;
#endif
        } else if (banded) {
            cs->A = SUNBandMatrix((sunindextype)n, (sunindextype)cs->u.upper,
                                  (sunindextype)cs->u.lower, cs->sctx);
            cs->LS = cs->A ? SUNLinSol_Band(cs->yv, cs->A, cs->sctx) : NULL;
        } else {
            cs->A = SUNDenseMatrix((sunindextype)n, (sunindextype)n, cs->sctx);
            cs->LS = cs->A ? SUNLinSol_Dense(cs->yv, cs->A, cs->sctx) : NULL;
        }
        flag = cs->LS ? CVodeSetLinearSolver(mem, cs->LS, cs->A) : -1;
    }
    if (flag == CV_SUCCESS && jac)
#ifdef DYNKIT_CVODE_KLU
        flag = CVodeSetJacFn(mem, sparse ? cv_jac_sparse : banded ? cv_jac_band : cv_jac);
#else
        flag = CVodeSetJacFn(mem, banded ? cv_jac_band : cv_jac);
#endif
    if (flag == CV_SUCCESS)
        flag = CVodeSetMaxNumSteps(mem, opts->max_steps > 0 ? opts->max_steps : 100000L);
    if (flag == CV_SUCCESS && opts->max_order > 0)
        flag = CVodeSetMaxOrd(mem, opts->max_order);
    if (flag == CV_SUCCESS && opts->initial_step > 0.0)
        flag = CVodeSetInitStep(mem, opts->initial_step);
    if (flag == CV_SUCCESS && opts->max_step > 0.0)
        flag = CVodeSetMaxStep(mem, opts->max_step);
    if (flag == CV_SUCCESS && tstop > t0)
        flag = CVodeSetStopTime(mem, tstop);
    if (flag != CV_SUCCESS)
        return fail(res, DYN_ERR_ARG, "CVODE setup failed", &cs->u);
    return DYN_OK;
}

/* The status of a failed CVode call (flag < 0) into res; t is the time reached. */
static void cv_failed(const cv_solver *cs, int flag, double t, dyn_result *res)
{
    res->t = t;
    if (cs->u.rhs_status) {
        res->rhs_status = cs->u.rhs_status;
        res->fail_t = cs->u.fail_t;
        char what[96];
        snprintf(what, sizeof what,
                 "the right-hand side or Jacobian failed at t = %s (status %d)",
                 dyn_shortest(cs->u.fail_t).s, cs->u.rhs_status);
        fail(res, DYN_ERR_RHS, what, NULL);
    } else if (flag == CV_TOO_MUCH_WORK) {
        fail(res, DYN_ERR_MAX_STEPS, "CVODE reached the limit of steps", &cs->u);
    } else if (flag == CV_TOO_MUCH_ACC || flag == CV_ERR_FAILURE || flag == CV_CONV_FAILURE) {
        fail(res, DYN_ERR_STEP_SIZE, "CVODE failed to reach the tolerance", &cs->u);
    } else {
        char what[64];
        snprintf(what, sizeof what, "CVODE failed with flag %d", flag);
        fail(res, DYN_ERR_ARG, what, &cs->u);
    }
}

/* The counters of the solve into res (steps = attempts = accepted + rejected). */
static void cv_counters(const cv_solver *cs, dyn_result *res)
{
    if (!cs->mem)
        return;
    long nst = 0, nfe = 0, netf = 0, ncf = 0, nje = 0, nfeLS = 0;
    CVodeGetNumSteps(cs->mem, &nst);
    CVodeGetNumRhsEvals(cs->mem, &nfe);
    CVodeGetNumErrTestFails(cs->mem, &netf);
    CVodeGetNumNonlinSolvConvFails(cs->mem, &ncf);
    CVodeGetNumJacEvals(cs->mem, &nje);
    CVodeGetNumLinRhsEvals(cs->mem, &nfeLS);
    res->stats.accepted = nst;
    res->stats.rejected = netf + ncf;
    res->stats.steps = nst + netf + ncf;
    res->stats.rhs_calls = nfe + nfeLS + cs->u.jac_rhs_calls;
    res->stats.jac_calls = nje;
    res->stats.jac_fd_columns = cs->u.jac_fd_columns;
    sunrealtype hlast = 0;
    CVodeGetLastStep(cs->mem, &hlast);
    res->h_last = hlast;
}

static void cv_close(cv_solver *cs, int n, double *y)
{
    if (y && cs->ycur)
        memcpy(y, cs->ycur, (size_t)n * sizeof *y);
    if (cs->LS)
        SUNLinSolFree(cs->LS);
    if (cs->A)
        SUNMatDestroy(cs->A);
    if (cs->av)
        N_VDestroy(cs->av);
    if (cs->yv)
        N_VDestroy(cs->yv);
    if (cs->mem)
        CVodeFree(&cs->mem);
    if (cs->sctx)
        SUNContext_Free(&cs->sctx);
    free(cs->u.jbuf);
    free(cs->u.jwork);
    free(cs->ycur);
}

int dyn_cvode_solve(const dyn_system *sys, double t0, const double *y0, const double *tout,
                    long n_out, const dyn_cvode_opts *opts, dyn_output_fn output, void *ctx,
                    double *y, dyn_result *res)
{
    static const dyn_cvode_opts no_opts;
    dyn_result local;
    if (!res)
        res = &local;
    cv_result_init(res, t0);
    if (!opts)
        opts = &no_opts;
    if (!sys || !sys->f || sys->n <= 0 || !y0)
        return fail(res, DYN_ERR_ARG, "no system, no right-hand side, n <= 0 or no y0", NULL);
    if (!tout || n_out <= 0)
        return fail(res, DYN_ERR_ARG, "no output times given", NULL);
    for (long k = 0; k < n_out; k++)
        if (!isfinite(tout[k]) || tout[k] < t0 || (k > 0 && tout[k] < tout[k - 1])) {
            snprintf(res->message, sizeof res->message,
                     "output time %s (number %ld) is not accepted: the times must be finite, "
                     ">= t0 = %s and non-decreasing",
                     dyn_shortest(tout[k]).s, k + 1, dyn_shortest(t0).s);
            res->status = DYN_ERR_ARG;
            return DYN_ERR_ARG;
        }
    const size_t N = (size_t)sys->n;
    cv_solver cs;
    if (cv_open(&cs, sys, t0, y0, tout[n_out - 1], opts, res) == DYN_OK) {
        double t = t0;
        for (long k = 0; k < n_out; k++) {
            if (tout[k] > t) {
                sunrealtype tret = t;
                int flag = CVode(cs.mem, tout[k], cs.yv, &tret, CV_NORMAL);
                if (flag < 0) {
                    cv_failed(&cs, flag, t, res);
                    break;
                }
                t = tout[k]; /* CV_NORMAL with a stop time: tret == tout[k] */
                memcpy(cs.ycur, N_VGetArrayPointer(cs.yv), N * sizeof *cs.ycur);
            }
            res->t = t;
            if (output) {
                res->stats.samples++;
                if (output(k, tout[k], cs.ycur, ctx)) {
                    snprintf(res->message, sizeof res->message,
                             "output stopped the run at t = %g", tout[k]);
                    res->status = DYN_STOPPED;
                    break;
                }
            }
        }
        cv_counters(&cs, res);
    }
    cv_close(&cs, sys->n, y);
    return res->status;
}

int dyn_cvode_solve_steps(const dyn_system *sys, double t0, double t1, const double *y0,
                          const dyn_cvode_opts *opts, dyn_output_fn output, void *ctx,
                          double *y, dyn_result *res)
{
    static const dyn_cvode_opts no_opts;
    dyn_result local;
    if (!res)
        res = &local;
    cv_result_init(res, t0);
    if (!opts)
        opts = &no_opts;
    if (!sys || !sys->f || sys->n <= 0 || !y0)
        return fail(res, DYN_ERR_ARG, "no system, no right-hand side, n <= 0 or no y0", NULL);
    if (!isfinite(t0) || !isfinite(t1) || !(t1 > t0))
        return fail(res, DYN_ERR_ARG, "the span must be finite with t1 > t0", NULL);
    const size_t N = (size_t)sys->n;
    cv_solver cs;
    if (cv_open(&cs, sys, t0, y0, t1, opts, res) == DYN_OK) {
        long k = 0, steps = 0;
        double t = t0;
        int more = 1;
        if (output) {
            res->stats.samples++;
            if (output(k++, t0, cs.ycur, ctx)) {
                snprintf(res->message, sizeof res->message, "output stopped the run at t = %g",
                         t0);
                res->status = DYN_STOPPED;
                more = 0;
            }
        }
        while (more && t < t1) {
            if (opts->max_steps > 0 && steps >= opts->max_steps) {
                cv_failed(&cs, CV_TOO_MUCH_WORK, t, res);
                break;
            }
            sunrealtype tret = t;
            int flag = CVode(cs.mem, t1, cs.yv, &tret, CV_ONE_STEP);
            if (flag < 0) {
                cv_failed(&cs, flag, t, res);
                break;
            }
            steps++;
            t = flag == CV_TSTOP_RETURN ? t1 : tret;
            memcpy(cs.ycur, N_VGetArrayPointer(cs.yv), N * sizeof *cs.ycur);
            res->t = t;
            if (output) {
                res->stats.samples++;
                if (output(k++, t, cs.ycur, ctx)) {
                    snprintf(res->message, sizeof res->message,
                             "output stopped the run at t = %g", t);
                    res->status = DYN_STOPPED;
                    break;
                }
            }
        }
        cv_counters(&cs, res);
    }
    cv_close(&cs, sys->n, y);
    return res->status;
}
