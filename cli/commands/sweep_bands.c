/* SPDX-License-Identifier: BSD-3-Clause */
/* Bands over the runs of a sweep (sweep_bands.h): the mean and the 5th, 50th and 95th
 * percentiles of each state over the runs at each time of the grid, percentiles by linear
 * interpolation between the order statistics at (n - 1) p / 100 (numpy's default, "linear",
 * Hyndman and Fan's definition 7), written through the data-file writers of the run tables
 * (table_formats.h), so in each of their formats. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/out_file.h"
#include "commands/sweep_bands.h"
#include "tables/table_formats.h"

static const double percents[] = {5.0, 50.0, 95.0};
#define N_STATS 4 /* mean and the percentiles */

int sweep_bands_plan(const cli_run *run, long n_runs, sweep_bands *b)
{
    memset(b, 0, sizeof *b);
    char err[256];
    if (dyn_grid_plan(run->t0, run->t1, run->step, run->end, &b->grid, err, sizeof err))
        return cli_usage_error("sweep", "--bands: %s", err);
    const long last = b->grid.samples - 1;
    b->every = last > SWEEP_BANDS_MAX_TIMES - 1 ? (last + SWEEP_BANDS_MAX_TIMES - 2) /
                                                      (SWEEP_BANDS_MAX_TIMES - 1)
                                                : 1;
    b->n_times = last / b->every + 1;
    const double doubles = (double)n_runs * (double)b->n_times * (double)run->model->n_states;
    if (doubles > 1.5e8)
        return cli_usage_error("sweep", "--bands: %ld runs of %ld times and %d states need "
                               "%.3g GB: give fewer --runs or a longer --step",
                               n_runs, b->n_times, run->model->n_states, doubles * 8e-9);
    b->series = malloc(((size_t)doubles + 1) * sizeof *b->series);
    if (!b->series) {
        cli_error("out of memory for the bands of %ld runs", n_runs);
        return CLI_FAILED;
    }
    for (size_t k = 0; k < (size_t)doubles; k++)
        b->series[k] = NAN;
    return CLI_OK;
}

void sweep_bands_free(sweep_bands *b)
{
    free(b->series);
    b->series = NULL;
}

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* mean and percentiles of v (n values, sorted here) into out (N_STATS; NaN when n = 0) */
static void stats(double *v, long n, double *out)
{
    if (n == 0) {
        for (int s = 0; s < N_STATS; s++)
            out[s] = NAN;
        return;
    }
    qsort(v, (size_t)n, sizeof *v, by_value);
    double sum = 0.0;
    for (long r = 0; r < n; r++)
        sum += v[r];
    out[0] = sum / (double)n;
    for (int s = 0; s < 3; s++) {
        const double h = (double)(n - 1) * percents[s] / 100.0;
        const long lo = (long)floor(h);
        const long hi = lo + 1 < n ? lo + 1 : lo;
        out[1 + s] = v[lo] + (h - (double)lo) * (v[hi] - v[lo]);
    }
}

int sweep_bands_write(const char *path, const sweep_bands *b, const cli_run *run,
                      const int *status, long n_runs)
{
    const dyn_model *m = run->model;
    const int n = m->n_states, cols = 1 + N_STATS * n;
    cli_format format;
    char err[512] = "a write failed";
    if (cli_format_of_path(path, &format, err, sizeof err)) {
        cli_error("--bands: %s", err);
        return CLI_FAILED;
    }
    const char **names = calloc((size_t)cols, sizeof *names);
    const char **units = calloc((size_t)cols, sizeof *units);
    char(*text)[96] = calloc((size_t)cols, sizeof *text);
    double *v = malloc(((size_t)n_runs + 1) * sizeof *v);
    double *row = malloc((size_t)cols * sizeof *row);
    cli_out outf;
    int bad = !names || !units || !text || !v || !row, open_rc = CLI_FAILED;
    if (!bad) {
        static const char *const prefix[N_STATS] = {"mean", "p5", "p50", "p95"};
        names[0] = "t";
        units[0] = m->time_unit && *m->time_unit ? m->time_unit : "s";
        for (int j = 0; j < n; j++)
            for (int s = 0; s < N_STATS; s++) {
                const int c = 1 + N_STATS * j + s;
                snprintf(text[c], sizeof text[c], "%s_%s", prefix[s], m->states[j].name);
                names[c] = text[c];
                units[c] = m->states[j].unit;
            }
        open_rc = cli_out_open(&outf, "--bands", path);
        bad = open_rc != CLI_OK;
    }
    if (bad) {
        free(names);
        free(units);
        free(text);
        free(v);
        free(row);
        return open_rc;
    }
    const int adaptive = dyn_method_is_adaptive(run->method);
    cli_table_info info = {
        .model = m->name,
        .method = run->method->name,
        .step = run->step * (double)b->every,
        .rtol = adaptive ? run->rtol : NAN,
        .atol = adaptive ? run->atol : NAN,
        .t0 = run->t0,
        .t1 = run->t1,
        .cols = cols,
        .n_y = cols - 1,
        .y_name = "bands",
        .names = names,
        .units = units,
        .header = CLI_HEADER_NAMES};
    cli_table *tab = cli_table_open(outf.f, format, &info, err, sizeof err);
    bad = tab == NULL;
    for (long k = 0; k < b->n_times && !bad; k++) {
        for (int j = 0; j < n; j++) {
            long got = 0;
            for (long r = 0; r < n_runs; r++) {
                const double x = b->series[((size_t)r * (size_t)b->n_times + (size_t)k) *
                                               (size_t)n + (size_t)j];
                if (status[r] == DYN_OK && !isnan(x))
                    v[got++] = x;
            }
            stats(v, got, row + N_STATS * j);
        }
        bad = cli_table_row(tab, dyn_grid_time(&b->grid, k * b->every), row, cols - 1, NULL,
                            0) != 0;
    }
    if (tab) {
        bad |= cli_table_finish(tab, err, sizeof err) != 0;
        cli_table_free(tab);
    }
    if (bad)
        cli_error("--bands '%s': %s", path, err);
    if (cli_out_close(&outf, !bad) != CLI_OK)
        bad = 1;
    free(names);
    free(units);
    free(text);
    free(v);
    free(row);
    return bad ? CLI_FAILED : CLI_OK;
}
