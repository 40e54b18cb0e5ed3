/* SPDX-License-Identifier: BSD-3-Clause */
/* The jit layer's public functions (dynkit/jit.h): choice of the backend, loading a C file,
 * loading a shared object, the check of a model. The backends (jit_cc.c, jit_tcc.c) and what
 * they share (jit_check.c, jit_so.c) never call back into this file. */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "jit_internal.h"

/* DYN_JIT_AUTO: $DYNKIT_JIT when set, else the system compiler (*automatic = 1), and libtcc
 * when there is no system compiler and none was named (*fallback = 1). See
 * docs/model-files.md, "Compiling models": the system compiler's code runs up to 3 times
 * faster than libtcc's, its first compilation of a model (about 0.13 s) is within the target,
 * and every later run only loads the cached object. */
static int choose_backend(const dyn_jit_opts *opts, dyn_jit_backend *b, int *automatic,
                          int *fallback, char *err, size_t errlen)
{
    *b = opts ? opts->backend : DYN_JIT_AUTO;
    *fallback = 0;
    *automatic = 0;
    if (*b == DYN_JIT_AUTO) {
        const char *env = getenv("DYNKIT_JIT");
        if (env && env[0] && strcmp(env, "auto") != 0) {
            if (strcmp(env, "cc") == 0)
                *b = DYN_JIT_CC;
            else if (strcmp(env, "tcc") == 0)
                *b = DYN_JIT_TCC;
            else
                return jit_fail(err, errlen,
                                "DYNKIT_JIT=%s is not a compiler backend (accepted: auto, cc, tcc)",
                                env);
        } else {
            *b = DYN_JIT_CC;
            *automatic = dyn_jit_backend_available(DYN_JIT_TCC);
            /* only when no compiler was named: a named one that is missing is an error */
            const char *cc1 = getenv("DYNKIT_CC"), *cc2 = getenv("CC");
            *fallback = *automatic && !(opts && opts->cc) && !(cc1 && cc1[0]) && !(cc2 && cc2[0]);
        }
    }
    if (*b != DYN_JIT_CC && *b != DYN_JIT_TCC)
        return jit_fail(err, errlen, "unknown compiler backend %d", (int)*b);
    if (!dyn_jit_backend_available(*b))
        return jit_fail(err, errlen,
                        "this dynkit was built without libtcc: install libtcc-dev and tcc "
                        "(apt-get install libtcc-dev tcc) and rebuild, or use the system C "
                        "compiler (cc)");
    return 0;
}

/* libtcc instead of the system compiler, with `why` in the model's note */
static int tcc_instead(const char *source, size_t len, const char *source_name,
                       const dyn_jit_opts *opts, const char *why, dyn_jit_model *out, char *err,
                       size_t errlen)
{
    if (jit_tcc_load(source, len, source_name, opts, out, err, errlen) != 0)
        return 1;
    char text[sizeof out->note];
    snprintf(text, sizeof text,
             "%.600s: compiled with libtcc instead, whose code runs up to 3 times slower", why);
    if (out->note[0]) /* why first, then what libtcc said */
        jit_note(text, sizeof text, out->note);
    snprintf(out->note, sizeof out->note, "%s", text);
    return 0;
}

int dyn_jit_load_source(const char *source, size_t len, const char *source_name,
                        const dyn_jit_opts *opts, dyn_jit_model *out, char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    memset(out, 0, sizeof *out);
    if (!source)
        return jit_fail(err, errlen, "no source to compile");
    if (memchr(source, '\0', len))
        return jit_fail(err, errlen, "%s: not a C source (contains a NUL byte)",
                        source_name ? source_name : "model");
    dyn_jit_backend b;
    int automatic, fallback;
    if (choose_backend(opts, &b, &automatic, &fallback, err, errlen) != 0)
        return 1;
    if (b == DYN_JIT_TCC)
        return jit_tcc_load(source, len, source_name, opts, out, err, errlen);
    char why[600];
    if (automatic && len > JIT_CC_MAX_SOURCE) { /* minutes and gigabytes for cc */
        snprintf(why, sizeof why,
                 "the generated C is %.1f MiB, more than the %u MiB given to the system C "
                 "compiler (DYNKIT_JIT=cc gives it anyway, at -O0)",
                 (double)len / (1 << 20), JIT_CC_MAX_SOURCE >> 20);
        return tcc_instead(source, len, source_name, opts, why, out, err, errlen);
    }
    int rc = jit_cc_load(source, len, source_name, opts, out, err, errlen);
    if (rc == 2 && fallback) /* no system compiler: libtcc */
        return jit_tcc_load(source, len, source_name, opts, out, err, errlen);
    if ((rc == 3 || rc == JIT_UNWRITABLE) && automatic) {
        /* the compiler's time limit, or a cache that cannot be written: named in out->note */
        snprintf(why, sizeof why, "%.500s", out->note);
        return tcc_instead(source, len, source_name, opts, why, out, err, errlen);
    }
    return rc != 0;
}

int dyn_jit_load_c_file(const char *path, const dyn_jit_opts *opts, dyn_jit_model *out, char *err,
                        size_t errlen)
{
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "rb");
    if (!f)
        return jit_fail(err, errlen, "cannot open %s: %s", path, strerror(errno));
    size_t cap = 1 << 16, len = 0;
    char *text = malloc(cap);
    for (;;) {
        if (!text) {
            fclose(f);
            return jit_fail(err, errlen, "%s: out of memory", path);
        }
        len += fread(text + len, 1, cap - len, f);
        if (len < cap)
            break;
        char *bigger = realloc(text, cap *= 2);
        if (!bigger)
            free(text);
        text = bigger;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(text);
        return jit_fail(err, errlen, "cannot read %s", path);
    }
    int rc = dyn_jit_load_source(text, len, path, opts, out, err, errlen);
    free(text);
    return rc;
}

int dyn_jit_check_model(const dyn_model *m, const char *where, char *err, size_t errlen)
{
    return jit_check_model(m, where ? where : "model", err, errlen);
}

/* ---- shared objects ---- */

static const char *base_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

int dyn_jit_load_shared(const char *path, dyn_jit_model *out, char *err, size_t errlen)
{
    return jit_load_so(path, -1, base_name(path), out, err, errlen);
}

void dyn_jit_unload(dyn_jit_model *m)
{
    if (!m || !m->handle) {
        if (m)
            m->model = NULL;
        return;
    }
    if (m->backend == DYN_JIT_TCC)
        jit_tcc_unload(m->handle);
    else
        jit_so_unload(m->handle);
    m->handle = NULL;
    m->model = NULL;
}
