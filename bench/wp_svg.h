/* SPDX-License-Identifier: BSD-3-Clause */
/* wp_svg.h — work-precision diagrams as standalone SVG: log-log axes with ticks at the powers
 * of ten, one line with markers per solver, in the look of the command line's plots
 * (cli/pages/svg_plot.c: same size, fonts, frame, grid and line colours).
 */
#ifndef DYNKIT_BENCH_WP_SVG_H
#define DYNKIT_BENCH_WP_SVG_H

#include <stdio.h>

#define WP_SVG_MAX_LINES 16

typedef struct wp_line {
    const char *label;
    int n;
    const double *x, *y; /* (n) positive values; others are skipped */
    int emphasis;        /* 1: solid and wider (dynkit's methods); 0: dashed (the peers) */
} wp_line;

typedef struct wp_plot {
    const char *title;
    const char *xlabel, *ylabel;
    int n_lines;
    wp_line lines[WP_SVG_MAX_LINES];
} wp_plot;

/* Writes the plot as an SVG document; returns 0, or non-zero on a write error. */
int wp_svg_write(FILE *out, const wp_plot *p);

#endif
