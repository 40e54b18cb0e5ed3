/* cvode.c — the SUNDIALS CVODE backend (dynkit/cvode.h): a dyn_system solved by CVODE's
 * variable-order BDF (or Adams) method with Newton iteration and the dense direct linear
 * solver, the model's Jacobian when it has one (Hindmarsh et al., ACM TOMS 31 (2005);
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
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

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
    double *jbuf;      /* (n x n) row-major Jacobian from the user's function */
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

static int cv_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *user_data,
                  N_Vector tmp1, N_Vector tmp2, N_Vector tmp3)
{
    cv_user *u = user_data;
    (void)fy;
    (void)tmp1;
    (void)tmp2;
    (void)tmp3;
    const int n = u->sys->n;
    int rc = u->jac(t, N_VGetArrayPointer(y), u->jbuf, u->sys->par);
    if (rc) {
        u->rhs_status = rc;
        u->fail_t = t;
        return -1;
    }
    for (int j = 0; j < n; j++) {
        sunrealtype *col = SUNDenseMatrix_Column(J, j); /* column-major */
        for (int i = 0; i < n; i++)
            col[i] = u->jbuf[(size_t)i * (size_t)n + (size_t)j];
    }
    return 0;
}

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
    res->status = status;
    if (u && u->msg[0])
        snprintf(res->message, sizeof res->message, "%s (%s)", what, u->msg);
    else
        snprintf(res->message, sizeof res->message, "%s", what);
    return status;
}

const char *dyn_cvode_version(void) { return SUNDIALS_VERSION; }

int dyn_cvode_solve(const dyn_system *sys, double t0, const double *y0, const double *tout,
                    long n_out, const dyn_cvode_opts *opts, dyn_output_fn output, void *ctx,
                    double *y, dyn_result *res)
{
    static const dyn_cvode_opts no_opts;
    dyn_result local;
    if (!res)
        res = &local;
    memset(res, 0, sizeof *res);
    res->t = t0;
    res->fail_t = NAN;
    res->fail_index = -1;
    res->event_index = -1;
    res->stiff_t = NAN;
    if (!opts)
        opts = &no_opts;
    if (!sys || !sys->f || sys->n <= 0 || !y0)
        return fail(res, DYN_ERR_ARG, "no system, no right-hand side, n <= 0 or no y0", NULL);
    if (!tout || n_out <= 0)
        return fail(res, DYN_ERR_ARG, "no output times given", NULL);
    for (long k = 0; k < n_out; k++)
        if (!isfinite(tout[k]) || tout[k] < t0 || (k > 0 && tout[k] < tout[k - 1])) {
            snprintf(res->message, sizeof res->message,
                     "output time %.17g (number %ld) is not accepted: the times must be finite, "
                     ">= t0 = %.17g and non-decreasing",
                     tout[k], k + 1, t0);
            res->status = DYN_ERR_ARG;
            return DYN_ERR_ARG;
        }
    const double rtol = opts->rtol > 0.0 ? opts->rtol : 1e-3;
    const double atol = opts->atol > 0.0 ? opts->atol : 1e-6;
    const int n = sys->n;
    const size_t N = (size_t)n;

    cv_user u;
    memset(&u, 0, sizeof u);
    u.sys = sys;
    u.jac = opts->jacobian;
    SUNContext sctx = NULL;
    void *mem = NULL;
    N_Vector yv = NULL, av = NULL;
    SUNMatrix A = NULL;
    SUNLinearSolver LS = NULL;
    double *ycur = malloc(N * sizeof *ycur);
    if (opts->jacobian)
        u.jbuf = malloc(N * N * sizeof *u.jbuf);
    if (!ycur || (opts->jacobian && !u.jbuf)) {
        fail(res, DYN_ERR_ARG, "out of memory", NULL);
        goto done;
    }
    memcpy(ycur, y0, N * sizeof *ycur);

    if (SUNContext_Create(DYN_SUN_COMM, &sctx) != 0) {
        fail(res, DYN_ERR_ARG, "SUNContext_Create failed", NULL);
        goto done;
    }
#if SUNDIALS_VERSION_MAJOR >= 7
    SUNContext_ClearErrHandlers(sctx);
    SUNContext_PushErrHandler(sctx, cv_err, &u);
#endif
    yv = N_VNew_Serial((sunindextype)n, sctx);
    if (!yv) {
        fail(res, DYN_ERR_ARG, "N_VNew_Serial failed", NULL);
        goto done;
    }
    memcpy(N_VGetArrayPointer(yv), y0, N * sizeof *ycur);
    mem = CVodeCreate(opts->adams ? CV_ADAMS : CV_BDF, sctx);
    if (!mem) {
        fail(res, DYN_ERR_ARG, "CVodeCreate failed", NULL);
        goto done;
    }
#if SUNDIALS_VERSION_MAJOR < 7
    CVodeSetErrHandlerFn(mem, cv_err, &u);
#endif
    int flag = CVodeInit(mem, cv_rhs, t0, yv);
    if (flag == CV_SUCCESS)
        flag = CVodeSetUserData(mem, &u);
    if (flag == CV_SUCCESS) {
        if (opts->atolv) {
            av = N_VNew_Serial((sunindextype)n, sctx);
            if (!av) {
                fail(res, DYN_ERR_ARG, "N_VNew_Serial failed", NULL);
                goto done;
            }
            memcpy(N_VGetArrayPointer(av), opts->atolv, N * sizeof *ycur);
            flag = CVodeSVtolerances(mem, rtol, av);
        } else {
            flag = CVodeSStolerances(mem, rtol, atol);
        }
    }
    if (flag == CV_SUCCESS) {
        A = SUNDenseMatrix((sunindextype)n, (sunindextype)n, sctx);
        LS = A ? SUNLinSol_Dense(yv, A, sctx) : NULL;
        flag = LS ? CVodeSetLinearSolver(mem, LS, A) : -1;
    }
    if (flag == CV_SUCCESS && opts->jacobian)
        flag = CVodeSetJacFn(mem, cv_jac);
    if (flag == CV_SUCCESS)
        flag = CVodeSetMaxNumSteps(mem, opts->max_steps > 0 ? opts->max_steps : 100000L);
    if (flag == CV_SUCCESS && opts->max_order > 0)
        flag = CVodeSetMaxOrd(mem, opts->max_order);
    if (flag == CV_SUCCESS && opts->initial_step > 0.0)
        flag = CVodeSetInitStep(mem, opts->initial_step);
    if (flag == CV_SUCCESS && opts->max_step > 0.0)
        flag = CVodeSetMaxStep(mem, opts->max_step);
    if (flag == CV_SUCCESS && tout[n_out - 1] > t0)
        flag = CVodeSetStopTime(mem, tout[n_out - 1]);
    if (flag != CV_SUCCESS) {
        fail(res, DYN_ERR_ARG, "CVODE setup failed", &u);
        goto done;
    }

    /* the output times */
    double t = t0;
    for (long k = 0; k < n_out; k++) {
        if (tout[k] > t) {
            sunrealtype tret = t;
            flag = CVode(mem, tout[k], yv, &tret, CV_NORMAL);
            if (flag < 0) {
                res->t = t;
                if (u.rhs_status) {
                    res->rhs_status = u.rhs_status;
                    res->fail_t = u.fail_t;
                    char what[96];
                    snprintf(what, sizeof what,
                             "the right-hand side or Jacobian failed at t = %.17g (status %d)",
                             u.fail_t, u.rhs_status);
                    fail(res, DYN_ERR_RHS, what, NULL);
                } else if (flag == CV_TOO_MUCH_WORK) {
                    fail(res, DYN_ERR_MAX_STEPS, "CVODE reached the limit of steps", &u);
                } else if (flag == CV_TOO_MUCH_ACC || flag == CV_ERR_FAILURE ||
                           flag == CV_CONV_FAILURE) {
                    fail(res, DYN_ERR_STEP_SIZE, "CVODE failed to reach the tolerance", &u);
                } else {
                    char what[64];
                    snprintf(what, sizeof what, "CVODE failed with flag %d", flag);
                    fail(res, DYN_ERR_ARG, what, &u);
                }
                break;
            }
            t = tout[k]; /* CV_NORMAL with a stop time: tret == tout[k] */
            memcpy(ycur, N_VGetArrayPointer(yv), N * sizeof *ycur);
        }
        res->t = t;
        if (output) {
            res->stats.samples++;
            if (output(k, tout[k], ycur, ctx)) {
                snprintf(res->message, sizeof res->message, "output stopped the run at t = %g",
                         tout[k]);
                res->status = DYN_STOPPED;
                break;
            }
        }
    }

    long nst = 0, nfe = 0, netf = 0, ncf = 0, nje = 0, nfeLS = 0;
    CVodeGetNumSteps(mem, &nst);
    CVodeGetNumRhsEvals(mem, &nfe);
    CVodeGetNumErrTestFails(mem, &netf);
    CVodeGetNumNonlinSolvConvFails(mem, &ncf);
    CVodeGetNumJacEvals(mem, &nje);
    CVodeGetNumLinRhsEvals(mem, &nfeLS);
    res->stats.steps = nst;
    res->stats.accepted = nst;
    res->stats.rejected = netf + ncf;
    res->stats.rhs_calls = nfe + nfeLS;
    res->stats.jac_calls = nje;
    sunrealtype hlast = 0;
    CVodeGetLastStep(mem, &hlast);
    res->h_last = hlast;

done:
    if (y && ycur)
        memcpy(y, ycur, N * sizeof *y);
    if (LS)
        SUNLinSolFree(LS);
    if (A)
        SUNMatDestroy(A);
    if (av)
        N_VDestroy(av);
    if (yv)
        N_VDestroy(yv);
    if (mem)
        CVodeFree(&mem);
    if (sctx)
        SUNContext_Free(&sctx);
    free(u.jbuf);
    free(ycur);
    return res->status;
}
