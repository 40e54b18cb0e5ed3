/* SPDX-License-Identifier: BSD-3-Clause */
/* peer_sundials.c — SUNDIALS (ARKODE and CVODE, serial vectors) as a peer in the benchmark
 * suite (suite.h).
 *
 * Measures, on the same right-hand sides as every other solver:
 * - fixed step: ARKODE with the classical Euler, Heun and RK4 tables (ARKodeButcherTable_Create
 *   from the suite's tables), one step per ARK_ONE_STEP call, after a ReInit per solve.
 *   ARKStep (explicit part only) computes them correctly. ERKStep of SUNDIALS 6.4.1 treats a
 *   table whose last node is c = 1 as first-same-as-last even when its last row is not b
 *   (fixed in 6.7.0): Heun and RK4 then reuse f(t + h, Y_s) as the next step's first stage,
 *   take 1 and 3 calls per step, and are wrong. Those rows are shown, marked, and never
 *   used as a reference; ERKStep's Euler (c = 0) is correct.
 * - adaptive: ERKStep with ARKODE_BOGACKI_SHAMPINE_4_2_3 and ARKODE_DORMAND_PRINCE_7_4_5
 *   (both truly first-same-as-last: last row of A equals b, checked at run time, so the
 *   6.4.1 defect does not apply), and ARKStep with ARKODE_FEHLBERG_13_7_8 (last node c = 1
 *   but not FSAL, so not through ERKStep). Scalar tolerances rtol = atol = tol (weighted RMS
 *   norm), stop time t1 (no interpolation at the end).
 * - stiff: CVODE, BDF with Newton iteration and the dense direct solver, with the analytic
 *   Jacobian and with CVODE's difference-quotient Jacobian.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "suite.h"

typedef enum { SUN_ERK, SUN_ARK, SUN_CVODE } sun_kind;

typedef struct sun_ctx {
    const bench_sys *sys;
    sun_kind kind;
    SUNContext sunctx;
    N_Vector y;
    void *mem;
    SUNMatrix A;
    SUNLinearSolver LS;
    ARKodeButcherTable table;
    int have_jac;
    long calls;
} sun_ctx;

/* The right-hand side: user_data is the context (counted) */
#define SUN_RHS(NAME, EVAL, PAR_T)                                                                 \
    static int NAME(realtype t, N_Vector y, N_Vector ydot, void *user_data)                        \
    {                                                                                              \
        sun_ctx *x = user_data;                                                                    \
        (void)t;                                                                                   \
        x->calls++;                                                                                \
        EVAL(N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), (const PAR_T *)x->sys->par);         \
        return 0;                                                                                  \
    }
SUN_RHS(sun_vdp, bench_vdp_eval, bench_vdp_par)
SUN_RHS(sun_plane, bench_plane_eval, bench_plane_par)
SUN_RHS(sun_arenstorf, bench_arenstorf_eval, bench_arenstorf_par)

static int sun_vdp_jac(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *user_data,
                       N_Vector t1, N_Vector t2, N_Vector t3)
{
    sun_ctx *x = user_data;
    double Jr[4];
    (void)t, (void)fy, (void)t1, (void)t2, (void)t3;
    bench_vdp_jac(N_VGetArrayPointer(y), Jr, x->sys->par);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            SM_ELEMENT_D(J, i, j) = Jr[2 * i + j]; /* column-major */
    return 0;
}

static ARKRhsFn sun_rhs(const bench_sys *sys)
{
    switch (sys->id) {
    case BENCH_PLANE: return sun_plane;
    case BENCH_ARENSTORF: return sun_arenstorf;
    default: return sun_vdp;
    }
}

static void sun_destroy(void *vctx)
{
    sun_ctx *x = vctx;
    if (!x)
        return;
    if (x->mem) {
        if (x->kind == SUN_ERK)
            ERKStepFree(&x->mem);
        else if (x->kind == SUN_ARK)
            ARKStepFree(&x->mem);
        else
            CVodeFree(&x->mem);
    }
    if (x->LS)
        SUNLinSolFree(x->LS);
    if (x->A)
        SUNMatDestroy(x->A);
    if (x->table)
        ARKodeButcherTable_Free(x->table);
    if (x->y)
        N_VDestroy(x->y);
    if (x->sunctx)
        SUNContext_Free(&x->sunctx);
    free(x);
}

static void set_y0(sun_ctx *x)
{
    memcpy(N_VGetArrayPointer(x->y), x->sys->y0, (size_t)x->sys->n * sizeof(double));
}

static void get_y(const sun_ctx *x, double *y)
{
    memcpy(y, N_VGetArrayPointer(x->y), (size_t)x->sys->n * sizeof(double));
}

/* fixed step: ReInit, then `steps` single steps of h */
static int sun_fixed_run(void *vctx, double h, long steps, double *y, bench_counts *counts)
{
    sun_ctx *x = vctx;
    const double t0 = x->sys->t0;
    double t = t0;
    int rc = 0;
    set_y0(x);
    x->calls = 0;
    if (x->kind == SUN_ERK) {
        rc |= ERKStepReInit(x->mem, sun_rhs(x->sys), t0, x->y);
        rc |= ERKStepSetFixedStep(x->mem, h);
        for (long k = 0; k < steps && rc >= 0; k++)
            rc = ERKStepEvolve(x->mem, t0 + 2.0 * (double)steps * h, x->y, &t, ARK_ONE_STEP);
    } else {
        rc |= ARKStepReInit(x->mem, sun_rhs(x->sys), NULL, t0, x->y);
        rc |= ARKStepSetFixedStep(x->mem, h);
        for (long k = 0; k < steps && rc >= 0; k++)
            rc = ARKStepEvolve(x->mem, t0 + 2.0 * (double)steps * h, x->y, &t, ARK_ONE_STEP);
    }
    get_y(x, y);
    if (counts) {
        counts->rhs = x->calls;
        counts->jac = 0;
        counts->steps = steps;
    }
    return rc < 0;
}

/* adaptive: ReInit, tolerances, stop time t1, one ARK_NORMAL call to t1 */
static int sun_adaptive_run(void *vctx, double tol, long steps, double *y, bench_counts *counts)
{
    sun_ctx *x = vctx;
    const double t0 = x->sys->t0, t1 = x->sys->t1;
    double t = t0;
    long nst = 0, nje = 0;
    int rc = 0;
    (void)steps;
    set_y0(x);
    x->calls = 0;
    if (x->kind == SUN_ERK) {
        rc |= ERKStepReInit(x->mem, sun_rhs(x->sys), t0, x->y);
        rc |= ERKStepSStolerances(x->mem, tol, tol);
        rc |= ERKStepSetStopTime(x->mem, t1);
        if (rc == 0)
            rc = ERKStepEvolve(x->mem, t1, x->y, &t, ARK_NORMAL);
        ERKStepGetNumSteps(x->mem, &nst);
    } else if (x->kind == SUN_ARK) {
        rc |= ARKStepReInit(x->mem, sun_rhs(x->sys), NULL, t0, x->y);
        rc |= ARKStepSStolerances(x->mem, tol, tol);
        rc |= ARKStepSetStopTime(x->mem, t1);
        if (rc == 0)
            rc = ARKStepEvolve(x->mem, t1, x->y, &t, ARK_NORMAL);
        ARKStepGetNumSteps(x->mem, &nst);
    } else {
        rc |= CVodeReInit(x->mem, t0, x->y);
        rc |= CVodeSStolerances(x->mem, tol, tol);
        rc |= CVodeSetStopTime(x->mem, t1);
        if (rc == 0)
            rc = CVode(x->mem, t1, x->y, &t, CV_NORMAL);
        CVodeGetNumSteps(x->mem, &nst);
        CVodeGetNumJacEvals(x->mem, &nje);
    }
    get_y(x, y);
    if (counts) {
        counts->rhs = x->calls;
        counts->jac = nje;
        counts->steps = nst;
    }
    return rc < 0 || t != t1;
}

static sun_ctx *sun_new(const bench_sys *sys, sun_kind kind)
{
    sun_ctx *x = calloc(1, sizeof *x);
    if (!x)
        return NULL;
    x->sys = sys;
    x->kind = kind;
    if (SUNContext_Create(NULL, &x->sunctx) != 0) {
        x->sunctx = NULL;
        sun_destroy(x);
        return NULL;
    }
    x->y = N_VNew_Serial(sys->n, x->sunctx);
    if (!x->y) {
        sun_destroy(x);
        return NULL;
    }
    set_y0(x);
    if (kind == SUN_ERK)
        x->mem = ERKStepCreate(sun_rhs(sys), sys->t0, x->y, x->sunctx);
    else if (kind == SUN_ARK)
        x->mem = ARKStepCreate(sun_rhs(sys), NULL, sys->t0, x->y, x->sunctx);
    else {
        x->mem = CVodeCreate(CV_BDF, x->sunctx);
        if (x->mem && CVodeInit(x->mem, sun_rhs(sys), sys->t0, x->y) != CV_SUCCESS) {
            sun_destroy(x);
            return NULL;
        }
    }
    if (!x->mem) {
        sun_destroy(x);
        return NULL;
    }
    int rc;
    if (kind == SUN_ERK)
        rc = ERKStepSetUserData(x->mem, x) | ERKStepSetMaxNumSteps(x->mem, 100000000L);
    else if (kind == SUN_ARK)
        rc = ARKStepSetUserData(x->mem, x) | ARKStepSetMaxNumSteps(x->mem, 100000000L);
    else
        rc = CVodeSetUserData(x->mem, x) | CVodeSetMaxNumSteps(x->mem, 100000000L);
    if (rc != 0) {
        sun_destroy(x);
        return NULL;
    }
    return x;
}

/* 1 if the table's last node is c = 1 but its last row is not b: SUNDIALS 6.4.1's ERKStep
 * would wrongly reuse the last stage as the next step's first. */
static int fake_fsal(ARKodeButcherTable B)
{
    const int s = B->stages;
    if (B->c[s - 1] != 1.0)
        return 0;
    for (int j = 0; j < s; j++)
        if (B->A[s - 1][j] != B->b[j])
            return 1;
    return 0;
}

static int add(bench_solver *out, int *count, int max, sun_ctx *x, const char *peer,
               const char *label, int flags, int order, double calls_per_step, const char *note,
               int (*run)(void *, double, long, double *, bench_counts *))
{
    if (!x)
        return 1;
    if (*count >= max) {
        sun_destroy(x);
        return 1;
    }
    bench_solver *s = &out[(*count)++];
    memset(s, 0, sizeof *s);
    snprintf(s->label, sizeof s->label, "%s", label);
    snprintf(s->note, sizeof s->note, "%s", note ? note : "");
    s->peer = peer;
    s->flags = flags;
    s->order = order;
    s->step_factor = 1.0;
    s->calls_per_step = calls_per_step;
    s->ctx = x;
    s->run = run;
    s->destroy = sun_destroy;
    return 0;
}

static int fixed_solvers(const bench_sys *sys, bench_method m, bench_solver *out, int max)
{
    const bench_table *tab = bench_fixed_table(m);
    int count = 0;
    for (int erk = 0; erk < 2; erk++) {
        sun_ctx *x = sun_new(sys, erk ? SUN_ERK : SUN_ARK);
        if (!x)
            return count;
        x->table = ARKodeButcherTable_Create(tab->s, tab->order, 0, (realtype *)tab->c,
                                             (realtype *)tab->a, (realtype *)tab->b, NULL);
        int rc = !x->table;
        if (!rc)
            rc = erk ? ERKStepSetTable(x->mem, x->table)
                     : ARKStepSetTables(x->mem, tab->order, 0, NULL, x->table);
        if (rc) {
            sun_destroy(x);
            return count;
        }
        const int wrong = erk && fake_fsal(x->table);
        char label[80], note[320] = "";
        snprintf(label, sizeof label, "ARKODE %s, %s table%s", erk ? "ERKStep" : "ARKStep",
                 tab->name, wrong ? " (wrong: see note)" : "");
        if (wrong)
            snprintf(note, sizeof note,
                     "SUNDIALS 6.4.1 ERKStep treats the %s table (last node c = 1, last row "
                     "not b) as first-same-as-last, reusing f(t + h, Y_s) as the next step's "
                     "first stage: %d instead of %d calls per step, and a wrong result "
                     "(fixed in 6.7.0); never a reference",
                     tab->name, tab->s - 1, tab->s);
        if (!erk && tab->c[tab->s - 1] != 1.0)
            snprintf(note, sizeof note,
                     "ARKStep evaluates f(t + h, y_{n+1}) after each step for its interpolant; "
                     "with the %s table it is not reused as the next step's first stage: %d "
                     "calls per step",
                     tab->name, tab->s + 1);
        if (add(out, &count, max, x, "ARKODE", label, wrong ? BENCH_WRONG : BENCH_SAME, tab->order,
                wrong ? tab->s - 1 : tab->s, note, sun_fixed_run))
            break;
    }
    return count;
}

static int sun_solvers(const bench_sys *sys, bench_task task, bench_method m, bench_solver *out,
                       int max)
{
    int count = 0;
    if (task == BENCH_TASK_FIXED)
        return fixed_solvers(sys, m, out, max);
    if (task == BENCH_TASK_ADAPTIVE) {
        const struct {
            const char *label;
            ARKODE_ERKTableID id;
            int order;
        } list[] = {{"ARKODE Bogacki-Shampine 4_2_3", ARKODE_BOGACKI_SHAMPINE_4_2_3, 3},
                    {"ARKODE Dormand-Prince 7_4_5", ARKODE_DORMAND_PRINCE_7_4_5, 5},
                    {"ARKODE Fehlberg 13_7_8", ARKODE_FEHLBERG_13_7_8, 8}};
        for (size_t i = 0; i < sizeof list / sizeof list[0]; i++) {
            ARKodeButcherTable B = ARKodeButcherTable_LoadERK(list[i].id);
            if (!B)
                continue;
            const int use_ark = fake_fsal(B); /* ERKStep 6.4.1 would treat it as FSAL */
            ARKodeButcherTable_Free(B);
            sun_ctx *x = sun_new(sys, use_ark ? SUN_ARK : SUN_ERK);
            if (!x)
                continue;
            const int rc = use_ark ? ARKStepSetTableNum(x->mem, ARKODE_DIRK_NONE, list[i].id)
                                   : ERKStepSetTableNum(x->mem, list[i].id);
            if (rc) {
                sun_destroy(x);
                continue;
            }
            char label[80];
            snprintf(label, sizeof label, "%s (%s)", list[i].label,
                     use_ark ? "ARKStep" : "ERKStep");
            if (add(out, &count, max, x, "ARKODE", label, 0, list[i].order, 0.0,
                    use_ark ? "last node c = 1 without FSAL: run through ARKStep, not "
                              "SUNDIALS 6.4.1's ERKStep"
                            : NULL,
                    sun_adaptive_run))
                break;
        }
        return count;
    }
    if (task == BENCH_TASK_STIFF && sys->id == BENCH_VDP_STIFF) {
        for (int fd = 0; fd < 2; fd++) {
            sun_ctx *x = sun_new(sys, SUN_CVODE);
            if (!x)
                break;
            x->A = SUNDenseMatrix(sys->n, sys->n, x->sunctx);
            x->LS = x->A ? SUNLinSol_Dense(x->y, x->A, x->sunctx) : NULL;
            int rc = !x->LS || CVodeSetLinearSolver(x->mem, x->LS, x->A) != CV_SUCCESS;
            if (!rc && !fd)
                rc = CVodeSetJacFn(x->mem, sun_vdp_jac) != CV_SUCCESS;
            if (rc) {
                sun_destroy(x);
                break;
            }
            if (add(out, &count, max, x, "CVODE",
                    fd ? "CVODE BDF, difference Jacobian" : "CVODE BDF, analytic Jacobian", 0, 5,
                    0.0, NULL, sun_adaptive_run))
                break;
        }
    }
    return count;
}

static const char *sun_version(void) { return "SUNDIALS " SUNDIALS_VERSION " (ARKODE, CVODE)"; }

const bench_peer bench_peer_sundials = {"sundials", sun_version, sun_solvers};
