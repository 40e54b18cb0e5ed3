/* SPDX-License-Identifier: BSD-3-Clause */
/* CSV output: header "t,<names>" and rows of numbers written as the shortest decimal that
 * reads back to the same double (dyn_format_double; round-trip as IEEE 754-2008 sec. 5.12.2
 * asks, in the fewest digits). */
#include <string.h>

#include "dynkit/io.h"
#include "dynkit/ode.h"

int dyn_csv_write_header(FILE *out, const dyn_var *vars, int n, const dyn_var *extra, int m)
{
    int bad = fputs("t", out) < 0;
    for (int i = 0; i < n; i++)
        bad |= fprintf(out, ",%s", vars[i].name) < 0;
    for (int i = 0; i < m; i++)
        bad |= fprintf(out, ",%s", extra[i].name) < 0;
    bad |= fputc('\n', out) == EOF;
    return bad ? DYN_ERR_IO : DYN_OK;
}

int dyn_csv_write_row_to(dyn_text_writer *w, double t, const double *y, int n,
                         const double *extra, int m)
{
    /* room for a number and its comma is checked here once, so each is written in place */
    for (int j = 0; j < 1 + n + m; j++) {
        if (sizeof w->buf - w->len < DYN_DOUBLE_CHARS + 1 && dyn_text_writer_flush(w) != DYN_OK)
            return DYN_ERR_IO;
        const double v = j == 0 ? t : j <= n ? y[j - 1] : extra[j - 1 - n];
        if (j)
            w->buf[w->len++] = ',';
        w->len += (size_t)dyn_format_double(v, w->buf + w->len);
    }
    if (w->len == sizeof w->buf && dyn_text_writer_flush(w) != DYN_OK)
        return DYN_ERR_IO;
    w->buf[w->len++] = '\n';
    return w->failed ? DYN_ERR_IO : DYN_OK;
}

int dyn_csv_write_row(FILE *out, double t, const double *y, int n, const double *extra, int m)
{
    /* a row of any width through a small writer on the stack: one fwrite per 4 KiB */
    char buf[4096];
    size_t len = 0;
    int bad = 0;
    for (int j = 0; j < 1 + n + m; j++) {
        if (sizeof buf - len < DYN_DOUBLE_CHARS + 2) {
            bad |= fwrite(buf, 1, len, out) != len;
            len = 0;
        }
        const double v = j == 0 ? t : j <= n ? y[j - 1] : extra[j - 1 - n];
        if (j)
            buf[len++] = ',';
        len += (size_t)dyn_format_double(v, buf + len);
    }
    buf[len++] = '\n';
    bad |= fwrite(buf, 1, len, out) != len;
    return bad ? DYN_ERR_IO : DYN_OK;
}
