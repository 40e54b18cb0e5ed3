/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit plot TABLE.csv|TABLE.json: a picture of a sweep's table (dynkit sweep,
 * docs/sweeps.md; read by sweep_table.c, the axes labelled with the units a JSON table
 * carries) as a standalone SVG 1.1 file, or (--html FILE, --output FILE.html) as a self-contained page
 * drawn by web/js/sweep.js with the same choice of picture. One varied name: a line of each
 * reduced column against it (svg_plot.c), through the runs in the order of the varied value
 * (not the run order). Two varied names: a heat map of one reduced column over their grid,
 * a cell per run (edges halfway between neighbouring values, so uneven grids are drawn
 * true), the colours of matplotlib's viridis map (van der Walt and Smith, 2015: even in
 * lightness, read in grey and by colour-blind readers) with a colour bar, failed runs and
 * nan in grey; when the values were sampled at random (--sample) rather than on a grid, a
 * point per run in the same colours. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/out_file.h"
#include "pages/pages.h"
#include "util/escape.h"
#include "pages/svg_axes.h"
#include "tables/sweep_table.h"

/* An axis label: the column's name, and its unit in brackets when the table has one (its
 * JSON does, its CSV does not). */
static const char *col_label(const sweep_table *t, int c, char *buf, size_t size)
{
    if (t->units[c] && t->units[c][0])
        snprintf(buf, size, "%s [%s]", t->names[c], t->units[c]);
    else
        snprintf(buf, size, "%s", t->names[c]);
    return buf;
}

/* 1 when name is a reduction's column: OP_NAME, or OP:NAME as in tables of earlier versions
 * of dynkit, OP one of the reductions of dynkit/sweep.h. */
static int is_reduction(const char *name)
{
    static const char *const ops[] = {"final",  "max",    "min",   "mean",
                                      "argmax", "argmin", "event", "count"};
    const size_t len = strcspn(name, "_:");
    for (size_t k = 0; name[len] && name[len + 1] && k < sizeof ops / sizeof ops[0]; k++)
        if (strlen(ops[k]) == len && strncmp(name, ops[k], len) == 0)
            return 1;
    return 0;
}

/* Varied columns: those before the reductions, which end the table (run, the varied names,
 * the reductions, status): a column is reduced when it and every column after it are named
 * like reductions, so that a varied parameter named like one (max_rate) before another
 * varied name is still told apart. */
static int is_varied(const sweep_table *t, int c)
{
    if (c <= 0 || c == t->status_col)
        return 0;
    for (int k = c; k < t->cols; k++)
        if (k != t->status_col && !is_reduction(t->names[k]))
            return 1;
    return 0;
}

/* The column named name; a reduction may be given as on the command line (max:height for
 * the column max_height). */
static int find_col(const sweep_table *t, const char *name)
{
    char alt[256];
    const size_t len = strlen(name);
    if (len >= sizeof alt)
        return -1;
    memcpy(alt, name, len + 1);
    const size_t colon = strcspn(alt, ":");
    if (alt[colon])
        alt[colon] = '_';
    for (int c = 0; c < t->cols; c++)
        if (strcmp(t->names[c], name) == 0 || strcmp(t->names[c], alt) == 0)
            return c;
    return -1;
}

static void col_names(const sweep_table *t, int varied, char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int c = 1; c < t->cols && used < size; c++)
        if (c != t->status_col && is_varied(t, c) == varied)
            used += (size_t)snprintf(buf + used, size - used, "%s%s", used ? ", " : "",
                                     t->names[c]);
}

/* ---- the heat map ---- */

#define HW 800.0
#define HH 520.0
#define HLEFT 84.0
#define HRIGHT 130.0
#define HTOP 44.0
#define HBOTTOM 62.0

/* viridis at 0, 1/8, ..., 1 (matplotlib's _cm_listed.py, every 32nd entry and the last) */
static const unsigned char viridis[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                            {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                            {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};

static void colour(double f, char *buf, size_t size)
{
    if (!isfinite(f)) {
        snprintf(buf, size, "#bbbbbb");
        return;
    }
    f = fmin(fmax(f, 0.0), 1.0) * 8.0;
    int k = (int)f;
    if (k > 7)
        k = 7;
    const double u = f - k;
    int rgb[3];
    for (int i = 0; i < 3; i++)
        rgb[i] = (int)lround((1.0 - u) * viridis[k][i] + u * viridis[k + 1][i]);
    snprintf(buf, size, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The distinct finite values of column c, sorted, into v (rows entries); returns how many. */
static long distinct(const sweep_table *t, int c, double *v)
{
    long n = 0;
    for (long r = 0; r < t->rows; r++)
        if (isfinite(t->data[r * t->cols + c]))
            v[n++] = t->data[r * t->cols + c];
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    long m = 0;
    for (long k = 0; k < n; k++)
        if (m == 0 || v[k] != v[m - 1])
            v[m++] = v[k];
    return m;
}

/* Edges of the cells around the sorted values: halfway between neighbours, the ends half a
 * spacing out (one value: +-1/2, or +-5% of it). */
static void edges(const double *v, long n, double *e)
{
    for (long k = 1; k < n; k++)
        e[k] = 0.5 * (v[k - 1] + v[k]);
    const double d0 = n > 1 ? v[1] - v[0] : (v[0] != 0 ? 0.1 * fabs(v[0]) : 1.0);
    const double d1 = n > 1 ? v[n - 1] - v[n - 2] : d0;
    e[0] = v[0] - 0.5 * d0;
    e[n] = v[n - 1] + 0.5 * d1;
}

static long index_of(const double *v, long n, double x)
{
    long lo = 0, hi = n - 1;
    while (lo <= hi) {
        long mid = (lo + hi) / 2;
        if (v[mid] == x)
            return mid;
        if (v[mid] < x)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

/* The tooltip of a cell or point: "x=1 y=2: z=3" with the column names escaped. */
static int cell_title(FILE *out, const sweep_table *t, const double *row, int xc, int yc, int zc)
{
    const int cols[3] = {xc, yc, zc};
    int bad = fputs("<title>", out) < 0;
    for (int k = 0; k < 3; k++) {
        bad |= fputs(k == 0 ? "" : k == 1 ? " " : ": ", out) < 0;
        bad |= cli_xml_escaped(out, t->names[cols[k]]);
        bad |= fprintf(out, "=%s", CLI_NUM(row[cols[k]])) < 0;
    }
    return bad | (fputs("</title>", out) < 0);
}

static int heat_map(FILE *out, const sweep_table *t, int xc, int yc, int zc, const char *title)
{
    double *xv = malloc((size_t)t->rows * sizeof *xv), *yv = malloc((size_t)t->rows * sizeof *yv);
    double *xe = malloc(((size_t)t->rows + 1) * sizeof *xe);
    double *ye = malloc(((size_t)t->rows + 1) * sizeof *ye);
    if (!xv || !yv || !xe || !ye) {
        free(xv);
        free(yv);
        free(xe);
        free(ye);
        return CLI_FAILED;
    }
    const long nx = distinct(t, xc, xv), ny = distinct(t, yc, yv);
    int bad = nx == 0 || ny == 0;
    /* values sampled at random (--sample) rather than on a grid: most cells of the grid of
     * their distinct values would be empty; a point per run instead */
    const int scatter = !bad && (double)nx * (double)ny > 2.0 * (double)t->rows;
    if (!bad && !scatter) {
        edges(xv, nx, xe);
        edges(yv, ny, ye);
    } else if (!bad) {
        const double px = 0.03 * (xv[nx - 1] - xv[0]) + (nx == 1);
        const double py = 0.03 * (yv[ny - 1] - yv[0]) + (ny == 1);
        xe[0] = xv[0] - px;
        xe[nx] = xv[nx - 1] + px;
        ye[0] = yv[0] - py;
        ye[ny] = yv[ny - 1] + py;
    }
    double zlo = INFINITY, zhi = -INFINITY;
    for (long r = 0; r < t->rows; r++) {
        const double z = t->data[r * t->cols + zc];
        if (isfinite(z)) {
            zlo = fmin(zlo, z);
            zhi = fmax(zhi, z);
        }
    }
    if (!(zlo <= zhi))
        zlo = 0, zhi = 1;
    if (zhi == zlo)
        zhi = zlo + (zlo != 0 ? fabs(zlo) * 1e-3 : 1.0);
    const double x0 = HLEFT, x1 = HW - HRIGHT, y0 = HH - HBOTTOM, y1 = HTOP;
    const double xlo = bad ? 0 : xe[0], xhi = bad ? 1 : xe[nx], ylo = bad ? 0 : ye[0],
                 yhi = bad ? 1 : ye[ny];
#define PX(v) (x0 + ((v) - xlo) / (xhi - xlo) * (x1 - x0))
#define PY(v) (y0 - ((v) - ylo) / (yhi - ylo) * (y0 - y1))
    bad |= fprintf(out,
                   "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/"
                   "2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
                   "font-family=\"sans-serif\">\n<rect width=\"100%%\" height=\"100%%\" "
                   "fill=\"white\"/>\n<g class=\"%s\"%s>\n",
                   HW, HH, HW, HH, scatter ? "points" : "cells",
                   scatter ? "" : " shape-rendering=\"crispEdges\"") < 0;
    char col[16];
    for (long r = 0; r < t->rows && !bad; r++) {
        const double *row = t->data + r * t->cols;
        const long ix = index_of(xv, nx, row[xc]), iy = index_of(yv, ny, row[yc]);
        if (ix < 0 || iy < 0)
            continue;
        colour((row[zc] - zlo) / (zhi - zlo), col, sizeof col);
        if (scatter) {
            bad |= fprintf(out, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"%s\">",
                           PX(row[xc]), PY(row[yc]), col) < 0;
            bad |= cell_title(out, t, row, xc, yc, zc);
            bad |= fputs("</circle>\n", out) < 0;
            continue;
        }
        const double a = PX(xe[ix]), b = PX(xe[ix + 1]), c = PY(ye[iy + 1]), d = PY(ye[iy]);
        bad |= fprintf(out,
                       "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" "
                       "fill=\"%s\">",
                       a, c, b - a, d - c, col) < 0;
        bad |= cell_title(out, t, row, xc, yc, zc);
        bad |= fputs("</rect>\n", out) < 0;
    }
    bad |= fputs("</g>\n", out) < 0;
    /* axes: ticks at nice values inside the edges */
    char label[64];
    bad |= svg_grid_begin(out);
    bad |= svg_frame_and_ticks_begin(out, x0, x1, y0, y1);
    const double sx = svg_nice_step(xhi - xlo, 8), sy = svg_nice_step(yhi - ylo, 6);
    for (long k = (long)ceil(xlo / sx - 1e-9); k <= (long)floor(xhi / sx + 1e-9); k++) {
        svg_tick_label(k * sx, sx, label, sizeof label);
        bad |= svg_xtick(out, PX(k * sx), y0, label);
    }
    for (long k = (long)ceil(ylo / sy - 1e-9); k <= (long)floor(yhi / sy + 1e-9); k++) {
        svg_tick_label(k * sy, sy, label, sizeof label);
        bad |= svg_ytick(out, x0, PY(k * sy), label);
    }
    char xl[320], yl[320], zl[320];
    bad |= svg_titles(out, x0, x1, y0, y1, HW, HH, col_label(t, xc, xl, sizeof xl),
                      col_label(t, yc, yl, sizeof yl), title);
    /* the colour bar: 64 bands from zlo (bottom) to zhi (top), ticks on its right */
    const double bx0 = x1 + 24, bx1 = x1 + 44;
    bad |= fputs("<g class=\"colorbar\" shape-rendering=\"crispEdges\">\n", out) < 0;
    for (int k = 0; k < 64; k++) {
        colour((k + 0.5) / 64.0, col, sizeof col);
        const double top = y0 - (k + 1) * (y0 - y1) / 64.0;
        bad |= fprintf(out,
                       "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" "
                       "fill=\"%s\"/>\n",
                       bx0, top, bx1 - bx0, (y0 - y1) / 64.0 + 0.5, col) < 0;
    }
    bad |= fprintf(out,
                   "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"none\" "
                   "stroke=\"#333\"/>\n</g>\n<g class=\"colorbar-ticks\" font-size=\"12\" "
                   "fill=\"#333\" stroke=\"#333\">\n",
                   bx0, y1, bx1 - bx0, y0 - y1) < 0;
    const double sz = svg_nice_step(zhi - zlo, 6);
    for (long k = (long)ceil(zlo / sz - 1e-9); k <= (long)floor(zhi / sz + 1e-9); k++) {
        const double y = y0 - (k * sz - zlo) / (zhi - zlo) * (y0 - y1);
        svg_tick_label(k * sz, sz, label, sizeof label);
        bad |= fprintf(out,
                       "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/><text x=\"%.2f\" "
                       "y=\"%.2f\" stroke=\"none\">%s</text>\n",
                       bx1, y, bx1 + 5, y, bx1 + 8, y + 4, label) < 0;
    }
    bad |= fprintf(out,
                   "</g>\n<text class=\"zlabel\" x=\"0\" y=\"0\" font-size=\"14\" "
                   "text-anchor=\"middle\" transform=\"translate(%.2f %.2f) rotate(-90)\">",
                   HW - 12, (y0 + y1) / 2) < 0;
    bad |= cli_xml_escaped(out, col_label(t, zc, zl, sizeof zl));
    bad |= fputs("</text>\n</svg>\n", out) < 0;
#undef PX
#undef PY
    free(xv);
    free(yv);
    free(xe);
    free(ye);
    return bad ? CLI_FAILED : CLI_OK;
}

typedef struct keyed_row {
    double x;
    long row;
} keyed_row;

static int cmp_keyed(const void *a, const void *b)
{
    const keyed_row *p = a, *q = b;
    if (isnan(p->x) != isnan(q->x))
        return isnan(p->x) ? 1 : -1; /* nan last */
    if (p->x != q->x && !isnan(p->x))
        return p->x < q->x ? -1 : 1;
    return p->row < q->row ? -1 : p->row > q->row;
}

/* The rows of t ordered by column c (ties in run order; nan last), in a new array: a table
 * of values sampled at random (--sample) is in run order, and a line through its points in
 * that order would zigzag. NULL when out of memory. */
static double *rows_by(const sweep_table *t, int c)
{
    keyed_row *key = malloc(((size_t)t->rows + 1) * sizeof *key);
    double *data = malloc(((size_t)t->rows * (size_t)t->cols + 1) * sizeof *data);
    if (key && data) {
        for (long r = 0; r < t->rows; r++)
            key[r] = (keyed_row){t->data[r * t->cols + c], r};
        qsort(key, (size_t)t->rows, sizeof *key, cmp_keyed);
        for (long r = 0; r < t->rows; r++)
            memcpy(data + r * t->cols, t->data + key[r].row * t->cols,
                   (size_t)t->cols * sizeof *data);
    } else {
        free(data);
        data = NULL;
    }
    free(key);
    return data;
}

/* The range max - min of column c (0 when constant or without finite values). */
static double col_span(const sweep_table *t, int c)
{
    double lo = INFINITY, hi = -INFINITY;
    for (long r = 0; r < t->rows; r++) {
        const double v = t->data[r * t->cols + c];
        if (isfinite(v)) {
            lo = fmin(lo, v);
            hi = fmax(hi, v);
        }
    }
    return hi >= lo ? hi - lo : 0.0;
}

/* The columns ycols against xc in panels stacked one under the other, one per unit in the
 * order the units first appear (unitless columns together only when their ranges are within
 * a factor of 10: cli_svg_share_axis); first is the first panel, with the title and xlabel. */
static int panels_of(FILE *out, const sweep_table *t, int xc, const int *ycols, int n_y,
                     const cli_svg_plot *first)
{
    static cli_svg_plot panels[CLI_SVG_MAX_LINES];
    static char ylabels[CLI_SVG_MAX_LINES][320];
    const cli_svg_plot *order[CLI_SVG_MAX_LINES];
    int done[CLI_SVG_MAX_LINES] = {0}, n = 0;
    n_y = n_y < CLI_SVG_MAX_LINES ? n_y : CLI_SVG_MAX_LINES;
    for (int a = 0; a < n_y; a++) {
        if (done[a])
            continue;
        const char *unit = t->units[ycols[a]] ? t->units[ycols[a]] : "";
        cli_svg_plot *p = &panels[n];
        *p = *first;
        p->title = n > 0 ? "" : first->title;
        for (int b = a; b < n_y; b++) {
            const char *ub = t->units[ycols[b]] ? t->units[ycols[b]] : "";
            if (!done[b] && strcmp(ub, unit) == 0 &&
                cli_svg_share_axis(unit, col_span(t, ycols[a]), col_span(t, ycols[b]))) {
                done[b] = 1;
                p->lines[p->n_lines++] =
                    (cli_svg_line){t->names[ycols[b]], t->data + xc, t->data + ycols[b],
                                   t->rows, t->cols, 0, NULL, NULL};
            }
        }
        /* the panel's names and their unit: "max_v, final_v [mV]" */
        char *yl = ylabels[n];
        yl[0] = '\0';
        for (int k = 0; k < p->n_lines; k++)
            snprintf(yl + strlen(yl), sizeof ylabels[0] - strlen(yl), "%s%s", k ? ", " : "",
                     p->lines[k].label);
        if (*unit)
            snprintf(yl + strlen(yl), sizeof ylabels[0] - strlen(yl), " [%s]", unit);
        p->ylabel = yl;
        order[n++] = p;
    }
    return cli_svg_write_panels(out, order, n);
}

/* Lines of the columns ycols against column xc (rows in the order of xc); when the table
 * has another varied name, one line per value of it (of the first column of ycols; at
 * most CLI_SVG_MAX_LINES). */
static int lines_of(FILE *out, const sweep_table *t, int xc, const int *ycols, int n_y,
                    const char *title)
{
    cli_svg_plot p;
    memset(&p, 0, sizeof p);
    char xl[320], yl[320];
    p.title = title;
    p.xlabel = col_label(t, xc, xl, sizeof xl);
    p.ylabel = n_y == 1 ? col_label(t, ycols[0], yl, sizeof yl) : "";
    int other = -1;
    for (int c = 1; c < t->cols; c++)
        if (c != xc && is_varied(t, c) && other < 0)
            other = c;
    if (other < 0) /* one panel per unit, as dynkit plot MODEL draws them */
        return panels_of(out, t, xc, ycols, n_y, &p);
    double *vals = malloc((size_t)t->rows * sizeof *vals);
    double *xy = malloc((size_t)t->rows * 2 * sizeof *xy);
    static char labels[CLI_SVG_MAX_LINES][160];
    if (!vals || !xy) {
        free(vals);
        free(xy);
        return CLI_FAILED;
    }
    const long nv = distinct(t, other, vals);
    long used = 0;
    p.ylabel = col_label(t, ycols[0], yl, sizeof yl);
    for (long v = 0; v < nv && p.n_lines < CLI_SVG_MAX_LINES; v++) {
        double *line_xy = xy + 2 * used;
        long n = 0;
        for (long r = 0; r < t->rows; r++)
            if (t->data[r * t->cols + other] == vals[v]) {
                line_xy[2 * n] = t->data[r * t->cols + xc];
                line_xy[2 * n + 1] = t->data[r * t->cols + ycols[0]];
                n++;
            }
        used += n;
        const int k = p.n_lines++;
        snprintf(labels[k], sizeof labels[0], "%s = %.6g", t->names[other], vals[v]);
        p.lines[k] = (cli_svg_line){labels[k], line_xy, line_xy + 1, n, 2, 0, NULL, NULL};
    }
    const int rc = cli_svg_write(out, &p);
    free(vals);
    free(xy);
    return rc;
}

/* lines_of on the rows ordered by column xc. */
static int lines(FILE *out, const sweep_table *unsorted, int xc, const int *ycols, int n_y,
                 const char *title)
{
    sweep_table sorted_rows = *unsorted;
    const sweep_table *t = &sorted_rows;
    double *by_x = rows_by(unsorted, xc);
    if (!by_x)
        return CLI_FAILED;
    sorted_rows.data = by_x;
    const int rc = lines_of(out, t, xc, ycols, n_y, title);
    free(by_x);
    return rc;
}

/* What the page draws: the table's columns and which of them make the picture. */
typedef struct sweep_page {
    const sweep_table *t;
    const char *title;
    int heat, x, other, n_y;
    const int *ycols;
} sweep_page;

static int page_data(cli_json *j, void *ctx)
{
    const sweep_page *p = ctx;
    const sweep_table *t = p->t;
    cli_json_begin_object(j);
    cli_json_key(j, "kind");
    cli_json_string(j, "sweep");
    cli_json_key(j, "title");
    cli_json_string(j, p->title);
    cli_json_key(j, "picture");
    cli_json_string(j, p->heat ? "heat" : "lines");
    cli_json_key(j, "x");
    cli_json_string(j, t->names[p->x]);
    cli_json_key(j, "other"); /* the second varied name: the heat map's y, a line per value */
    if (p->other >= 0)
        cli_json_string(j, t->names[p->other]);
    else
        cli_json_null(j);
    cli_json_key(j, "y");
    cli_json_begin_array(j);
    for (int k = 0; k < p->n_y; k++)
        cli_json_string(j, t->names[p->ycols[k]]);
    cli_json_end_array(j);
    cli_json_key(j, "labels"); /* the columns' axis labels, with units when the table has them */
    cli_json_begin_object(j);
    char buf[320];
    for (int c = 1; c < t->cols; c++) {
        cli_json_key(j, t->names[c]);
        cli_json_string(j, col_label(t, c, buf, sizeof buf));
    }
    cli_json_end_object(j);
    cli_json_key(j, "rows");
    cli_json_number(j, (double)t->rows);
    cli_json_key(j, "columns"); /* the numbers of the columns drawn, in row order; nan: null */
    cli_json_begin_object(j);
    const int digits = j->digits;
    j->digits = 17;
    for (int c = 1; c < t->cols; c++)
        if (c == p->x || c == p->other || (c != t->status_col && !is_varied(t, c))) {
            cli_json_key(j, t->names[c]);
            cli_json_numbers(j, t->data + c, t->rows, t->cols);
        }
    j->digits = digits;
    cli_json_end_object(j);
    cli_json_end_object(j);
    return j->bad;
}

/* A band table (dynkit sweep --bands): for each state X (those of ys, comma-separated, or
 * all), its mean over the runs against t with the band from p5_X to p95_X shaded, and its
 * median. */
static int band_plot(FILE *out, const sweep_table *t, const char *ys, const char *title)
{
    cli_svg_plot p;
    memset(&p, 0, sizeof p);
    static char labels[CLI_SVG_MAX_LINES][160];
    char xl[320], names[1024] = "";
    p.title = title;
    p.xlabel = col_label(t, 0, xl, sizeof xl);
    p.ylabel = "";
    for (int c = 1; c < t->cols; c++) {
        if (strncmp(t->names[c], "mean_", 5) != 0)
            continue;
        const char *x = t->names[c] + 5;
        char want[160];
        snprintf(want, sizeof want, ",%s,", x);
        char list[1100];
        snprintf(list, sizeof list, ",%s,", ys ? ys : "");
        const size_t used = strlen(names);
        snprintf(names + used, sizeof names - used, "%s%s", used ? ", " : "", x);
        if (ys && !strstr(list, want))
            continue;
        char lo[170], hi[170], med[170];
        snprintf(lo, sizeof lo, "p5_%s", x);
        snprintf(hi, sizeof hi, "p95_%s", x);
        snprintf(med, sizeof med, "p50_%s", x);
        const int clo = find_col(t, lo), chi = find_col(t, hi), cmed = find_col(t, med);
        if (clo < 0 || chi < 0 || p.n_lines + 2 > CLI_SVG_MAX_LINES)
            continue;
        int k = p.n_lines++;
        snprintf(labels[k], sizeof labels[0], "mean %s (shaded: 5%% to 95%% of the runs)", x);
        p.lines[k] = (cli_svg_line){labels[k], t->data, t->data + c, t->rows, t->cols, 0,
                                    t->data + clo, t->data + chi};
        if (cmed >= 0) {
            k = p.n_lines++;
            snprintf(labels[k], sizeof labels[0], "median %s", x);
            p.lines[k] = (cli_svg_line){labels[k], t->data, t->data + cmed, t->rows, t->cols, 0,
                                        NULL, NULL};
        }
    }
    if (p.n_lines == 0)
        return cli_usage_error("plot", "--y %s: no band of that name (accepted: %s)",
                               ys ? ys : "", names);
    return cli_svg_write(out, &p);
}

int cli_plot_sweep_table(int argc, char **argv)
{
    const char *x = NULL, *y = NULL, *title = NULL, *output = NULL, *html = NULL;
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int r;
        if ((r = cli_option(argc, argv, &i, "x", &v)) != 0)
            x = v;
        else if ((r = cli_option(argc, argv, &i, "y", &v)) != 0)
            y = v;
        else if ((r = cli_option(argc, argv, &i, "title", &v)) != 0)
            title = v;
        else if ((r = cli_option(argc, argv, &i, "output", &v)) != 0)
            output = v;
        else if ((r = cli_option(argc, argv, &i, "html", &v)) != 0)
            html = v;
        else
            return cli_usage_error("plot",
                                   "'%s': a sweep's table takes --y NAME[,NAME...], --x NAME, "
                                   "--title TEXT, --output FILE.svg|FILE.html and --html FILE",
                                   argv[i]);
        if (r < 0)
            return cli_usage_error("plot", "%s needs a value", argv[i]);
    }
    sweep_table t;
    char err[512], names[2048];
    cli_input_note(argv[0], "the table plotted");
    if (sweep_table_read(argv[0], &t, err, sizeof err)) {
        sweep_table_free(&t);
        return cli_usage_error("plot", "%s", err);
    }
    if (t.bands) {
        int rc = CLI_OK;
        if (x || html || (output && !cli_has_extension(output, ".svg")))
            rc = cli_usage_error("plot", "a band table (dynkit sweep --bands) is drawn against "
                                         "t as SVG: it takes --y NAME[,NAME...], --title TEXT "
                                         "and --output FILE.svg");
        cli_out outf = {0};
        if (rc == CLI_OK)
            rc = cli_out_open(&outf, "--output", output);
        if (rc == CLI_OK) {
            const char *base = strrchr(argv[0], '/');
            char auto_title[512];
            snprintf(auto_title, sizeof auto_title, "%s: over the runs",
                     base ? base + 1 : argv[0]);
            rc = band_plot(outf.f, &t, y, title ? title : auto_title);
            const int close_rc = cli_out_close(&outf, rc == CLI_OK);
            if (rc == CLI_OK)
                rc = close_rc;
        }
        sweep_table_free(&t);
        return rc;
    }
    int rc = CLI_OK, varied[2], n_varied = 0, ycols[CLI_SVG_MAX_LINES], n_y = 0;
    for (int c = 1; c < t.cols; c++)
        if (is_varied(&t, c) && n_varied < 2)
            varied[n_varied++] = c;
    if (x) {
        int c = find_col(&t, x);
        if (c < 0 || !is_varied(&t, c)) {
            col_names(&t, 1, names, sizeof names);
            rc = cli_usage_error("plot", "--x %s: not a varied name of %s (accepted: %s)", x,
                                 argv[0], names);
        }
        varied[0] = c;
        if (n_varied == 0)
            n_varied = 1;
    }
    if (rc == CLI_OK && n_varied == 0)
        rc = cli_usage_error("plot", "%s has no varied name to plot against", argv[0]);
    if (rc == CLI_OK && y) {
        char buf[1024];
        snprintf(buf, sizeof buf, "%s", y);
        for (char *p = buf; p && rc == CLI_OK;) {
            char *comma = strchr(p, ',');
            if (comma)
                *comma = '\0';
            int c = find_col(&t, p);
            if (c < 1 || is_varied(&t, c) || c == t.status_col || n_y >= CLI_SVG_MAX_LINES) {
                col_names(&t, 0, names, sizeof names);
                rc = cli_usage_error("plot", "--y %s: not a reduced column of %s (accepted: %s)",
                                     p, argv[0], names);
            }
            ycols[n_y++] = c;
            p = comma ? comma + 1 : NULL;
        }
    } else if (rc == CLI_OK) {
        for (int c = 1; c < t.cols && n_y < (n_varied == 2 && !x ? 1 : CLI_SVG_MAX_LINES); c++)
            if (!is_varied(&t, c) && c != t.status_col)
                ycols[n_y++] = c;
        if (n_y == 0)
            rc = cli_usage_error("plot", "%s has no reduced column to plot", argv[0]);
    }
    const int heat = rc == CLI_OK && n_varied == 2 && !x;
    if (heat && n_y != 1)
        rc = cli_usage_error("plot", "a heat map over %s and %s shows one reduced column: give "
                                     "--y NAME (or --x NAME for lines against one of them)",
                             t.names[varied[0]], t.names[varied[1]]);
    if (rc == CLI_OK && html && output)
        rc = cli_usage_error("plot", "give --html FILE or --output FILE, not both");
    static const char *const svg_html[] = {".svg", ".html", ".htm", NULL},
                             *const html_only[] = {".html", ".htm", NULL};
    if (rc == CLI_OK)
        rc = cli_out_check_extension("plot", "--output", output, svg_html);
    if (rc == CLI_OK)
        rc = cli_out_check_extension("plot", "--html", html, html_only);
    if (rc == CLI_OK && output &&
        (cli_has_extension(output, ".html") || cli_has_extension(output, ".htm")))
        html = output, output = NULL;
    const char *path = html ? html : output;
    /* written to a temporary file renamed over the name at the end (out_file.h) */
    cli_out outf = {0};
    if (rc == CLI_OK)
        rc = cli_out_open(&outf, html ? "--html" : "--output", path);
    FILE *out = outf.f;
    char auto_title[512];
    if (rc == CLI_OK) {
        const char *base = strrchr(argv[0], '/');
        base = base ? base + 1 : argv[0];
        if (heat)
            snprintf(auto_title, sizeof auto_title, "%s: %s over %s and %s", base,
                     t.names[ycols[0]], t.names[varied[0]], t.names[varied[1]]);
        else
            snprintf(auto_title, sizeof auto_title, "%s: against %s", base, t.names[varied[0]]);
        if (html) {
            int other = -1;
            for (int c = 1; c < t.cols && other < 0; c++)
                if (c != varied[0] && is_varied(&t, c))
                    other = c;
            sweep_page page = {&t, title ? title : auto_title, heat, varied[0], other, n_y, ycols};
            rc = cli_html_page_write(out, page.title, "sweep.html", page_data, &page);
        } else if (heat) {
            rc = heat_map(out, &t, varied[0], varied[1], ycols[0], title ? title : auto_title);
        } else {
            rc = lines(out, &t, varied[0], ycols, n_y, title ? title : auto_title);
        }
    }
    if (outf.f) {
        int close_rc = cli_out_close(&outf, rc == CLI_OK);
        if (rc == CLI_OK)
            rc = close_rc;
    }
    sweep_table_free(&t);
    return rc;
}
