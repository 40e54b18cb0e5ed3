/* SPDX-License-Identifier: BSD-3-Clause */
/* wp_svg.c — work-precision diagrams as SVG (wp_svg.h): error on a logarithmic x axis,
 * cost (time or right-hand-side calls) on a logarithmic y axis, one polyline with circle
 * markers per solver. Sizes, fonts, frame, grid and palette are those of cli/pages/svg_plot.c so
 * that the pictures in docs/ look like the command line's plots; the axes are drawn by the
 * same code (cli/pages/svg_axes.c).
 */
#include "wp_svg.h"
#include "util/escape.h"
#include "pages/svg_axes.h"

#include <math.h>
#include <string.h>

#define W 800.0
#define H 500.0
#define LEFT 84.0
#define RIGHT 24.0
#define TOP 44.0
#define BOTTOM 62.0

/* the command line's eight line colours, then four more for the longer legends here */
static const char *const palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                      "#9467bd", "#8c564b", "#e377c2", "#17becf",
                                      "#bcbd22", "#7f7f7f", "#393b79", "#637939"};

typedef struct logaxis {
    double lo, hi; /* decades shown: 10^lo .. 10^hi */
} logaxis;

static logaxis make_axis(double vmin, double vmax)
{
    logaxis a;
    if (!(vmin > 0 && vmax >= vmin)) {
        vmin = 1.0;
        vmax = 10.0;
    }
    a.lo = floor(log10(vmin));
    a.hi = ceil(log10(vmax));
    if (a.hi <= a.lo)
        a.hi = a.lo + 1;
    return a;
}

static double px_x(const logaxis *a, double v)
{
    return LEFT + (log10(v) - a->lo) / (a->hi - a->lo) * (W - LEFT - RIGHT);
}

static double px_y(const logaxis *a, double v)
{
    return H - BOTTOM - (log10(v) - a->lo) / (a->hi - a->lo) * (H - TOP - BOTTOM);
}

/* 10^k as text: 1, 10, 100, 1000, otherwise 1e-5 */
static void decade_label(int k, char *buf, size_t size)
{
    if (k >= 0 && k <= 3)
        snprintf(buf, size, "%.0f", pow(10.0, k));
    else
        snprintf(buf, size, "1e%d", k);
}

static int axes(FILE *out, const wp_plot *p, const logaxis *ax, const logaxis *ay)
{
    int bad = 0;
    char label[32];
    const double x0 = LEFT, x1 = W - RIGHT, y0 = H - BOTTOM, y1 = TOP;
    bad |= svg_grid_begin(out);
    for (int k = (int)ax->lo; k <= (int)ax->hi; k++)
        bad |= svg_line(out, px_x(ax, pow(10.0, k)), y0, px_x(ax, pow(10.0, k)), y1);
    for (int k = (int)ay->lo; k <= (int)ay->hi; k++)
        bad |= svg_line(out, x0, px_y(ay, pow(10.0, k)), x1, px_y(ay, pow(10.0, k)));
    bad |= svg_frame_and_ticks_begin(out, x0, x1, y0, y1);
    for (int k = (int)ax->lo; k <= (int)ax->hi; k++) {
        decade_label(k, label, sizeof label);
        bad |= svg_xtick(out, px_x(ax, pow(10.0, k)), y0, label);
    }
    for (int k = (int)ay->lo; k <= (int)ay->hi; k++) {
        decade_label(k, label, sizeof label);
        bad |= svg_ytick(out, x0, px_y(ay, pow(10.0, k)), label);
    }
    bad |= svg_titles(out, x0, x1, y0, y1, W, H, p->xlabel, p->ylabel, p->title);
    return bad;
}

static int ok_point(const wp_line *l, int k)
{
    return l->x[k] > 0 && l->y[k] > 0 && isfinite(l->x[k]) && isfinite(l->y[k]);
}

static int line(FILE *out, const wp_line *l, const char *color, const logaxis *ax,
                const logaxis *ay)
{
    int bad = 0, first = 1;
    bad |= fprintf(out,
                   "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"%s\"%s "
                   "stroke-linejoin=\"round\" points=\"",
                   color, l->emphasis ? "2.2" : "1.4",
                   l->emphasis ? "" : " stroke-dasharray=\"6 3\"") < 0;
    for (int k = 0; k < l->n; k++)
        if (ok_point(l, k)) {
            bad |= fprintf(out, "%s%.2f,%.2f", first ? "" : " ", px_x(ax, l->x[k]),
                           px_y(ay, l->y[k])) < 0;
            first = 0;
        }
    bad |= fputs("\"/>\n", out) < 0;
    for (int k = 0; k < l->n; k++) /* markers: filled for dynkit, hollow for the peers */
        if (ok_point(l, k))
            bad |= fprintf(out,
                           "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%s\" fill=\"%s\" stroke=\"%s\" "
                           "stroke-width=\"1.2\"/>\n",
                           px_x(ax, l->x[k]), px_y(ay, l->y[k]), l->emphasis ? "3" : "2.6",
                           l->emphasis ? color : "#fff", color) < 0;
    return bad;
}

/* The legend sits outside the frame, on the right: many solvers' curves leave no free
 * corner inside it. */
static double legend_width(const wp_plot *p)
{
    size_t longest = 0;
    for (int i = 0; i < p->n_lines; i++)
        longest = strlen(p->lines[i].label) > longest ? strlen(p->lines[i].label) : longest;
    return 44.0 + 6.2 * (double)longest;
}

static int legend(FILE *out, const wp_plot *p)
{
    int bad = 0;
    const double w = legend_width(p), h = 8.0 + 16.0 * p->n_lines;
    const double x = W - RIGHT + 12, y = TOP; /* to the right of the frame */
    bad |= fprintf(out,
                   "<g class=\"legend\" font-size=\"11\">\n<rect x=\"%.2f\" y=\"%.2f\" "
                   "width=\"%.2f\" height=\"%.2f\" fill=\"#fff\" fill-opacity=\"0.85\" "
                   "stroke=\"#bbb\"/>\n",
                   x, y, w, h) < 0;
    for (int i = 0; i < p->n_lines; i++) {
        const wp_line *l = &p->lines[i];
        const char *color = palette[i % (int)(sizeof palette / sizeof *palette)];
        const double ly = y + 15 + 16.0 * i;
        bad |= fprintf(out,
                       "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" "
                       "stroke-width=\"%s\"%s/><text x=\"%.2f\" y=\"%.2f\">",
                       x + 8, ly - 4, x + 30, ly - 4, color, l->emphasis ? "2.2" : "1.4",
                       l->emphasis ? "" : " stroke-dasharray=\"6 3\"", x + 36, ly) < 0;
        bad |= cli_xml_escaped(out, l->label);
        bad |= fputs("</text>\n", out) < 0;
    }
    bad |= fputs("</g>\n", out) < 0;
    return bad;
}

int wp_svg_write(FILE *out, const wp_plot *p)
{
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (int i = 0; i < p->n_lines; i++)
        for (int k = 0; k < p->lines[i].n; k++)
            if (ok_point(&p->lines[i], k)) {
                xmin = fmin(xmin, p->lines[i].x[k]);
                xmax = fmax(xmax, p->lines[i].x[k]);
                ymin = fmin(ymin, p->lines[i].y[k]);
                ymax = fmax(ymax, p->lines[i].y[k]);
            }
    const logaxis ax = make_axis(xmin, xmax), ay = make_axis(ymin, ymax);
    const double width = W + 12 + legend_width(p);
    int bad = fprintf(out,
                      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" "
                      "height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
                      "font-family=\"sans-serif\">\n"
                      "<rect width=\"100%%\" height=\"100%%\" fill=\"#fff\"/>\n",
                      width, H, width, H) < 0;
    bad |= axes(out, p, &ax, &ay);
    bad |= fputs("<g class=\"lines\">\n", out) < 0;
    for (int i = 0; i < p->n_lines; i++)
        bad |=
            line(out, &p->lines[i], palette[i % (int)(sizeof palette / sizeof *palette)], &ax, &ay);
    bad |= fputs("</g>\n", out) < 0;
    bad |= legend(out, p);
    bad |= fputs("</svg>\n", out) < 0;
    return bad || fflush(out) != 0;
}
