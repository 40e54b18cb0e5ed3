/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_output.h — what dynkit continue writes (cont_output.c, cont_svg.c): the special
 * points as text, every point as CSV or JSON, the diagram as SVG. */
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

/* The text summary (no output path and no --json, or an output file beside it), the CSV or
 * JSON to output (NULL: none; "-": stdout), JSON on stdout with json, the SVG to svg (NULL:
 * none). Returns CLI_OK or CLI_FAILED (message printed). */
int cont_write_outputs(const cont_view *v, const char *output, int json, const char *svg);

void cont_write_csv(FILE *f, const cont_view *v);
void cont_write_json(FILE *f, const cont_view *v);
void cont_write_text(FILE *f, const cont_view *v);
/* The SVG document; 0 or non-zero when a write failed. */
int cont_write_svg(FILE *f, const cont_view *v);

#endif
