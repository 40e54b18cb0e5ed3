/* SPDX-License-Identifier: BSD-3-Clause */
/* Data files of a run's table (t, the states, extra outputs; names, units and the run's
 * settings), in the format the extension of --output names: CSV (RFC 4180, streamed), JSON
 * (RFC 8259, streamed), NumPy .npy (NPY format 1.0) and .npz (a ZIP archive of .npy files,
 * PKWARE APPNOTE 6.3), MATLAB .mat (level 5 MAT-file, written with matio when dynkit is built
 * with it). The formats and their layout are described in docs/data-files.md. */
#ifndef DYNKIT_CLI_TABLE_FORMATS_H
#define DYNKIT_CLI_TABLE_FORMATS_H

#include <stddef.h>
#include <stdio.h>

typedef enum cli_format {
    CLI_FORMAT_CSV,
    CLI_FORMAT_JSON,
    CLI_FORMAT_MAT,
    CLI_FORMAT_NPY,
    CLI_FORMAT_NPZ
} cli_format;

/* The CSV header line: names (default), "name [unit]", or none. */
typedef enum cli_header { CLI_HEADER_NAMES, CLI_HEADER_UNITS, CLI_HEADER_NONE } cli_header;

/* The accepted extensions, for messages: ".csv, .json, .mat, .npy, .npz". */
#define CLI_FORMAT_EXTENSIONS ".csv, .json, .mat, .npy, .npz"

/* The format of an output file by the extension of path (case-insensitive); "-" (standard
 * output) and a device or pipe without such an extension (/dev/stdout, /dev/null) are CSV. Returns 0, or -1 with a message in err: an unknown or missing extension
 * (naming the accepted ones), or .mat when dynkit was built without matio (saying how to get
 * it). */
int cli_format_of_path(const char *path, cli_format *format, char *err, size_t errlen);
/* "csv", "json", "mat", "npy", "npz". */
const char *cli_format_name(cli_format format);
/* 1 when dynkit was built with matio (.mat files). */
int cli_format_have_mat(void);

/* What the file says about its table. Strings are borrowed until cli_table_free. */
typedef struct cli_table_info {
    const char *model;  /* model name */
    const char *method; /* method name, or NULL when no integration made the table */
    double step;        /* step or sample time in s; NaN when none */
    double rtol, atol;  /* scalar tolerances of an adaptive method; NaN otherwise */
    double t0, t1;      /* the span asked for */
    int cols;           /* 1 + n_y + the extra outputs */
    int n_y;            /* columns 1..n_y are the states (y), the rest extra outputs */
    const char *y_name; /* the states' variable in .mat/.npz: "y" when NULL */
    const char *const *names; /* (cols) column names, names[0] = "t" */
    const char *const *units; /* (cols) their units, "" when none */
    cli_header header;  /* CSV only */
    /* A sweep's table (dynkit sweep) when sweep = 1: one row per run, column 0 the run
     * number, then n_varied varied names, n_reduced reductions and, when a run failed, the
     * status; n_y is then the model's number of states (JSON "states"), not a split of the
     * columns, and .npz and .mat hold one variable per column, named as the column. */
    int sweep, n_varied, n_reduced;
} cli_table_info;

/* 1 when a column of a sweep's table named name would have the name of another variable of
 * its .npz or .mat file (the settings, names, units, run, status). */
int cli_table_name_taken(const char *name);

typedef struct cli_table cli_table;

/* Start a table in format on out (a stream the caller opened for writing, binary-safe; the
 * caller closes it after cli_table_finish). CSV and JSON stream each row; NPY streams when
 * out is seekable (the header is rewritten at the end) and keeps the rows in memory otherwise;
 * NPZ and MAT keep the rows in memory and write at cli_table_finish. Returns the table, or
 * NULL with a message in err (out of memory, a write error). */
cli_table *cli_table_open(FILE *out, cli_format format, const cli_table_info *info, char *err,
                          size_t errlen);
/* Free block (a caller's names and units the table's info borrows) with the table. */
void cli_table_keep(cli_table *tab, const char **block);
/* One row: t, y (n values), extra (m values; NULL when m = 0), n + m + 1 = info->cols.
 * Returns 0, or -1 when writing failed or memory ran out (the error is kept for
 * cli_table_finish). */
int cli_table_row(cli_table *tab, double t, const double *y, int n, const double *extra, int m);
/* Write what is kept, close the document (JSON), flush. Returns 0, or -1 with a message in
 * err. Call once. */
int cli_table_finish(cli_table *tab, char *err, size_t errlen);
/* Rows given so far. */
long cli_table_rows(const cli_table *tab);
/* The rows of cols columns (n_y states) a table of format may keep in memory (LONG_MAX for
 * the streamed formats), with *why the limit's reason (NULL when none). */
long cli_table_limit(cli_format format, int cols, int n_y, const char **why);
/* 1 when a row was refused because the table kept all the rows it may (cli_table_limit),
 * with a sentence in why; the rows kept are still written by cli_table_finish. */
int cli_table_full(const cli_table *tab, char *why, size_t len);
void cli_table_free(cli_table *tab);

/* ---- the writers of the buffered formats (table_numpy.c, table_mat.c) ---- */
/* rows x cols doubles, row-major */
int cli_npy_write(FILE *out, const double *data, long rows, int cols, char *err, size_t errlen);
/* The .npy header of a rows x cols float64 array, padded to header_size bytes (a multiple of
 * 64; 0: the smallest). Returns the header's size, or -1 if it does not fit. */
long cli_npy_header(char *buf, size_t size, long rows, int cols, long header_size);
int cli_npz_write(FILE *out, const cli_table_info *info, const double *data, long rows,
                  char *err, size_t errlen);
int cli_mat_write(FILE *out, const cli_table_info *info, const double *data, long rows,
                  char *err, size_t errlen);

#endif
