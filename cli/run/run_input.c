/* SPDX-License-Identifier: BSD-3-Clause */
/* --forces FILE: a time table of a model's inputs (e.g. the cart's body forces), read,
 * checked against the model's input columns and attached to the run's parameters. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run/run_parse.h"
#include "util/out_file.h"

/* --forces: read the table, check its columns against the model's inputs, attach it to
 * the parameters, and take the step and span from it unless they were given. */
int cli_load_input(const char *command, cli_run *run, unsigned given)
{
    const dyn_model *m = run->model;
    char err[512], list[512];
    const char *path = run->forces_path;
    if (m->n_inputs <= 0 || !m->set_input) {
        size_t used = 0;
        list[0] = '\0';
        for (int i = 0; i < dyn_model_count(); i++)
            if (dyn_model_at(i)->n_inputs > 0 && used < sizeof list)
                used += (size_t)snprintf(list + used, sizeof list - used, "%s%s",
                                         used ? ", " : "", dyn_model_at(i)->name);
        return cli_usage_error(command,
                               "--forces: model %s takes no input table (models with inputs: "
                               "%s)",
                               m->name, list[0] ? list : "none");
    }
    dyn_table table;
    cli_input_note(path, "the --forces table");
    const int read_rc = dyn_table_read_file(path, DYN_TABLE_TIME_FIRST, &table, err, sizeof err);
    if (read_rc == DYN_ERR_CAPACITY) { /* out of memory: no usage error */
        cli_error("--forces: %s", err);
        return CLI_FAILED;
    }
    if (read_rc)
        return cli_usage_error(command, "--forces: %s", err);
    const int cols = 1 + m->n_inputs;
    int index[16];
    size_t used = 0;
    list[0] = '\0';
    for (int j = 0; j < cols && used < sizeof list; j++)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", j ? "," : "",
                                 j ? m->inputs[j - 1].name : "t");
    int rc = CLI_OK;
    if (cols > (int)(sizeof index / sizeof index[0]))
        rc = cli_usage_error(command, "--forces: model %s has too many inputs", m->name);
    for (int j = 0; j < cols && rc == CLI_OK; j++) {
        const char *name = j ? m->inputs[j - 1].name : "t";
        index[j] = dyn_table_column(&table, name);
        if (index[j] < 0)
            rc = cli_usage_error(command,
                                 "--forces: %s has no column '%s' (model %s needs the columns "
                                 "%s; others are ignored)",
                                 path, name, m->name, list);
    }
    if (rc == CLI_OK && index[0] != 0)
        rc = cli_usage_error(command, "--forces: in %s the first column must be t (needs %s)",
                             path, list);
    if (rc == CLI_OK && !(run->input = malloc((size_t)table.rows * (size_t)cols * sizeof(double)))) {
        cli_error("out of memory");
        rc = CLI_FAILED;
    }
    if (rc != CLI_OK) {
        dyn_table_free(&table);
        return rc;
    }
    for (long k = 0; k < table.rows; k++)
        for (int j = 0; j < cols; j++)
            run->input[k * cols + j] = table.data[k * table.cols + index[j]];
    run->input_rows = table.rows;
    dyn_table_free(&table);
    if (m->set_input(run->par, run->input, run->input_rows, run->interp, err, sizeof err))
        return cli_usage_error(command, "--forces %s: %s", path, err);
    const double *in = run->input;
    const long rows = run->input_rows;
    const double first = in[0], last = in[(rows - 1) * cols];
    if (!(given & GIVEN_TSPAN)) {
        if (rows < 2)
            return cli_usage_error(command,
                                   "--forces %s has a single row, so it spans no time: give "
                                   "--tspan T0:T1",
                                   path);
        run->t0 = first;
        run->t1 = last;
    }
    if (!(given & GIVEN_STEP)) {
        /* the sample time is the first spacing (exactly Ts for t_k = k Ts); the table must
         * be uniform for it to be the step */
        const double dt = rows > 1 ? in[cols] - in[0] : 0.0;
        for (long k = 2; k < rows && dt > 0.0; k++)
            if (!(fabs(in[k * cols] - (first + (double)k * dt)) <= 1e-9 * dt))
                return cli_usage_error(command,
                                       "--forces %s: the sample times are not uniform (row "
                                       "%ld: t = %s), so there is no sample time to use as "
                                       "the step: give --step H",
                                       path, k + 1, CLI_NUM(in[k * cols]));
        if (!(dt > 0.0))
            return cli_usage_error(command,
                                   "--forces %s has a single row: give --step H", path);
        run->step = dt;
    }
    return CLI_OK;
}
