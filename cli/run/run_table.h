/* SPDX-License-Identifier: BSD-3-Clause */
/* A run's table (run_table.c): a parsed run given to the table formats of tables/. */
#ifndef DYNKIT_CLI_RUN_TABLE_H
#define DYNKIT_CLI_RUN_TABLE_H

#include "cli.h"
#include "tables/table_formats.h"

/* cli_table_open for a run of dynkit run: the model's states and (with --outputs) extra
 * outputs, the method, step and tolerances of run. */
cli_table *cli_table_open_run(FILE *out, cli_format format, const cli_run *run,
                              cli_header header, char *err, size_t errlen);
/* The format of run's --output, checked against --header: CLI_OK, or a usage error
 * (printed) and CLI_USAGE. */
int cli_run_format(const cli_run *run, cli_format *format);

#endif
