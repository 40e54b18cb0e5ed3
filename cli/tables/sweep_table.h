/* SPDX-License-Identifier: BSD-3-Clause */
/* A sweep's table (dynkit sweep, docs/sweeps.md) read back for a picture: its CSV (names
 * only) or its JSON (names and units; docs/data-files.md). */
#ifndef DYNKIT_CLI_SWEEP_TABLE_H
#define DYNKIT_CLI_SWEEP_TABLE_H

#include <stddef.h>

#define SWEEP_TABLE_MAX_COLS 256

typedef struct sweep_table {
    int cols;
    char *names[SWEEP_TABLE_MAX_COLS];
    char *units[SWEEP_TABLE_MAX_COLS]; /* NULL when the file has none (CSV) */
    long rows;
    double *data;   /* (rows x cols); text fields (a CSV's status) and null are NaN */
    int status_col; /* -1 if none */
    int bands;      /* a band table (dynkit sweep --bands): t, mean_X, p5_X, p50_X, p95_X */
} sweep_table;

/* Read the table at path: JSON when its name ends in .json, CSV otherwise; the first column
 * must be run (or t in a band table, which has a column p5_X). Returns 0, or -1 with a message in err; call sweep_table_free either way. */
int sweep_table_read(const char *path, sweep_table *t, char *err, size_t errlen);
void sweep_table_free(sweep_table *t);

#endif
