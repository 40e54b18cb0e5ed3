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

/* Split argv (MODEL first) into pass (for cli_run_parse: MODEL and the run options named
 * in run_opts, each "--name VALUE", and the flags in run_flags, both given as "--name" in
 * static storage) and the command's own options. pass holds 2 argc + 1 pointers. Returns CLI_OK or a usage error (printed). */
int cli_analysis_args(const char *command, int argc, char **argv, const char *const *run_opts,
                      int n_run_opts, const char *const *run_flags, int n_run_flags,
                      const cli_aopt *own, int n_own, char **pass, int *n_pass);

/* "NAME=VALUE" split at '=' into name (size bytes); the value's start, or NULL. */
const char *cli_analysis_name_value(const char *text, char *name, size_t size);

#endif
