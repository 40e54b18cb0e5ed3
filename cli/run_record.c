/* Recorded runs for pictures: one run of a model kept in memory (t, states, extra outputs),
 * thinned to a number of samples a screen can show (every k-th sample, always the first and
 * the last), and the names and units of its columns. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pages.h"

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
        return "s";
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
    long every, last_k, capacity;
    const char *warned[8];
    int n_warned;
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
    fprintf(stderr, "dynkit: warning (%s) at t = %.6g s: %s\n", r->s->label, t, w);
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

static int on_sample(long k, double t, const double *y, void *ctx)
{
    recorder *r = ctx;
    warn_once(r, t, y);
    if (k % r->every == 0 || k == r->last_k)
        store(r, t, y);
    return 0;
}

int cli_series_record(const cli_run *run, const dyn_tableau *method, double step, long max_rows,
                      cli_series *s)
{
    const dyn_model *m = run->model;
    dyn_grid grid;
    char why[256];
    memset(s, 0, sizeof *s);
    s->method = method;
    s->step = step;
    s->cols = 1 + m->n_states + m->n_outputs;
    snprintf(s->label, sizeof s->label, "%s, h = %g s", method->name, step);
    if (dyn_grid_plan(run->t0, run->t1, step, run->end, &grid, why, sizeof why))
        return cli_usage_error(NULL, "%s: --step %g over --tspan %g:%g: %s", s->label, step,
                               run->t0, run->t1, why);
    recorder r = {.run = run, .s = s, .last_k = grid.samples - 1};
    /* the smallest k with ceil((samples - 1) / k) + 1 <= max_rows */
    r.every = max_rows > 1 ? (grid.samples - 1 + max_rows - 2) / (max_rows - 1) : 1;
    if (r.every < 1)
        r.every = 1;
    if (run->every > r.every)
        r.every = run->every;
    r.capacity = (grid.samples + r.every - 1) / r.every + 1;
    s->samples = grid.samples;
    const int n = m->n_states;
    double *work = malloc(dyn_fixed_work_size(method, n) * sizeof *work);
    double *y = malloc((size_t)n * sizeof *y);
    s->data = malloc((size_t)r.capacity * (size_t)s->cols * sizeof *s->data);
    if (!work || !y || !s->data) {
        free(work);
        free(y);
        snprintf(s->message, sizeof s->message, "out of memory for %ld samples of %d columns",
                 r.capacity, s->cols);
        s->status = DYN_ERR_ARG;
        return CLI_FAILED;
    }
    dyn_fixed_opts opts = {0};
    opts.end = run->end;
    opts.output = on_sample;
    opts.output_ctx = &r;
    dyn_system sys = {m->rhs, n, run->par};
    dyn_result res;
    s->status =
        dyn_fixed_solve(method, &sys, run->t0, run->t1, step, run->y0, y, work, &opts, &res);
    if (s->status == DYN_ERR_NONFINITE && res.fail_index >= 0)
        snprintf(s->message, sizeof s->message,
                 "%s: state %s became NaN or Inf at t = %.17g; the samples up to t = %.17g "
                 "are shown",
                 s->label, m->states[res.fail_index].name, res.fail_t, res.t);
    else if (s->status != DYN_OK)
        snprintf(s->message, sizeof s->message, "%s: %s; the samples up to t = %.17g are shown",
                 s->label, res.message, res.t);
    /* a failed run ends at its last good state */
    if (s->status != DYN_OK && s->rows > 0 && s->data[(s->rows - 1) * s->cols] < res.t)
        store(&r, res.t, y);
    free(work);
    free(y);
    return s->status == DYN_OK ? CLI_OK : CLI_FAILED;
}

void cli_series_free(cli_series *s)
{
    free(s->data);
    s->data = NULL;
    s->rows = 0;
}
