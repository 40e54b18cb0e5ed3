/* SPDX-License-Identifier: BSD-3-Clause */
/* The entry of a live page's WebAssembly module: one run of the model the module was built
 * with (dynkit_model(), the model's C as the jit compiles it, or a built-in model), set up as
 * `dynkit run` sets it up (cli/run/run_options.c: the defaults, the parameters, prepare, the
 * default initial state of those parameters, then the initial values given) and run by the
 * library's dyn_run with the options `dynkit run` passes (cli/run/run_solve.c). The page's
 * script writes the settings into the buffers these functions return and reads the samples
 * back (t, the states, the extra outputs per row). Every PROGRESS_ROWS samples the run tells
 * the page how many rows it has (the module's one import, dynkit.progress), so that a long
 * run is drawn as it computes. Compiled for wasm32-wasi only (backends/wasm/CMakeLists.txt);
 * docs/web.md, "Live pages". */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/model.h"
#include "dynkit/run.h"

#define LIVE_EXPORT(name) __attribute__((export_name(name)))

const dyn_model *dynkit_model(void);

/* The page's function that reads the rows written so far (their count); it may copy them
 * but not change them. */
__attribute__((import_module("dynkit"), import_name("progress"))) void dk_live_progress(double n);

#define PROGRESS_ROWS 1024

/* The settings of a run, written by the page before dk_live_run. */
enum {
    SET_T0, SET_T1, SET_STEP, SET_RTOL, SET_ATOL, SET_END, SET_AT_STEPS, SET_EVERY,
    SET_MAX_ROWS, SET_COUNT
};

static double settings[SET_COUNT];
static double *params, *inits, *given; /* (n_params), (n_states), (n_states) 1: use inits */
static char method_name[64];
static double *rows;
static long n_rows, cap_rows;
static int n_cols;
static char message[1024];
static double rhs_calls; /* of the last run */

static const dyn_model *model(void)
{
    static const dyn_model *m;
    if (!m)
        m = dynkit_model();
    return m;
}

LIVE_EXPORT("dk_live_settings") double *dk_live_settings(void) { return settings; }
LIVE_EXPORT("dk_live_method") char *dk_live_method(void) { return method_name; }
LIVE_EXPORT("dk_live_message") const char *dk_live_message(void) { return message; }
LIVE_EXPORT("dk_live_rows") const double *dk_live_rows(void) { return rows; }
LIVE_EXPORT("dk_live_cols") int dk_live_cols(void) { return n_cols; }
LIVE_EXPORT("dk_live_rhs_calls") double dk_live_rhs_calls(void) { return rhs_calls; }

/* The buffers of the parameters, the initial values and which of them are given; 0 when out
 * of memory. */
LIVE_EXPORT("dk_live_setup") int dk_live_setup(void)
{
    const dyn_model *m = model();
    if (!m)
        return 0;
    if (!params) {
        params = calloc((size_t)(m->n_params > 0 ? m->n_params : 1), sizeof *params);
        inits = calloc((size_t)m->n_states, sizeof *inits);
        given = calloc((size_t)m->n_states, sizeof *given);
    }
    n_cols = 1 + m->n_states + m->n_outputs;
    return params && inits && given;
}
LIVE_EXPORT("dk_live_params") double *dk_live_params(void) { return params; }
LIVE_EXPORT("dk_live_inits") double *dk_live_inits(void) { return inits; }
LIVE_EXPORT("dk_live_given") double *dk_live_given(void) { return given; }

typedef struct recording {
    const dyn_model *m;
    const void *par;
} recording;

static int on_sample(long k, double t, const double *y, void *ctx)
{
    (void)k;
    const recording *r = ctx;
    const dyn_model *m = r->m;
    if (n_rows >= cap_rows) {
        const long limit = (long)settings[SET_MAX_ROWS];
        if (n_rows >= limit) {
            snprintf(message, sizeof message, "the run was cut at %ld samples", limit);
            return 1;
        }
        long cap = cap_rows ? 2 * cap_rows : 4096;
        if (cap > limit)
            cap = limit;
        double *grown = realloc(rows, (size_t)cap * (size_t)n_cols * sizeof *rows);
        if (!grown) {
            snprintf(message, sizeof message, "out of memory after %ld samples", n_rows);
            return 1;
        }
        rows = grown;
        cap_rows = cap;
    }
    double *row = rows + n_rows * n_cols;
    row[0] = t;
    memcpy(row + 1, y, (size_t)m->n_states * sizeof *y);
    if (m->n_outputs > 0 && m->compute_outputs(t, y, r->par, row + 1 + m->n_states))
        for (int i = 0; i < m->n_outputs; i++)
            row[1 + m->n_states + i] = __builtin_nan("");
    n_rows++;
    if (n_rows % PROGRESS_ROWS == 0)
        dk_live_progress((double)n_rows);
    return 0;
}

/* One run with the settings: the number of rows (dk_live_rows, n_cols doubles each), or -1
 * when it could not start; the message (dk_live_message) says why a run stopped or failed. */
LIVE_EXPORT("dk_live_run") long dk_live_run(void)
{
    const dyn_model *m = model();
    message[0] = '\0';
    n_rows = 0;
    if (!m || !dk_live_setup()) {
        snprintf(message, sizeof message, "out of memory");
        return -1;
    }
    const dyn_tableau *method = dyn_run_method_find(method_name);
    if (!method) {
        snprintf(message, sizeof message, "unknown method '%s'", method_name);
        return -1;
    }
    void *par = calloc(1, m->par_size ? m->par_size : 1);
    double *y0 = calloc((size_t)m->n_states, sizeof *y0);
    double *y = calloc((size_t)m->n_states, sizeof *y);
    if (!par || !y0 || !y) {
        free(par), free(y0), free(y);
        snprintf(message, sizeof message, "out of memory");
        return -1;
    }
    char err[512];
    dyn_model_default_params(m, par, err, sizeof err);
    for (int i = 0; i < m->n_params; i++)
        dyn_model_set_param(m, par, i, params[i]);
    if (m->seed_offset) { /* seed 0, as `dynkit run` without --seed */
        double *sd = (double *)((char *)par + m->seed_offset);
        sd[0] = sd[1] = 0.0;
    }
    if (m->prepare && m->prepare(par, err, sizeof err)) {
        snprintf(message, sizeof message, "%s", err);
        free(par), free(y0), free(y);
        return -1;
    }
    dyn_model_initial_state(m, par, y0);
    for (int i = 0; i < m->n_states; i++)
        if (given[i] != 0.0)
            y0[i] = inits[i];
    recording rec = {m, par};
    dyn_run_opts o = {0};
    o.method = method;
    o.t0 = settings[SET_T0];
    o.t1 = settings[SET_T1];
    o.step = settings[SET_STEP];
    o.end = (dyn_end_policy)(int)settings[SET_END];
    o.rtol = settings[SET_RTOL];
    o.atol = settings[SET_ATOL];
    o.at_steps = settings[SET_AT_STEPS] != 0.0;
    o.every = (long)settings[SET_EVERY];
    o.output = on_sample;
    o.output_ctx = &rec;
    dyn_result res;
    memset(&res, 0, sizeof res);
    const int status = dyn_run(m, par, y0, &o, y, &res);
    rhs_calls = (double)res.stats.rhs_calls;
    if (status != DYN_OK && !message[0])
        snprintf(message, sizeof message, "%s", status < 0 ? "out of memory" : res.message);
    free(par), free(y0), free(y);
    return n_rows;
}
