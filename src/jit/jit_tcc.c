/* SPDX-License-Identifier: BSD-3-Clause */
/* The libtcc backend of the jit layer: the model's source compiled in process into memory
 * (nothing written to disk but the embedded headers, once, into the cache's include
 * directory, or put into the text when the cache cannot be written: jit_inline.c), relocated,
 * and its entry point called. libtcc is not re-entrant: one
 * compilation at a time (a mutex). Calls into dynkit from the model are resolved in the
 * running program (libtcc looks undefined symbols up with dlsym). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jit_internal.h"

#ifdef DYNKIT_HAVE_TCC
#include <libtcc.h>
#include <pthread.h>

#ifndef DYNKIT_TCC_LIB_DIR
#define DYNKIT_TCC_LIB_DIR "/usr/lib/x86_64-linux-gnu/tcc"
#endif

static pthread_mutex_t tcc_lock = PTHREAD_MUTEX_INITIALIZER;

/* libtcc's diagnostics, one per line */
typedef struct messages {
    char text[16384];
    size_t len;
} messages;

static void on_message(void *opaque, const char *msg)
{
    messages *m = opaque;
    size_t n = strlen(msg);
    if (m->len + n + 2 > sizeof m->text)
        return;
    memcpy(m->text + m->len, msg, n);
    m->len += n;
    m->text[m->len++] = '\n';
    m->text[m->len] = '\0';
}

static int fail_with(char *err, size_t errlen, const char *what, const char *where,
                     const messages *m)
{
    if (m->len > 0) {
        /* the diagnostics name the user's file and line (#line); cut at a line end */
        size_t keep = m->len;
        if (errlen > 0 && keep >= errlen) {
            keep = errlen - 1;
            while (keep > 0 && m->text[keep] != '\n')
                keep--;
        }
        while (keep > 0 && m->text[keep - 1] == '\n')
            keep--;
        return jit_fail(err, errlen, "%.*s", (int)keep, m->text);
    }
    return jit_fail(err, errlen, "%s %s failed (libtcc gave no message)", what, where);
}

int jit_tcc_load(const char *source, size_t len, const char *source_name, const dyn_jit_opts *opts,
                 dyn_jit_model *out, char *err, size_t errlen)
{
    const char *where = source_name && source_name[0] ? source_name : "model.c";
    char cache[1024], inc[1100] = "", note[sizeof out->note] = "";
    int rc = jit_cache_dir(opts, cache, sizeof cache, err, errlen);
    if (rc == 0)
        rc = jit_include_dir(cache, inc, sizeof inc, note, sizeof note, err, errlen);
    if (rc == JIT_UNWRITABLE) { /* the headers in the text instead of a directory */
        char why[sizeof out->note];
        snprintf(why, sizeof why, "%s: the headers were given to libtcc in memory", err);
        jit_note(note, sizeof note, why);
        inc[0] = '\0';
    } else if (rc != 0) {
        return 1;
    }
    char *text = jit_source_with_line(source, len, where, NULL);
    if (text && !inc[0]) {
        char *whole = jit_headers_inline(text);
        free(text);
        text = whole;
    }
    messages *msgs = calloc(1, sizeof *msgs);
    if (!text || !msgs) {
        free(text);
        free(msgs);
        return jit_fail(err, errlen, "out of memory");
    }

    rc = 0;
    double t_start = jit_now();
    pthread_mutex_lock(&tcc_lock);
    TCCState *s = tcc_new();
    if (!s) {
        rc = jit_fail(err, errlen, "libtcc: cannot create a compiler state");
        goto done;
    }
    tcc_set_error_func(s, msgs, on_message);
    const char *lib_dir = getenv("DYNKIT_TCC_LIB_DIR");
    tcc_set_lib_path(s, lib_dir && lib_dir[0] ? lib_dir : DYNKIT_TCC_LIB_DIR);
    if (inc[0])
        tcc_add_include_path(s, inc);
    tcc_set_output_type(s, TCC_OUTPUT_MEMORY);
    if (tcc_compile_string(s, text) < 0) {
        rc = fail_with(err, errlen, "compiling", where, msgs);
        goto done;
    }
    tcc_add_library(s, "m");
    if (tcc_relocate(s, TCC_RELOCATE_AUTO) < 0) {
        if (strstr(msgs->text, "undefined symbol"))
            on_message(msgs, "(a function the model calls is neither in it, nor in libm, nor "
                             "exported by this program: a program that loads models links "
                             "dynkit with ENABLE_EXPORTS / -rdynamic, or links libdynkit.so)");
        rc = fail_with(err, errlen, "linking", where, msgs);
        goto done;
    }
    void *sym = tcc_get_symbol(s, DYN_MODEL_ENTRY);
    if (!sym) {
        rc = jit_fail(err, errlen,
                      "%s does not define the entry point %s() (model.h: "
                      "const dyn_model *dynkit_model(void))",
                      where, DYN_MODEL_ENTRY);
        goto done;
    }
    double seconds = jit_now() - t_start;
    pthread_mutex_unlock(&tcc_lock);

    dyn_model_entry_fn entry;
    memcpy(&entry, &sym, sizeof entry);
    const dyn_model *m = entry();
    if (jit_check_model(m, where, err, errlen) != 0) {
        pthread_mutex_lock(&tcc_lock);
        tcc_delete(s);
        pthread_mutex_unlock(&tcc_lock);
        free(text);
        free(msgs);
        return 1;
    }
    out->model = m;
    out->handle = s;
    out->backend = DYN_JIT_TCC;
    out->cached = 0;
    out->compile_seconds = seconds;
    out->so_path[0] = '\0';
    snprintf(out->note, sizeof out->note, "%s", note);
    free(text);
    free(msgs);
    return 0;

done:
    if (s)
        tcc_delete(s);
    pthread_mutex_unlock(&tcc_lock);
    free(text);
    free(msgs);
    return rc;
}

void jit_tcc_unload(void *handle)
{
    pthread_mutex_lock(&tcc_lock);
    tcc_delete(handle);
    pthread_mutex_unlock(&tcc_lock);
}

#else /* no libtcc */

int jit_tcc_load(const char *source, size_t len, const char *source_name, const dyn_jit_opts *opts,
                 dyn_jit_model *out, char *err, size_t errlen)
{
    (void)source, (void)len, (void)source_name, (void)opts, (void)out;
    return jit_fail(err, errlen, "this dynkit was built without libtcc");
}

void jit_tcc_unload(void *handle) { (void)handle; }

#endif
