/* SPDX-License-Identifier: BSD-3-Clause */
/* Opening a model by name or path for the bindings (Python, MEX): a built-in model, the
 * Brusselator of a chosen size (brusselator:N), or a model file — an XPPAUT .ode file or a
 * mechanism (.mech), translated to C by dynkit_lang, a C file that defines dynkit_model(),
 * or a compiled shared object — loaded by dynkit_jit, as `dynkit run MODEL` opens it. */
#ifndef DYNKIT_BINDINGS_MODEL_OPEN_H
#define DYNKIT_BINDINGS_MODEL_OPEN_H

#include <stddef.h>

#include "dynkit/jit.h"
#include "dynkit/model.h"

typedef struct dkb_model {
    const dyn_model *model;
    dyn_jit_model jit;      /* a loaded model file (jit.model != NULL), else unused */
    dyn_model *sized;       /* brusselator:N (owned), else NULL */
    char path[1024];        /* the file, "" for a built-in model */
} dkb_model;

/* A warning of the translation (a line of the file left out), for the caller to show. */
typedef void (*dkb_warn_fn)(const char *message, void *ctx);

/* Open spec into out: 0, or non-zero with the reason (FILE:LINE:COL for a file's error) in
 * err. Close with dkb_model_close. */
int dkb_model_open(const char *spec, dkb_model *out, dkb_warn_fn warn, void *warn_ctx,
                   char *err, size_t errlen);
void dkb_model_close(dkb_model *m);

/* A model file's text (malloc'd, NUL-terminated, *len bytes, at most 16 MiB), or NULL with
 * the reason in err. */
char *dkb_read_file(const char *path, size_t *len, char *err, size_t errlen);

/* The parameter struct of m with its defaults and prepared (malloc'd, m->par_size bytes at
 * least one), or NULL with the reason in err. */
void *dkb_model_params(const dyn_model *m, char *err, size_t errlen);

#endif /* DYNKIT_BINDINGS_MODEL_OPEN_H */
