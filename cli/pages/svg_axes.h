/* SPDX-License-Identifier: BSD-3-Clause */
/* The parts of an SVG plot's axes that the command line's plots (svg_plot.c, the sweep
 * tables' heat maps of sweep_plot.c) and the benchmark's work-precision diagrams
 * (bench/wp_svg.c) draw alike: grid lines, the frame, ticks at nice steps with their
 * numbers, axis labels and title (their text through escape.h). Positions are in
 * pixels; the plot area is x0..x1 (left to right) by y1..y0 (top to bottom). Each function
 * returns non-zero when a write failed. Only stdio: no part of the library. */
#ifndef DYNKIT_SVG_AXES_H
#define DYNKIT_SVG_AXES_H

#include <stddef.h>
#include <stdio.h>

/* The step between ticks: 1, 2 or 5 times a power of ten, about range / target. */
double svg_nice_step(double range, int target);

/* Tick v (a multiple of step) as text into buf, with no rounding noise
 * (0.30000000000000004) and no "-0": as many decimals as step needs, %.3g for very large or
 * small magnitudes. */
void svg_tick_label(double v, double step, char *buf, size_t size);

/* The offset and scale of an axis whose ticks first*step .. last*step need more than six
 * significant digits to tell apart (an energy conserved to 1e-9 J: 237.453059002,
 * 237.453059004, ...): the ticks are then labelled (v - offset) / scale (0, 2, 4, ...) and
 * the axis carries the note "x1e-9 + 237.453059" (svg_offset_note). Returns 1 with offset
 * and scale set, or 0 when plain labels are short enough (offset 0, scale 1). */
int svg_tick_offset(long first, long last, double step, double *offset, double *scale);
/* The note of an axis with svg_tick_offset's offset and scale, e.g. "×1e-9 + 237.453059",
 * as a text element at (x, y) anchored by anchor ("start", "end"). */
int svg_offset_note(FILE *out, double x, double y, const char *anchor, double offset,
                    double scale);

/* Opens the group of grid lines. */
int svg_grid_begin(FILE *out);

/* One line from (xa, ya) to (xb, yb). */
int svg_line(FILE *out, double xa, double ya, double xb, double yb);

/* Closes the grid, draws the frame around the plot area and opens the group of ticks. */
int svg_frame_and_ticks_begin(FILE *out, double x0, double x1, double y0, double y1);

/* A tick below the x axis (at y0) at x, and one left of the y axis (at x0) at y. */
int svg_xtick(FILE *out, double x, double y0, const char *label);
int svg_ytick(FILE *out, double x0, double y, const char *label);

/* Closes the ticks and writes the axis labels and the title of a w by h picture. */
int svg_titles(FILE *out, double x0, double x1, double y0, double y1, double w, double h,
               const char *xlabel, const char *ylabel, const char *title);

#endif
