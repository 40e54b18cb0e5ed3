/* SPDX-License-Identifier: BSD-3-Clause */
/* MODEL arguments of the commands: a built-in model's name ("did you mean" for typos), the
 * Brusselator of a chosen size (brusselator:N, built by the library), or a
 * model file: an XPPAUT .ode file (translated to C by dynkit_lang) or a C file that defines
 * dynkit_model() (model.h), both compiled to native code and loaded by dynkit_jit, or a
 * shared object already compiled. A loaded model stays loaded until the tool exits. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "cli.h"
#include "dynkit/ani.h"
#include "dynkit/brusselator.h"
#include "dynkit/jit.h"
#include "dynkit/lang.h"
#include "dynkit/mbs.h"
#include "util/escape.h"
#include "util/out_file.h"

enum { MODEL_FILE_MAX_BYTES = 16 << 20, MAX_LOADED = 16 };

static dyn_jit_model loaded[MAX_LOADED];
static int n_loaded;
/* loaded from a model file with algebraic equations (0=...), for the messages of a failed
 * run: the C text defines the solver's constants */
static unsigned char loaded_algebraic[MAX_LOADED];
static char loaded_path[MAX_LOADED][1024]; /* the file each was loaded from */
/* the C a model file was translated to (a live page compiles it again), NULL for C files */
static char *loaded_c[MAX_LOADED];
static char *pending_c; /* the translation of the model file being loaded */
static int verbose;
/* for the mechanism file opened next: the constraints need not hold at its initial state
 * (--project-init), and lines to read after the file's own (dynkit inverse --prescribe) */
static int mech_unchecked;
static const char *mech_extra;
static int mech_extra_line; /* the first line of mech_extra in the text read, 0: none */

void cli_model_set_unchecked(int on) { mech_unchecked = on; }
void cli_model_set_mech_extra(const char *lines) { mech_extra = lines; }

void cli_set_verbose(int on) { verbose = on; }
int cli_verbose(void) { return verbose; }

static void unload_all(void)
{
    while (n_loaded > 0) {
        dyn_jit_unload(&loaded[--n_loaded]);
        free(loaded_c[n_loaded]);
        loaded_c[n_loaded] = NULL;
    }
}

/* Models built for a size the user chose (brusselator:N), freed at exit. */
static dyn_model *sized[MAX_LOADED];
static int n_sized;

static void free_sized(void)
{
    while (n_sized > 0)
        dyn_brusselator_free(sized[--n_sized]);
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
                               "unknown model '%s' (did you mean '%s'? accepted: %s, "
                               "brusselator:N, or a model file NAME.ode, NAME.mech or NAME.c)",
                               spec, near, list);
    return cli_usage_error(command,
                           "unknown model '%s' (accepted: %s, brusselator:N, or a model file "
                           "NAME.ode, NAME.mech or NAME.c)",
                           spec, list);
}

/* The whole file into a malloc'd, NUL-terminated buffer; NULL with a message printed. */
char *cli_read_model_file(const char *path, size_t *len)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        cli_error("cannot open model file '%s': %s", path, strerror(errno));
        return NULL;
    }
    if (S_ISDIR(st.st_mode)) {
        cli_error("model file '%s' is a directory", path);
        return NULL;
    }
    cli_input_note(path, "the model file");
    FILE *f = fopen(path, "rb");
    if (!f) {
        cli_error("cannot open model file '%s': %s", path, strerror(errno));
        return NULL;
    }
    char *buf = malloc(MODEL_FILE_MAX_BYTES + 1);
    size_t n = buf ? fread(buf, 1, MODEL_FILE_MAX_BYTES + 1, f) : 0;
    const int bad = !buf || ferror(f);
    fclose(f);
    if (bad || n > MODEL_FILE_MAX_BYTES) {
        cli_error("cannot read model file '%s': %s", path,
                !buf                       ? "out of memory"
                : n > MODEL_FILE_MAX_BYTES ? "larger than 16 MiB"
                                           : "read error");
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    if (mech_extra && ends_with(path, ".mech")) {
        const size_t ne = strlen(mech_extra);
        char *all = realloc(buf, n + ne + 2);
        if (!all) {
            free(buf);
            cli_error("out of memory");
            return NULL;
        }
        buf = all;
        if (n && buf[n - 1] != '\n')
            buf[n++] = '\n';
        mech_extra_line = 1;
        for (size_t i = 0; i < n; i++)
            mech_extra_line += buf[i] == '\n';
        memcpy(buf + n, mech_extra, ne + 1);
        n += ne;
    }
    *len = n;
    return buf;
}

static void print_note(const char *path, int line, const char *message, void *ctx)
{
    (void)ctx;
    const size_t w = strlen(DYN_LANG_WARNING);
    char where[1024], shown[4096]; /* control bytes of the file escaped */
    cli_terminal_text(path, 0, where, sizeof where);
    if (strncmp(message, DYN_LANG_WARNING, w) == 0)
        cli_warning("%s:%d: %s", where, line,
                cli_terminal_text(message + w, 0, shown, sizeof shown));
    else if (verbose)
        cli_note("%s:%d: %s", where, line,
                cli_terminal_text(message, 0, shown, sizeof shown));
}

static int compile_failed(const char *what, const char *path, const char *err)
{
    const size_t n = strlen(err);
    cli_error("%s '%s' failed:\n%.*s", what, path, (int)(n && err[n - 1] == '\n' ? n - 1 : n),
              err);
    return CLI_USAGE;
}

/* A mechanism's generated C is straight-line arithmetic: above MECH_CC_MAX_SOURCE the system
 * compiler takes seconds (the bicycle's 158 kB: 3.9 s of CPU time at -O2) where libtcc takes
 * 0.01 s, and libtcc's code is only about 1.3 times slower there (1.57 against 1.24 us per
 * right-hand side; docs/mechanisms.md, "Speed"). So with DYNKIT_JIT unset (or auto) such a
 * source goes to libtcc when it is built in; DYNKIT_JIT=cc keeps the system compiler. */
enum { MECH_CC_MAX_SOURCE = 64 * 1024 };

const dyn_jit_opts *cli_mech_jit_opts(size_t source_len)
{
    static const dyn_jit_opts tcc = {.backend = DYN_JIT_TCC};
    const char *env = getenv("DYNKIT_JIT");
    if (source_len <= MECH_CC_MAX_SOURCE || (env && env[0] && strcmp(env, "auto") != 0) ||
        !dyn_jit_backend_available(DYN_JIT_TCC))
        return NULL;
    return &tcc;
}

static int keep_loaded(const dyn_jit_model *jm, int algebraic, const char *path,
                       const dyn_model **model)
{
    if (n_loaded == 0)
        atexit(unload_all);
    loaded_algebraic[n_loaded] = (unsigned char)algebraic;
    snprintf(loaded_path[n_loaded], sizeof loaded_path[0], "%s", path);
    loaded_c[n_loaded] = pending_c;
    pending_c = NULL;
    loaded[n_loaded++] = *jm;
    *model = jm->model;
    if (jm->note[0]) /* libtcc instead of the compiler, a damaged cache entry replaced */
        cli_note("%s: %s", path, jm->note);
    if (verbose && jm->cached)
        cli_note("%s: loaded from the cache (%s)", path, jm->so_path);
    else if (verbose)
        cli_note("%s: compiled in %.3f s (%s)", path, jm->compile_seconds,
                jm->backend == DYN_JIT_TCC ? "libtcc, in memory" : jm->so_path);
    return CLI_OK;
}

/* The files of --table NAME=FILE, for the next model file opened. */
enum { MAX_TABLE_FILES = 64, MAX_TABLE_NAME = 128 };
static dyn_lang_table_file table_files[MAX_TABLE_FILES];
static char table_names[MAX_TABLE_FILES][MAX_TABLE_NAME];
static int n_table_files;

int cli_model_table_options(const char *command, int argc, char **argv)
{
    n_table_files = 0;
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        const int r = cli_option(argc, argv, &i, "table", &v);
        if (r < 0)
            return cli_usage_error(command, "option --table needs a value: NAME=FILE");
        if (r == 0)
            continue;
        const char *eq = strchr(v, '=');
        if (!eq || eq == v || !eq[1] || (size_t)(eq - v) >= MAX_TABLE_NAME)
            return cli_usage_error(command,
                                   "--table '%s' is not accepted: give NAME=FILE, a table of "
                                   "the model file ('table NAME FILE') and the file to read "
                                   "it from",
                                   v);
        if (n_table_files >= MAX_TABLE_FILES)
            return cli_usage_error(command, "more than %d --table options", MAX_TABLE_FILES);
        snprintf(table_names[n_table_files], MAX_TABLE_NAME, "%.*s", (int)(eq - v), v);
        table_files[n_table_files] = (dyn_lang_table_file){table_names[n_table_files], eq + 1};
        cli_input_note(eq + 1, "a --table file");
        n_table_files++;
    }
    return CLI_OK;
}

static int open_model_file(const char *spec, const dyn_model **model)
{
    dyn_jit_model jm;
    char err[8192];
    if (n_loaded >= MAX_LOADED) {
        cli_error("more than %d model files in one command", MAX_LOADED);
        return CLI_USAGE;
    }
    if (ends_with(spec, ".so")) {
        cli_input_note(spec, "the model file");
        if (dyn_jit_load_shared(spec, &jm, err, sizeof err))
            return compile_failed("loading", spec, err);
        return keep_loaded(&jm, 0, spec, model);
    }
    int rc, algebraic = 0;
    if (ends_with(spec, ".c")) {
        struct stat st;
        const int found = stat(spec, &st) == 0;
        if (!found || S_ISDIR(st.st_mode)) {
            cli_error("cannot open model file '%s': %s", spec,
                    found ? "is a directory" : strerror(errno));
            return CLI_USAGE;
        }
        cli_input_note(spec, "the model file");
        rc = dyn_jit_load_c_file(spec, NULL, &jm, err, sizeof err);
    } else {
        size_t len = 0;
        char *text = cli_read_model_file(spec, &len);
        if (!text)
            return CLI_USAGE;
        char *c_source = NULL;
        dyn_lang_diag diag;
        rc = ends_with(spec, ".mech")
                 ? dyn_mech_to_c_flags(spec, text, len, table_files, n_table_files,
                                       mech_unchecked ? DYN_MECH_UNCHECKED_INIT : 0u,
                                       &c_source, &diag, print_note, NULL)
                 : dyn_ode_to_c_tables(spec, text, len, table_files, n_table_files, &c_source,
                                       &diag, print_note, NULL);
        free(text);
        if (rc != 0) {
            char shown[2048];
            if (mech_extra && mech_extra_line > 0 && diag.line >= mech_extra_line) {
                /* a line of the command's (--prescribe), not of the file */
                snprintf(diag.path, sizeof diag.path, "--prescribe");
                diag.line -= mech_extra_line - 1;
            }
            fputs(dyn_lang_diag_format(&diag, shown, sizeof shown), stderr);
            return rc == 1 ? CLI_FAILED : CLI_USAGE;
        }
        algebraic = strstr(c_source, "#define DK_ALG_M ") != NULL;
        const size_t c_len = strlen(c_source);
        rc = dyn_jit_load_source(c_source, c_len,
                                 spec, ends_with(spec, ".mech") ? cli_mech_jit_opts(c_len) : NULL,
                                 &jm, err, sizeof err);
        free(pending_c);
        pending_c = c_source;
    }
    if (rc != 0) {
        free(pending_c);
        pending_c = NULL;
        return compile_failed("compiling model", spec, err);
    }
    return keep_loaded(&jm, algebraic, spec, model);
}

const char *cli_model_c_source(const dyn_model *m)
{
    for (int i = 0; i < n_loaded; i++)
        if (loaded[i].model == m)
            return loaded_c[i];
    return NULL;
}

char *cli_model_mech_scene_source(const char *path)
{
    if (!ends_with(path, ".mech"))
        return NULL;
    size_t len = 0;
    char *text = cli_read_model_file(path, &len);
    if (!text)
        return NULL;
    char *c_source = NULL;
    dyn_lang_diag diag;
    const unsigned flags =
        DYN_MECH_SCENE_INPUTS | (mech_unchecked ? DYN_MECH_UNCHECKED_INIT : 0u);
    if (dyn_mech_to_c_flags(path, text, len, table_files, n_table_files, flags, &c_source,
                            &diag, NULL, NULL) != 0)
        c_source = NULL;
    free(text);
    return c_source;
}

char *cli_model_ani_source(const char *ode_path, const char *ani_path)
{
    const int mech = ends_with(ode_path, ".mech");
    if (!ends_with(ode_path, ".ode") && !mech)
        return NULL;
    size_t len = 0, ani_len = 0;
    char *text = cli_read_model_file(ode_path, &len);
    char *ani = text ? cli_read_model_file(ani_path, &ani_len) : NULL;
    char *c_source = NULL;
    dyn_lang_diag diag;
    const unsigned flags = mech_unchecked ? DYN_MECH_UNCHECKED_INIT : 0u;
    if (ani && (mech ? dyn_mech_ani_to_c(ode_path, text, len, table_files, n_table_files, flags,
                                         ani_path, ani, ani_len, &c_source, &diag)
                     : dyn_ani_ode_to_c(ode_path, text, len, table_files, n_table_files,
                                        ani_path, ani, ani_len, &c_source, &diag)) != 0)
        c_source = NULL;
    free(text);
    free(ani);
    return c_source;
}

int cli_model_has_algebraic(const dyn_model *m)
{
    for (int i = 0; i < n_loaded; i++)
        if (loaded[i].model == m)
            return loaded_algebraic[i];
    return 0;
}

const char *cli_model_path(const dyn_model *m)
{
    if (m->source)
        return m->source;
    for (int i = 0; i < n_loaded; i++)
        if (loaded[i].model == m)
            return loaded_path[i];
    return NULL;
}

int cli_model_is_file(const char *spec)
{
    return ends_with(spec, ".ode") || ends_with(spec, ".mech") || ends_with(spec, ".c") ||
           ends_with(spec, ".so");
}

/* The Brusselator of size N (dynkit/brusselator.h): "brusselator" (the default N) or
 * "brusselator:N". Returns 1 when spec names it (then *rc is the status), else 0. */
static int open_brusselator(const char *command, const char *spec, const dyn_model **model,
                            int *rc)
{
    static const char name[] = "brusselator";
    const size_t len = sizeof name - 1;
    if (strncmp(spec, name, len) != 0 || (spec[len] != '\0' && spec[len] != ':'))
        return 0;
    long N = DYN_BRUSSELATOR_DEFAULT_N;
    if (spec[len] == ':') {
        const char *digits = spec + len + 1;
        char *end = NULL;
        errno = 0;
        N = strtol(digits, &end, 10);
        if (end == digits || *end != '\0' || errno || N < 1 || N > DYN_BRUSSELATOR_MAX_N) {
            *rc = cli_usage_error(command,
                                  "model '%s': N must be a whole number from 1 to %d, as in "
                                  "brusselator:200 (2N states; brusselator alone: N = %d)",
                                  spec, DYN_BRUSSELATOR_MAX_N, DYN_BRUSSELATOR_DEFAULT_N);
            return 1;
        }
    }
    if (n_sized >= MAX_LOADED) {
        fprintf(stderr, "dynkit: too many models at once (at most %d)\n", MAX_LOADED);
        *rc = CLI_USAGE;
        return 1;
    }
    char err[256];
    dyn_model *m = dyn_brusselator_new((int)N, err, sizeof err);
    if (!m) {
        cli_error("model %s: %s", spec, err);
        *rc = CLI_FAILED;
        return 1;
    }
    if (n_sized == 0)
        atexit(free_sized);
    sized[n_sized++] = m;
    *model = m;
    *rc = CLI_OK;
    return 1;
}

int cli_param_is_size(const dyn_model *m, const char *name)
{
    return m->rhs == dyn_brusselator_rhs && strcmp(name, "N") == 0;
}

int cli_model_open(const char *command, const char *spec, const dyn_model **model)
{
    *model = NULL;
    if (n_table_files > 0 && !ends_with(spec, ".ode") && !ends_with(spec, ".mech"))
        return cli_usage_error(command,
                               "--table %s=%s: '%s' is not a model file NAME.ode (only .ode "
                               "and .mech files read tables from files)",
                               table_files[0].name, table_files[0].path, spec);
    if (cli_model_is_file(spec))
        return open_model_file(spec, model);
    int rc;
    if (open_brusselator(command, spec, model, &rc))
        return rc;
    *model = dyn_model_find(spec);
    return *model ? CLI_OK : unknown_model(command, spec);
}
