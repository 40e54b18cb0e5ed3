/* One run of a model with the method of the run options: the fixed-step driver for
 * fixed-step methods (the homework's loop), the general driver dyn_solve for adaptive
 * methods and for runs with events. The workspace is allocated here, outside the
 * library's step loop. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"

int cli_run_solve(const cli_run *run, long every, dyn_output_fn output, void *output_ctx,
                  dyn_event_fn on_event, void *event_ctx, dyn_progress_fn progress,
                  void *progress_ctx, double *y, dyn_result *res)
{
    const dyn_model *m = run->model;
    const int n = m->n_states;
    dyn_system sys = {m->rhs, n, run->par};
    const int adaptive = dyn_method_is_adaptive(run->method);
    if (!adaptive && run->n_events == 0) {
        size_t size = dyn_fixed_work_size(run->method, n);
        double *work = malloc(size * sizeof *work);
        if (!work)
            return -1;
        dyn_fixed_opts opts = {0};
        opts.end = run->end;
        opts.every = every;
        opts.output = output;
        opts.output_ctx = output_ctx;
        opts.trace = run->trace_steps > 0 ? cli_print_trace : NULL;
        opts.trace_ctx = (void *)run;
        opts.trace_steps = run->trace_steps;
        opts.progress = progress;
        opts.progress_ctx = progress_ctx;
        int rc = dyn_fixed_solve(run->method, &sys, run->t0, run->t1, run->step, run->y0, y,
                                 work, &opts, res);
        free(work);
        return rc;
    }
    dyn_solve_opts opts = {0};
    opts.rtol = run->rtol;
    opts.atol = run->atol;
    opts.rtolv = run->rtolv;
    opts.atolv = run->atolv;
    opts.end = run->end;
    if (adaptive) {
        opts.initial_step = run->initial_step;
        opts.max_step = run->max_step;
        opts.max_steps = run->max_steps;
        if (run->times) {
            opts.out_times = run->times;
            opts.n_out_times = run->n_times;
        } else {
            opts.out_step = run->step;
        }
    } else {
        opts.h = run->step; /* samples at every step, as the fixed-step driver gives them */
    }
    opts.output = output;
    opts.output_ctx = output_ctx;
    opts.events = run->events;
    opts.n_events = run->n_events;
    opts.on_event = on_event;
    opts.event_ctx = event_ctx;
    opts.jacobian = m->jacobian;
    opts.trace = run->trace_steps > 0 ? cli_print_trace : NULL;
    opts.trace_ctx = (void *)run;
    opts.trace_steps = run->trace_steps;
    opts.progress = progress;
    opts.progress_ctx = progress_ctx;
    const size_t size = dyn_solve_work_size(run->method, n, &opts);
    const size_t isize = dyn_solve_iwork_size(run->method, n);
    double *work = malloc(size * sizeof *work);
    int *iwork = isize ? malloc(isize * sizeof *iwork) : NULL;
    if (!work || (isize && !iwork)) {
        free(work);
        free(iwork);
        return -1;
    }
    opts.iwork = iwork;
    int rc = dyn_solve(run->method, &sys, run->t0, run->t1, run->y0, y, work, &opts, res);
    free(work);
    free(iwork);
    return rc;
}

char *cli_stats_line(const cli_run *run, const dyn_result *res, char *buf, size_t size)
{
    const dyn_stats *s = &res->stats;
    int w = snprintf(buf, size, "steps=%ld accepted=%ld rejected=%ld rhs=%ld", s->steps,
                     s->accepted, s->rejected, s->rhs_calls);
    if (dyn_method_is_stiff(run->method) && w >= 0 && (size_t)w < size)
        snprintf(buf + w, size - (size_t)w, " jac=%ld", s->jac_calls);
    return buf;
}
