/* SPDX-License-Identifier: BSD-3-Clause */
/* The run options of the commands that draw (animate, plot): the shared run options of
 * cli_run_parse, the runs to overlay (--compare METHOD[:STEP], repeatable) and the
 * command's own options; then recording every run for the picture. */
#include <stdlib.h>
#include <string.h>

#include "util/escape.h"
#include "pages/pages.h"

int cli_compare_parse(const char *command, const char *text, cli_compare *c)
{
    char name[64], names[640];
    const char *colon = strchr(text, ':');
    size_t len = colon ? (size_t)(colon - text) : strlen(text);
    memset(c, 0, sizeof *c);
    if (len == 0 || len >= sizeof name)
        return cli_usage_error(command,
                               "--compare '%s' is not accepted: give METHOD or METHOD:STEP, e.g. "
                               "euler or rk4:0.001 (methods: %s)",
                               text, cli_method_names(names, sizeof names));
    memcpy(name, text, len);
    name[len] = '\0';
    c->method = cli_method_find(name);
    if (!c->method) {
        char what[96];
        snprintf(what, sizeof what, "--compare '%.60s'", text);
        return cli_method_error(command, what, name);
    }
    if (colon && (cli_parse_number(colon + 1, &c->step) || !(c->step > 0)))
        return cli_usage_error(command,
                               "--compare '%s': the step '%s' is not accepted: give a step size "
                               "in s, a finite number > 0 (e.g. rk4:0.001)",
                               text, colon + 1);
    return CLI_OK;
}

int cli_view_parse(const char *command, int argc, char **argv, const char *const *extra,
                   const char **extra_values, cli_view *v)
{
    memset(v, 0, sizeof *v);
    char **rest = calloc((size_t)argc + 1, sizeof *rest);
    if (!rest) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    int n_rest = 0, rc = CLI_OK;
    for (int k = 0; extra && extra[k]; k++)
        extra_values[k] = NULL;
    for (int i = 0; i < argc && rc == CLI_OK; i++) {
        const char *value = NULL;
        int r = i > 0 ? cli_option(argc, argv, &i, "compare", &value) : 0;
        if (r < 0) {
            rc = cli_usage_error(command, "option --compare needs a value (METHOD[:STEP])");
        } else if (r > 0) {
            if (v->n_compare >= CLI_MAX_COMPARE)
                rc = cli_usage_error(command, "at most %d --compare runs are accepted",
                                     CLI_MAX_COMPARE);
            else
                rc = cli_compare_parse(command, value, &v->compare[v->n_compare++]);
            continue;
        }
        int taken = 0;
        for (int k = 0; i > 0 && rc == CLI_OK && extra && extra[k] && !taken; k++) {
            r = cli_option(argc, argv, &i, extra[k], &value);
            if (r < 0)
                rc = cli_usage_error(command, "option --%s needs a value", extra[k]);
            else if (r > 0)
                extra_values[k] = value;
            taken = r != 0;
        }
        if (!taken && rc == CLI_OK)
            rest[n_rest++] = argv[i];
    }
    int other_adaptive = 0;
    for (int k = 0; k < v->n_compare; k++)
        other_adaptive |= dyn_method_is_adaptive(v->compare[k].method);
    if (rc == CLI_OK)
        rc = cli_run_parse_with(command, n_rest, rest, other_adaptive, &v->run);
    free(rest);
    if (rc == CLI_OK && v->run.final_only)
        rc = cli_usage_error(command, "--final is not accepted here: a picture shows every "
                                      "sample (--every K thins them)");
    if (rc == CLI_OK && v->run.header != 0)
        rc = cli_usage_error(command, "--header is not accepted here: it sets the header of "
                                      "CSV files (dynkit run)");
    if (rc == CLI_OK && v->run.trace_steps > 0)
        rc = cli_usage_error(command, "--trace is not accepted here (see 'dynkit run --trace')");
    if (rc == CLI_OK && v->run.stats)
        rc = cli_usage_error(command, "--stats is not accepted here: it prints the counts of "
                                      "one run (see 'dynkit run --stats')");
    if (rc == CLI_OK && v->run.events_path)
        rc = cli_usage_error(command, "--events-output is not accepted here: it writes the "
                                      "events of one run (see 'dynkit run --events-output')");
    if (rc == CLI_OK && v->run.with_outputs)
        rc = cli_usage_error(command, "--outputs is not needed here: the picture has the "
                                      "model's extra outputs already");
    for (int k = 0; k < v->n_compare && rc == CLI_OK; k++)
        if (dyn_method_is_map(v->compare[k].method) != dyn_method_is_map(v->run.method))
            rc = cli_usage_error(command, "--compare %s: %s is %s, so only %s can run it",
                                 v->compare[k].method->name, v->run.model->name,
                                 dyn_method_is_map(v->run.method) ? "a discrete map"
                                                                  : "a differential equation",
                                 dyn_method_is_map(v->run.method) ? "the method discrete"
                                                                  : "an integrator");
        else if (cli_method_is_cvode(v->compare[k].method) && v->run.n_events > 0)
            rc = cli_usage_error(command, "--compare cvode: the CVODE backend runs without "
                                          "events here; leave out --event");
        else if (v->run.model->n_noise > 0 && !dyn_method_is_map(v->run.method) &&
                 !cli_method_is_sde_adaptive(v->compare[k].method) &&
                 strcmp(v->compare[k].method->name, "euler") != 0)
            rc = cli_usage_error(command, "--compare %s: model %s has noise (wiener, normal or "
                                 "ran), which only euler (Euler-Maruyama), rkmil and sriw1 "
                                 "integrate",
                                 v->compare[k].method->name, v->run.model->name);
        else if (v->run.model->n_noise == 0 && cli_method_is_sde_adaptive(v->compare[k].method))
            rc = cli_usage_error(command, "--compare %s: %s integrates models with noise, "
                                 "and %s has none", v->compare[k].method->name,
                                 v->compare[k].method->name, v->run.model->name);
    return rc;
}

int cli_view_record(cli_view *v)
{
    int rc = CLI_OK;
    for (int k = 0; k <= v->n_compare; k++) {
        const dyn_tableau *method = k ? v->compare[k - 1].method : v->run.method;
        double step = k ? v->compare[k - 1].step : 0.0; /* 0: the run's */
        cli_series *s = &v->series[v->n_series];
        int r = cli_series_record(&v->run, method, step, CLI_MAX_ROWS, s);
        if (s->data)
            v->n_series++;
        if (r == CLI_USAGE)
            return r;
        if (r != CLI_OK) {
            char shown[4 * sizeof s->message + 8];
            cli_stderr("dynkit: run failed: %s\n",
                       cli_terminal_text(s->message, 1, shown, sizeof shown));
            if (rc == CLI_OK)
                rc = r;
        }
    }
    return rc;
}

void cli_view_free(cli_view *v)
{
    for (int k = 0; k < v->n_series; k++)
        cli_series_free(&v->series[k]);
    v->n_series = 0;
    cli_run_free(&v->run);
}
