/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit run MODEL: integrate a model and stream CSV (header "t,<states>[,<outputs>]");
 * with --event, the events as CSV "event,t,<states>" (--events-output) or on stderr. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/lang.h"

#include "cli.h"
#include "util/escape.h"
#include "run/run_table.h"
#include "util/out_file.h"

/* Where samples go: CSV rows, or (with --final) only the latest sample kept in memory. */
typedef struct csv_sink {
    int section;              /* the rows are a Poincaré section's (on_event) */
    FILE *out;
    cli_table *table;    /* the rows, in the format of --output */
    const cli_run *run;
    double *extra;       /* (n_outputs) */
    long rows;
    double last_t;            /* time of the last row written */
    int io_failed;
    int io_errno;             /* errno of the failed write */
    int table_full;           /* the table kept all the rows its format may (cli_table_full) */
    const char *warned[8];    /* each distinct warning is printed once */
    int n_warned;
    long every;               /* keep samples k % every == 0 and the last one */
    long last_k;              /* index of the last sample, or -1 when not known beforehand */
    /* when last_k is not known: the latest sample not written yet, written at the end */
    double *pending_y;        /* (n) */
    double pending_t;
    int pending;
    int seen;                 /* samples seen */
    /* progress by samples (a long output grid inside few steps), besides the driver's */
    cli_progress *progress;   /* NULL: none */
    long count;               /* samples seen */
} csv_sink;

/* Where events go: CSV rows (event,t,<states>) or lines on stderr; a Poincaré section's
 * crossings are the rows of the table (sink). */
typedef struct event_sink {
    FILE *out;
    const cli_run *run;
    int io_failed;
    struct csv_sink *sink;
    long crossings;      /* of the section so far */
    double last_cross;   /* the time of the last one (poimap=period) */
} event_sink;

/* Warning w at time t, once per run (w is a constant string: compared by address). */
static void warn_once(csv_sink *sink, double t, const char *w)
{
    for (int i = 0; i < sink->n_warned; i++)
        if (sink->warned[i] == w)
            return;
    cli_stderr("dynkit: warning at t = %.6g s: %s\n", t, w);
    if (sink->n_warned < (int)(sizeof sink->warned / sizeof sink->warned[0]))
        sink->warned[sink->n_warned++] = w;
}

static void check_warning(csv_sink *sink, double t, const double *y)
{
    const dyn_model *m = sink->run->model;
    const char *w = m->warn ? m->warn(t, y, sink->run->par) : NULL;
    if (w)
        warn_once(sink, t, w);
}

static int write_sample(csv_sink *sink, double t, const double *y)
{
    const dyn_model *m = sink->run->model;
    int n_extra = sink->run->with_outputs ? m->n_outputs : 0;
    if (n_extra && m->compute_outputs(t, y, sink->run->par, sink->extra)) {
        for (int i = 0; i < n_extra; i++)
            sink->extra[i] = 0.0 / 0.0;
        warn_once(sink, t,
                  "the model's outputs failed (a non-zero status): they are written as nan "
                  "while they fail");
    }
    if (cli_table_row(sink->table, t, y, m->n_states, sink->extra, n_extra)) {
        if (cli_table_full(sink->table, NULL, 0)) {
            sink->table_full = 1; /* the run stops here; its rows are written */
            return 1;
        }
        sink->io_failed = 1;
        sink->io_errno = errno;
        return 1;
    }
    sink->rows++;
    sink->last_t = t;
    return cli_stop_signal != 0; /* SIGINT/SIGTERM: stop after a complete row */
}

/* The rows of samples thinned to every K-th and the last. */
static long thinned_rows(long samples, long every)
{
    return samples <= 1 ? samples : (samples - 1) / every + 1 + ((samples - 1) % every != 0);
}

/* The samples the run gives when that is known beforehand (a grid or --times, no events
 * that may end it early, no transient whose samples are left out), else -1. */
static long expected_samples(const cli_run *run, const dyn_grid *grid, int at_steps)
{
    if (run->final_only)
        return 1;
    if (run->n_events > 0 || cli_run_resets(run) > 0 || (at_steps && !run->times) ||
        run->section.kind != DYN_POINCARE_NONE ||
        run->model->t_trans > run->t0)
        return -1;
    return run->times ? run->n_times : grid->samples;
}

static int on_sample(long k, double t, const double *y, void *ctx)
{
    csv_sink *sink = ctx;
    const int n = sink->run->model->n_states;
    check_warning(sink, t, y);
    sink->seen = 1;
    if (sink->progress && (++sink->count & 0xffff) == 0) {
        const cli_run *run = sink->run;
        cli_progress_update(t, (t - run->t0) / (run->t1 - run->t0), sink->progress);
    }
    if (sink->section)
        return cli_stop_signal != 0; /* the rows are the section's crossings */
    if (sink->last_k < 0) { /* keep it in case it turns out to be the last one */
        memcpy(sink->pending_y, y, (size_t)n * sizeof *y);
        sink->pending_t = t;
        sink->pending = 1;
    }
    if (k % sink->every != 0 && k != sink->last_k)
        return 0;
    if (sink->run->final_only)
        return 0; /* the last sample is written after the solve */
    sink->pending = 0;
    return write_sample(sink, t, y);
}

/* A crossing of the Poincaré section: a row (t, the states) as XPPAUT writes it: t = k*T
 * for a section in t, the time since the last crossing for poimap=period (none for the
 * first); none before the model's transient. Every crossing is written (--every and
 * @ nout thin samples). */
static int on_crossing(event_sink *es, double t, const double *y)
{
    const cli_run *run = es->run;
    csv_sink *sink = es->sink;
    if (t < run->model->t_trans)
        return 0;
    const long k = es->crossings++;
    double row_t = cli_section_time(run, t);
    if (run->section.kind == DYN_POINCARE_PERIOD) {
        const double since = t - es->last_cross;
        es->last_cross = t;
        if (k == 0)
            return 0;
        row_t = since;
    }
    if (run->final_only) { /* the last crossing is written after the solve */
        memcpy(sink->pending_y, y, (size_t)run->model->n_states * sizeof *y);
        sink->pending_t = row_t;
        sink->pending = 1;
        return 0;
    }
    return write_sample(sink, row_t, y);
}

static int on_event(int index, double t, const double *y, int direction, void *ctx)
{
    event_sink *es = ctx;
    const cli_run *run = es->run;
    const dyn_model *m = run->model;
    if (index == run->n_events)
        return on_crossing(es, t, y);
    const char *name = run->events[index].name;
    if (es->out) {
        if (fprintf(es->out, "%s,", name) < 0 ||
            dyn_csv_write_row(es->out, t, y, m->n_states, NULL, 0) != DYN_OK)
            es->io_failed = 1;
    } else {
        cli_stderr("dynkit: event %s (%s) at t = %s:", name, direction > 0 ? "rising" : "falling",
                   CLI_NUM(t));
        for (int i = 0; i < m->n_states; i++)
            cli_stderr(" %s = %s", m->states[i].name, CLI_NUM(y[i]));
        fputc('\n', stderr);
    }
    return 0;
}

/* Progress on a terminal, and the stop asked by SIGINT/SIGTERM (checked between steps,
 * also when no sample is written for a long time: --final, --every). */
static int on_progress(double t, double fraction, void *ctx)
{
    cli_progress *p = ctx;
    if (p->enabled)
        cli_progress_update(t, fraction, p);
    return cli_stop_signal != 0;
}

static void run_help(void)
{
    puts("Usage: dynkit run MODEL [options]\n"
         "\n"
         "Integrate MODEL and write the samples as CSV (or .json, .npy, .npz, .mat by the\n"
         "extension of --output): a header t,<state names> and one row per sample\n"
         "t0 + k*step, each number the shortest decimal that reads back to the same double\n"
         "(0.1, not 0.10000000000000001). Fixed-step methods (euler, heun,\n"
         "rk4, ...) take steps of --step; adaptive methods (bs23 = ode23, dp45 = ode45,\n"
         "dop853; for stiff problems rodas4, and cvode when built with SUNDIALS) choose their\n"
         "steps to meet --rtol/--atol (defaults: the model's, else 1e-6 and 1e-9)\n"
         "and interpolate the samples on the --step grid or at --times (without either: the\n"
         "model's grid, or every accepted step when that grid exceeds 1e6 samples or the\n"
         "model asks for it). Without --method a model runs its default method ('dynkit info\n"
         "MODEL'): an adaptive one for the built-in models and .ode files, the one a C model\n"
         "names.\n"
         "\n"
         "Examples:\n"
         "  dynkit run vanderpol --method heun --step 0.01 --tspan 0:15 --final\n"
         "  dynkit run plane --method dp45 --rtol 1e-8 --atol 1e-10 --final --stats\n"
         "  dynkit run robertson --tspan 0:1e11 --rtol 1e-8 --atol 1e-14 --stats\n"
         "  dynkit run pendulum --method dp45 --rtol 1e-10 --tspan 0:20 --event turn \\\n"
         "      --event bottom:stop --events-output events.csv\n"
         "  dynkit run pendulum --method euler --step 0.2 --tspan 0:0.2 --trace 1\n"
         "  dynkit run pendulum --set l=1 --init dphi=pi/4 --tspan 0:10 --outputs\n"
         "  dynkit run pendulum --init phi=45deg -m ode45 --outputs -o swing.mat\n"
         "  dynkit inverse cart --output forces.csv      # the forces, and the run's --init:\n"
         "  dynkit run cart --forces forces.csv --method heun --init dsX=-20 \\\n"
         "      --init dsY=4.934802200544679 --init omega=4.934802200544679\n");
    cli_run_options_help(stdout);
    puts("\nOutput files are written under a temporary name beside FILE and renamed when the\n"
         "run ends: a bad option or a run that fails before its first sample leaves an\n"
         "existing FILE as it was; a failed run that produced samples keeps them in FILE.\n"
         "SIGINT (Ctrl-C) or SIGTERM ends a run after its current row: the output holds\n"
         "every complete row up to there, and the exit status is 130 or 143.\n"
         "\nExit status: 0 success, 1 failed run (e.g. a state became NaN or Inf; the samples\n"
         "up to there are still written) or an output that cannot be written, 2 bad command\n"
         "line.");
}

static void report_failure(const cli_run *run, const dyn_result *res, const double *y_good,
                           const csv_sink *sink)
{
    const dyn_model *m = run->model;
    /* names and the message with their control bytes escaped (a model file's name) */
    char state[256], model[256], message[4 * sizeof res->message + 8];
    if (res->fail_index >= 0 && res->fail_index < m->n_states)
        cli_terminal_text(m->states[res->fail_index].name, 0, state, sizeof state);
    cli_terminal_text(m->name, 0, model, sizeof model);
    cli_terminal_text(res->message, 1, message, sizeof message);
    if (res->status == DYN_ERR_NONFINITE && res->fail_index >= 0 &&
        dyn_method_is_adaptive(run->method))
        cli_stderr("dynkit: run failed: state %s of model %s became NaN or Inf at t = %s "
                   "(method %s, rtol %g, atol %g; every smaller step failed too)\n",
                   state, model, CLI_NUM(res->fail_t), run->method->name,
                   run->rtol > 0 ? run->rtol : DYN_DEFAULT_RTOL,
                   run->atol > 0 ? run->atol : DYN_DEFAULT_ATOL);
    else if (res->status == DYN_ERR_NONFINITE && res->fail_index >= 0)
        cli_stderr("dynkit: run failed: state %s of model %s became NaN or Inf at t = %s "
                   "(method %s, step %g)\n",
                   state, model, CLI_NUM(res->fail_t), run->method->name, run->step);
    else if (res->status == DYN_ERR_MAX_STEPS)
        cli_stderr("dynkit: run failed: %s (--max-steps N sets the limit, default 1e7)\n", message);
    else
        cli_stderr("dynkit: run failed: %s\n", message);
    /* a model file's algebraic equations: a right-hand side that is not finite is theirs
     * (alg_solver.c); a stiff method may fail on the step size before */
    if (cli_model_has_algebraic(m) && res->status != DYN_STOPPED && res->status != DYN_ERR_IO)
        cli_stderr("dynkit: the model's algebraic equations (0=...) %s\n",
                   res->status == DYN_ERR_NONFINITE ||
                           (res->status == DYN_ERR_RHS && res->rhs_status == DYN_LANG_ALG_FAILED)
                       ? "have no solution near the branch followed there: it ends at an "
                         "impasse point (or the equations have no solution at all)"
                       : "may have no solution past there: the branch followed may end at an "
                         "impasse point");
    if (res->status == DYN_ERR_MAX_STEPS && res->stats.steps == 0) {
        cli_stderr("dynkit: no step was taken: no sample was written\n"); /* a fixed grid */
        return;
    }
    cli_stderr("dynkit: last good state at t = %s:", CLI_NUM(res->t));
    for (int i = 0; i < m->n_states; i++)
        cli_stderr(" %s = %s", m->states[i].name, CLI_NUM(y_good[i]));
    cli_stderr("\ndynkit: %s\n", sink->io_failed   ? "the output could not be written"
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
    const int general = dyn_method_is_adaptive(run.method) || run.n_events > 0 ||
                        cli_run_resets(&run) > 0 || run.section.kind != DYN_POINCARE_NONE;
    dyn_grid grid = {0};
    char why[256], line[160];
    const int at_steps = cli_run_at_steps(&run);
    if (!run.times && !at_steps &&
        dyn_grid_plan(run.t0, run.t1, run.step, run.end, &grid, why, sizeof why)) {
        rc = cli_usage_error("run", "--step %g over --tspan %g:%g: %s", run.step, run.t0, run.t1,
                             why);
        cli_run_free(&run);
        return rc;
    }
    /* the format of --output (its extension), before any file is opened */
    cli_format format;
    cli_table *table = NULL;
    char ferr[512] = "";
    if (cli_run_format(&run, &format) != CLI_OK) {
        cli_run_free(&run);
        return CLI_USAGE;
    }
    if (!run.times && !at_steps && grid.samples == 1 && run.t1 > run.t0) {
        rc = cli_usage_error("run",
                             "--step %g is longer than --tspan %g:%g: with --end grid the run "
                             "would have no sample after T0 (--end exact takes one shorter "
                             "step to T1)",
                             run.step, run.t0, run.t1);
        cli_run_free(&run);
        return rc;
    }
    if (format == CLI_FORMAT_NPZ || format == CLI_FORMAT_MAT) {
        /* a table its file cannot hold is refused before the run, not after it */
        const int cols = 1 + n + (run.with_outputs ? m->n_outputs : 0);
        const char *limit_why;
        const long limit = cli_table_limit(format, cols, n, &limit_why);
        const long samples = expected_samples(&run, &grid, at_steps);
        const long rows = run.final_only ? samples
                                         : thinned_rows(samples, run.every > 1 ? run.every : 1);
        if (rows > limit) {
            /* the smallest K whose rows fit (the last sample is always kept) */
            long every = limit > 2 ? (samples - 1 + limit - 3) / (limit - 2) : samples;
            while (every > 1 && thinned_rows(samples, every - 1) <= limit)
                every--;
            while (thinned_rows(samples, every) > limit && every < samples)
                every++;
            rc = cli_usage_error("run",
                                 "--output '%s': the run would write %ld rows of %d columns; "
                                 "at most %ld fit in %s: write .csv or .npy (streamed, no "
                                 "limit), or keep fewer rows with --every %ld",
                                 run.output_path, rows, cols, limit, limit_why, every);
            cli_run_free(&run);
            return rc;
        }
    }
    if (run.events_path && (cli_same_file(run.output_path, run.events_path) ||
                            (!run.output_path && strcmp(run.events_path, "-") == 0))) {
        rc = cli_usage_error("run",
                             "--output and --events-output name the same file '%s': give "
                             "two files",
                             run.events_path);
        cli_run_free(&run);
        return rc;
    }
    cli_out outf = {0}, evf = {0};
    if ((rc = cli_out_open(&outf, "--output", run.output_path)) != CLI_OK) {
        cli_run_free(&run);
        return rc;
    }
    if (run.events_path &&
        (rc = cli_out_open(&evf, "--events-output", run.events_path)) != CLI_OK) {
        cli_out_close(&outf, 0);
        cli_run_free(&run);
        return rc;
    }
    FILE *out = outf.f, *evout = evf.f;
    int keep = 0; /* keep the output files (else the real names keep what they had) */
    dyn_result res;
    memset(&res, 0, sizeof res);
    double *buffers = calloc((size_t)(2 * n + m->n_outputs + 1), sizeof *buffers);
    if (!buffers) {
        cli_error("out of memory");
        rc = CLI_FAILED;
        goto done;
    }
    csv_sink sink = {.out = out,
                     .run = &run,
                     .extra = buffers + n,
                     .pending_y = buffers + n + m->n_outputs,
                     .last_t = -HUGE_VAL};
    event_sink es = {.out = evout, .run = &run, .sink = &sink};
    sink.section = run.section.kind != DYN_POINCARE_NONE;
    if (!(sink.table = table = cli_table_open_run(out, format, &run, run.header, ferr,
                                                  sizeof ferr))) {
        cli_error("--output: %s", ferr);
        rc = CLI_FAILED;
        goto done;
    }
    if (evout) {
        fputs("event,t", evout);
        for (int i = 0; i < n; i++)
            fprintf(evout, ",%s", m->states[i].name);
        fputc('\n', evout);
    }
    if (at_steps && m->samples != DYN_SAMPLES_STEPS && !run.quiet)
        cli_note("the model's step %g over %g:%g would give %.3g samples; writing "
                "a sample at every accepted step instead (give --step or --times for a grid)",
                run.step, run.t0, run.t1, (run.t1 - run.t0) / run.step + 1.0);
    for (int i = 0; i < m->n_events && !run.quiet; i++)
        if (m->events[i].direction == DYN_EVENT_JUMPS) {
            /* XPPAUT's global with sign 0: the one place its rule is not followed */
            cli_note("event %s fires only when a reset takes its condition onto or "
                    "across zero (XPPAUT's global with sign 0); XPPAUT 6.11 also fires it where "
                    "one of its own steps ends with the condition within 5e-16 of zero, at a "
                    "time that is not the crossing's: dynkit does not",
                    m->events[i].name);
            break;
        }
    if (m->n_bdry > 0 && !run.quiet) {
        cli_stderr("dynkit: note: %s's boundary conditions are not used by run, which "
                   "integrates the initial-value problem from the initial state; "
                   "'dynkit bvp' solves them. Ignored:",
                   m->name);
        for (int k = 0; k < m->n_bdry; k++)
            cli_stderr("%s line %s", k ? ";" : "", m->bdry_text[k]);
        fputc('\n', stderr);
    }
    cli_progress progress;
    cli_progress_start(&progress, run.quiet);
    sink.progress = progress.enabled ? &progress : NULL;
    /* thinning: every K-th sample and the last; the last is known beforehand only for a
     * fixed-step run without events (the general driver may end early at an event) */
    sink.last_k = general ? -1 : grid.samples - 1;
    const long thin = run.final_only ? 0x7fffffffffffffffL : run.every;
    /* the fixed-step driver thins the samples itself unless the model checks every state for
     * warnings */
    sink.every = general || m->warn ? thin : 1;
    cli_signals_graceful(1);
    int solved = cli_run_solve(&run, general || m->warn ? 1 : thin, on_sample, &sink, on_event,
                               &es, on_progress, &progress, buffers, &res);
    cli_signals_graceful(0);
    cli_progress_finish(&progress);
    if (solved < 0) {
        cli_error("out of memory");
        rc = CLI_FAILED;
        goto done;
    }
    if (res.status == DYN_ERR_ARG) {
        rc = cli_usage_error("run", "%s", res.message);
        goto done;
    }
    if (sink.section) {
        if (sink.pending) /* --final: the last crossing */
            write_sample(&sink, sink.pending_t, sink.pending_y);
    } else if (run.final_only) {
        /* the last sample; after a failure, the last good state */
        if (general && res.status == DYN_OK && sink.pending)
            write_sample(&sink, sink.pending_t, sink.pending_y);
        else
            write_sample(&sink, res.t, buffers); /* the driver leaves the state there */
    } else if (sink.pending) {
        write_sample(&sink, sink.pending_t, sink.pending_y); /* the last one is always kept */
    } else if (!general && res.status != DYN_OK && sink.seen && res.t > sink.last_t) {
        /* a failed or stopped fixed-step run thinned by --every: its last good sample */
        write_sample(&sink, res.t, buffers);
    }
    /* the formats kept in memory (npz, mat) are written now, json's document closed */
    const int pipe_gone = !outf.path && sink.io_failed && sink.io_errno == EPIPE;
    if (!pipe_gone && cli_table_finish(table, ferr, sizeof ferr)) {
        const int finish_errno = errno;
        if (outf.path)
            cli_error("--output '%s': %s", outf.path, ferr);
        else if (errno != EPIPE)
            cli_error("--output: %s", ferr);
        errno = finish_errno;
        outf.failure_told = outf.path != NULL;
        sink.io_failed = 1;
        sink.io_errno = errno;
    }
    /* a failed run keeps its file when it produced samples */
    keep = res.status == DYN_OK || sink.seen;
    if (sink.table_full) {
        char full[200];
        cli_table_full(table, full, sizeof full);
        cli_error("--output: %s; the run stopped there and its rows are "
                "written, the last at t = %s (CSV files, and NPY files that are not pipes, are "
                "streamed, with no limit; --every K keeps fewer rows)",
                full, CLI_NUM(sink.last_t));
        rc = CLI_FAILED;
    }
    if (pipe_gone || (!outf.path && sink.io_failed && sink.io_errno == EPIPE)) {
        /* the reader of a pipe is gone (| head): end quietly */
        clearerr(stdout);
        rc = CLI_FAILED;
        goto done;
    }
    errno = 0;
    if (fflush(out) != 0 || sink.io_failed || ferror(out)) {
        /* a cut file never replaces the real name; a closed pipe ends quietly */
        const int e = errno ? errno : sink.io_errno;
        if (outf.path && !outf.failure_told)
            cli_error("writing --output '%s' failed: %s%s", outf.path,
                      e ? strerror(e) : "a write failed",
                      outf.tmp ? "; the file was left as it was" : "");
        else if (!outf.path && errno != EPIPE)
            cli_error("writing the output failed: %s",
                    errno ? strerror(errno) : "a write failed");
        if (!outf.path)
            clearerr(stdout); /* reported here, not again at exit */
        outf.failure_told = 1;
        keep = 0;
        rc = CLI_FAILED;
    }
    errno = 0;
    if (evout && (fflush(evout) != 0 || es.io_failed || ferror(evout))) {
        cli_error("writing --events-output '%s' failed: %s%s", run.events_path,
                  errno ? strerror(errno) : "a write failed",
                  evf.tmp ? "; the file was left as it was" : "");
        evf.failure_told = 1;
        keep = 0;
        rc = CLI_FAILED;
    }
    if (res.stiff)
        cli_warning("%s; a method for stiff problems would need far fewer steps",
                res.stiff_message);
    if (res.stopped_by_event && !run.quiet)
        cli_stderr("dynkit: the run stopped at %s%s, t = %s\n",
                   res.event_index < run.n_events ? "event " : "the section's first crossing",
                   res.event_index < run.n_events ? run.events[res.event_index].name : "",
                   CLI_NUM(res.t));
    if (run.stats)
        cli_stderr("%s\n", cli_stats_line(&run, &res, line, sizeof line));
    if (cli_stop_signal) {
        cli_stderr("dynkit: %s: the run stopped at t = %s; the samples up to it were written\n",
                   cli_signal_name(), CLI_NUM(res.t));
        rc = cli_signal_status();
    } else if (res.status != DYN_OK && !sink.table_full) {
        report_failure(&run, &res, buffers, &sink);
        rc = CLI_FAILED;
    }
done:
    if (cli_out_close(&outf, keep) != CLI_OK && rc == CLI_OK)
        rc = CLI_FAILED;
    if (cli_out_close(&evf, keep) != CLI_OK && rc == CLI_OK)
        rc = CLI_FAILED;
    free(buffers);
    cli_table_free(table);
    cli_run_free(&run);
    return rc;
}
