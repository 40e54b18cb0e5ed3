/* dynkit run MODEL: integrate a model and stream CSV (header "t,<states>[,<outputs>]"). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* Where samples go: CSV rows, or (with --final) only the latest sample kept in memory. */
typedef struct csv_sink {
    FILE *out;
    const cli_run *run;
    double *extra;       /* (n_outputs) */
    long rows;
    int io_failed;
    const char *warned[8];    /* each distinct warning is printed once */
    int n_warned;
    long every;               /* keep samples k % every == 0 and the last one */
    long last_k;
} csv_sink;

static void check_warning(csv_sink *sink, double t, const double *y)
{
    const dyn_model *m = sink->run->model;
    const char *w = m->warn ? m->warn(t, y, sink->run->par) : NULL;
    if (!w)
        return;
    for (int i = 0; i < sink->n_warned; i++)
        if (sink->warned[i] == w)
            return;
    fprintf(stderr, "dynkit: warning at t = %.6g s: %s\n", t, w);
    if (sink->n_warned < (int)(sizeof sink->warned / sizeof sink->warned[0]))
        sink->warned[sink->n_warned++] = w;
}

static int write_sample(csv_sink *sink, double t, const double *y)
{
    const dyn_model *m = sink->run->model;
    int n_extra = sink->run->with_outputs ? m->n_outputs : 0;
    if (n_extra && m->compute_outputs(t, y, sink->run->par, sink->extra)) {
        for (int i = 0; i < n_extra; i++)
            sink->extra[i] = 0.0 / 0.0;
    }
    if (dyn_csv_write_row(sink->out, t, y, m->n_states, sink->extra, n_extra)) {
        sink->io_failed = 1;
        return 1;
    }
    sink->rows++;
    return 0;
}

static int on_sample(long k, double t, const double *y, void *ctx)
{
    csv_sink *sink = ctx;
    check_warning(sink, t, y);
    if (k % sink->every != 0 && k != sink->last_k)
        return 0;
    if (sink->run->final_only)
        return 0; /* the last good state is written after the solve */
    return write_sample(sink, t, y);
}

static void run_help(void)
{
    puts("Usage: dynkit run MODEL [options]\n"
         "\n"
         "Integrate MODEL with a fixed-step method and write the samples as CSV: a header\n"
         "t,<state names> and one row per sample t0 + k*step, numbers printed with %.17g.\n"
         "\n"
         "Examples:\n"
         "  dynkit run vanderpol --method heun --step 0.01 --tspan 0:15 --final\n"
         "  dynkit run pendulum --method euler --step 0.2 --tspan 0:0.2 --trace 1\n"
         "  dynkit run pendulum --set l=1 --init dphi=pi/4 --tspan 0:10 --outputs\n"
         "  dynkit inverse cart --output forces.csv   (prints the --init options for:)\n"
         "  dynkit run cart --forces forces.csv --method heun --init dsX=-20 ...\n");
    cli_run_options_help(stdout);
    puts("\nExit status: 0 success, 1 failed run (e.g. a state became NaN or Inf; the samples\n"
         "up to there are still written), 2 bad command line.");
}

static void report_failure(const cli_run *run, const dyn_result *res, const double *y_good,
                           const csv_sink *sink)
{
    const dyn_model *m = run->model;
    if (res->status == DYN_ERR_NONFINITE && res->fail_index >= 0)
        fprintf(stderr,
                "dynkit: run failed: state %s of model %s became NaN or Inf at t = %.17g "
                "(method %s, step %g)\n",
                m->states[res->fail_index].name, m->name, res->fail_t, run->method->name,
                run->step);
    else
        fprintf(stderr, "dynkit: run failed: %s\n", res->message);
    fprintf(stderr, "dynkit: last good state at t = %.17g:", res->t);
    for (int i = 0; i < m->n_states; i++)
        fprintf(stderr, " %s = %.17g", m->states[i].name, y_good[i]);
    fprintf(stderr, "\ndynkit: %s\n",
            sink->io_failed ? "the output could not be written"
            : run->final_only ? "it was written as the final row"
                              : "the samples up to it were written");
}

int cli_cmd_run(int argc, char **argv)
{
    if (argc >= 1 && cli_is_help(argv[0])) {
        run_help();
        return CLI_OK;
    }
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            run_help();
            return CLI_OK;
        }
    cli_run run;
    int rc = cli_run_parse("run", argc, argv, &run);
    if (rc != CLI_OK) {
        cli_run_free(&run);
        return rc;
    }
    const dyn_model *m = run.model;
    const int n = m->n_states;
    dyn_grid grid;
    char why[256];
    if (dyn_grid_plan(run.t0, run.t1, run.step, run.end, &grid, why, sizeof why)) {
        rc = cli_usage_error("run", "--step %g over --tspan %g:%g: %s", run.step, run.t0, run.t1,
                             why);
        cli_run_free(&run);
        return rc;
    }
    FILE *out = stdout;
    if (run.output_path && !(out = fopen(run.output_path, "w"))) {
        rc = cli_usage_error("run", "cannot open --output '%s' for writing: %s", run.output_path,
                             strerror(errno));
        cli_run_free(&run);
        return rc;
    }
    size_t work_size = dyn_fixed_work_size(run.method, n);
    double *work = malloc(work_size * sizeof *work);
    double *buffers = calloc((size_t)(n + m->n_outputs + 1), sizeof *buffers);
    if (!work || !buffers) {
        fprintf(stderr, "dynkit: error: out of memory\n");
        rc = CLI_FAILED;
        goto done;
    }
    csv_sink sink = {.out = out, .run = &run, .extra = buffers + n};
    int n_extra = run.with_outputs ? m->n_outputs : 0;
    if (dyn_csv_write_header(out, m->states, n, m->outputs, n_extra)) {
        fprintf(stderr, "dynkit: error: cannot write the output\n");
        rc = CLI_FAILED;
        goto done;
    }
    cli_progress progress;
    cli_progress_start(&progress, run.quiet);
    sink.last_k = grid.samples - 1;
    /* the driver thins the samples itself unless the model checks every state for warnings */
    const long keep = run.final_only ? 0x7fffffffffffffffL : run.every;
    sink.every = m->warn ? keep : 1;
    dyn_fixed_opts opts = {0};
    opts.end = run.end;
    opts.every = m->warn ? 1 : keep;
    opts.output = on_sample;
    opts.output_ctx = &sink;
    opts.trace = run.trace_steps > 0 ? cli_print_trace : NULL;
    opts.trace_ctx = &run;
    opts.trace_steps = run.trace_steps;
    opts.progress = progress.enabled ? cli_progress_update : NULL;
    opts.progress_ctx = &progress;
    dyn_system sys = {m->rhs, n, run.par};
    dyn_result res;
    dyn_fixed_solve(run.method, &sys, run.t0, run.t1, run.step, run.y0, buffers, work, &opts,
                    &res);
    cli_progress_finish(&progress);
    if (res.status == DYN_ERR_ARG) {
        rc = cli_usage_error("run", "%s", res.message);
        goto done;
    }
    if (run.final_only && res.status != DYN_ERR_ARG)
        write_sample(&sink, res.t, buffers); /* the driver leaves the last good state there */
    if (fflush(out) != 0 || sink.io_failed) {
        fprintf(stderr, "dynkit: error: writing the output failed: %s\n", strerror(errno));
        rc = CLI_FAILED;
    }
    if (res.status != DYN_OK) {
        report_failure(&run, &res, buffers, &sink);
        rc = CLI_FAILED;
    }
done:
    if (out != stdout)
        fclose(out);
    free(work);
    free(buffers);
    cli_run_free(&run);
    return rc;
}
