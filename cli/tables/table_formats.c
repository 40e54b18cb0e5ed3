/* SPDX-License-Identifier: BSD-3-Clause */
/* Data files of a run's table: the format chosen by the output's extension, and the streamed
 * writers: CSV (RFC 4180) and JSON (RFC 8259; the settings, names and units, then one array
 * per row), their numbers the shortest decimal that reads back to the same double
 * (dyn_format_double), their rows gathered in a dyn_text_writer (one fwrite per 64 KiB). NPY streams too when the
 * stream can seek (NPY format 1.0: the header, which holds the row count, is written first
 * with room for any count and rewritten at the end); the other formats keep the rows and are
 * written at the end by table_numpy.c and table_mat.c. See docs/data-files.md. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "dynkit/io.h"
#include "util/escape.h"
#include "tables/table_formats.h"

#ifndef DYNKIT_VERSION
#define DYNKIT_VERSION "0.1.0"
#endif

struct cli_table {
    FILE *out;
    cli_format format;
    cli_table_info info;
    long rows;
    int failed;      /* a write failed */
    int no_memory;   /* keeping the rows failed */
    int full;        /* a row would have passed limit_rows: not kept */
    long limit_rows; /* rows a buffered format may keep (cli_table_limit) */
    const char *limit_why; /* and why */
    /* kept rows (buffered formats), row-major */
    double *data;
    long capacity;
    /* NPY streamed: where the header starts and its size */
    int npy_stream;
    long npy_start, npy_header;
    const char **owned; /* freed with the table (cli_table_keep) */
    /* CSV and JSON rows: gathered here, one fwrite per 64 KiB */
    dyn_text_writer *text;
};

static const struct {
    const char *ext;
    cli_format format;
} extensions[] = {{".csv", CLI_FORMAT_CSV},
                  {".json", CLI_FORMAT_JSON},
                  {".mat", CLI_FORMAT_MAT},
                  {".npy", CLI_FORMAT_NPY},
                  {".npz", CLI_FORMAT_NPZ}};

int cli_format_have_mat(void)
{
#ifdef DYNKIT_HAVE_MATIO
    return 1;
#else
    return 0;
#endif
}

const char *cli_format_name(cli_format format)
{
    for (size_t i = 0; i < sizeof extensions / sizeof extensions[0]; i++)
        if (extensions[i].format == format)
            return extensions[i].ext + 1;
    return "?";
}

/* 1 if path is a device or a pipe (/dev/stdout, /dev/null, a FIFO): no file whose name could
 * say the wrong format. */
static int is_stream(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

int cli_format_of_path(const char *path, cli_format *format, char *err, size_t errlen)
{
    *format = CLI_FORMAT_CSV;
    if (strcmp(path, "-") == 0 || (cli_is_stdout_name(path) && !cli_is_stdout_format(path)))
        return 0; /* "-.json" is standard output as JSON: its extension read below */
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    int known = 0;
    for (size_t i = 0; dot && i < sizeof extensions / sizeof extensions[0]; i++)
        known |= strcasecmp(dot, extensions[i].ext) == 0;
    if (!known && is_stream(path))
        return 0; /* a device or pipe without a format's extension: CSV, as standard output */
    if (!dot || dot == base) {
        snprintf(err, errlen,
                 "'%s' has no file extension to choose the format by (accepted: %s; '-' is "
                 "standard output as CSV, '-.json' as JSON, ...)",
                 path, CLI_FORMAT_EXTENSIONS);
        return -1;
    }
    for (size_t i = 0; i < sizeof extensions / sizeof extensions[0]; i++)
        if (strcasecmp(dot, extensions[i].ext) == 0) {
            *format = extensions[i].format;
            if (*format == CLI_FORMAT_MAT && !cli_format_have_mat()) {
                snprintf(err, errlen,
                         "'%s': dynkit was built without matio, so it cannot write MATLAB "
                         ".mat files (install libmatio-dev and rebuild; or write .csv or .json, "
                         "which MATLAB reads with readmatrix and jsondecode)",
                         path);
                return -1;
            }
            return 0;
        }
    snprintf(err, errlen, "'%s': unknown file extension '%s' (accepted: %s; '-' is standard "
                          "output as CSV, '-.json' as JSON, ...)",
             path, dot, CLI_FORMAT_EXTENSIONS);
    return -1;
}

int cli_table_name_taken(const char *name)
{
    static const char *const taken[] = {"run",  "status", "names", "units", "model", "method",
                                        "step", "rtol",   "atol",  "tspan", "dynkit"};
    for (size_t i = 0; i < sizeof taken / sizeof taken[0]; i++)
        if (strcmp(name, taken[i]) == 0)
            return 1;
    return 0;
}

/* ---- CSV ---- */

/* One header field, quoted (RFC 4180) when it holds a comma, a quote or a line break. */
static int csv_field(FILE *out, const char *name, const char *unit)
{
    char text[256];
    if (unit && *unit)
        snprintf(text, sizeof text, "%s [%s]", name, unit);
    else
        snprintf(text, sizeof text, "%s", name);
    if (!strpbrk(text, ",\"\r\n"))
        return fputs(text, out) < 0;
    int bad = fputc('"', out) == EOF;
    for (const char *p = text; *p; p++) {
        if (*p == '"')
            bad |= fputc('"', out) == EOF;
        bad |= fputc(*p, out) == EOF;
    }
    return bad | (fputc('"', out) == EOF);
}

static int csv_header(cli_table *tab)
{
    const cli_table_info *in = &tab->info;
    if (in->header == CLI_HEADER_NONE)
        return 0;
    int bad = 0;
    for (int j = 0; j < in->cols; j++) {
        if (j)
            bad |= fputc(',', tab->out) == EOF;
        bad |= csv_field(tab->out, in->names[j],
                         in->header == CLI_HEADER_UNITS ? in->units[j] : NULL);
    }
    return bad | (fputc('\n', tab->out) == EOF);
}

/* ---- JSON ---- */

/* A number as the shortest string that reads back to it, or null when not finite (JSON has
 * no NaN or Inf); negative zero as -0.0, since JSON readers (Python's json, JavaScript)
 * read "-0" as the integer 0. */
static int json_number(FILE *out, double v)
{
    char num[DYN_DOUBLE_CHARS];
    if (!isfinite(v))
        return fputs("null", out) < 0;
    if (v == 0.0 && signbit(v))
        return fputs("-0.0", out) < 0;
    dyn_format_double(v, num);
    return fputs(num, out) < 0;
}

/* The same into a row's writer. */
static int json_number_to(dyn_text_writer *w, double v)
{
    if (!isfinite(v))
        return dyn_text_write(w, "null", 4) != DYN_OK;
    if (v == 0.0 && signbit(v))
        return dyn_text_write(w, "-0.0", 4) != DYN_OK;
    return dyn_text_write_double(w, v) != DYN_OK;
}

static int json_strings(FILE *out, const char *key, const char *const *s, int n)
{
    int bad = fprintf(out, "  \"%s\": [", key) < 0;
    for (int i = 0; i < n; i++) {
        if (i)
            bad |= fputs(", ", out) < 0;
        bad |= cli_json_escaped(out, s[i]);
    }
    return bad | (fputs("],\n", out) < 0);
}

static int json_header(cli_table *tab)
{
    const cli_table_info *in = &tab->info;
    FILE *out = tab->out;
    int bad = fputs("{\n  \"dynkit\": ", out) < 0;
    bad |= cli_json_escaped(out, DYNKIT_VERSION);
    bad |= fputs(",\n  \"model\": ", out) < 0;
    bad |= cli_json_escaped(out, in->model);
    bad |= fputs(",\n  \"method\": ", out) < 0;
    bad |= in->method ? cli_json_escaped(out, in->method) : fputs("null", out) < 0;
    bad |= fputs(",\n  \"step\": ", out) < 0;
    bad |= json_number(out, in->step);
    bad |= fputs(",\n  \"rtol\": ", out) < 0;
    bad |= json_number(out, in->rtol);
    bad |= fputs(",\n  \"atol\": ", out) < 0;
    bad |= json_number(out, in->atol);
    bad |= fputs(",\n  \"tspan\": [", out) < 0;
    bad |= json_number(out, in->t0);
    bad |= fputs(", ", out) < 0;
    bad |= json_number(out, in->t1);
    bad |= fprintf(out, "],\n  \"states\": %d,\n", in->n_y) < 0;
    if (in->sweep)
        bad |= fprintf(out, "  \"varied\": %d,\n  \"reduced\": %d,\n", in->n_varied,
                       in->n_reduced) < 0;
    bad |= json_strings(out, "columns", in->names, in->cols);
    bad |= json_strings(out, "units", in->units, in->cols);
    bad |= fputs("  \"rows\": [", out) < 0;
    return bad;
}

static int json_row(cli_table *tab, double t, const double *y, int n, const double *extra, int m)
{
    dyn_text_writer *w = tab->text;
    int bad = tab->rows ? dyn_text_write(w, ",\n    [", 7) : dyn_text_write(w, "\n    [", 6);
    bad |= json_number_to(w, t);
    for (int i = 0; i < n + m; i++) {
        bad |= dyn_text_write(w, ",", 1);
        bad |= json_number_to(w, i < n ? y[i] : extra[i - n]);
    }
    return bad | dyn_text_write(w, "]", 1);
}

static int json_end(cli_table *tab)
{
    return fputs(tab->rows ? "\n  ]\n}\n" : "]\n}\n", tab->out) < 0;
}

/* ---- NPY streamed ---- */

static long npy_max_header(int cols)
{
    char buf[256];
    return cli_npy_header(buf, sizeof buf, LONG_MAX, cols, 0);
}

static int npy_row(cli_table *tab, double t, const double *y, int n, const double *extra, int m)
{
    unsigned char bytes[8];
    int bad = 0;
    for (int j = 0; j < 1 + n + m; j++) {
        double v = j == 0 ? t : j <= n ? y[j - 1] : extra[j - 1 - n];
        uint64_t u;
        memcpy(&u, &v, sizeof u);
        for (int b = 0; b < 8; b++)
            bytes[b] = (unsigned char)(u >> (8 * b)); /* little-endian '<f8' */
        bad |= fwrite(bytes, 1, 8, tab->out) != 8;
    }
    return bad;
}

static int npy_stream_end(cli_table *tab)
{
    char buf[256];
    if (cli_npy_header(buf, sizeof buf, tab->rows, tab->info.cols, tab->npy_header) !=
        tab->npy_header)
        return 1;
    if (fflush(tab->out) != 0 || fseek(tab->out, tab->npy_start, SEEK_SET) != 0)
        return 1;
    int bad = fwrite(buf, 1, (size_t)tab->npy_header, tab->out) != (size_t)tab->npy_header;
    return bad | (fseek(tab->out, 0, SEEK_END) != 0);
}

/* ---- kept rows ---- */

/* The memory a process may use: the machine's, or less under a limit on the address space
 * or the data segment (ulimit -v, -d); +inf when unknown. */
static double memory_bytes(void)
{
    double bytes = HUGE_VAL;
#ifdef _SC_PHYS_PAGES
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0)
        bytes = (double)pages * (double)page;
#endif
    const int kinds[] = {RLIMIT_AS, RLIMIT_DATA};
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        struct rlimit rl;
        if (getrlimit(kinds[i], &rl) == 0 && rl.rlim_cur != RLIM_INFINITY &&
            (double)rl.rlim_cur < bytes)
            bytes = (double)rl.rlim_cur;
    }
    return bytes;
}

/* The rows of cols columns (n_y of them the states) that a table of this format may keep in
 * memory, and why: what the file can hold (an .npz archive without ZIP64 and each variable
 * of a level 5 MAT-file: 4 GiB, less 1 MiB for the names and headers) and a quarter of the
 * memory the process may use (the writers copy the columns once more). A run that reaches
 * it stops with its rows written, instead of failing or being killed for memory at the
 * end. LONG_MAX for the streamed formats. */
long cli_table_limit(cli_format format, int cols, int n_y, const char **why)
{
    const double row_bytes = 8.0 * (cols > 0 ? cols : 1);
    double rows = (double)LONG_MAX;
    *why = NULL;
    if (format == CLI_FORMAT_NPZ || format == CLI_FORMAT_MAT) {
        const int widest = format == CLI_FORMAT_NPZ
                               ? cols
                               : (n_y > cols - 1 - n_y ? n_y : cols - 1 - n_y);
        rows = (4294967295.0 - 1048576.0) / (8.0 * (widest > 0 ? widest : 1));
        *why = format == CLI_FORMAT_NPZ ? "an .npz file without ZIP64 (4 GiB)"
                                        : "a variable of a level 5 MAT-file (4 GiB)";
    }
    if (format == CLI_FORMAT_NPZ || format == CLI_FORMAT_MAT || format == CLI_FORMAT_NPY) {
        const double budget = memory_bytes() / 4.0 / row_bytes;
        if (budget < rows) {
            rows = budget;
            *why = "a quarter of the memory this process may use";
        }
    }
    return rows >= (double)LONG_MAX ? LONG_MAX : (long)rows;
}

static int keep_row(cli_table *tab, double t, const double *y, int n, const double *extra, int m)
{
    const int cols = tab->info.cols;
    if (tab->rows >= tab->limit_rows) {
        tab->full = 1;
        return -1;
    }
    if (tab->rows == tab->capacity) {
        long cap = tab->capacity ? 2 * tab->capacity : 1024;
        if (cap > tab->limit_rows)
            cap = tab->limit_rows;
        if ((double)cap * cols * sizeof(double) > (double)SIZE_MAX / 2)
            return -1;
        double *d = realloc(tab->data, (size_t)cap * (size_t)cols * sizeof *d);
        if (!d)
            return -1;
        tab->data = d;
        tab->capacity = cap;
    }
    double *row = tab->data + tab->rows * cols;
    row[0] = t;
    memcpy(row + 1, y, (size_t)n * sizeof *y);
    if (m > 0)
        memcpy(row + 1 + n, extra, (size_t)m * sizeof *extra);
    return 0;
}

/* ---- the table ---- */

cli_table *cli_table_open(FILE *out, cli_format format, const cli_table_info *info, char *err,
                          size_t errlen)
{
    cli_table *tab = calloc(1, sizeof *tab);
    if (!tab) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    tab->out = out;
    tab->format = format;
    tab->info = *info;
    /* a sweep's .mat file has a variable per column: no wider than the split of a run's */
    tab->limit_rows = cli_table_limit(format, info->cols, info->sweep ? 0 : info->n_y,
                                      &tab->limit_why);
    if (!tab->info.y_name)
        tab->info.y_name = "y";
    if (format == CLI_FORMAT_CSV || format == CLI_FORMAT_JSON) {
        if (!(tab->text = malloc(sizeof *tab->text))) {
            snprintf(err, errlen, "out of memory");
            free(tab);
            return NULL;
        }
        dyn_text_writer_init(tab->text, out);
    }
    int bad = 0;
    switch (format) {
    case CLI_FORMAT_CSV:
        bad = csv_header(tab);
        break;
    case CLI_FORMAT_JSON:
        bad = json_header(tab);
        break;
    case CLI_FORMAT_NPY: {
        /* stream when the stream can go back to the header */
        long start = ftell(out);
        if (start >= 0 && fseek(out, start, SEEK_SET) == 0) {
            char buf[256];
            tab->npy_stream = 1;
            tab->npy_start = start;
            tab->npy_header = npy_max_header(info->cols);
            bad = tab->npy_header < 0 ||
                  cli_npy_header(buf, sizeof buf, 0, info->cols, tab->npy_header) !=
                      tab->npy_header ||
                  fwrite(buf, 1, (size_t)tab->npy_header, out) != (size_t)tab->npy_header;
        }
        break;
    }
    case CLI_FORMAT_MAT:
    case CLI_FORMAT_NPZ:
        break;
    }
    if (bad) {
        snprintf(err, errlen, "writing the %s header failed: %s", cli_format_name(format),
                 strerror(errno));
        free(tab->text);
        free(tab);
        return NULL;
    }
    return tab;
}

int cli_table_row(cli_table *tab, double t, const double *y, int n, const double *extra, int m)
{
    int bad = 0;
    if (tab->failed || tab->no_memory || tab->full)
        return -1;
    switch (tab->format) {
    case CLI_FORMAT_CSV:
        bad = dyn_csv_write_row_to(tab->text, t, y, n, extra, m) != DYN_OK;
        break;
    case CLI_FORMAT_JSON:
        bad = json_row(tab, t, y, n, extra, m);
        break;
    case CLI_FORMAT_NPY:
        if (tab->npy_stream)
            bad = npy_row(tab, t, y, n, extra, m);
        else if (keep_row(tab, t, y, n, extra, m) && !tab->full)
            tab->no_memory = 1;
        break;
    case CLI_FORMAT_MAT:
    case CLI_FORMAT_NPZ:
        if (keep_row(tab, t, y, n, extra, m) && !tab->full)
            tab->no_memory = 1;
        break;
    }
    if (tab->no_memory || tab->full)
        return -1;
    if (bad) {
        tab->failed = 1;
        return -1;
    }
    tab->rows++;
    return 0;
}

long cli_table_rows(const cli_table *tab) { return tab->rows; }

int cli_table_full(const cli_table *tab, char *why, size_t len)
{
    if (!tab->full)
        return 0;
    snprintf(why, len, "%ld rows of %d columns fill %s", tab->rows, tab->info.cols,
             tab->limit_why ? tab->limit_why : "the table");
    return 1;
}

int cli_table_finish(cli_table *tab, char *err, size_t errlen)
{
    if (tab->no_memory) {
        snprintf(err, errlen,
                 "out of memory keeping %ld rows of %d columns for the %s file (CSV and NPY "
                 "files are streamed; --every K keeps fewer rows)",
                 tab->rows, tab->info.cols, cli_format_name(tab->format));
        return -1;
    }
    int bad = tab->failed;
    if (tab->text)
        bad |= dyn_text_writer_flush(tab->text) != DYN_OK;
    if (!bad) {
        switch (tab->format) {
        case CLI_FORMAT_CSV:
            break;
        case CLI_FORMAT_JSON:
            bad = json_end(tab);
            break;
        case CLI_FORMAT_NPY:
            if (tab->npy_stream)
                bad = npy_stream_end(tab);
            else
                return cli_npy_write(tab->out, tab->data, tab->rows, tab->info.cols, err,
                                     errlen);
            break;
        case CLI_FORMAT_NPZ:
            return cli_npz_write(tab->out, &tab->info, tab->data, tab->rows, err, errlen);
        case CLI_FORMAT_MAT:
            return cli_mat_write(tab->out, &tab->info, tab->data, tab->rows, err, errlen);
        }
    }
    bad |= fflush(tab->out) != 0;
    if (bad) {
        snprintf(err, errlen, "writing the %s file failed: %s", cli_format_name(tab->format),
                 errno ? strerror(errno) : "write error");
        return -1;
    }
    return 0;
}

void cli_table_free(cli_table *tab)
{
    if (!tab)
        return;
    free(tab->owned);
    free(tab->data);
    free(tab->text);
    free(tab);
}

void cli_table_keep(cli_table *tab, const char **block) { tab->owned = block; }
