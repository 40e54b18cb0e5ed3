/* SPDX-License-Identifier: BSD-3-Clause */
/* A run's table (run/run_table.h): the columns, names, units and settings of a parsed run
 * (cli_run) given to the table formats of tables/, and the format its --output names. The
 * formats know nothing of runs; this is where a run meets them (docs/data-files.md). */
#include <math.h>
#include <stdlib.h>

#include "cli.h"
#include "run/run_table.h"

cli_table *cli_table_open_run(FILE *out, cli_format format, const cli_run *run, cli_header header,
                              char *err, size_t errlen)
{
    const dyn_model *m = run->model;
    const int n_extra = run->with_outputs ? m->n_outputs : 0;
    const int cols = 1 + m->n_states + n_extra;
    const char **s = malloc(2 * (size_t)cols * sizeof *s);
    if (!s) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    for (int j = 0; j < cols; j++) {
        const dyn_var *v = j == 0 ? NULL : j <= m->n_states ? &m->states[j - 1]
                                                            : &m->outputs[j - 1 - m->n_states];
        s[j] = v ? v->name : "t";
        s[cols + j] = v ? (v->unit ? v->unit : "") : cli_time_unit(m);
    }
    const int adaptive = dyn_method_is_adaptive(run->method);
    /* the samples' step: the fixed step, or the output grid of an adaptive run */
    const int on_grid = !adaptive || (!run->times && !cli_run_at_steps(run));
    cli_table_info info = {
        .model = m->name,
        .method = run->method->name,
        .step = on_grid ? run->step : NAN,
        .rtol = adaptive && !run->rtolv ? (run->rtol > 0   ? run->rtol
                                          : m->rtol > 0    ? m->rtol
                                                           : DYN_DEFAULT_RTOL)
                                        : NAN,
        .atol = adaptive && !run->atolv ? (run->atol > 0   ? run->atol
                                          : m->atol > 0    ? m->atol
                                                           : DYN_DEFAULT_ATOL)
                                        : NAN,
        .t0 = run->t0,
        .t1 = run->t1,
        .cols = cols,
        .n_y = m->n_states,
        .names = s,
        .units = s + cols,
        .header = header,
    };
    cli_table *tab = cli_table_open(out, format, &info, err, errlen);
    if (!tab) {
        free(s);
        return NULL;
    }
    cli_table_keep(tab, s);
    return tab;
}

int cli_run_format(const struct cli_run *run, cli_format *format)
{
    char err[512];
    if (cli_format_of_path(run->output_path ? run->output_path : "-", format, err, sizeof err))
        return cli_usage_error("run", "--output %s", err);
    if (run->header != CLI_HEADER_NAMES && *format != CLI_FORMAT_CSV)
        return cli_usage_error("run", "--header applies to CSV output; a .%s file %s",
                               cli_format_name(*format),
                               *format == CLI_FORMAT_NPY
                                   ? "holds the numbers only (its columns are those of the "
                                     "CSV header)"
                                   : "carries the names and units anyway");
    return CLI_OK;
}
