/* SPDX-License-Identifier: BSD-3-Clause */
/* Standalone SVG line plots (SVG 1.1): a frame with ticks at 1, 2 or 5 times a power of ten
 * and their numbers, grid lines, the axis labels with units, a title, a legend in the corner
 * with the fewest points, and one polyline per line (split where a point is not finite);
 * several such panels stacked in one document (one per unit of the y axis). */
#include <math.h>
#include <string.h>

#include "pages/pages.h"
#include "util/escape.h"
#include "pages/svg_axes.h"

#define W 800.0
#define H 500.0
#define LEFT 84.0
#define RIGHT 24.0
#define TOP 44.0
#define BOTTOM 62.0

/* The line colours of the pages (web/js/util.js uses the same). */
static const char *const palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                      "#9467bd", "#8c564b", "#e377c2", "#17becf"};

typedef struct axis {
    double lo, hi; /* shown range */
    double step;   /* between ticks */
} axis;

static axis make_axis(double lo, double hi, int target)
{
    axis a;
    if (!(lo <= hi)) { /* no finite point */
        lo = 0.0;
        hi = 1.0;
    }
    if (hi - lo <= 1e-12 * fmax(fabs(lo), fabs(hi))) {
        double d = lo != 0.0 ? 0.1 * fabs(lo) : 1.0;
        lo -= d;
        hi += d;
    }
    const double pad = 0.03 * (hi - lo);
    a.lo = lo - pad;
    a.hi = hi + pad;
    a.step = svg_nice_step(a.hi - a.lo, target);
    return a;
}

/* The axis over a fixed window [lo, hi] when lo < hi, else over the data (make_axis). */
static axis window_or_data(const double win[2], double lo, double hi, int target)
{
    if (!(win[0] < win[1]))
        return make_axis(lo, hi, target);
    return (axis){win[0], win[1], svg_nice_step(win[1] - win[0], target)};
}

static double to_px_x(const axis *a, double v)
{
    return LEFT + (v - a->lo) / (a->hi - a->lo) * (W - LEFT - RIGHT);
}

static double to_px_y(const axis *a, double v)
{
    return H - BOTTOM - (v - a->lo) / (a->hi - a->lo) * (H - TOP - BOTTOM);
}

/* Tick positions k * step inside the range: first and last k. */
static void tick_range(const axis *a, long *first, long *last)
{
    *first = (long)ceil(a->lo / a->step - 1e-9);
    *last = (long)floor(a->hi / a->step + 1e-9);
}

static void data_range(const cli_svg_plot *p, int use_x, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (int i = 0; i < p->n_lines; i++) {
        const cli_svg_line *l = &p->lines[i];
        const double *v = use_x ? l->x : l->y;
        for (long k = 0; k < l->n; k++) {
            double x = v[k * l->stride];
            if (isfinite(x) && isfinite((use_x ? l->y : l->x)[k * l->stride])) {
                *lo = fmin(*lo, x);
                *hi = fmax(*hi, x);
            }
            if (!use_x && l->lo && isfinite(l->x[k * l->stride]))
                for (int e = 0; e < 2; e++) {
                    const double b = (e ? l->hi : l->lo)[k * l->stride];
                    if (isfinite(b)) {
                        *lo = fmin(*lo, b);
                        *hi = fmax(*hi, b);
                    }
                }
        }
    }
}

static int axes(FILE *out, const cli_svg_plot *p, const axis *ax, const axis *ay)
{
    int bad = 0;
    char label[64];
    const double x0 = LEFT, x1 = W - RIGHT, y0 = H - BOTTOM, y1 = TOP;
    long kx0, kx1, ky0, ky1;
    tick_range(ax, &kx0, &kx1);
    tick_range(ay, &ky0, &ky1);
    bad |= svg_grid_begin(out);
    for (long k = kx0; k <= kx1; k++)
        bad |= svg_line(out, to_px_x(ax, k * ax->step), y0, to_px_x(ax, k * ax->step), y1);
    for (long k = ky0; k <= ky1; k++)
        bad |= svg_line(out, x0, to_px_y(ay, k * ay->step), x1, to_px_y(ay, k * ay->step));
    bad |= svg_frame_and_ticks_begin(out, x0, x1, y0, y1);
    /* ticks that differ only in late digits are labelled from an offset (svg_tick_offset) */
    double xoff, xscale, yoff, yscale;
    const int x_offset = svg_tick_offset(kx0, kx1, ax->step, &xoff, &xscale);
    const int y_offset = svg_tick_offset(ky0, ky1, ay->step, &yoff, &yscale);
    /* the offset is a whole number of steps: labels from the tick's index, no rounding */
    const double kxoff = round(xoff / ax->step), kyoff = round(yoff / ay->step);
    for (long k = kx0; k <= kx1; k++) {
        const double v = (double)k * ax->step;
        svg_tick_label(((double)k - kxoff) * (ax->step / xscale), ax->step / xscale, label,
                       sizeof label);
        bad |= svg_xtick(out, to_px_x(ax, v), y0, label);
    }
    for (long k = ky0; k <= ky1; k++) {
        const double v = (double)k * ay->step;
        svg_tick_label(((double)k - kyoff) * (ay->step / yscale), ay->step / yscale, label,
                       sizeof label);
        bad |= svg_ytick(out, x0, to_px_y(ay, v), label);
    }
    if (x_offset)
        bad |= svg_offset_note(out, x1, y0 + 36, "end", xoff, xscale);
    if (y_offset)
        bad |= svg_offset_note(out, x0, y1 - 6, "start", yoff, yscale);
    bad |= svg_titles(out, x0, x1, y0, y1, W, H, p->xlabel, p->ylabel, p->title);
    return bad;
}

/* The finite points of a line as dots: one path of zero-length segments with round caps. */
static int dots(FILE *out, const cli_svg_line *l, const char *color, const axis *ax,
                const axis *ay)
{
    int bad = fprintf(out,
                      "<path fill=\"none\" stroke=\"%s\" stroke-width=\"3\" "
                      "stroke-linecap=\"round\" d=\"",
                      color) < 0;
    for (long k = 0; k < l->n; k++) {
        const double x = l->x[k * l->stride], y = l->y[k * l->stride];
        if (isfinite(x) && isfinite(y))
            bad |= fprintf(out, "M%.2f,%.2fh0", to_px_x(ax, x), to_px_y(ay, y)) < 0;
    }
    bad |= fputs("\"/>\n", out) < 0;
    return bad;
}

/* A line's band: one polygon along hi and back along lo through the points where x, lo and
 * hi are finite, in the line's colour, light. */
static int band(FILE *out, const cli_svg_line *l, const char *color, const axis *ax,
                const axis *ay)
{
    int bad = fprintf(out, "<polygon fill=\"%s\" fill-opacity=\"0.18\" stroke=\"none\" "
                           "points=\"",
                      color) < 0;
    for (int e = 1; e >= 0; e--)
        for (long j = 0; j < l->n; j++) {
            const long k = e ? j : l->n - 1 - j;
            const double x = l->x[k * l->stride], b = (e ? l->hi : l->lo)[k * l->stride];
            const double o = (e ? l->lo : l->hi)[k * l->stride];
            if (isfinite(x) && isfinite(b) && isfinite(o))
                bad |= fprintf(out, "%.2f,%.2f ", to_px_x(ax, x), to_px_y(ay, b)) < 0;
        }
    bad |= fputs("\"/>\n", out) < 0;
    return bad;
}

/* One line: polylines of its runs of finite points (dots for a line of points). */
static int line(FILE *out, const cli_svg_line *l, const char *color, const axis *ax, const axis *ay)
{
    if (l->points)
        return dots(out, l, color, ax, ay);
    int bad = 0, open = 0;
    for (long k = 0; k < l->n; k++) {
        double x = l->x[k * l->stride], y = l->y[k * l->stride];
        if (!isfinite(x) || !isfinite(y)) {
            if (open)
                bad |= fputs("\"/>\n", out) < 0;
            open = 0;
            continue;
        }
        if (!open)
            bad |= fprintf(out,
                           "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.6\" "
                           "stroke-linejoin=\"round\" points=\"",
                           color) < 0;
        bad |= fprintf(out, "%s%.2f,%.2f", open ? " " : "", to_px_x(ax, x), to_px_y(ay, y)) < 0;
        open = 1;
    }
    if (open)
        bad |= fputs("\"/>\n", out) < 0;
    return bad;
}

/* Points of the lines inside the box [x0, x1] x [y0, y1] (pixels). */
static long points_inside(const cli_svg_plot *p, const axis *ax, const axis *ay, double x0,
                          double x1, double y0, double y1)
{
    long count = 0;
    for (int i = 0; i < p->n_lines; i++) {
        const cli_svg_line *l = &p->lines[i];
        for (long k = 0; k < l->n; k++) {
            const double px = to_px_x(ax, l->x[k * l->stride]);
            const double py = to_px_y(ay, l->y[k * l->stride]);
            count += px >= x0 && px <= x1 && py >= y0 && py <= y1;
        }
    }
    return count;
}

/* The legend in the corner of the frame where the fewest points are drawn (top right when
 * several are empty), so that it covers as little data as it can. */
static int legend(FILE *out, const cli_svg_plot *p, const axis *ax, const axis *ay, int first_color)
{
    int bad = 0;
    size_t longest = 0;
    for (int i = 0; i < p->n_lines; i++)
        longest = strlen(p->lines[i].label) > longest ? strlen(p->lines[i].label) : longest;
    const double w = 40.0 + 7.0 * (double)longest, h = 8.0 + 18.0 * p->n_lines;
    const double xs[4] = {W - RIGHT - w - 8, LEFT + 8, W - RIGHT - w - 8, LEFT + 8};
    const double ys[4] = {TOP + 8, TOP + 8, H - BOTTOM - h - 8, H - BOTTOM - h - 8};
    int best = 0;
    long fewest = -1;
    for (int c = 0; c < 4; c++) {
        const long n = points_inside(p, ax, ay, xs[c] - 4, xs[c] + w + 4, ys[c] - 4, ys[c] + h + 4);
        if (fewest < 0 || n < fewest) {
            fewest = n;
            best = c;
        }
    }
    const double x = xs[best], y = ys[best];
    bad |= fprintf(out,
                   "<g class=\"legend\" font-size=\"12\">\n<rect x=\"%.2f\" y=\"%.2f\" "
                   "width=\"%.2f\" height=\"%.2f\" fill=\"#fff\" fill-opacity=\"0.85\" "
                   "stroke=\"#bbb\"/>\n",
                   x, y, w, h) < 0;
    for (int i = 0; i < p->n_lines; i++) {
        const double ly = y + 16 + 18.0 * i;
        const char *color = palette[(first_color + i) % (int)(sizeof palette / sizeof *palette)];
        if (p->lines[i].points)
            bad |= fprintf(out,
                           "<path stroke=\"%s\" stroke-width=\"4\" stroke-linecap=\"round\" "
                           "d=\"M%.2f,%.2fh0M%.2f,%.2fh0M%.2f,%.2fh0\"/>",
                           color, x + 10, ly - 4, x + 19, ly - 4, x + 28, ly - 4) < 0;
        else
            bad |= fprintf(out,
                           "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
                           "stroke=\"%s\" stroke-width=\"2\"/>",
                           x + 8, ly - 4, x + 30, ly - 4, color) < 0;
        bad |= fprintf(out, "<text x=\"%.2f\" y=\"%.2f\">", x + 36, ly) < 0;
        bad |= cli_xml_escaped(out, p->lines[i].label);
        bad |= fputs("</text>\n", out) < 0;
    }
    bad |= fputs("</g>\n", out) < 0;
    return bad;
}

/* One plot: its axes, lines and legend; colours continue from first_color. */
static int panel(FILE *out, const cli_svg_plot *p, int first_color)
{
    double lo, hi;
    data_range(p, 1, &lo, &hi);
    const axis ax = window_or_data(p->xwin, lo, hi, 8);
    data_range(p, 0, &lo, &hi);
    const axis ay = window_or_data(p->ywin, lo, hi, 6);
    const int n_colors = (int)(sizeof palette / sizeof *palette);
    int bad = axes(out, p, &ax, &ay);
    if (p->xwin[0] < p->xwin[1] || p->ywin[0] < p->ywin[1]) /* lines outside stay out */
        bad |= fprintf(out,
                       "<clipPath id=\"window%d\"><rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" "
                       "height=\"%.2f\"/></clipPath>\n<g class=\"lines\" "
                       "clip-path=\"url(#window%d)\">\n",
                       first_color, LEFT, TOP, W - LEFT - RIGHT, H - TOP - BOTTOM,
                       first_color) < 0;
    else
        bad |= fputs("<g class=\"lines\">\n", out) < 0;
    for (int i = 0; i < p->n_lines; i++)
        if (p->lines[i].lo && p->lines[i].hi)
            bad |= band(out, &p->lines[i], palette[(first_color + i) % n_colors], &ax, &ay);
    for (int i = 0; i < p->n_lines; i++)
        bad |= line(out, &p->lines[i], palette[(first_color + i) % n_colors], &ax, &ay);
    bad |= fputs("</g>\n", out) < 0;
    bad |= legend(out, p, &ax, &ay, first_color);
    return bad;
}

int cli_svg_write(FILE *out, const cli_svg_plot *p) { return cli_svg_write_panels(out, &p, 1); }

int cli_svg_share_axis(const char *unit, double span_a, double span_b)
{
    if (unit && *unit && strcmp(unit, "1") != 0)
        return 1;
    if (span_a == 0.0 || span_b == 0.0)
        return span_a == span_b;
    return fmax(span_a, span_b) <= 10.0 * fmin(span_a, span_b);
}

int cli_svg_write_panels(FILE *out, const cli_svg_plot *const *plots, int n)
{
    int bad = fprintf(out,
                      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" "
                      "height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
                      "font-family=\"sans-serif\">\n"
                      "<rect width=\"100%%\" height=\"100%%\" fill=\"#fff\"/>\n",
                      W, H * n, W, H * n) < 0;
    int color = 0;
    for (int k = 0; k < n; k++) {
        if (n > 1)
            bad |= fprintf(out, "<g class=\"panel\" transform=\"translate(0,%.0f)\">\n", H * k) < 0;
        bad |= panel(out, plots[k], color);
        color += plots[k]->n_lines;
        if (n > 1)
            bad |= fputs("</g>\n", out) < 0;
    }
    bad |= fputs("</svg>\n", out) < 0;
    if (bad || fflush(out)) {
        cli_error("writing the SVG failed");
        return CLI_FAILED;
    }
    return CLI_OK;
}
