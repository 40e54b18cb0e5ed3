/* SPDX-License-Identifier: BSD-3-Clause */
/* verify.c — every method on problems with known solutions (dynkit/verify.h): the error at
 * the end of the span against the reference, the digits reached, the work (calls of f and of
 * the Jacobian, steps) and the time, per method and tolerance or step.
 *
 * References (the data and their sources are in src/problems/references.c):
 *  - van der Pol mu = 1 at t = 15 and mu = 1000 at t = 3000: computed in __float128 by
 *    Taylor series of orders 30 and 40 (tools/vdp_reference.c); at t = 2000 the mu = 1000
 *    value agrees with the Test Set's vdpolm to 4e-15 (F. Mazzia, C. Magherini, Test Set for
 *    IVP Solvers, release 2.4, Univ. Bari 2008).
 *  - Arenstorf: the orbit of E. Hairer, S. P. Nørsett, G. Wanner, "Solving Ordinary
 *    Differential Equations I", 2nd ed., Springer 1993, sec. II.0, eq. (0.2), periodic with
 *    T = 17.0652165601579625588917206249; reference y(T) of the double-data problem
 *    (tools/taylor_reference.c), which equals y(0) to 1.5e-11.
 *  - Robertson at t = 1e11 and HIRES at t = 321.8122: Test Set for IVP Solvers (Mazzia &
 *    Magherini, release 2.4, 2008), problems ROBER and HIRES, computed there with RADAU5 in
 *    extended precision; HIRES confirmed here to 2.8e-16 by a __float128 Taylor series.
 *  - The Brusselator with diffusion (HNW II, sec. IV.10, BRUSS), N = 20 (40 states) at
 *    t = 10: SciPy's DOP853 at 1e-13, confirmed by its Radau IIA to 1.0e-11
 *    (tools/brusselator_reference.py).
 *  - The oscillator x'' = -x: exact, (cos t, -sin t) from (1, 0).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dynkit/brusselator.h"
#include "dynkit/model.h"
#include "dynkit/problems.h"
#include "dynkit/solve.h"
#include "dynkit/verify.h"

const double dyn_verify_rtols[DYN_VERIFY_N_RTOL] = {1e-3, 1e-6, 1e-9};

/* ---- the oscillator, defined here: y = (x, v), x' = v, v' = -x ---- */

static int osc_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)par;
    dydt[0] = y[1];
    dydt[1] = -y[0];
    return 0;
}

static int osc_jac(double t, const double *y, double *J, void *par)
{
    (void)t;
    (void)y;
    (void)par;
    J[0] = 0.0;
    J[1] = 1.0;
    J[2] = -1.0;
    J[3] = 0.0;
    return 0;
}

#define OSC_T1 20.0

/* ---- the problems ---- */

static const long steps_vdp[] = {750, 1500, 3000};        /* h = 0.02, 0.01, 0.005 */
static const long steps_aren[] = {25000, 50000, 100000};  /* h = T / steps */
static const long steps_osc[] = {200, 400, 800};          /* h = 0.1, 0.05, 0.025 */

typedef struct vp {
    dyn_verify_problem pub;
    const char *ref;        /* dyn_reference name, or NULL (exact) */
} vp;

static const vp problems[] = {
    {{.name = "vanderpol-mu1",
      .title = "van der Pol, mu = 1, y0 = (2, 0), t in [0, 15]",
      .reference = "__float128 Taylor series, orders 30 and 40, and RK4 with Richardson "
                   "extrapolation (tools/vdp_reference.c)",
      .model = "vanderpol", .t0 = 0.0, .t1 = 15.0, .n = 2, .stiff = 0, .relative = 0,
      .atol_scale = 1.0, .n_fixed = 3, .fixed_steps = steps_vdp},
     "vanderpol-mu1-15"},
    {{.name = "arenstorf",
      .title = "Arenstorf orbit over one period T = 17.0652165601579625588917206249",
      .reference = "periodic orbit of Hairer, Norsett & Wanner, Solving ODEs I, sec. II.0; y(T) "
                   "of the double-data problem, = y(0) to 1.5e-11 (tools/taylor_reference.c)",
      .model = "arenstorf", .t0 = 0.0, .t1 = DYN_ARENSTORF_PERIOD, .n = 4, .stiff = 0,
      .relative = 0, .atol_scale = 1.0, .n_fixed = 3, .fixed_steps = steps_aren},
     "arenstorf-period"},
    {{.name = "oscillator",
      .title = "harmonic oscillator x'' = -x, (x, x') = (1, 0), t in [0, 20]",
      .reference = "exact: (cos 20, -sin 20)",
      .model = NULL, .t0 = 0.0, .t1 = OSC_T1, .n = 2, .stiff = 0, .relative = 0,
      .atol_scale = 1.0, .n_fixed = 3, .fixed_steps = steps_osc},
     NULL},
    {{.name = "vanderpol-mu1000",
      .title = "van der Pol, mu = 1000, y0 = (2, 0), t in [0, 3000] (stiff)",
      .reference = "__float128 Taylor series, orders 30 and 40 (tools/vdp_reference.c); at "
                   "t = 2000 within 4e-15 of the Test Set's vdpolm (Mazzia & Magherini, Bari, "
                   "release 2.4, 2008)",
      .model = "vanderpol", .t0 = 0.0, .t1 = 3000.0, .n = 2, .stiff = 1, .relative = 1,
      .atol_scale = 1e-3},
     "vanderpol-mu1000-3000"},
    {{.name = "robertson",
      .title = "Robertson's kinetics, t in [0, 1e11] (stiff)",
      .reference = "Test Set for IVP Solvers (Mazzia & Magherini, Univ. Bari, release 2.4, "
                   "2008), ROBER: RADAU5 in extended precision",
      .model = "robertson", .t0 = 0.0, .t1 = 1e11, .n = 3, .stiff = 1, .relative = 1,
      .atol_scale = 1e-6},
     "robertson-1e11"},
    {{.name = "hires",
      .title = "HIRES kinetics, 8 states, t in [0, 321.8122] (stiff)",
      .reference = "Test Set for IVP Solvers (Mazzia & Magherini, Univ. Bari, release 2.4, "
                   "2008), HIRES: RADAU5 in extended precision; confirmed by a __float128 "
                   "Taylor series",
      .model = "hires", .t0 = 0.0, .t1 = 321.8122, .n = 8, .stiff = 1, .relative = 1,
      .atol_scale = 1e-4},
     "hires-321.8122"},
    {{.name = "brusselator",
      .title = "Brusselator with diffusion, N = 20 (40 states, band 2 + 2), t in [0, 10] (stiff)",
      .reference = "SciPy DOP853 at 1e-13, confirmed by SciPy Radau IIA to 1.0e-11 "
                   "(tools/brusselator_reference.py); the problem BRUSS of Hairer & Wanner, "
                   "Solving ODEs II, sec. IV.10",
      .model = "brusselator:20", .t0 = 0.0, .t1 = 10.0, .n = 40, .stiff = 1, .relative = 1,
      .atol_scale = 1.0},
     "brusselator-20-10"},
};

#define N_PROBLEMS ((int)(sizeof problems / sizeof problems[0]))
#define MAX_N 40

int dyn_verify_problem_count(void) { return N_PROBLEMS; }

const dyn_verify_problem *dyn_verify_problem_at(int i)
{
    return i >= 0 && i < N_PROBLEMS ? &problems[i].pub : NULL;
}

const dyn_verify_problem *dyn_verify_problem_find(const char *name)
{
    for (int i = 0; name && i < N_PROBLEMS; i++)
        if (strcmp(problems[i].pub.name, name) == 0)
            return &problems[i].pub;
    return NULL;
}

static const vp *vp_of(const dyn_verify_problem *p) { return (const vp *)p; }

int dyn_verify_reference(const dyn_verify_problem *p, double *ref, char *err, size_t errlen)
{
    const vp *v = vp_of(p);
    if (!v->ref) {
        ref[0] = cos(OSC_T1);
        ref[1] = -sin(OSC_T1);
        return 0;
    }
    const dyn_reference *r = dyn_reference_find(v->ref);
    if (!r || r->n != p->n || r->t1 != p->t1) {
        if (err && errlen)
            snprintf(err, errlen, "problem %s: reference %s is missing or does not match",
                     p->name, v->ref);
        return 1;
    }
    memcpy(ref, r->y, (size_t)p->n * sizeof *ref);
    return 0;
}

/* The system of a problem: parameters (par_size bytes, caller-owned), initial state. */
typedef struct setup {
    dyn_system sys;
    dyn_jac_fn jac;
    /* the model's band of the Jacobian (dyn_model.jac_banded ...), for dyn_solve's runs */
    int banded, lower, upper;
    dyn_jac_fn jac_band;
    double y0[MAX_N];
    double ref[MAX_N];
    void *par;
} setup;

/* The system of problem p from its model m and reference r. */
static int setup_model(const dyn_model *m, const dyn_reference *r, const dyn_verify_problem *p,
                       setup *s, char *err, size_t errlen)
{
    s->par = calloc(1, m->par_size);
    if (!s->par) {
        if (err && errlen)
            snprintf(err, errlen, "out of memory");
        return 1;
    }
    if (dyn_reference_setup(r, s->par, s->y0, err, errlen))
        return 1;
    s->sys = (dyn_system){m->rhs, m->n_states, s->par};
    s->jac = m->jacobian;
    s->banded = m->jac_banded;
    s->lower = m->jac_lower;
    s->upper = m->jac_upper;
    s->jac_band = m->jacobian_band;
    return dyn_verify_reference(p, s->ref, err, errlen);
}

static int setup_problem(const dyn_verify_problem *p, setup *s, char *err, size_t errlen)
{
    const vp *v = vp_of(p);
    memset(s, 0, sizeof *s);
    if (!v->ref) {
        s->sys = (dyn_system){osc_rhs, 2, NULL};
        s->jac = osc_jac;
        s->y0[0] = 1.0;
        s->y0[1] = 0.0;
        return dyn_verify_reference(p, s->ref, err, errlen);
    }
    const dyn_reference *r = dyn_reference_find(v->ref);
    dyn_model *sized = dyn_model_find(p->model) ? NULL : dyn_brusselator_for_name(p->model);
    const dyn_model *m = sized ? sized : dyn_model_find(p->model);
    if (!r || !m || m->n_states != p->n || p->n > MAX_N) {
        if (err && errlen)
            snprintf(err, errlen, "problem %s: model %s or reference %s missing", p->name,
                     p->model, v->ref);
        dyn_brusselator_free(sized);
        return 1;
    }
    /* the right-hand side and Jacobian are functions of the library: the model itself is
     * not needed after the setup */
    const int rc = setup_model(m, r, p, s, err, errlen);
    dyn_brusselator_free(sized);
    return rc;
}

/* ---- the rows ---- */

/* A method of the run: a registry entry or an extra. */
typedef struct vmethod {
    const char *name;
    const dyn_tableau *tab;        /* NULL for an extra */
    const dyn_verify_method *extra;
    int adaptive, stiff;
} vmethod;

/* The library's integrators (not the discrete map, which solves no differential
 * equation), then the extra methods. */
static int n_integrators(void)
{
    int k = 0;
    for (int i = 0; i < dyn_method_count(); i++)
        k += !dyn_method_is_map(dyn_method_at(i));
    return k;
}

static const dyn_tableau *integrator_at(int i)
{
    for (int j = 0; j < dyn_method_count(); j++)
        if (!dyn_method_is_map(dyn_method_at(j)) && i-- == 0)
            return dyn_method_at(j);
    return NULL;
}

static int n_methods(const dyn_verify_opts *o) { return n_integrators() + o->n_extra; }

static vmethod method_at(const dyn_verify_opts *o, int i)
{
    vmethod m = {0};
    if (i < n_integrators()) {
        m.tab = integrator_at(i);
        m.name = m.tab->name;
        m.adaptive = dyn_method_is_adaptive(m.tab);
        m.stiff = dyn_method_is_stiff(m.tab);
    } else {
        m.extra = &o->extra[i - n_integrators()];
        m.name = m.extra->name;
        m.adaptive = 1;
        m.stiff = m.extra->stiff;
    }
    return m;
}

static int method_selected(const dyn_verify_opts *o, const vmethod *m)
{
    if (!o->method)
        return 1;
    if (strcmp(o->method, m->name) == 0)
        return 1;
    return m->tab && m->tab->alias && strcmp(o->method, m->tab->alias) == 0;
}

/* Rows of one problem and method. */
static long rows_of(const dyn_verify_opts *o, const dyn_verify_problem *p, const vmethod *m)
{
    if (!m->adaptive) {
        if (p->stiff || p->n_fixed == 0)
            return 1; /* skipped, one row that says so */
        return o->quick && p->n_fixed > 2 ? 2 : p->n_fixed;
    }
    return o->quick ? 2 : DYN_VERIFY_N_RTOL;
}

static int check_names(const dyn_verify_opts *o, char *err, size_t errlen)
{
    char list[640];
    size_t used = 0;
    if (o->problem && !dyn_verify_problem_find(o->problem)) {
        list[0] = '\0';
        for (int i = 0; i < N_PROBLEMS && used < sizeof list; i++)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "",
                                     problems[i].pub.name);
        if (err && errlen)
            snprintf(err, errlen, "unknown problem '%s' (accepted: %s)", o->problem, list);
        return 1;
    }
    if (o->method) {
        int found = 0;
        for (int i = 0; i < n_methods(o); i++) {
            vmethod m = method_at(o, i);
            found |= method_selected(o, &m);
        }
        if (!found) {
            list[0] = '\0';
            used = 0;
            for (int i = 0; i < n_methods(o) && used < sizeof list; i++)
                used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "",
                                         method_at(o, i).name);
            if (err && errlen)
                snprintf(err, errlen, "unknown method '%s' (accepted: %s)", o->method, list);
            return 1;
        }
    }
    return 0;
}

long dyn_verify_count(const dyn_verify_opts *opts, char *err, size_t errlen)
{
    static const dyn_verify_opts none;
    const dyn_verify_opts *o = opts ? opts : &none;
    if (check_names(o, err, errlen))
        return -1;
    long count = 0;
    for (int i = 0; i < N_PROBLEMS; i++) {
        const dyn_verify_problem *p = &problems[i].pub;
        if (o->problem && strcmp(o->problem, p->name) != 0)
            continue;
        for (int k = 0; k < n_methods(o); k++) {
            vmethod m = method_at(o, k);
            if (method_selected(o, &m))
                count += rows_of(o, p, &m);
        }
    }
    return count;
}

static double now_seconds(void)
{
    struct timespec ts;
    if (timespec_get(&ts, TIME_UTC) != TIME_UTC)
        return (double)clock() / CLOCKS_PER_SEC;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Error of y against the reference in the problem's norm. */
static double error_of(const dyn_verify_problem *p, const double *y, const double *ref)
{
    double e = 0.0;
    for (int i = 0; i < p->n; i++) {
        double d = fabs(y[i] - ref[i]);
        if (p->relative && ref[i] != 0.0)
            d /= fabs(ref[i]);
        if (!(d <= e)) /* NaN wins */
            e = d;
    }
    return e;
}

static void finish_row(dyn_verify_row *row, const setup *s, const double *y, const dyn_result *res)
{
    const dyn_verify_problem *p = row->problem;
    row->status = res->status;
    row->stats = res->stats;
    row->t_reached = res->t;
    row->stiff_detected = res->stiff;
    row->error = NAN;
    row->digits = NAN;
    if (res->status == DYN_OK) {
        row->outcome = DYN_VERIFY_DONE;
        row->error = error_of(p, y, s->ref);
        row->digits = row->error > 0.0 ? -log10(row->error) : INFINITY;
        if (!isfinite(row->error)) {
            row->outcome = DYN_VERIFY_FAILED;
            snprintf(row->note, sizeof row->note, "the final state is not finite");
        } else if (res->stiff) {
            snprintf(row->note, sizeof row->note, "stiff from t = %.3g (the stiffness test)",
                     res->stiff_t);
        }
    } else if (res->status == DYN_ERR_MAX_STEPS || res->status == DYN_ERR_STEP_SIZE) {
        row->outcome = DYN_VERIFY_LIMIT;
        if (res->status == DYN_ERR_MAX_STEPS)
            snprintf(row->note, sizeof row->note, "too many steps: stopped at t = %.3g%s",
                     res->t, res->stiff ? "; stiff" : "");
        else
            snprintf(row->note, sizeof row->note, "step size too small at t = %.3g%s",
                     res->t, res->stiff ? "; stiff" : "");
    } else {
        row->outcome = DYN_VERIFY_FAILED;
        snprintf(row->note, sizeof row->note, "failed at t = %.3g: %.120s", res->t,
                 res->message);
    }
    /* an explicit method that gives up on a stiff problem is the expected, honest result */
    row->ok = row->outcome == DYN_VERIFY_DONE ||
              (row->outcome != DYN_VERIFY_DONE && p->stiff && !row->stiff_method);
}

/* One solve: a fixed-step table at h, a registry method under dyn_solve, or an extra. */
static void run_row(const vmethod *m, const setup *s, long max_steps, dyn_verify_row *row)
{
    const dyn_verify_problem *p = row->problem;
    const int n = p->n;
    double y[MAX_N];
    dyn_result res;
    memset(&res, 0, sizeof res);
    memcpy(y, s->y0, (size_t)n * sizeof *y);
    double start = now_seconds();
    if (!m->adaptive) {
        size_t size = dyn_fixed_work_size(m->tab, n);
        double *work = malloc(size * sizeof *work);
        if (!work) {
            res.status = DYN_ERR_ARG;
            snprintf(res.message, sizeof res.message, "out of memory");
        } else {
            start = now_seconds();
            dyn_fixed_solve(m->tab, &s->sys, p->t0, p->t1, row->h, s->y0, y, work, NULL, &res);
        }
        row->seconds = now_seconds() - start;
        free(work);
    } else if (m->extra) {
        m->extra->solve(&s->sys, s->jac, p->t0, p->t1, s->y0, row->rtol, row->atol, max_steps, y,
                        &res, m->extra->ctx);
        row->seconds = now_seconds() - start;
    } else {
        dyn_solve_opts o = {0};
        o.rtol = row->rtol;
        o.atol = row->atol;
        o.max_steps = max_steps;
        o.jacobian = s->jac;
        o.jac_banded = s->banded;
        o.jac_lower = s->lower;
        o.jac_upper = s->upper;
        o.jacobian_band = s->jac_band;
        const size_t size = dyn_solve_work_size(m->tab, n, &o);
        const size_t isize = dyn_solve_iwork_size(m->tab, n);
        double *work = malloc(size * sizeof *work);
        int *iwork = isize ? malloc(isize * sizeof *iwork) : NULL;
        o.iwork = iwork;
        if (!work || (isize && !iwork)) {
            res.status = DYN_ERR_ARG;
            snprintf(res.message, sizeof res.message, "out of memory");
        } else {
            start = now_seconds();
            dyn_solve(m->tab, &s->sys, p->t0, p->t1, s->y0, y, work, &o, &res);
        }
        row->seconds = now_seconds() - start;
        free(work);
        free(iwork);
    }
    finish_row(row, s, y, &res);
}

int dyn_verify_run(const dyn_verify_opts *opts, dyn_verify_row *rows, long capacity,
                   long *n_rows, char *err, size_t errlen)
{
    static const dyn_verify_opts none;
    const dyn_verify_opts *o = opts ? opts : &none;
    long made = 0;
    if (n_rows)
        *n_rows = 0;
    const long count = dyn_verify_count(o, err, errlen);
    if (count < 0)
        return DYN_ERR_ARG;
    if (!rows || capacity < count) {
        if (err && errlen)
            snprintf(err, errlen, "room for %ld rows, %ld needed", capacity, count);
        return DYN_ERR_ARG;
    }
    const long limit = o->explicit_max_steps > 0 ? o->explicit_max_steps
                       : o->quick                ? 20000L
                                                 : 100000L;
    int status = DYN_OK;
    for (int i = 0; i < N_PROBLEMS && status == DYN_OK; i++) {
        const dyn_verify_problem *p = &problems[i].pub;
        if (o->problem && strcmp(o->problem, p->name) != 0)
            continue;
        setup s;
        if (setup_problem(p, &s, err, errlen)) {
            free(s.par);
            status = DYN_ERR_ARG;
            break;
        }
        for (int k = 0; k < n_methods(o) && status == DYN_OK; k++) {
            const vmethod m = method_at(o, k);
            if (!method_selected(o, &m))
                continue;
            const long nr = rows_of(o, p, &m);
            for (long j = 0; j < nr && status == DYN_OK; j++) {
                dyn_verify_row *row = &rows[made];
                memset(row, 0, sizeof *row);
                row->problem = p;
                row->method = m.name;
                row->adaptive = m.adaptive;
                row->stiff_method = m.stiff;
                row->error = row->digits = row->order = NAN;
                row->t_reached = p->t0;
                if (!m.adaptive && (p->stiff || p->n_fixed == 0)) {
                    row->outcome = DYN_VERIFY_SKIPPED;
                    row->ok = 1;
                    snprintf(row->note, sizeof row->note,
                             "stiff: skipped (explicit fixed steps would have to resolve the "
                             "fastest decay)");
                } else if (!m.adaptive) {
                    row->steps = p->fixed_steps[j];
                    row->h = (p->t1 - p->t0) / (double)row->steps;
                    run_row(&m, &s, 0, row);
                    if (j > 0 && rows[made - 1].error > 0.0 && row->error > 0.0)
                        row->order = log(rows[made - 1].error / row->error) /
                                     log((double)row->steps / (double)rows[made - 1].steps);
                } else {
                    row->rtol = dyn_verify_rtols[j];
                    row->atol = p->atol_scale * row->rtol;
                    run_row(&m, &s, p->stiff && !m.stiff ? limit : 0, row);
                }
                made++;
                if (n_rows)
                    *n_rows = made;
                if (o->on_row && o->on_row(row, o->row_ctx))
                    status = DYN_STOPPED;
            }
        }
        free(s.par);
    }
    return status;
}
