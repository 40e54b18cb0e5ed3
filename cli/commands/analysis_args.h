/* SPDX-License-Identifier: BSD-3-Clause */
/* The command lines of the analysis commands (equilibria, steady, lyapunov): the run
 * options passed on to cli_run_parse and each command's own options (analysis_args.c). */
#ifndef DYNKIT_CLI_ANALYSIS_ARGS_H
#define DYNKIT_CLI_ANALYSIS_ARGS_H

#include "cli.h"

/* One option of a command: "--name" with a value stored in *value (given once), or a
 * flag setting *flag to 1. repeat: the values of a repeated option are joined by commas
 * into the caller's buffer list (list_size bytes) instead. */
typedef struct cli_aopt {
    const char *name;
    const char **value; /* NULL for a flag */
    int *flag;
    char *list;         /* repeatable: values joined with ',' */
    size_t list_size;
} cli_aopt;

/* The start of an analysis command: with -h or --help anywhere, help() is printed and
 * *done set; a missing MODEL is a usage error; else argv (MODEL first) is split into the
 * run options named in run_opts ("--name" in static storage, each with a value), parsed
 * into run by cli_run_parse, and the command's own options. Returns CLI_OK or a usage
 * error (printed); run is to be freed with cli_run_free in every case. */
int cli_analysis_parse(const char *command, int argc, char **argv, void (*help)(void),
                       const char *const *run_opts, int n_run_opts, const cli_aopt *own,
                       int n_own, cli_run *run, int *done);

/* print(f, ctx) to output (NULL or "-": standard output; a file is kept only when every
 * write succeeded). Returns CLI_OK or CLI_FAILED. */
int cli_analysis_write(const char *output, void (*print)(FILE *, const void *),
                       const void *ctx);

/* "NAME=VALUE" split at '=' into name (size bytes); the value's start, or NULL. */
const char *cli_analysis_name_value(const char *text, char *name, size_t size);

#endif
