/* SPDX-License-Identifier: BSD-3-Clause */
/* What a parsed run will do, asked by the option checks (run_options.c), the solve
 * (run_solve.c) and its table (run_table.c): where an adaptive run samples, and whether the
 * model's events reset the state. Depends on cli_run only, so those three do not depend on
 * one another. */
#include "cli.h"

int cli_run_at_steps(const cli_run *run)
{
    if (!dyn_method_is_adaptive(run->method) || run->times || run->step_given)
        return 0;
    if (run->model->samples == DYN_SAMPLES_STEPS)
        return 1;
    /* the model's step over the span: more samples than a default should write? */
    const double samples = (run->t1 - run->t0) / run->step + 1.0;
    return !(samples <= (double)CLI_MAX_GRID_SAMPLES);
}

int cli_run_resets(const cli_run *run) { return dyn_run_resets(run->model); }
