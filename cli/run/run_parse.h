/* SPDX-License-Identifier: BSD-3-Clause */
/* Private to the tool: the pieces of run-option parsing shared by run_options.c (the
 * option loop), run_values.c (option values: span, tolerances, times, events, --set/--init)
 * and run_input.c (--forces tables). */
#ifndef DYNKIT_CLI_RUN_PARSE_H
#define DYNKIT_CLI_RUN_PARSE_H

#include "cli.h"

/* Which options were given (the defaults of step and span depend on --forces). */
enum {
    GIVEN_STEP = 1,
    GIVEN_TSPAN = 2,
    GIVEN_INTERP = 4,
    GIVEN_RTOL = 8,
    GIVEN_ATOL = 16,
    GIVEN_MAX_STEP = 32,
    GIVEN_INITIAL_STEP = 64,
    GIVEN_MAX_STEPS = 128,
    GIVEN_METHOD = 256,
    GIVEN_SEED = 512
};

/* The limit on the steps of an adaptive run without --max-steps: a run that needs more is
 * one whose tolerances or span ask too much (DYN_ERR_MAX_STEPS, the message says so). */
#define CLI_DEFAULT_MAX_STEPS 10000000L

/* --set/--init are applied after all options are read, so record them first. */
typedef struct assignment {
    const char *text;
    int is_param;
} assignment;

/* Each parser prints a usage error naming the option and what is accepted and returns
 * CLI_USAGE, or returns CLI_OK. */
/* --tspan T0:T1 into t0 < t1. */
int cli_parse_tspan(const char *command, const char *text, double *t0, double *t1);
/* One --set (parameter) or --init (state) assignment into run. */
int cli_apply_assignment(const char *command, cli_run *run, const assignment *as);
/* 1 when as's VALUE is a plain number (no formula of the parameters). */
int cli_assignment_is_number(const assignment *as);
/* A tolerance: one number >= 0 (*scalar), or one per state, comma-separated (*vec, owned). */
int cli_parse_tolerance(const char *command, const char *opt, const char *text, int n,
                        double *scalar, double **vec);
/* --times LIST or @FILE into run (increasing times within the span). */
int cli_parse_times(const char *command, const char *text, cli_run *run);
/* --event NAME[:stop] of the model into run. */
int cli_add_event(const char *command, const char *text, cli_run *run);
/* --section SPEC into run (run_section.c), and the model's @ poimap when --section was not
 * given; cli_section_free releases what they keep. */
int cli_parse_section(const char *command, const char *text, cli_run *run);
int cli_section_from_model(const char *command, cli_run *run);
void cli_section_free(cli_run *run);
/* A finite number > 0 for option opt. */
int cli_parse_positive(const char *command, const char *opt, const char *text, double *out);
/* --forces: read the table, check its columns, attach it to the parameters, and take the
 * step and span from it unless they were given. */
int cli_load_input(const char *command, cli_run *run, unsigned given);

#endif
