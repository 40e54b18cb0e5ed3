/* SPDX-License-Identifier: BSD-3-Clause */
/* Reading numeric CSV tables (io.h): a header line of column names, then rows of finite
 * numbers, into a caller-freed dyn_table; errors name the source, the line and the field.
 * The format is the plain subset of RFC 4180 that dynkit writes (no quoted fields, except
 * that a header name may be enclosed in double quotes); numbers follow C's strtod.
 * Lines are read with fgetc into a growing buffer, so any line length works in plain C11,
 * up to DYN_TABLE_MAX_LINE bytes; a table holds at most DYN_TABLE_MAX_CELLS numbers. A UTF-8
 * byte order mark (Excel's "CSV UTF-8") is skipped; UTF-16 files, CR-only line ends and NUL
 * bytes are refused with their own messages; bytes of the input are escaped (\xNN) when a
 * message quotes them; duplicate column names are found by sorting (n log n).
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h"
#include "dynkit/ode.h"

typedef struct line_reader {
    FILE *in;
    char *buf;
    size_t cap;
    long number; /* 1-based number of the line in buf */
    int why;     /* after -1: LINE_* */
    int read_errno;
} line_reader;

enum { LINE_IO = 1, LINE_MEMORY, LINE_NUL, LINE_LONG, LINE_UTF16, LINE_CR };

/* Read the next line into r->buf without its end of line (LF or CRLF). Returns 1 for a
 * line, 0 at the end of the input, -1 for a read error, no memory or bytes that are no
 * text (r->why says which). */
static int next_line(line_reader *r)
{
    size_t len = 0;
    int c;
    for (;;) {
        c = fgetc(r->in);
        if (c == EOF || c == '\n')
            break;
        if (c == '\0') {
            r->why = r->number == 0 && len >= 2 &&
                             (((unsigned char)r->buf[0] == 0xFF && (unsigned char)r->buf[1] == 0xFE) ||
                              ((unsigned char)r->buf[0] == 0xFE && (unsigned char)r->buf[1] == 0xFF))
                         ? LINE_UTF16
                         : LINE_NUL;
            r->number++;
            return -1;
        }
        if (len >= DYN_TABLE_MAX_LINE) {
            r->why = LINE_LONG;
            r->number++;
            return -1;
        }
        if (len + 2 > r->cap) {
            size_t cap = r->cap ? 2 * r->cap : 256;
            char *grown = realloc(r->buf, cap);
            if (!grown) {
                r->why = LINE_MEMORY;
                return -1;
            }
            r->buf = grown;
            r->cap = cap;
        }
        r->buf[len++] = (char)c;
    }
    if (c == EOF && ferror(r->in)) {
        r->why = LINE_IO;
        r->read_errno = errno;
        return -1;
    }
    if (c == EOF && len == 0)
        return 0;
    if (!r->buf) { /* an empty line before any allocation */
        r->buf = malloc(256);
        if (!r->buf) {
            r->why = LINE_MEMORY;
            return -1;
        }
        r->cap = 256;
    }
    if (len > 0 && r->buf[len - 1] == '\r')
        len--;
    r->buf[len] = '\0';
    r->number++;
    if (r->number == 1 && len >= 2 &&
        (((unsigned char)r->buf[0] == 0xFF && (unsigned char)r->buf[1] == 0xFE) ||
         ((unsigned char)r->buf[0] == 0xFE && (unsigned char)r->buf[1] == 0xFF))) {
        r->why = LINE_UTF16;
        return -1;
    }
    if (r->number == 1 && len >= 3 && memcmp(r->buf, "\xEF\xBB\xBF", 3) == 0)
        memmove(r->buf, r->buf + 3, len - 2); /* UTF-8 byte order mark */
    if (memchr(r->buf, '\r', len)) {
        r->why = LINE_CR;
        return -1;
    }
    return 1;
}

/* Why next_line failed, as "SOURCE:LINE: ..." into err; returns the status. */
static int line_error(const line_reader *r, const char *src, char *err, size_t errlen);

/* Trim blanks at both ends in place; returns the start. */
static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    char *end = s + strlen(s);
    while (end > s && isspace((unsigned char)end[-1]))
        *--end = '\0';
    return s;
}

/* 1 if the line carries no data: blank, or a comment starting with '#'. */
static int skip_line(const char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    return *s == '\0' || *s == '#';
}

static void set_err(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static void set_err(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    if (!err || !errlen)
        return;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

static int line_error(const line_reader *r, const char *src, char *err, size_t errlen)
{
    switch (r->why) {
    case LINE_NUL:
        set_err(err, errlen, "%s:%ld: a NUL byte: this is no text file (CSV; UTF-16 text has them: save it as "
                "UTF-8)", src, r->number);
        return DYN_ERR_ARG;
    case LINE_LONG:
        set_err(err, errlen, "%s:%ld: the line is longer than %d bytes", src, r->number,
                DYN_TABLE_MAX_LINE);
        return DYN_ERR_ARG;
    case LINE_UTF16:
        set_err(err, errlen,
                "%s: the file is UTF-16 encoded: save it as UTF-8 or ASCII text (CSV)", src);
        return DYN_ERR_ARG;
    case LINE_CR:
        set_err(err, errlen,
                "%s:%ld: a carriage return inside the line: lines end with CR only (old Mac "
                "style); save the file with LF or CRLF line ends",
                src, r->number);
        return DYN_ERR_ARG;
    case LINE_MEMORY:
        set_err(err, errlen, "%s:%ld: out of memory", src, r->number + 1);
        return DYN_ERR_CAPACITY;
    default:
        set_err(err, errlen, "%s: cannot read: %s", src,
                r->read_errno ? strerror(r->read_errno) : "a read error");
        return DYN_ERR_IO;
    }
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Count the comma-separated fields of s. */
static int count_fields(const char *s)
{
    int n = 1;
    for (; *s; s++)
        n += *s == ',';
    return n;
}

void dyn_table_free(dyn_table *table)
{
    if (!table)
        return;
    if (table->names)
        for (int i = 0; i < table->cols; i++)
            free(table->names[i]);
    free(table->names);
    free(table->data);
    memset(table, 0, sizeof *table);
}

int dyn_table_column(const dyn_table *table, const char *name)
{
    for (int i = 0; name && table->names && i < table->cols; i++)
        if (strcmp(table->names[i], name) == 0)
            return i;
    return -1;
}

/* Parse the header in line into table->names. */
static int read_header(dyn_table *table, char *line, const char *src, long lineno, char *err,
                       size_t errlen)
{
    int cols = count_fields(line);
    table->names = calloc((size_t)cols, sizeof *table->names);
    if (!table->names) {
        set_err(err, errlen, "%s: out of memory", src);
        return DYN_ERR_CAPACITY;
    }
    table->cols = cols;
    char *field = line;
    for (int i = 0; i < cols; i++) {
        char *comma = strchr(field, ',');
        if (comma)
            *comma = '\0';
        char *name = trim(field);
        size_t len = strlen(name);
        if (len >= 2 && name[0] == '"' && name[len - 1] == '"') {
            name[len - 1] = '\0';
            name = trim(name + 1);
        }
        if (!*name) {
            set_err(err, errlen, "%s:%ld: column %d of the header has no name", src, lineno,
                    i + 1);
            return DYN_ERR_ARG;
        }
        table->names[i] = malloc(strlen(name) + 1);
        if (!table->names[i]) {
            set_err(err, errlen, "%s: out of memory", src);
            return DYN_ERR_CAPACITY;
        }
        strcpy(table->names[i], name);
        field = comma ? comma + 1 : field + strlen(field);
    }
    /* a name twice: sorted, equal names are neighbours */
    char **sorted = malloc((size_t)cols * sizeof *sorted);
    if (!sorted) {
        set_err(err, errlen, "%s: out of memory", src);
        return DYN_ERR_CAPACITY;
    }
    memcpy(sorted, table->names, (size_t)cols * sizeof *sorted);
    qsort(sorted, (size_t)cols, sizeof *sorted, compare_names);
    for (int i = 1; i < cols; i++)
        if (strcmp(sorted[i - 1], sorted[i]) == 0) {
            char name[128];
            set_err(err, errlen, "%s:%ld: column name '%s' appears twice in the header", src,
                    lineno, dyn_text_escaped(sorted[i], name, sizeof name));
            free(sorted);
            return DYN_ERR_ARG;
        }
    free(sorted);
    return DYN_OK;
}

/* Parse one data line into row (table->cols values). */
static int read_row(const dyn_table *table, char *line, double *row, const char *src,
                    long lineno, char *err, size_t errlen)
{
    int n = count_fields(line);
    if (n != table->cols) {
        set_err(err, errlen, "%s:%ld: %d field%s, but the header has %d columns", src, lineno,
                n, n == 1 ? "" : "s", table->cols);
        return DYN_ERR_ARG;
    }
    char *field = line;
    for (int i = 0; i < n; i++) {
        char *comma = strchr(field, ',');
        if (comma)
            *comma = '\0';
        char *text = trim(field), *end;
        if (!*text) {
            set_err(err, errlen, "%s:%ld: field %d (%s) is empty", src, lineno, i + 1,
                    table->names[i]);
            return DYN_ERR_ARG;
        }
        double v = strtod(text, &end);
        char shown[96], name[96];
        if (end == text || *end != '\0') {
            set_err(err, errlen, "%s:%ld: field %d (%s) '%s' is not a number", src, lineno,
                    i + 1, dyn_text_escaped(table->names[i], name, sizeof name),
                    dyn_text_escaped(text, shown, sizeof shown));
            return DYN_ERR_ARG;
        }
        if (!isfinite(v)) {
            set_err(err, errlen, "%s:%ld: field %d (%s) '%s' is not a finite number", src,
                    lineno, i + 1, dyn_text_escaped(table->names[i], name, sizeof name),
                    dyn_text_escaped(text, shown, sizeof shown));
            return DYN_ERR_ARG;
        }
        row[i] = v;
        field = comma ? comma + 1 : field + strlen(field);
    }
    return DYN_OK;
}

int dyn_table_read(FILE *in, const char *source, unsigned flags, dyn_table *table, char *err,
                   size_t errlen)
{
    const char *src = source ? source : "input";
    line_reader r = {in, NULL, 0, 0, 0, 0};
    size_t cap_rows = 0;
    int got, rc = DYN_OK;
    memset(table, 0, sizeof *table);
    if (err && errlen)
        err[0] = '\0';
    while ((got = next_line(&r)) == 1 && skip_line(r.buf)) {
    }
    if (got <= 0) {
        if (got < 0)
            rc = line_error(&r, src, err, errlen);
        else
            set_err(err, errlen, "%s: empty: no header line (expected e.g. t,Fx,Fy)", src);
        free(r.buf);
        return got < 0 ? rc : DYN_ERR_ARG;
    }
    long header_line = r.number;
    rc = read_header(table, r.buf, src, header_line, err, errlen);
    double prev_t = 0.0;
    long prev_line = 0;
    while (rc == DYN_OK && (got = next_line(&r)) == 1) {
        if (skip_line(r.buf))
            continue;
        if ((size_t)table->rows == cap_rows) {
            size_t cap = cap_rows ? 2 * cap_rows : 64;
            if ((double)cap * table->cols > (double)DYN_TABLE_MAX_CELLS)
                cap = (size_t)(DYN_TABLE_MAX_CELLS / table->cols);
            if (cap <= cap_rows) {
                set_err(err, errlen, "%s:%ld: more than %g numbers: the table is too large",
                        src, r.number, (double)DYN_TABLE_MAX_CELLS);
                rc = DYN_ERR_ARG;
                break;
            }
            double *grown = realloc(table->data, cap * (size_t)table->cols * sizeof *grown);
            if (!grown) {
                set_err(err, errlen, "%s: out of memory", src);
                rc = DYN_ERR_CAPACITY;
                break;
            }
            table->data = grown;
            cap_rows = cap;
        }
        double *row = table->data + (size_t)table->rows * (size_t)table->cols;
        rc = read_row(table, r.buf, row, src, r.number, err, errlen);
        if (rc != DYN_OK)
            break;
        if ((flags & DYN_TABLE_TIME_FIRST) && table->rows > 0 && !(row[0] > prev_t)) {
            set_err(err, errlen,
                    "%s:%ld: %s = %s does not increase (line %ld has %s = %s); the "
                    "first column must increase strictly",
                    src, r.number, table->names[0], dyn_shortest(row[0]).s, prev_line,
                    table->names[0], dyn_shortest(prev_t).s);
            rc = DYN_ERR_ARG;
            break;
        }
        prev_t = row[0];
        prev_line = r.number;
        table->rows++;
    }
    if (rc == DYN_OK && got < 0)
        rc = line_error(&r, src, err, errlen);
    if (rc == DYN_OK && table->rows == 0) {
        set_err(err, errlen, "%s:%ld: no data rows after the header", src, header_line);
        rc = DYN_ERR_ARG;
    }
    free(r.buf);
    if (rc != DYN_OK)
        dyn_table_free(table);
    return rc;
}

int dyn_table_read_file(const char *path, unsigned flags, dyn_table *table, char *err,
                        size_t errlen)
{
    memset(table, 0, sizeof *table);
    FILE *in = fopen(path, "r");
    if (!in) {
        set_err(err, errlen, "cannot open %s: %s", path, strerror(errno));
        return DYN_ERR_IO;
    }
    int rc = dyn_table_read(in, path, flags, table, err, errlen);
    fclose(in);
    return rc;
}
