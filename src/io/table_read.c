/* Reading numeric CSV tables (io.h): a header line of column names, then rows of finite
 * numbers, into a caller-freed dyn_table; errors name the source, the line and the field.
 * The format is the plain subset of RFC 4180 that dynkit writes (no quoted fields, except
 * that a header name may be enclosed in double quotes); numbers follow C's strtod.
 * Lines are read with fgetc into a growing buffer, so any line length works in plain C11.
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
} line_reader;

/* Read the next line into r->buf without its end of line (LF or CRLF). Returns 1 for a
 * line, 0 at the end of the input, -1 for a read error or no memory. */
static int next_line(line_reader *r)
{
    size_t len = 0;
    int c;
    for (;;) {
        c = fgetc(r->in);
        if (c == EOF || c == '\n')
            break;
        if (len + 2 > r->cap) {
            size_t cap = r->cap ? 2 * r->cap : 256;
            char *grown = realloc(r->buf, cap);
            if (!grown)
                return -1;
            r->buf = grown;
            r->cap = cap;
        }
        r->buf[len++] = (char)c;
    }
    if (c == EOF && (ferror(r->in) || len == 0))
        return ferror(r->in) ? -1 : 0;
    if (!r->buf) { /* an empty line before any allocation */
        r->buf = malloc(256);
        if (!r->buf)
            return -1;
        r->cap = 256;
    }
    if (len > 0 && r->buf[len - 1] == '\r')
        len--;
    r->buf[len] = '\0';
    r->number++;
    return 1;
}

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
{
    va_list ap;
    if (!err || !errlen)
        return;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
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
        return DYN_ERR_IO;
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
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = strcmp(table->names[j], name) == 0;
        if (seen) {
            set_err(err, errlen, "%s:%ld: column name '%s' appears twice in the header", src,
                    lineno, name);
            return DYN_ERR_ARG;
        }
        table->names[i] = malloc(strlen(name) + 1);
        if (!table->names[i]) {
            set_err(err, errlen, "%s: out of memory", src);
            return DYN_ERR_IO;
        }
        strcpy(table->names[i], name);
        field = comma ? comma + 1 : field + strlen(field);
    }
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
        if (end == text || *end != '\0') {
            set_err(err, errlen, "%s:%ld: field %d (%s) '%s' is not a number", src, lineno,
                    i + 1, table->names[i], text);
            return DYN_ERR_ARG;
        }
        if (!isfinite(v)) {
            set_err(err, errlen, "%s:%ld: field %d (%s) '%s' is not a finite number", src,
                    lineno, i + 1, table->names[i], text);
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
    line_reader r = {in, NULL, 0, 0};
    size_t cap_rows = 0;
    int got, rc = DYN_OK;
    memset(table, 0, sizeof *table);
    if (err && errlen)
        err[0] = '\0';
    while ((got = next_line(&r)) == 1 && skip_line(r.buf)) {
    }
    if (got <= 0) {
        if (got < 0)
            set_err(err, errlen, "%s: read error or out of memory", src);
        else
            set_err(err, errlen, "%s: empty: no header line (expected e.g. t,Fx,Fy)", src);
        free(r.buf);
        return got < 0 ? DYN_ERR_IO : DYN_ERR_ARG;
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
            double *grown = realloc(table->data, cap * (size_t)table->cols * sizeof *grown);
            if (!grown) {
                set_err(err, errlen, "%s: out of memory", src);
                rc = DYN_ERR_IO;
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
                    "%s:%ld: %s = %.17g does not increase (line %ld has %s = %.17g); the "
                    "first column must increase strictly",
                    src, r.number, table->names[0], row[0], prev_line, table->names[0], prev_t);
            rc = DYN_ERR_ARG;
            break;
        }
        prev_t = row[0];
        prev_line = r.number;
        table->rows++;
    }
    if (rc == DYN_OK && got < 0) {
        set_err(err, errlen, "%s:%ld: read error or out of memory", src, r.number + 1);
        rc = DYN_ERR_IO;
    }
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
