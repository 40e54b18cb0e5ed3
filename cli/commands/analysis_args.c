/* SPDX-License-Identifier: BSD-3-Clause */
/* The command lines of the analysis commands: --help, the missing MODEL, run options
 * passed on to cli_run_parse, the command's own options and flags, every other word
 * refused with the nearest option named (cli_unknown_option); and their output written
 * to standard output or a file kept only when complete. */
#include "commands/analysis_args.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/out_file.h"

const char *cli_analysis_name_value(const char *text, char *name, size_t size)
{
    const char *eq = strchr(text, '=');
    if (!eq || eq == text || (size_t)(eq - text) >= size)
        return NULL;
    memcpy(name, text, (size_t)(eq - text));
    name[eq - text] = '\0';
    return eq + 1;
}

static int own_option(const char *command, int argc, char **argv, int *i, const cli_aopt *o)
{
    const char *v = NULL;
    const int r = cli_option(argc, argv, i, o->name, &v);
    if (r == 0)
        return 0;
    if (r < 0)
        return cli_usage_error(command, "option --%s needs a value", o->name);
    if (o->list) {
        const size_t used = strlen(o->list);
        if (used + strlen(v) + 2 > o->list_size)
            return cli_usage_error(command, "--%s: too many values", o->name);
        if (used)
            strcat(o->list, ",");
        strcat(o->list, v);
        return 1;
    }
    if (*o->value)
        return cli_usage_error(command, "--%s is given once", o->name);
    *o->value = v;
    return 1;
}

static int split_args(const char *command, int argc, char **argv, const char *const *run_opts,
                      int n_run_opts, const cli_aopt *own, int n_own, char **pass, int *n_pass)
{
    const int n_all = n_run_opts + n_own;
    const char **all = malloc((size_t)n_all * sizeof *all);
    char(*names)[48] = malloc((size_t)n_all * sizeof *names);
    if (!all || !names) {
        free(all);
        free(names);
        return CLI_FAILED;
    }
    for (int k = 0; k < n_all; k++) {
        if (k < n_run_opts) {
            all[k] = run_opts[k];
            continue;
        }
        snprintf(names[k], sizeof names[k], "--%s", own[k - n_run_opts].name);
        all[k] = names[k];
    }
    int rc = CLI_OK;
    pass[(*n_pass)++] = argv[0];
    for (int i = 1; i < argc && rc == CLI_OK; i++) {
        int done = 0;
        for (int k = 0; k < n_run_opts && !done && rc == CLI_OK; k++) {
            const char *v = NULL;
            const int r = cli_option(argc, argv, &i, run_opts[k] + 2, &v);
            if (r < 0)
                rc = cli_usage_error(command, "option %s needs a value", run_opts[k]);
            else if (r > 0) {
                pass[(*n_pass)++] = (char *)run_opts[k];
                pass[(*n_pass)++] = (char *)v;
                done = 1;
            }
        }
        for (int k = 0; k < n_own && !done && rc == CLI_OK; k++) {
            if (!own[k].value && !own[k].list) {
                if (cli_flag(argv[i], own[k].name)) {
                    *own[k].flag = 1;
                    done = 1;
                }
                continue;
            }
            const int r = own_option(command, argc, argv, &i, &own[k]);
            if (r == CLI_USAGE)
                rc = r;
            else
                done = r == 1;
        }
        if (!done && rc == CLI_OK)
            rc = cli_unknown_option(command, argv[i], all, n_all);
    }
    free(all);
    free(names);
    return rc;
}

int cli_analysis_parse(const char *command, int argc, char **argv, void (*help)(void),
                       const char *const *run_opts, int n_run_opts, const cli_aopt *own, int n_own,
                       cli_run *run, int *done)
{
    memset(run, 0, sizeof *run);
    *done = 0;
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            help();
            *done = 1;
            return CLI_OK;
        }
    if (argc < 1 || argv[0][0] == '-') {
        char names[512];
        return cli_usage_error(command, "missing MODEL (accepted: %s, or a model file)",
                               dyn_model_names(names, sizeof names));
    }
    char **pass = calloc((size_t)(2 * argc + 1), sizeof *pass);
    if (!pass)
        return CLI_FAILED;
    int n_pass = 0;
    int rc = split_args(command, argc, argv, run_opts, n_run_opts, own, n_own, pass, &n_pass);
    if (rc == CLI_OK)
        rc = cli_run_parse(command, n_pass, pass, run);
    free(pass);
    return rc;
}

int cli_analysis_write(const char *output, void (*print)(FILE *, const void *), const void *ctx)
{
    cli_out out;
    const char *path = output && strcmp(output, "-") != 0 ? output : NULL;
    int rc = cli_out_open(&out, "--output", path);
    if (rc != CLI_OK)
        return rc;
    print(out.f, ctx);
    const int bad = fflush(out.f) != 0 || ferror(out.f);
    if (out.f != stdout)
        return cli_out_close(&out, !bad);
    return bad ? CLI_FAILED : CLI_OK;
}
