/* SPDX-License-Identifier: BSD-3-Clause */
/* One run of a model with the method of the run options: the parsed options as the
 * library's dyn_run_opts, run by dyn_run (dynkit/run.h), which chooses the solver family
 * (fixed-step driver, general driver, noise, delays, Volterra integrals, CVODE) as every
 * front door does; the tool adds its trace printer, its warnings on stderr and the backends
 * it is built with. And the counts of a run as one line. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static void warn_stderr(const char *message, void *ctx)
{
    (void)ctx;
    cli_warning("%s", message);
}

int cli_run_solve(const cli_run *run, long every, dyn_output_fn output, void *output_ctx,
                  dyn_event_fn on_event, void *event_ctx, dyn_progress_fn progress,
                  void *progress_ctx, double *y, dyn_result *res)
{
    dyn_run_opts o = {0};
    o.method = run->method;
    o.t0 = run->t0;
    o.t1 = run->t1;
    o.step = run->step;
    o.end = run->end;
    o.rtol = run->rtol;
    o.atol = run->atol;
    o.rtolv = run->rtolv;
    o.atolv = run->atolv;
    o.times = run->times;
    o.n_times = run->n_times;
    o.at_steps = cli_run_at_steps(run);
    o.max_step = run->max_step;
    o.initial_step = run->initial_step;
    o.max_steps = run->max_steps;
    /* the Poincaré section after the asked events: reported with index run->n_events */
    dyn_event *events = NULL;
    const int n_events = run->n_events + (run->section.kind != DYN_POINCARE_NONE);
    if (n_events > run->n_events) {
        if (!(events = malloc((size_t)n_events * sizeof *events)))
            return -1;
        if (run->n_events)
            memcpy(events, run->events, (size_t)run->n_events * sizeof *events);
        if (cli_section_event(run, &events[run->n_events]) < 0) {
            free(events);
            return -1;
        }
    }
    o.events = events ? events : run->events;
    o.n_events = n_events;
    o.seed = run->seed;
    o.stream = run->stream;
    o.every = every;
    o.output = output;
    o.output_ctx = output_ctx;
    o.on_event = on_event;
    o.event_ctx = event_ctx;
    o.progress = progress;
    o.progress_ctx = progress_ctx;
    o.trace = cli_print_trace;
    o.trace_ctx = (void *)run;
    o.trace_steps = run->trace_steps;
    o.warn = warn_stderr;
    o.backends = cli_run_backends();
    const int rc = dyn_run(run->model, run->par, run->y0, &o, y, res);
    free(events);
    return rc;
}

char *cli_stats_line(const cli_run *run, const dyn_result *res, char *buf, size_t size)
{
    const dyn_stats *s = &res->stats;
    int w = snprintf(buf, size, "steps=%ld accepted=%ld rejected=%ld rhs=%ld", s->steps,
                     s->accepted, s->rejected, s->rhs_calls);
    if (dyn_method_is_stiff(run->method) && w >= 0 && (size_t)w < size)
        w += snprintf(buf + w, size - (size_t)w, " jac=%ld", s->jac_calls);
    /* columns of the exact Jacobian that could not be evaluated (an entry not finite) */
    if (s->jac_fd_columns > 0 && w >= 0 && (size_t)w < size)
        w += snprintf(buf + w, size - (size_t)w, " jac_fd_columns=%ld", s->jac_fd_columns);
    /* the matrices of the linear systems (cli_linear_choose; --verbose says why) */
    if (dyn_method_is_stiff(run->method) && w >= 0 && (size_t)w < size) {
        cli_linear lin;
        cli_linear_for_run(run, &lin);
        if (lin.kind == CLI_LINEAR_BAND)
            snprintf(buf + w, size - (size_t)w, " linear=band lower=%d upper=%d", lin.lower,
                     lin.upper);
        else if (lin.kind == CLI_LINEAR_SPARSE)
            snprintf(buf + w, size - (size_t)w, " linear=sparse nnz=%d", lin.nnz);
        else
            snprintf(buf + w, size - (size_t)w, " linear=dense");
    }
    return buf;
}
