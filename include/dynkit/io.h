/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/io.h — writing results: numbers as the shortest decimal that reads back to the same
 * double (dyn_format_double), buffered text output, CSV rows; reading numeric CSV tables
 * (e.g. force inputs).
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

/* ---- numbers as text (shortest_double.c) ---- */

/* Bytes of a buffer that holds every string of dyn_format_double and its NUL (the longest,
 * e.g. "-2.2250738585072014e-308", has 24 characters). */
#define DYN_DOUBLE_CHARS 32

/* Write x into buf (DYN_DOUBLE_CHARS bytes) as the shortest decimal string that strtod reads
 * back to the same double, the last digit correctly rounded (Ryu, Adams 2018), NUL-terminated;
 * returns its length. Layout: with X the decimal exponent of the first digit, plain decimal
 * when -4 <= X < 16 ("0.0001", "0.01", "-2.5", "20", "9007199254740992": an integer has no
 * point), else "d.ddde-X" or "d.dddeX" (no '+', no leading zeros: "1e-5", "1.5e16",
 * "5e-324", "1.7976931348623157e308"); "0", "-0", "inf", "-inf", "nan" (any NaN). Finite
 * values are valid JSON numbers; strtod, NumPy and pandas read every string back. */
int dyn_format_double(double x, char *buf);

/* x as dyn_format_double's text, for printf: printf("t = %s", dyn_shortest(t).s) (the
 * array lives until the end of the full expression, C11 6.2.4). */
typedef struct dyn_shortest_text {
    char s[DYN_DOUBLE_CHARS];
} dyn_shortest_text;

static inline dyn_shortest_text dyn_shortest(double x)
{
    dyn_shortest_text r;
    dyn_format_double(x, r.s);
    return r;
}

/* ---- buffered text output (text_writer.c) ---- */

#define DYN_TEXT_WRITER_BUFFER 65536

/* Text gathered in buf and handed to out with one fwrite per full buffer. A failed write
 * is kept (failed): later writes do nothing and return DYN_ERR_IO. */
typedef struct dyn_text_writer {
    FILE *out;
    size_t len;
    int failed;
    char buf[DYN_TEXT_WRITER_BUFFER];
} dyn_text_writer;

/* Start writing to out (nothing is written yet). */
void dyn_text_writer_init(dyn_text_writer *w, FILE *out);
/* Append n bytes of s; DYN_OK or DYN_ERR_IO. */
int dyn_text_write(dyn_text_writer *w, const char *s, size_t n);
/* Append x as dyn_format_double writes it; DYN_OK or DYN_ERR_IO. */
int dyn_text_write_double(dyn_text_writer *w, double x);
/* Hand what is buffered to out with fwrite (the stream's own buffer is not flushed: call
 * fflush for that). Call before anything else writes to out. DYN_OK or DYN_ERR_IO. */
int dyn_text_writer_flush(dyn_text_writer *w);

/* ---- CSV (csv_write.c) ---- */

/* Header line "t,<names of vars>,<names of extra>" (extra may be NULL with m = 0).
 * Returns DYN_OK or DYN_ERR_IO. */
int dyn_csv_write_header(FILE *out, const dyn_var *vars, int n, const dyn_var *extra, int m);
/* One row "t,y...,extra..." with dyn_format_double's numbers, written with one fwrite.
 * Returns DYN_OK or DYN_ERR_IO. */
int dyn_csv_write_row(FILE *out, double t, const double *y, int n, const double *extra, int m);
/* The same row appended to w (rows of many runs share one fwrite per buffer). */
int dyn_csv_write_row_to(dyn_text_writer *w, double t, const double *y, int n,
                         const double *extra, int m);

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
/* s for a terminal, into buf (text_escape.c; the one escaper of every message that quotes
 * outside text): printable ASCII and well-formed UTF-8 are kept, every other byte is
 * written \xNN: control characters (ESC, BEL, and the C1 controls U+0080..U+009F, which
 * some terminals obey too), DEL, and bytes that are not UTF-8, so text from a file cannot
 * move the cursor, set a window title or change colours. Tab and line feed are kept when
 * lines is 1. Cut with "..." when buf is too small (4 times the length of s, plus 1,
 * always suffices; size >= 4). Returns buf. */
const char *dyn_terminal_text(const char *s, int lines, char *buf, size_t size);
/* dyn_terminal_text(s, 0, buf, size): one line. */
const char *dyn_text_escaped(const char *s, char *buf, size_t size);
/* The character that starts at *p, *p moved past it; DYN_UTF8_REPLACEMENT (U+FFFD) for a
 * byte that does not begin a well-formed UTF-8 sequence (RFC 3629), that byte alone
 * consumed. *p must not point at the terminating NUL. */
#define DYN_UTF8_REPLACEMENT 0xFFFDL
long dyn_utf8_next(const unsigned char **p);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_IO_H */
