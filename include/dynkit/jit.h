/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/jit.h — C source to a loaded dyn_model: the system C compiler into a cached shared
 * object (content-addressed, safe when several runs start at once) or libtcc in process,
 * and loading with a check of the model ABI (DYN_MODEL_ABI, model.h).
 *
 * Part of the optional layer `dynkit_jit` (needs dlopen, and libtcc when built with it);
 * never prints or exits.
 */
#ifndef DYNKIT_JIT_H
#define DYNKIT_JIT_H

#include <stddef.h>

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum dyn_jit_backend {
    DYN_JIT_AUTO = 0, /* the default chosen from measurements (docs/model-files.md) */
    DYN_JIT_CC = 1,   /* the system C compiler ($DYNKIT_CC, else $CC, else cc) into a cache */
    DYN_JIT_TCC = 2   /* libtcc, in process, nothing written to disk but the headers */
} dyn_jit_backend;

typedef struct dyn_jit_opts {
    dyn_jit_backend backend;
    const char *cache_dir;  /* NULL: $DYNKIT_CACHE_DIR, else $XDG_CACHE_HOME/dynkit, else
                             * ~/.cache/dynkit */
    const char *cc;         /* NULL: $DYNKIT_CC, else $CC, else "cc" */
    const char *cflags;     /* NULL: $DYNKIT_CFLAGS, else "-O2" (-O1 above 256 KiB of source,
                             * -O0 above 1 MiB), plus what a shared object needs, and
                             * -ffp-contract=off before them */
    double cc_timeout;      /* seconds the system compiler may take (it is then stopped);
                             * 0: $DYNKIT_CC_TIMEOUT, else 60 */
} dyn_jit_opts;
/* DYN_JIT_AUTO reads $DYNKIT_JIT (auto, cc or tcc) first; it compiles with libtcc (when
 * built in) a source larger than 1 MiB, and one the system compiler did not finish within
 * its time limit, and says so in dyn_jit_model.note. The cache holds
 * include-<version>-<hash>/ (dynkit's public headers, embedded in the library, written once)
 * and NAME-<hash>.so, one per (source, source name, dynkit version, DYN_MODEL_ABI, headers,
 * compiler command and flags); it is never pruned: removing it is always safe. What is read
 * from it is checked first (owner, mode, the SHA-256 an object ends with): another user's
 * entry is refused, a damaged object compiled again (docs/model-files.md, "The cache"). */

/* A loaded model: model points into the compiled code, valid until dyn_jit_unload. */
typedef struct dyn_jit_model {
    const dyn_model *model;
    void *handle;           /* dlopen handle or TCCState */
    int backend;            /* the backend used (DYN_JIT_CC or DYN_JIT_TCC) */
    int cached;             /* 1: the shared object came from the cache, no compilation */
    double compile_seconds; /* time spent compiling (0 when cached) */
    char so_path[1024];     /* the shared object loaded (cc), "" for tcc */
    char note[1024];        /* for the user, "" when nothing: libtcc used instead of the
                             * system compiler and why, a damaged cache entry replaced */
} dyn_jit_model;

/* Compile C source (len bytes) that defines dynkit_model() (model.h) and load it.
 * source_name names it in messages (the user's file). opts may be NULL. Returns 0, or
 * non-zero with a message in err: the compiler's own diagnostics (which point at the
 * user's lines through #line directives), a missing compiler, an ABI mismatch. */
int dyn_jit_load_source(const char *source, size_t len, const char *source_name,
                        const dyn_jit_opts *opts, dyn_jit_model *out, char *err,
                        size_t errlen);
/* The same for a C file on disk (read, then dyn_jit_load_source). */
int dyn_jit_load_c_file(const char *path, const dyn_jit_opts *opts, dyn_jit_model *out,
                        char *err, size_t errlen);
/* Load an already compiled shared object that defines dynkit_model and dynkit_model_abi;
 * refused with a clear message when the ABI differs or the symbols are missing. */
int dyn_jit_load_shared(const char *path, dyn_jit_model *out, char *err, size_t errlen);
/* Release a loaded model (its dyn_model is invalid afterwards). */
void dyn_jit_unload(dyn_jit_model *m);

/* The cache directory opts selects (see dyn_jit_opts) into buf, not created; 0, or non-zero
 * when there is none (no HOME) or it does not fit. */
int dyn_jit_cache_dir(const dyn_jit_opts *opts, char *buf, size_t size);
/* 1 when the backend is built in (DYN_JIT_TCC needs libtcc at build time), else 0. */
int dyn_jit_backend_available(dyn_jit_backend backend);
/* "auto", "cc", "tcc" */
const char *dyn_jit_backend_name(int backend);
/* The checks a loaded model passes (entry point returned non-NULL, n_states > 0, rhs, names,
 * arrays present for their counts, parameters inside par_size, a finite default run): 0, or
 * non-zero with a message naming `where`. */
int dyn_jit_check_model(const dyn_model *m, const char *where, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_JIT_H */
