/* SPDX-License-Identifier: BSD-3-Clause */
/* CSV output: header "t,<names>" and rows printed with %.17g, enough digits for every
 * double to round-trip through text (IEEE 754-2008, sec. 5.12.2). */
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

int dyn_csv_write_row(FILE *out, double t, const double *y, int n, const double *extra, int m)
{
    int bad = fprintf(out, "%.17g", t) < 0;
    for (int i = 0; i < n; i++)
        bad |= fprintf(out, ",%.17g", y[i]) < 0;
    for (int i = 0; i < m; i++)
        bad |= fprintf(out, ",%.17g", extra[i]) < 0;
    bad |= fputc('\n', out) == EOF;
    return bad ? DYN_ERR_IO : DYN_OK;
}
