/* SPDX-License-Identifier: BSD-3-Clause */
/* The growing store of a run's samples for the bindings (samples.h). */
#include "samples.h"

#include <stdlib.h>
#include <string.h>

int dkb_samples_add(dkb_samples *s, double t, const double *y, const double *out)
{
    if (s->count == s->cap) {
        const long cap = s->cap ? 2 * s->cap : 256;
        double *nt = realloc(s->t, (size_t)cap * sizeof *nt);
        if (nt)
            s->t = nt;
        double *ny = realloc(s->y, (size_t)cap * (size_t)s->n * sizeof *ny + 1);
        if (ny)
            s->y = ny;
        double *no = s->n_out ? realloc(s->out, (size_t)cap * (size_t)s->n_out * sizeof *no)
                              : NULL;
        if (no)
            s->out = no;
        if (!nt || !ny || (s->n_out && !no))
            return 1;
        s->cap = cap;
    }
    s->t[s->count] = t;
    memcpy(s->y + (size_t)s->count * (size_t)s->n, y, (size_t)s->n * sizeof *y);
    if (s->n_out)
        memcpy(s->out + (size_t)s->count * (size_t)s->n_out, out,
               (size_t)s->n_out * sizeof *out);
    s->count++;
    return 0;
}

void dkb_samples_free(dkb_samples *s)
{
    free(s->t);
    free(s->y);
    free(s->out);
    memset(s, 0, sizeof *s);
}
