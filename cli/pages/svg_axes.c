/* SPDX-License-Identifier: BSD-3-Clause */
/* Grid, frame, ticks (at nice steps, with their numbers) and titles of an SVG plot
 * (svg_axes.h). */
#include <math.h>

#include "util/escape.h"
#include "pages/svg_axes.h"

double svg_nice_step(double range, int target)
{
    double raw = range / target, p = pow(10.0, floor(log10(raw))), f = raw / p;
    return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * p;
}

void svg_tick_label(double v, double step, char *buf, size_t size)
{
    if (fabs(v) < 1e-6 * step) /* a multiple of step: 0 up to rounding, never "-0" */
        v = 0.0;
    int digits = (int)ceil(-log10(step) - 1e-9);
    double mag = fmax(fabs(v), step);
    if (mag >= 1e5 || mag < 1e-3) {
        /* enough significant digits to tell neighbouring ticks apart (194000, 194050) */
        int sig = (int)(floor(log10(mag)) - floor(log10(step) + 1e-9)) + 1;
        snprintf(buf, size, "%.*g", sig < 3 ? 3 : sig > 17 ? 17 : sig, v);
    } else
        snprintf(buf, size, "%.*f", digits > 0 ? digits : 0, v);
}

int svg_tick_offset(long first, long last, double step, double *offset, double *scale)
{
    const double a = (double)first * step, b = (double)last * step;
    *offset = 0.0;
    *scale = 1.0;
    if (!(step > 0.0) || fmax(fabs(a), fabs(b)) < 1e5 * step)
        return 0;
    /* the offset: the ticks' common leading digits, down to the power of ten above their
     * span; the scale: the power of ten of the step */
    const double span = pow(10.0, ceil(log10(b - a + step)));
    *offset = floor(a / span) * span;
    *scale = pow(10.0, floor(log10(step) + 1e-9));
    return 1;
}

int svg_offset_note(FILE *out, double x, double y, const char *anchor, double offset,
                    double scale)
{
    /* the offset to the digit of the scale (no rounding noise of its computation) */
    int digits = offset != 0.0 ? (int)(floor(log10(fabs(offset))) - floor(log10(scale) + 1e-9)) + 1
                               : 1;
    if (digits < 1)
        digits = 1;
    if (digits > 17)
        digits = 17;
    const int e = (int)lround(log10(scale));
    char note[96];
    /* "\xc3\x97" is the multiplication sign and "\xe2\x88\x92" the minus sign in UTF-8 */
    if (offset == 0.0)
        snprintf(note, sizeof note, "\xc3\x97" "1e%d", e);
    else
        snprintf(note, sizeof note, "\xc3\x97" "1e%d %s %.*g", e,
                 offset < 0 ? "\xe2\x88\x92" : "+", digits, fabs(offset));
    return fprintf(out,
                   "<text class=\"offset\" x=\"%.2f\" y=\"%.2f\" text-anchor=\"%s\" "
                   "stroke=\"none\">%s</text>\n",
                   x, y, anchor, note) < 0;
}

int svg_grid_begin(FILE *out)
{
    return fputs("<g class=\"grid\" stroke=\"#e4e4e4\" stroke-width=\"1\">\n", out) < 0;
}

int svg_line(FILE *out, double xa, double ya, double xb, double yb)
{
    return fprintf(out, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", xa, ya, xb,
                   yb) < 0;
}

int svg_frame_and_ticks_begin(FILE *out, double x0, double x1, double y0, double y1)
{
    int bad = fputs("</g>\n", out) < 0;
    bad |= fprintf(out,
                   "<rect class=\"frame\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" "
                   "fill=\"none\" stroke=\"#333\" stroke-width=\"1\"/>\n",
                   x0, y1, x1 - x0, y0 - y1) < 0;
    bad |= fputs("<g class=\"ticks\" font-size=\"12\" fill=\"#333\" stroke=\"#333\">\n", out) < 0;
    return bad;
}

int svg_xtick(FILE *out, double x, double y0, const char *label)
{
    return fprintf(out,
                   "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/><text x=\"%.2f\" "
                   "y=\"%.2f\" text-anchor=\"middle\" stroke=\"none\">%s</text>\n",
                   x, y0, x, y0 + 5, x, y0 + 19, label) < 0;
}

int svg_ytick(FILE *out, double x0, double y, const char *label)
{
    return fprintf(out,
                   "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/><text x=\"%.2f\" "
                   "y=\"%.2f\" text-anchor=\"end\" stroke=\"none\">%s</text>\n",
                   x0 - 5, y, x0, y, x0 - 8, y + 4, label) < 0;
}

int svg_titles(FILE *out, double x0, double x1, double y0, double y1, double w, double h,
               const char *xlabel, const char *ylabel, const char *title)
{
    int bad = fputs("</g>\n", out) < 0;
    bad |= fprintf(out,
                   "<text class=\"xlabel\" x=\"%.2f\" y=\"%.2f\" font-size=\"14\" "
                   "text-anchor=\"middle\">",
                   (x0 + x1) / 2, h - 18) < 0;
    bad |= cli_xml_escaped(out, xlabel);
    bad |= fprintf(out,
                   "</text>\n<text class=\"ylabel\" x=\"0\" y=\"0\" font-size=\"14\" "
                   "text-anchor=\"middle\" transform=\"translate(20 %.2f) rotate(-90)\">",
                   (y0 + y1) / 2) < 0;
    bad |= cli_xml_escaped(out, ylabel);
    bad |= fprintf(out,
                   "</text>\n<text class=\"title\" x=\"%.2f\" y=\"26\" font-size=\"16\" "
                   "text-anchor=\"middle\">",
                   w / 2) < 0;
    bad |= cli_xml_escaped(out, title);
    bad |= fputs("</text>\n", out) < 0;
    return bad;
}
