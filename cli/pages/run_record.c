/* SPDX-License-Identifier: BSD-3-Clause */
/* Recorded runs for pictures: one run of a model kept in memory (t, states, extra outputs),
 * with any method (cli_run_solve: adaptive methods give samples on the --step grid, at
 * --times or at every accepted step; cvode when built), thinned to a number of samples a screen can show (every k-th sample, always the
 * first and the last), and the names and units of its columns. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pages/pages.h"

int cli_series_column(const dyn_model *m, const char *name)
{
    if (strcmp(name, "t") == 0)
        return 0;
    int i = dyn_model_state_index(m, name);
    if (i >= 0)
        return 1 + i;
    i = dyn_model_output_index(m, name);
    return i >= 0 ? 1 + m->n_states + i : -1;
}

const char *cli_series_column_name(const dyn_model *m, int j)
{
    if (j == 0)
        return "t";
    if (j <= m->n_states)
        return m->states[j - 1].name;
    return m->outputs[j - 1 - m->n_states].name;
}

const char *cli_series_column_unit(const dyn_model *m, int j)
{
    if (j == 0)
        return cli_time_unit(m);
    if (j <= m->n_states)
        return m->states[j - 1].unit;
    return m->outputs[j - 1 - m->n_states].unit;
}

char *cli_series_column_names(const dyn_model *m, char *buf, size_t size)
{
    size_t used = 0;
    if (size)
        buf[0] = '\0';
    for (int j = 0; j < 1 + m->n_states + m->n_outputs && used < size; j++)
        used += (size_t)snprintf(buf + used, size - used, "%s%s", j ? ", " : "",
                                 cli_series_column_name(m, j));
    return buf;
}

typedef struct recorder {
    const cli_run *run;
    cli_series *s;
    long every, capacity;
    int grows;      /* sample count not known: thin as the rows fill up */
    long seen;      /* samples seen */
    double *latest; /* (n_states) the last sample seen, kept even when thinned away */
    double latest_t;
    int have_latest;
    const char *warned[8];
    int n_warned;
    long crossings;     /* of the Poincaré section so far */
    double last_cross;  /* the time of the last one */
} recorder;

static void warn_once(recorder *r, double t, const double *y)
{
    const dyn_model *m = r->run->model;
    const char *w = m->warn ? m->warn(t, y, r->run->par) : NULL;
    if (!w || r->run->quiet)
        return;
    for (int i = 0; i < r->n_warned; i++)
        if (r->warned[i] == w)
            return;
    cli_stderr("dynkit: warning (%s) at t = %.6g s: %s\n", r->s->label, t, w);
    if (r->n_warned < (int)(sizeof r->warned / sizeof r->warned[0]))
        r->warned[r->n_warned++] = w;
}

static void store(recorder *r, double t, const double *y)
{
    const dyn_model *m = r->run->model;
    cli_series *s = r->s;
    if (s->rows >= r->capacity)
        return;
    double *row = s->data + s->rows * s->cols;
    row[0] = t;
    memcpy(row + 1, y, (size_t)m->n_states * sizeof *y);
    if (m->n_outputs > 0 && m->compute_outputs(t, y, r->run->par, row + 1 + m->n_states))
        for (int i = 0; i < m->n_outputs; i++)
            row[1 + m->n_states + i] = NAN;
    s->rows++;
}

/* Rows full with more samples to come: keep rows 0, 2, 4, ... (samples 0, 2k, 4k, ...) and
 * take every 2k-th sample from now on. */
static void halve(recorder *r)
{
    cli_series *s = r->s;
    long kept = 0;
    for (long i = 0; i < s->rows; i += 2, kept++)
        if (kept != i)
            memcpy(s->data + kept * s->cols, s->data + i * s->cols,
                   (size_t)s->cols * sizeof *s->data);
    s->rows = kept;
    r->every *= 2;
}

/* A crossing of the run's Poincaré section (cli_run.section): a row, as dynkit run writes
 * it (t = k*T for a section in t; for poimap=period the time since the crossing before),
 * none before the model's transient. */
static int on_crossing(int index, double t, const double *y, int direction, void *ctx)
{
    (void)direction;
    recorder *r = ctx;
    const cli_run *run = r->run;
    if (index != run->n_events || t < run->model->t_trans)
        return 0;
    double row_t = cli_section_time(run, t);
    if (run->section.kind == DYN_POINCARE_PERIOD) {
        const double since = t - r->last_cross;
        r->last_cross = t;
        if (r->crossings++ == 0)
            return 0;
        row_t = since;
    }
    if (r->s->rows >= r->capacity - 2)
        halve(r);
    store(r, row_t, y);
    r->seen++;
    return 0;
}

static int on_sample(long k, double t, const double *y, void *ctx)
{
    recorder *r = ctx;
    warn_once(r, t, y);
    if (r->run->section.kind != DYN_POINCARE_NONE)
        return 0; /* the rows are the section's crossings */
    r->seen++;
    if (k % r->every == 0) {
        if (r->grows && r->s->rows >= r->capacity - 2)
            halve(r);
        if (k % r->every == 0)
            store(r, t, y);
    }
    memcpy(r->latest, y, (size_t)r->run->model->n_states * sizeof *y);
    r->latest_t = t;
    r->have_latest = 1;
    return 0;
}

/* "rk4, h = 0.01 s"; adaptive methods: "dp45, rtol = 0.001, atol = 1e-06"; a map:
 * "discrete map, 2000 steps". */
static void label(const cli_run *run, const dyn_tableau *method, double step, char *buf,
                  size_t size)
{
    dyn_grid g;
    if (dyn_method_is_map(method) &&
        dyn_grid_plan(run->t0, run->t1, step, run->end, &g, NULL, 0) == DYN_OK)
        snprintf(buf, size, "%s map, %ld steps", method->name, g.whole_steps);
    else if (dyn_method_is_adaptive(method))
        snprintf(buf, size, "%s, rtol = %g, atol = %g", method->name,
                 run->rtol > 0 ? run->rtol : DYN_DEFAULT_RTOL,
                 run->atol > 0 ? run->atol : DYN_DEFAULT_ATOL);
    else
        snprintf(buf, size, "%s, h = %g %s", method->name, step, cli_time_unit(run->model));
}

int cli_series_record(const cli_run *run, const dyn_tableau *method, double step, long max_rows,
                      cli_series *s)
{
    const dyn_model *m = run->model;
    dyn_grid grid;
    char why[256];
    /* this run: the options of run with its own method and step */
    cli_run one = *run;
    one.method = method;
    if (step > 0.0) {
        one.step = step;
        one.step_given = 1;
    }
    step = one.step;
    memset(s, 0, sizeof *s);
    s->method = method;
    s->step = step;
    s->cols = 1 + m->n_states + m->n_outputs;
    label(run, method, step, s->label, sizeof s->label);
    recorder r = {.run = run, .s = s};
    long samples = -1; /* not known beforehand */
    if (cli_run_at_steps(&one) || run->section.kind != DYN_POINCARE_NONE) {
        r.grows = 1;
        r.every = run->every > 1 ? run->every : 1;
        r.capacity = max_rows > 4 ? max_rows : 4;
    } else {
        /* the samples: the grid t0 + k*step (the output grid of adaptive methods), or
         * --times */
        if (dyn_grid_plan(run->t0, run->t1, step, run->end, &grid, why, sizeof why))
            return cli_usage_error(NULL, "%s: --step %g over --tspan %g:%g: %s", s->label, step,
                                   run->t0, run->t1, why);
        samples = dyn_method_is_adaptive(method) && run->times ? run->n_times + 1 : grid.samples;
        /* the smallest k with ceil((samples - 1) / k) + 1 <= max_rows */
        r.every = max_rows > 1 ? (samples - 1 + max_rows - 2) / (max_rows - 1) : 1;
        if (r.every < 1)
            r.every = 1;
        if (run->every > r.every)
            r.every = run->every;
        r.capacity = (samples + r.every - 1) / r.every + 2;
    }
    s->samples = samples;
    const int n = m->n_states;
    double *y = malloc(2 * (size_t)n * sizeof *y);
    s->data = malloc((size_t)r.capacity * (size_t)s->cols * sizeof *s->data);
    if (!y || !s->data) {
        free(y);
        snprintf(s->message, sizeof s->message, "out of memory for %ld samples of %d columns",
                 r.capacity, s->cols);
        s->status = DYN_ERR_ARG;
        return CLI_FAILED;
    }
    r.latest = y + n;
    /* a global may assign parameters (XPPAUT's spike counter): each series starts from the
     * run's values, and they are back when it ends */
    void *par0 = malloc(m->par_size ? m->par_size : 1);
    if (!par0) {
        free(y);
        snprintf(s->message, sizeof s->message, "out of memory");
        s->status = DYN_ERR_ARG;
        return CLI_FAILED;
    }
    memcpy(par0, run->par, m->par_size);
    dyn_result res;
    memset(&res, 0, sizeof res);
    const int section = run->section.kind != DYN_POINCARE_NONE;
    if (cli_run_solve(&one, 1, on_sample, &r, section ? on_crossing : NULL, section ? &r : NULL,
                      NULL, NULL, y, &res) < 0) {
        res.status = DYN_ERR_ARG;
        snprintf(res.message, sizeof res.message, "out of memory for the solver's workspace");
    }
    s->status = res.status;
    if (s->status == DYN_ERR_NONFINITE && res.fail_index >= 0)
        snprintf(s->message, sizeof s->message,
                 "%s: state %s became NaN or Inf at t = %s; the samples up to t = %s "
                 "are shown",
                 s->label, m->states[res.fail_index].name, CLI_NUM(res.fail_t), CLI_NUM(res.t));
    else if (s->status != DYN_OK)
        snprintf(s->message, sizeof s->message, "%s: %s; the samples up to t = %s are shown",
                 s->label, res.message, CLI_NUM(res.t));
    /* the last sample is always kept (a grown series keeps a slot for it) */
    if (r.have_latest && !section &&
        (s->rows == 0 || s->data[(s->rows - 1) * s->cols] < r.latest_t))
        store(&r, r.latest_t, r.latest);
    s->samples = s->samples > 0 ? s->samples : r.seen;
    memcpy(run->par, par0, m->par_size);
    free(par0);
    free(y);
    return s->status == DYN_OK ? CLI_OK : CLI_FAILED;
}

void cli_series_free(cli_series *s)
{
    free(s->data);
    s->data = NULL;
    s->rows = 0;
}
