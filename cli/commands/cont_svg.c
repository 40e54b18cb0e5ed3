/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_svg.c — the bifurcation diagram of dynkit continue as SVG (cont_output.h): the
 * parameter against a state, each branch a polyline, solid where its points are stable and
 * dashed where not (periodic orbits by their maximum and minimum), the special points
 * marked and labelled (LP, HB, ...), axis names with their units, within XPPAUT's
 * autoxmin..autoymax window when the file gives it; the curves of folds and Hopf points in
 * the two parameters below. For the page (cont_page.c) the periodic points whose orbits it
 * holds are dots that carry the orbit's number (data-orbit). The axes come from
 * svg_axes.h. */
#include <math.h>
#include <string.h>

#include "cli.h"
#include "cont_output.h"
#include "pages/svg_axes.h"
#include "util/escape.h"

#define SW 720.0
#define SH 440.0
#define SL 70.0
#define SR 20.0
#define ST 36.0
#define SB 52.0

static const char *const colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                     "#9467bd", "#8c564b", "#e377c2", "#17becf"};

typedef struct frame {
    double xlo, xhi, ylo, yhi;
} frame;

static double px(const frame *r, double x)
{
    return SL + (x - r->xlo) / (r->xhi - r->xlo) * (SW - SL - SR);
}

static double py(const frame *r, double y)
{
    return SH - SB - (y - r->ylo) / (r->yhi - r->ylo) * (SH - ST - SB);
}

static void widen(double *lo, double *hi)
{
    if (!(*lo <= *hi)) {
        *lo = 0.0;
        *hi = 1.0;
    }
    const double d = *hi - *lo > 0.0 ? 0.04 * (*hi - *lo) : fmax(0.1 * fabs(*lo), 1.0);
    *lo -= d;
    *hi += d;
}

/* the value on the y axis of point k of branch b: the state (max or min), or par2 */
static double yval(const cont_view *v, const dyn_branch *b, long k, int curves, int lower)
{
    if (curves)
        return b->pts[k].par[1];
    const double *x = lower && b->xmin ? b->xmin : b->x;
    return x[(size_t)k * (size_t)b->n + (size_t)v->iy];
}

static int wanted(const dyn_branch *b, int curves)
{
    return curves ? b->n_par == 2 : b->n_par == 1;
}

/* "name [unit]", or the name alone without a unit */
static const char *with_unit(const char *name, const char *unit, char *buf, size_t size)
{
    if (unit && *unit)
        snprintf(buf, size, "%s [%s]", name, unit);
    else
        snprintf(buf, size, "%s", name);
    return buf;
}

/* the line styles' key, left of the x axis's name */
static int key(FILE *f)
{
    const double y = SH - 14, x = SL;
    return fprintf(f, "<g font-size=\"11\" fill=\"#333\" stroke-width=\"1.6\">"
                      "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#333\"/>"
                      "<text x=\"%.1f\" y=\"%.1f\" stroke=\"none\">stable</text>"
                      "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#333\" "
                      "stroke-dasharray=\"5,4\"/>"
                      "<text x=\"%.1f\" y=\"%.1f\" stroke=\"none\">unstable</text></g>\n",
                   x, y - 4, x + 22, y - 4, x + 26, y, x + 70, y - 4, x + 92, y - 4, x + 96,
                   y) < 0;
}

static int axes(FILE *f, const frame *r, const char *xl, const char *yl, const char *title)
{
    int bad = svg_grid_begin(f);
    const double sx = svg_nice_step(r->xhi - r->xlo, 8), sy = svg_nice_step(r->yhi - r->ylo, 6);
    char lab[64];
    const long x0 = (long)ceil(r->xlo / sx - 1e-9), x1 = (long)floor(r->xhi / sx + 1e-9);
    const long y0 = (long)ceil(r->ylo / sy - 1e-9), y1 = (long)floor(r->yhi / sy + 1e-9);
    for (long k = x0; k <= x1; k++)
        bad |= svg_line(f, px(r, k * sx), SH - SB, px(r, k * sx), ST);
    for (long k = y0; k <= y1; k++)
        bad |= svg_line(f, SL, py(r, k * sy), SW - SR, py(r, k * sy));
    bad |= svg_frame_and_ticks_begin(f, SL, SW - SR, SH - SB, ST);
    for (long k = x0; k <= x1; k++) {
        svg_tick_label(k * sx, sx, lab, sizeof lab);
        bad |= svg_xtick(f, px(r, k * sx), SH - SB, lab);
    }
    for (long k = y0; k <= y1; k++) {
        svg_tick_label(k * sy, sy, lab, sizeof lab);
        bad |= svg_ytick(f, SL, py(r, k * sy), lab);
    }
    bad |= svg_titles(f, SL, SW - SR, SH - SB, ST, SW, SH, xl, yl, title);
    return bad;
}

/* the dots of the periodic points whose orbits the page holds, at their maximum and minimum */
static int orbit_dots(FILE *f, const cont_view *v, const frame *r, const cont_orbit_set *marks)
{
    int bad = fputs("<g class=\"dk-orbits\" fill-opacity=\"0.55\">\n", f) < 0;
    for (long q = 0; q < marks->count; q++) {
        const dyn_branch *b = &v->d->branches[marks->refs[q].branch];
        const long k = marks->refs[q].point;
        const double x = b->pts[k].par[0];
        for (int lower = 0; lower < 2; lower++) {
            const double y = yval(v, b, k, 0, lower);
            if (!isfinite(x) || !isfinite(y) || x < r->xlo || x > r->xhi || y < r->ylo ||
                y > r->yhi)
                continue;
            bad |= fprintf(f, "<circle class=\"dk-orbit\" data-orbit=\"%ld\" cx=\"%.2f\" "
                              "cy=\"%.2f\" r=\"2.2\" fill=\"%s\"/>\n",
                           q, px(r, x), py(r, y), colors[marks->refs[q].branch % 8]) < 0;
        }
    }
    return bad | (fputs("</g>\n", f) < 0);
}

/* The labels already drawn on a panel, as boxes in SVG units (11 px text: about 7 px a
 * character, 11 px high), so that a label does not cover another: a periodic branch's first
 * point (EP) sits on the Hopf point (HB) it starts from. */
#define LABEL_MAX 512
typedef struct {
    double x0[LABEL_MAX], y0[LABEL_MAX], x1[LABEL_MAX], y1[LABEL_MAX];
    int count;
} label_boxes;

static int label_free(const label_boxes *b, double x0, double y0, double x1, double y1)
{
    if (x0 < 0 || x1 > SW || y0 < 0)
        return 0;
    for (int i = 0; i < b->count; i++)
        if (x0 < b->x1[i] && b->x0[i] < x1 && y0 < b->y1[i] && b->y0[i] < y1)
            return 0;
    return 1;
}

/* The baseline start (*tx, *ty) of a label of n characters for the mark at (x, y): above
 * right, else below right, above left, below left, else stacked further up; recorded. */
static void place_label(label_boxes *b, double x, double y, size_t n, double *tx, double *ty)
{
    const double w = 7.0 * (double)n, h = 11.0;
    const double dx[4] = {4, 4, -4 - w, -4 - w}, dy[4] = {-4, 4 + h, -4, 4 + h};
    int k = 0;
    while (k < 4 && !label_free(b, x + dx[k], y + dy[k] - h, x + dx[k] + w, y + dy[k]))
        k++;
    if (k < 4) {
        *tx = x + dx[k];
        *ty = y + dy[k];
    } else {
        *tx = x + dx[0];
        *ty = y + dy[0];
        while (*ty - h > h && !label_free(b, *tx, *ty - h, *tx + w, *ty))
            *ty -= h;
    }
    if (b->count < LABEL_MAX) {
        b->x0[b->count] = *tx;
        b->y0[b->count] = *ty - h;
        b->x1[b->count] = *tx + w;
        b->y1[b->count] = *ty;
        b->count++;
    }
}

static int panel(FILE *f, const cont_view *v, int curves, const cont_orbit_set *marks)
{
    const dyn_model *m = v->m;
    const dyn_cont_opts *o = &v->s->opts;
    frame r = {INFINITY, -INFINITY, INFINITY, -INFINITY};
    for (int bi = 0; bi < v->d->count; bi++) {
        const dyn_branch *b = &v->d->branches[bi];
        if (!wanted(b, curves))
            continue;
        for (long k = 0; k < b->count; k++)
            for (int lower = 0; lower < 2; lower++) {
                const double x = b->pts[k].par[0], y = yval(v, b, k, curves, lower);
                if (isfinite(x) && isfinite(y)) {
                    r.xlo = fmin(r.xlo, x);
                    r.xhi = fmax(r.xhi, x);
                    r.ylo = fmin(r.ylo, y);
                    r.yhi = fmax(r.yhi, y);
                }
            }
    }
    widen(&r.xlo, &r.xhi);
    widen(&r.ylo, &r.yhi);
    const double *w = v->s->window;
    if (!curves && w[0] < w[1]) {
        r.xlo = w[0];
        r.xhi = w[1];
    }
    if (!curves && w[2] < w[3]) {
        r.ylo = w[2];
        r.yhi = w[3];
    }
    char title[256];
    snprintf(title, sizeof title,
             !curves  ? "%s: bifurcation diagram"
             : o->map ? "%s: folds, flips and Neimark-Sacker points"
                      : "%s: folds and Hopf points",
             m->name);
    char xl[200], yl[200];
    with_unit(m->params[o->ip].name, m->params[o->ip].unit, xl, sizeof xl);
    if (curves)
        with_unit(m->params[o->ip2].name, m->params[o->ip2].unit, yl, sizeof yl);
    else
        with_unit(m->states[v->iy].name, m->states[v->iy].unit, yl, sizeof yl);
    int bad = axes(f, &r, xl, yl, title);
    if (!curves) /* the curves in two parameters have no stability */
        bad |= key(f);
    bad |= fprintf(f, "<defs><clipPath id=\"plot%d\"><rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" "
                      "height=\"%.1f\"/></clipPath></defs>\n<g clip-path=\"url(#plot%d)\" "
                      "fill=\"none\" stroke-width=\"1.6\">\n",
                   curves, SL, ST, SW - SL - SR, SH - ST - SB, curves) < 0;
    for (int bi = 0; bi < v->d->count; bi++) {
        const dyn_branch *b = &v->d->branches[bi];
        if (!wanted(b, curves))
            continue;
        const char *c = colors[bi % 8];
        for (int lower = 0; lower < (b->xmin ? 2 : 1); lower++)
            for (long k = 0; k + 1 < b->count; k++) {
                const double xa = b->pts[k].par[0], xb = b->pts[k + 1].par[0];
                const double ya = yval(v, b, k, curves, lower), yb = yval(v, b, k + 1, curves, lower);
                if (!(isfinite(xa) && isfinite(xb) && isfinite(ya) && isfinite(yb)))
                    continue;
                const int solid = curves || (b->pts[k].stable == 1 && b->pts[k + 1].stable == 1);
                bad |= fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
                                  "stroke=\"%s\"%s/>\n",
                               px(&r, xa), py(&r, ya), px(&r, xb), py(&r, yb), c,
                               solid ? "" : " stroke-dasharray=\"5,4\"") < 0;
            }
    }
    bad |= fputs("</g>\n", f) < 0;
    if (!curves && marks)
        bad |= orbit_dots(f, v, &r, marks);
    bad |= fputs("<g font-size=\"11\">\n", f) < 0;
    label_boxes placed = {0};
    for (int bi = 0; bi < v->d->count; bi++) {
        const dyn_branch *b = &v->d->branches[bi];
        if (!wanted(b, curves))
            continue;
        for (long k = 0; k < b->count; k++) {
            const dyn_cont_label l = b->pts[k].label;
            const double x = b->pts[k].par[0], y = yval(v, b, k, curves, 0);
            if (l == DYN_LABEL_NONE || !isfinite(x) || !isfinite(y) || x < r.xlo || x > r.xhi ||
                y < r.ylo || y > r.yhi)
                continue;
            const char *name = dyn_cont_label_name(l);
            double tx, ty;
            place_label(&placed, px(&r, x), py(&r, y), strlen(name), &tx, &ty);
            bad |= fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3\" fill=\"#000\"/>"
                              "<text x=\"%.2f\" y=\"%.2f\">%s</text>\n",
                           px(&r, x), py(&r, y), tx, ty, name) < 0;
        }
    }
    bad |= fputs("</g>\n", f) < 0;
    return bad;
}

int cont_write_svg(FILE *f, const cont_view *v, const cont_orbit_set *marks)
{
    int curves = 0;
    for (int bi = 0; bi < v->d->count; bi++)
        curves |= v->d->branches[bi].n_par == 2;
    const int panels = 1 + curves;
    int bad = fprintf(f,
                      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
                      "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\">\n"
                      "<rect width=\"100%%\" height=\"100%%\" fill=\"#fff\"/>\n",
                      SW, SH * panels, SW, SH * panels) < 0;
    bad |= panel(f, v, 0, marks);
    if (curves) {
        bad |= fprintf(f, "<g transform=\"translate(0,%.0f)\">\n", SH) < 0;
        bad |= panel(f, v, 1, NULL);
        bad |= fputs("</g>\n", f) < 0;
    }
    bad |= fputs("</svg>\n", f) < 0;
    return bad;
}
