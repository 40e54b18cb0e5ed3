/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/io.h — writing results: CSV with numbers that round-trip (%.17g); reading numeric
 * CSV tables (e.g. force inputs).
 *
 * The library writes only to streams the caller opened and hands in; it reports failures
 * by status (DYN_ERR_IO) and never closes the stream.
 */
#ifndef DYNKIT_IO_H
#define DYNKIT_IO_H

#include <stdio.h>

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Header line "t,<names of vars>,<names of extra>" (extra may be NULL with m = 0).
 * Returns DYN_OK or DYN_ERR_IO. */
int dyn_csv_write_header(FILE *out, const dyn_var *vars, int n, const dyn_var *extra, int m);
/* One row "t,y...,extra..." with %.17g. Returns DYN_OK or DYN_ERR_IO. */
int dyn_csv_write_row(FILE *out, double t, const double *y, int n, const double *extra, int m);

/* ---- reading numeric CSV tables (table_read.c) ---- */

/* A numeric table read from CSV: rows x cols doubles and the column names of the header.
 * Filled by dyn_table_read*, owned by the caller, released with dyn_table_free. */
typedef struct dyn_table {
    long rows;
    int cols;
    double *data;  /* (rows x cols) row-major */
    char **names;  /* (cols) column names, trimmed of surrounding blanks */
} dyn_table;

/* Flags of dyn_table_read. */
enum {
    DYN_TABLE_TIME_FIRST = 1 /* column 0 is time: it must increase strictly */
};

/* Limits of dyn_table_read: bytes of one line, numbers of one table. */
#define DYN_TABLE_MAX_LINE (16 * 1024 * 1024)
#define DYN_TABLE_MAX_CELLS 100000000L

/* Read CSV from in: a header line of comma-separated names, then rows of as many finite
 * numbers (strtod syntax; blanks around fields, blank lines, lines starting with '#' and
 * CRLF endings are accepted). source names the input in messages (e.g. the file name).
 * On success returns DYN_OK and fills table (zeroed first). On failure returns DYN_ERR_ARG
 * (bad content: empty input, no data rows, empty or duplicate column name, a field that is
 * not a finite number, a wrong number of fields, time not increasing, a NUL byte, a UTF-16
 * file, CR-only line ends, a line longer than DYN_TABLE_MAX_LINE, more than
 * DYN_TABLE_MAX_CELLS numbers), DYN_ERR_IO (read error, e.g. a directory) or
 * DYN_ERR_CAPACITY (out of memory), with "SOURCE:LINE: what is wrong" in err (bytes of the
 * input escaped as \xNN), and table left empty. A UTF-8 byte order mark is skipped. */
int dyn_table_read(FILE *in, const char *source, unsigned flags, dyn_table *table, char *err,
                   size_t errlen);
/* dyn_table_read on the file at path (opened and closed here); a file that cannot be opened
 * is DYN_ERR_IO with "cannot open PATH: reason" in err. */
int dyn_table_read_file(const char *path, unsigned flags, dyn_table *table, char *err,
                        size_t errlen);
/* Index of the column called name, or -1. */
int dyn_table_column(const dyn_table *table, const char *name);
/* Release what dyn_table_read allocated and zero the struct; safe on a zeroed table. */
void dyn_table_free(dyn_table *table);
/* s with the bytes outside printable ASCII written as \xNN (so that a file's bytes never
 * reach a terminal raw), cut with "..." to fit size bytes of buf; returns buf. */
const char *dyn_text_escaped(const char *s, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_IO_H */
