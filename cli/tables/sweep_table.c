/* SPDX-License-Identifier: BSD-3-Clause */
/* A sweep's table read back (sweep_table.h): the CSV that dynkit sweep writes (RFC 4180
 * without quoted fields: one header line of names, numbers, a status word) or its JSON
 * (RFC 8259; the layout of docs/data-files.md: "columns", "units" and "rows", other members
 * skipped), which carries the units of the columns. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "tables/sweep_table.h"

void sweep_table_free(sweep_table *t)
{
    for (int c = 0; c < t->cols; c++) {
        free(t->names[c]);
        free(t->units[c]);
    }
    free(t->data);
    t->cols = 0;
    t->data = NULL;
}

/* Room for one more row; 0 or -1 (out of memory). */
static int grow(sweep_table *t, long *capacity)
{
    if (t->rows < *capacity)
        return 0;
    const long cap = *capacity ? 2 * *capacity : 256;
    double *d = realloc(t->data, (size_t)cap * (size_t)t->cols * sizeof *d);
    if (!d)
        return -1;
    t->data = d;
    *capacity = cap;
    return 0;
}

static int is_sweep(sweep_table *t, const char *path, char *err, size_t errlen)
{
    if (t->cols >= 2 && strcmp(t->names[0], "run") == 0)
        return 0;
    for (int c = 1; c < t->cols && strcmp(t->names[0], "t") == 0; c++)
        if (strncmp(t->names[c], "p5_", 3) == 0) {
            t->bands = 1;
            return 0;
        }
    snprintf(err, errlen,
             "%s is not a sweep's table (its first column should be run, as dynkit sweep "
             "writes it)",
             path);
    return -1;
}

static int read_csv(FILE *f, const char *path, sweep_table *t, char *err, size_t errlen)
{
    size_t cap = 1 << 16;
    char *line = malloc(cap);
    long capacity = 0, lineno = 0;
    int rc = line ? 0 : -1;
    while (rc == 0 && fgets(line, (int)cap, f)) {
        lineno++;
        line[strcspn(line, "\r\n")] = '\0';
        if (!line[0])
            continue;
        if (t->cols == 0) {
            for (char *p = line; p && t->cols < SWEEP_TABLE_MAX_COLS;) {
                char *comma = strchr(p, ',');
                if (comma)
                    *comma = '\0';
                t->names[t->cols] = strdup(p);
                if (strcmp(p, "status") == 0)
                    t->status_col = t->cols;
                t->cols++;
                p = comma ? comma + 1 : NULL;
            }
            rc = is_sweep(t, path, err, errlen);
            continue;
        }
        if (grow(t, &capacity)) {
            rc = -1;
            break;
        }
        double *row = t->data + (size_t)t->rows * (size_t)t->cols;
        char *p = line;
        for (int c = 0; c < t->cols; c++) {
            char *end;
            row[c] = strtod(p, &end);
            if (end == p || (*end && *end != ','))
                row[c] = NAN;
            p += strcspn(p, ",");
            if (c < t->cols - 1 && *p != ',') {
                snprintf(err, errlen, "%s:%ld: %d fields, the header has %d", path, lineno, c + 1,
                         t->cols);
                rc = -1;
                break;
            }
            if (*p)
                p++;
        }
        t->rows++;
    }
    free(line);
    return rc;
}

/* ---- JSON ---- */

typedef struct json_in {
    const char *p, *end, *begin;
    const char *path;
    char *err;
    size_t errlen;
} json_in;

static void ws(json_in *in)
{
    while (in->p < in->end && strchr(" \t\r\n", *in->p) && *in->p)
        in->p++;
}

static int fail(json_in *in, const char *what)
{
    long line = 1;
    for (const char *q = in->begin; q < in->p; q++)
        line += *q == '\n';
    snprintf(in->err, in->errlen, "%s:%ld: not a sweep's JSON table: %s", in->path, line, what);
    return -1;
}

static int expect(json_in *in, char c)
{
    ws(in);
    if (in->p >= in->end || *in->p != c) {
        char what[32];
        snprintf(what, sizeof what, "'%c' expected", c);
        return fail(in, what);
    }
    in->p++;
    return 0;
}

/* A string into a new buffer (UTF-8; \uXXXX escapes of the BMP and surrogate pairs). */
static char *json_string(json_in *in)
{
    if (expect(in, '"'))
        return NULL;
    const char *start = in->p;
    size_t n = 0;
    while (in->p < in->end && *in->p != '"') /* an upper bound of the decoded length */
        in->p += *in->p == '\\' && in->p + 1 < in->end ? 2 : 1, n += 4;
    if (in->p >= in->end) {
        fail(in, "an unterminated string");
        return NULL;
    }
    char *s = malloc(n + 1), *o = s;
    if (!s)
        return NULL;
    for (const char *q = start; q < in->p; q++) {
        if (*q != '\\') {
            *o++ = *q;
            continue;
        }
        const char e = *++q;
        const char *simple = strchr("\"\\/bfnrt", e);
        if (e && simple) {
            *o++ = "\"\\/\b\f\n\r\t"[simple - "\"\\/bfnrt"];
            continue;
        }
        unsigned long u = 0;
        if (e != 'u' || in->p - q < 5) {
            free(s);
            fail(in, "a bad escape in a string");
            return NULL;
        }
        char hex[5] = {q[1], q[2], q[3], q[4], 0};
        u = strtoul(hex, NULL, 16);
        q += 4;
        if (u >= 0xD800 && u < 0xDC00 && in->p - q >= 7 && q[1] == '\\' && q[2] == 'u') {
            char lo[5] = {q[3], q[4], q[5], q[6], 0};
            u = 0x10000 + ((u - 0xD800) << 10) + (strtoul(lo, NULL, 16) - 0xDC00);
            q += 6;
        }
        if (u < 0x80) {
            *o++ = (char)u;
        } else if (u < 0x800) {
            *o++ = (char)(0xC0 | (u >> 6));
            *o++ = (char)(0x80 | (u & 0x3F));
        } else if (u < 0x10000) {
            *o++ = (char)(0xE0 | (u >> 12));
            *o++ = (char)(0x80 | ((u >> 6) & 0x3F));
            *o++ = (char)(0x80 | (u & 0x3F));
        } else {
            *o++ = (char)(0xF0 | (u >> 18));
            *o++ = (char)(0x80 | ((u >> 12) & 0x3F));
            *o++ = (char)(0x80 | ((u >> 6) & 0x3F));
            *o++ = (char)(0x80 | (u & 0x3F));
        }
    }
    *o = '\0';
    in->p++;
    return s;
}

/* A number, or null as NaN. */
static int json_number(json_in *in, double *v)
{
    ws(in);
    if (in->end - in->p >= 4 && strncmp(in->p, "null", 4) == 0) {
        in->p += 4;
        *v = NAN;
        return 0;
    }
    char *end;
    *v = strtod(in->p, &end);
    if (end == in->p || !strchr("-0123456789", *in->p))
        return fail(in, "a number expected");
    in->p = end;
    return 0;
}

/* Any value, skipped. */
static int json_skip(json_in *in, int depth)
{
    ws(in);
    if (in->p >= in->end || depth > 64)
        return fail(in, "a value expected");
    const char c = *in->p;
    if (c == '"') {
        char *s = json_string(in);
        free(s);
        return s ? 0 : -1;
    }
    if (c == '[' || c == '{') {
        const char close = c == '[' ? ']' : '}';
        in->p++;
        ws(in);
        if (in->p < in->end && *in->p == close) {
            in->p++;
            return 0;
        }
        for (;;) {
            if (c == '{') {
                char *key = json_string(in);
                free(key);
                if (!key || expect(in, ':'))
                    return -1;
            }
            if (json_skip(in, depth + 1))
                return -1;
            ws(in);
            if (in->p < in->end && *in->p == ',') {
                in->p++;
                continue;
            }
            return expect(in, close);
        }
    }
    for (const char *word = "true\0false\0null\0"; *word; word += strlen(word) + 1)
        if ((size_t)(in->end - in->p) >= strlen(word) && strncmp(in->p, word, strlen(word)) == 0) {
            in->p += strlen(word);
            return 0;
        }
    double v;
    return json_number(in, &v);
}

/* Each item of an array, read by item(in, ctx); 0, or -1 with the message in err. */
static int json_array(json_in *in, int (*item)(json_in *, void *), void *ctx)
{
    if (expect(in, '['))
        return -1;
    ws(in);
    if (in->p < in->end && *in->p == ']') {
        in->p++;
        return 0;
    }
    for (;;) {
        if (item(in, ctx))
            return -1;
        ws(in);
        if (in->p < in->end && *in->p == ',') {
            in->p++;
            continue;
        }
        return expect(in, ']');
    }
}

typedef struct strings_in {
    char **into;
    int n;
} strings_in;

static int string_item(json_in *in, void *ctx)
{
    strings_in *st = ctx;
    char *s = json_string(in);
    if (!s)
        return -1;
    if (st->n >= SWEEP_TABLE_MAX_COLS) {
        free(s);
        return fail(in, "too many columns");
    }
    st->into[st->n++] = s;
    return 0;
}

/* An array of strings into into[], at most SWEEP_TABLE_MAX_COLS; *n receives how many. */
static int json_strings(json_in *in, char **into, int *n)
{
    strings_in st = {into, 0};
    const int rc = json_array(in, string_item, &st);
    *n = st.n;
    return rc;
}

typedef struct rows_in {
    sweep_table *t;
    long capacity;
    int col; /* of the row being read */
} rows_in;

static int number_item(json_in *in, void *ctx)
{
    rows_in *r = ctx;
    if (r->col >= r->t->cols)
        return fail(in, "a row of more numbers than columns");
    double *row = r->t->data + (size_t)r->t->rows * (size_t)r->t->cols;
    return json_number(in, &row[r->col++]);
}

static int row_item(json_in *in, void *ctx)
{
    rows_in *r = ctx;
    if (grow(r->t, &r->capacity))
        return fail(in, "out of memory");
    r->col = 0;
    if (json_array(in, number_item, r))
        return -1;
    if (r->col != r->t->cols)
        return fail(in, "a row of fewer numbers than columns");
    r->t->rows++;
    return 0;
}

static int json_rows(json_in *in, sweep_table *t)
{
    if (t->cols == 0)
        return fail(in, "\"rows\" before \"columns\"");
    rows_in r = {t, 0, 0};
    return json_array(in, row_item, &r);
}

static int read_json(FILE *f, const char *path, sweep_table *t, char *err, size_t errlen)
{
    size_t cap = 1 << 16, len = 0, got;
    char *text = malloc(cap);
    while (text && (got = fread(text + len, 1, cap - len - 1, f)) > 0) {
        len += got;
        if (cap - len < 2) {
            char *more = realloc(text, cap *= 2);
            if (!more)
                free(text);
            text = more;
        }
    }
    if (!text) {
        snprintf(err, errlen, "out of memory reading %s", path);
        return -1;
    }
    text[len] = '\0';
    json_in in = {text, text + len, text, path, err, errlen};
    int rc = expect(&in, '{'), n_units = 0;
    while (rc == 0) {
        char *key = json_string(&in);
        rc = key && expect(&in, ':') == 0 ? 0 : -1;
        if (rc == 0 && strcmp(key, "columns") == 0) {
            rc = json_strings(&in, t->names, &t->cols);
        } else if (rc == 0 && strcmp(key, "units") == 0) {
            rc = json_strings(&in, t->units, &n_units);
        } else if (rc == 0 && strcmp(key, "rows") == 0) {
            rc = is_sweep(t, path, err, errlen) || json_rows(&in, t);
        } else if (rc == 0) {
            rc = json_skip(&in, 0);
        }
        free(key);
        ws(&in);
        if (rc == 0 && in.p < in.end && *in.p == ',') {
            in.p++;
            continue;
        }
        if (rc == 0)
            rc = expect(&in, '}');
        break;
    }
    if (rc == 0 && n_units != t->cols && n_units != 0) {
        snprintf(err, errlen, "%s: %d units for %d columns", path, n_units, t->cols);
        rc = -1;
    }
    for (int c = 0; c < t->cols; c++)
        if (strcmp(t->names[c], "status") == 0)
            t->status_col = c;
    free(text);
    return rc;
}

int sweep_table_read(const char *path, sweep_table *t, char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    t->status_col = -1;
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "cannot open %s: %s", path, strerror(errno));
        return -1;
    }
    const char *dot = strrchr(path, '.');
    int rc = dot && strcasecmp(dot, ".json") == 0 ? read_json(f, path, t, err, errlen)
                                                  : read_csv(f, path, t, err, errlen);
    fclose(f);
    if (rc == 0 && t->cols == 0)
        rc = is_sweep(t, path, err, errlen);
    if (rc == 0 && t->rows == 0) {
        snprintf(err, errlen, "%s has no rows", path);
        rc = -1;
    }
    return rc;
}
