/* SPDX-License-Identifier: BSD-3-Clause */
/* MODEL arguments of the commands: a built-in model's name ("did you mean" for typos), or a
 * model file: an XPPAUT .ode file (translated to C by dynkit_lang) or a C file that defines
 * dynkit_model() (model.h), both compiled to native code and loaded by dynkit_jit, or a
 * shared object already compiled. A loaded model stays loaded until the tool exits. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "cli.h"
#include "dynkit/jit.h"
#include "dynkit/lang.h"

enum { MODEL_FILE_MAX_BYTES = 16 << 20, MAX_LOADED = 16 };

static dyn_jit_model loaded[MAX_LOADED];
static int n_loaded;
static int verbose;

void cli_set_verbose(int on) { verbose = on; }
int cli_verbose(void) { return verbose; }

static void unload_all(void)
{
    while (n_loaded > 0)
        dyn_jit_unload(&loaded[--n_loaded]);
}

static int ends_with(const char *s, const char *suffix)
{
    const size_t ls = strlen(s), lx = strlen(suffix);
    return ls > lx && strcasecmp(s + ls - lx, suffix) == 0;
}

static int unknown_model(const char *command, const char *spec)
{
    const char *names[64];
    char list[512];
    const int n = dyn_model_count() < 64 ? dyn_model_count() : 64;
    for (int i = 0; i < n; i++)
        names[i] = dyn_model_at(i)->name;
    const char *near = dyn_lang_nearest(spec, names, n);
    dyn_model_names(list, sizeof list);
    if (near)
        return cli_usage_error(command,
                               "unknown model '%s' (did you mean '%s'? accepted: %s, or a "
                               "model file NAME.ode or NAME.c)",
                               spec, near, list);
    return cli_usage_error(command,
                           "unknown model '%s' (accepted: %s, or a model file NAME.ode or "
                           "NAME.c)",
                           spec, list);
}

/* The whole file into a malloc'd, NUL-terminated buffer; NULL with a message printed. */
static char *read_model_file(const char *path, size_t *len)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        fprintf(stderr, "dynkit: error: cannot open model file '%s': %s\n", path, strerror(errno));
        return NULL;
    }
    if (S_ISDIR(st.st_mode)) {
        fprintf(stderr, "dynkit: error: model file '%s' is a directory\n", path);
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "dynkit: error: cannot open model file '%s': %s\n", path, strerror(errno));
        return NULL;
    }
    char *buf = malloc(MODEL_FILE_MAX_BYTES + 1);
    size_t n = buf ? fread(buf, 1, MODEL_FILE_MAX_BYTES + 1, f) : 0;
    const int bad = !buf || ferror(f);
    fclose(f);
    if (bad || n > MODEL_FILE_MAX_BYTES) {
        fprintf(stderr, "dynkit: error: cannot read model file '%s': %s\n", path,
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

static void print_note(const char *path, int line, const char *message, void *ctx)
{
    (void)ctx;
    if (verbose)
        fprintf(stderr, "dynkit: note: %s:%d: %s\n", path, line, message);
}

static int compile_failed(const char *what, const char *path, const char *err)
{
    fprintf(stderr, "dynkit: error: %s '%s' failed:\n%s%s", what, path, err,
            err[0] && err[strlen(err) - 1] == '\n' ? "" : "\n");
    return CLI_USAGE;
}

static int keep_loaded(const dyn_jit_model *jm, const char *path, const dyn_model **model)
{
    if (n_loaded == 0)
        atexit(unload_all);
    loaded[n_loaded++] = *jm;
    *model = jm->model;
    if (verbose && jm->cached)
        fprintf(stderr, "dynkit: note: %s: loaded from the cache (%s)\n", path, jm->so_path);
    else if (verbose)
        fprintf(stderr, "dynkit: note: %s: compiled in %.3f s (%s)\n", path, jm->compile_seconds,
                jm->backend == DYN_JIT_TCC ? "libtcc, in memory" : jm->so_path);
    return CLI_OK;
}

static int open_model_file(const char *spec, const dyn_model **model)
{
    dyn_jit_model jm;
    char err[8192];
    if (n_loaded >= MAX_LOADED) {
        fprintf(stderr, "dynkit: error: more than %d model files in one command\n", MAX_LOADED);
        return CLI_USAGE;
    }
    if (ends_with(spec, ".so")) {
        if (dyn_jit_load_shared(spec, &jm, err, sizeof err))
            return compile_failed("loading", spec, err);
        return keep_loaded(&jm, spec, model);
    }
    int rc;
    if (ends_with(spec, ".c")) {
        struct stat st;
        const int found = stat(spec, &st) == 0;
        if (!found || S_ISDIR(st.st_mode)) {
            fprintf(stderr, "dynkit: error: cannot open model file '%s': %s\n", spec,
                    found ? "is a directory" : strerror(errno));
            return CLI_USAGE;
        }
        rc = dyn_jit_load_c_file(spec, NULL, &jm, err, sizeof err);
    } else {
        size_t len = 0;
        char *text = read_model_file(spec, &len);
        if (!text)
            return CLI_USAGE;
        char *c_source = NULL;
        dyn_lang_diag diag;
        rc = dyn_ode_to_c(spec, text, len, &c_source, &diag, print_note, NULL);
        free(text);
        if (rc != 0) {
            char shown[2048];
            fputs(dyn_lang_diag_format(&diag, shown, sizeof shown), stderr);
            return rc == 1 ? CLI_FAILED : CLI_USAGE;
        }
        rc = dyn_jit_load_source(c_source, strlen(c_source), spec, NULL, &jm, err, sizeof err);
        free(c_source);
    }
    if (rc != 0)
        return compile_failed("compiling model", spec, err);
    return keep_loaded(&jm, spec, model);
}

int cli_model_is_file(const char *spec)
{
    return ends_with(spec, ".ode") || ends_with(spec, ".c") || ends_with(spec, ".so");
}

int cli_model_open(const char *command, const char *spec, const dyn_model **model)
{
    *model = NULL;
    if (cli_model_is_file(spec))
        return open_model_file(spec, model);
    *model = dyn_model_find(spec);
    return *model ? CLI_OK : unknown_model(command, spec);
}
