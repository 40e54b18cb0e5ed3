/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_output.h — what dynkit continue writes (cont_output.c, cont_svg.c, cont_page.c): the
 * special points as text, every point as CSV or JSON, the diagram as SVG and as a page. */
#ifndef DYNKIT_CLI_CONT_OUTPUT_H
#define DYNKIT_CLI_CONT_OUTPUT_H

#include <stdio.h>

#include "cont_settings.h"

typedef struct cont_view {
    const dyn_model *m;
    const void *par;       /* the parameters' base values */
    const dyn_diagram *d;
    const cont_settings *s;
    int iy;                /* the state on the SVG's y axis */
} cont_view;

/* The periodic points whose orbits a page holds: the branch's index in d->branches and the
 * point's index on it. */
typedef struct cont_orbit_ref {
    int branch;
    long point;
} cont_orbit_ref;

typedef struct cont_orbit_set {
    cont_orbit_ref *refs; /* (count), owned */
    long count;
    long computed;        /* periodic points with an orbit in the diagram */
} cont_orbit_set;

/* The outputs of one computation: the text summary on standard output when nothing else is
 * asked for there or in a file; JSON on stdout with json; output (NULL: none; "-" or
 * "-.EXT": stdout) as CSV, JSON, SVG or a page by its extension; svg and html (NULL: none)
 * the diagram as SVG and as a page. Returns CLI_OK or CLI_FAILED (message printed). */
int cont_write_outputs(const cont_view *v, const char *output, int json, const char *svg,
                       const char *html);

void cont_write_csv(FILE *f, const cont_view *v);
void cont_write_json(FILE *f, const cont_view *v);
void cont_write_text(FILE *f, const cont_view *v);
/* The SVG document, marks (NULL: none) the periodic points drawn as dots for the page; 0 or
 * non-zero when a write failed. */
int cont_write_svg(FILE *f, const cont_view *v, const cont_orbit_set *marks);

/* The page (cont_page.c): the SVG with the orbits' dots, and the orbits of the periodic
 * points (every one up to CONT_PAGE_NUMBERS numbers of 5 digits, about 250 kB; else the
 * labelled ones and every k-th other), shown when a dot is clicked. CLI_OK or CLI_FAILED
 * (message printed). */
#define CONT_PAGE_NUMBERS 30000L
int cont_write_page(FILE *f, const cont_view *v);
/* The orbits a page holds (out->refs freed by the caller); 0, or -1 when out of memory. */
int cont_orbits_pick(const dyn_diagram *d, long budget, cont_orbit_set *out);

#endif
