/* SPDX-License-Identifier: BSD-3-Clause */
/* Opening a model for the bindings (model_open.h): the public APIs of the library
 * (dyn_model_find, dyn_brusselator_named), dynkit_lang (dyn_ode_to_c_tables,
 * dyn_mech_to_c) and dynkit_jit (dyn_jit_load_source, dyn_jit_load_c_file,
 * dyn_jit_load_shared), with the command line's rules: files up to 16 MiB, a mechanism's
 * large generated C to libtcc when it is built in. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "dynkit/brusselator.h"
#include "dynkit/lang.h"
#include "dynkit/mbs.h"
#include "model_open.h"

enum { MODEL_FILE_MAX_BYTES = 16 << 20, MECH_CC_MAX_SOURCE = 64 * 1024 };

static int ends_with(const char *s, const char *suffix)
{
    const size_t ls = strlen(s), lx = strlen(suffix);
    return ls > lx && strcasecmp(s + ls - lx, suffix) == 0;
}

char *dkb_read_file(const char *path, size_t *len, char *err, size_t errlen)
{
    struct stat st;
    if (stat(path, &st) != 0 || S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "cannot open model file '%s': %s", path,
                 S_ISDIR(st.st_mode) ? "is a directory" : strerror(errno));
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "cannot open model file '%s': %s", path, strerror(errno));
        return NULL;
    }
    char *buf = malloc(MODEL_FILE_MAX_BYTES + 1);
    const size_t n = buf ? fread(buf, 1, MODEL_FILE_MAX_BYTES + 1, f) : 0;
    const int bad = !buf || ferror(f);
    fclose(f);
    if (bad || n > MODEL_FILE_MAX_BYTES) {
        snprintf(err, errlen, "cannot read model file '%s': %s", path,
                 !buf                       ? "out of memory"
                 : n > MODEL_FILE_MAX_BYTES ? "larger than 16 MiB"
                                            : "read error");
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

typedef struct warn_ctx {
    dkb_warn_fn warn;
    void *ctx;
} warn_ctx;

static void on_note(const char *path, int line, const char *message, void *ctx)
{
    const warn_ctx *w = ctx;
    const size_t k = strlen(DYN_LANG_WARNING);
    if (!w->warn || strncmp(message, DYN_LANG_WARNING, k) != 0)
        return;
    char text[1024];
    snprintf(text, sizeof text, "%s:%d: %s", path, line, message + k);
    w->warn(text, w->ctx);
}

static int open_file(const char *spec, dkb_model *out, warn_ctx *w, char *err, size_t errlen)
{
    if (ends_with(spec, ".so"))
        return dyn_jit_load_shared(spec, &out->jit, err, errlen);
    if (ends_with(spec, ".c"))
        return dyn_jit_load_c_file(spec, NULL, &out->jit, err, errlen);
    size_t len = 0;
    char *text = dkb_read_file(spec, &len, err, errlen);
    if (!text)
        return 1;
    char *c_source = NULL;
    dyn_lang_diag diag;
    const int mech = ends_with(spec, ".mech");
    int rc = mech ? dyn_mech_to_c(spec, text, len, NULL, 0, &c_source, &diag, on_note, w)
                  : dyn_ode_to_c_tables(spec, text, len, NULL, 0, &c_source, &diag, on_note, w);
    free(text);
    if (rc != 0) {
        dyn_lang_diag_format(&diag, err, errlen);
        const size_t n = strlen(err);
        if (n > 0 && err[n - 1] == '\n')
            err[n - 1] = '\0';
        return rc;
    }
    const size_t c_len = strlen(c_source);
    static const dyn_jit_opts tcc = {.backend = DYN_JIT_TCC};
    const dyn_jit_opts *opts = mech && c_len > MECH_CC_MAX_SOURCE &&
                                       dyn_jit_backend_available(DYN_JIT_TCC)
                                   ? &tcc
                                   : NULL;
    rc = dyn_jit_load_source(c_source, c_len, spec, opts, &out->jit, err, errlen);
    free(c_source);
    return rc;
}

int dkb_model_open(const char *spec, dkb_model *out, dkb_warn_fn warn, void *warn_ctx_,
                   char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!spec || !spec[0]) {
        snprintf(err, errlen, "no model given: a built-in model's name or a model file");
        return 1;
    }
    const dyn_model *m = dyn_model_find(spec);
    if (m) {
        out->model = m;
        return 0;
    }
    if (strncmp(spec, "brusselator:", 12) == 0) {
        out->sized = dyn_brusselator_new(atoi(spec + 12), err, errlen);
        out->model = out->sized;
        return out->sized ? 0 : 1;
    }
    if (!ends_with(spec, ".ode") && !ends_with(spec, ".mech") && !ends_with(spec, ".c") &&
        !ends_with(spec, ".so")) {
        char names[512];
        snprintf(err, errlen,
                 "unknown model '%s' (accepted: %s, brusselator:N, or a model file NAME.ode, "
                 "NAME.mech or NAME.c)",
                 spec, dyn_model_names(names, sizeof names));
        return 1;
    }
    warn_ctx w = {warn, warn_ctx_};
    if (open_file(spec, out, &w, err, errlen)) {
        memset(out, 0, sizeof *out);
        return 1;
    }
    out->model = out->jit.model;
    snprintf(out->path, sizeof out->path, "%s", spec);
    return 0;
}

void dkb_model_close(dkb_model *m)
{
    if (m->jit.model)
        dyn_jit_unload(&m->jit);
    if (m->sized)
        dyn_brusselator_free(m->sized);
    memset(m, 0, sizeof *m);
}

void *dkb_model_params(const dyn_model *m, char *err, size_t errlen)
{
    void *par = calloc(1, m->par_size > 0 ? m->par_size : 1);
    if (!par) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    if (dyn_model_default_params(m, par, err, errlen)) {
        free(par);
        return NULL;
    }
    return par;
}
