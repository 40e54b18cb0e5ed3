/* SPDX-License-Identifier: BSD-3-Clause */
/* Live pages (`animate --live`, `plot --live`): the model's C (a model file's translation,
 * a C model's file, or a few lines naming a built-in model) compiled to WebAssembly with
 * clang --target=wasm32-wasi and linked with the core library built for it
 * (backends/wasm: libdynkit.a, live_run.o), then written into the page as base64 with the
 * settings of the run, which web/js/live.js turns into controls and reruns. Where the
 * toolchain or the library is missing the page stays static and the reason is given.
 * docs/web.md, "Live pages". */
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "dynkit/run.h"
#include "pages/pages.h"

extern char **environ;

#define LIVE_PACKAGES "clang lld wasi-libc libclang-rt-14-dev-wasm32"

static int is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The folder of the library for wasm32 (libdynkit.a, live_run.o, include/) into dir. */
static int find_wasm_dir(char *dir, size_t size)
{
    char probe[1400], exe[900];
    const char *env = getenv("DYNKIT_WASM_DIR");
    if (env && env[0]) {
        snprintf(dir, size, "%s", env);
        snprintf(probe, sizeof probe, "%s/libdynkit.a", dir);
        return is_file(probe) ? 0 : -1;
    }
    const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash)
            *slash = '\0';
        /* the build tree (build/dynkit beside build/wasm32), then the installed layout */
        static const char *const rel[] = {"wasm32", "../lib/dynkit/wasm32",
#ifdef DYNKIT_WASM_REL_DIR
                                          DYNKIT_WASM_REL_DIR,
#endif
                                          NULL};
        for (int i = 0; rel[i]; i++) {
            snprintf(probe, sizeof probe, "%s/%s/libdynkit.a", exe, rel[i]);
            if (is_file(probe)) {
                if ((size_t)snprintf(dir, size, "%s/%s", exe, rel[i]) >= size)
                    return -1;
                return 0;
            }
        }
    }
#ifdef DYNKIT_WASM_INSTALL_DIR
    snprintf(probe, sizeof probe, "%s/libdynkit.a", DYNKIT_WASM_INSTALL_DIR);
    if (is_file(probe)) {
        snprintf(dir, size, "%s", DYNKIT_WASM_INSTALL_DIR);
        return 0;
    }
#endif
    return -1;
}

static const char *wasm_cc(void)
{
    const char *env = getenv("DYNKIT_WASM_CC");
    if (env && env[0])
        return env;
#ifdef DYNKIT_WASM_CC
    return DYNKIT_WASM_CC;
#else
    return "clang";
#endif
}

/* The model's C: its file's translation, a C model's file, or a function returning the
 * built-in model; malloc'd, or NULL with the reason in why. */
static char *model_source(const dyn_model *m, char *why, size_t size, int *scene_inputs)
{
    const char *path = cli_model_path(m);
    char *scene = path ? cli_model_mech_scene_source(path) : NULL;
    if (scene) { /* a mechanism: its scene's inputs too, to draw the page's runs */
        *scene_inputs = 1;
        return scene;
    }
    const char *c = cli_model_c_source(m);
    if (c)
        return strdup(c);
    if (path) {
        const size_t n = strlen(path);
        if (n < 2 || strcmp(path + n - 2, ".c") != 0) {
            snprintf(why, size, "a compiled model (.so) has no C to compile for the page");
            return NULL;
        }
        size_t len = 0;
        char *text = cli_read_model_file(path, &len);
        if (!text)
            snprintf(why, size, "cannot read %s", path);
        return text;
    }
    for (int i = 0; i < dyn_model_count(); i++)
        if (dyn_model_at(i) == m) {
            char *text = malloc(160);
            if (text)
                snprintf(text, 160,
                         "#include <dynkit/model.h>\n"
                         "const dyn_model *dynkit_model(void) { return dyn_model_at(%d); }\n",
                         i);
            return text;
        }
    snprintf(why, size, "model %s is built by the tool for its size and has no C of its own",
             m->name);
    return NULL;
}

static int write_file(const char *path, const char *text, size_t len)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    const int bad = fwrite(text, 1, len, f) != len;
    return fclose(f) != 0 || bad ? -1 : 0;
}

static unsigned char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    unsigned char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? 2 * cap : 1 << 16;
            unsigned char *grown = realloc(buf, cap);
            if (!grown) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = grown;
        }
        const size_t r = fread(buf + n, 1, cap - n, f);
        n += r;
        if (r == 0)
            break;
    }
    fclose(f);
    *len = n;
    return buf;
}

/* clang with argv, its diagnostics into log; the exit status, or -1 when it did not start. */
static int run_compiler(char *const argv[], const char *log)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, log, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    pid_t pid;
    const int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0)
        return -1;
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 256;
}

static void remove_dir(const char *dir)
{
    static const char *const names[] = {"model.c", "model.wasm", "cc.log"};
    char path[1200];
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        unlink(path);
    }
    rmdir(dir);
}

static void json_base64(cli_json *j, const unsigned char *p, size_t n);
static void json_module(cli_json *j, const cli_live *live);

/* The C source (taken and freed) compiled with the library for wasm32 into out. */
static int build_source(char *source, cli_live *out)
{
    char dir[1024];
    if (find_wasm_dir(dir, sizeof dir - 32) != 0) {
        const char *env = getenv("DYNKIT_WASM_DIR");
        if (env && env[0])
            snprintf(out->why, sizeof out->why,
                     "DYNKIT_WASM_DIR=%s has no libdynkit.a (the WebAssembly library that %s "
                     "make when dynkit is built)",
                     env, LIVE_PACKAGES);
        else
            snprintf(out->why, sizeof out->why,
                     "dynkit was built without the WebAssembly library (install %s and build "
                     "dynkit again)",
                     LIVE_PACKAGES);
        free(source);
        return -1;
    }
    const char *tmp = getenv("TMPDIR");
    char work[1024];
    if ((size_t)snprintf(work, sizeof work, "%s/dynkit-live-XXXXXX", tmp && tmp[0] ? tmp : "/tmp") >=
        sizeof work - 32)
        snprintf(work, sizeof work, "/tmp/dynkit-live-XXXXXX");
    if (!mkdtemp(work)) {
        snprintf(out->why, sizeof out->why, "cannot make a temporary folder: %s",
                 strerror(errno));
        free(source);
        return -1;
    }
    char c_path[1100], wasm_path[1100], log_path[1100], inc[1100], lib[1100], obj[1100];
    snprintf(c_path, sizeof c_path, "%s/model.c", work);
    snprintf(wasm_path, sizeof wasm_path, "%s/model.wasm", work);
    snprintf(log_path, sizeof log_path, "%s/cc.log", work);
    snprintf(inc, sizeof inc, "-I%s/include", dir);
    snprintf(lib, sizeof lib, "%s/libdynkit.a", dir);
    snprintf(obj, sizeof obj, "%s/live_run.o", dir);
    int rc = write_file(c_path, source, strlen(source));
    free(source);
    if (rc == 0) {
        char cc[512];
        snprintf(cc, sizeof cc, "%s", wasm_cc());
        /* wasi-libc's printf family without long double reports that lack on stderr, which
         * brings in its stdio and three imports of the system interface; the family with long
         * double (formatted in software) needs none: the module's one import is the
         * page's dynkit.progress (backends/wasm/live_run.c) */
        char *argv[] = {cc, "--target=wasm32-wasi", "-O2", "-ffp-contract=off",
                        "-mexec-model=reactor", "-w", inc, c_path, obj, lib,
                        "-lc-printscan-long-double", "-lm",
                        "-Wl,--strip-debug", "-o", wasm_path, NULL};
        rc = run_compiler(argv, log_path);
        if (rc != 0) {
            size_t n = 0;
            unsigned char *log = rc > 0 ? read_all(log_path, &n) : NULL;
            const char *first = log && n ? (const char *)log : "";
            int shown = (int)n;
            const char *nl = log && n ? memchr(log, '\n', n) : NULL;
            if (nl)
                shown = (int)(nl - first);
            if (rc < 0)
                snprintf(out->why, sizeof out->why,
                         "the compiler %s did not start (install %s)", cc, LIVE_PACKAGES);
            else
                snprintf(out->why, sizeof out->why,
                         "%s --target=wasm32-wasi failed: %.*s (install %s)", cc,
                         shown > 300 ? 300 : shown, first, LIVE_PACKAGES);
            free(log);
        }
    } else {
        snprintf(out->why, sizeof out->why, "cannot write in %.900s: %s", work, strerror(errno));
    }
    if (rc == 0) {
        out->module = read_all(wasm_path, &out->size);
        if (!out->module)
            snprintf(out->why, sizeof out->why, "cannot read the compiled module in %.900s", work);
    }
    remove_dir(work);
    return out->module ? 0 : -1;
}

int cli_live_build(const dyn_model *m, cli_live *out)
{
    memset(out, 0, sizeof *out);
    char *source = model_source(m, out->why, sizeof out->why, &out->scene_inputs);
    return source ? build_source(source, out) : -1;
}

int cli_live_build_ani(const dyn_model *m, const char *ani_path, cli_live *out)
{
    const char *path = cli_model_path(m);
    char *source = path && ani_path ? cli_model_ani_source(path, ani_path) : NULL;
    if (source) {
        memset(out, 0, sizeof *out);
        if (build_source(source, out) == 0) {
            out->ani_outputs = 1;
            /* a mechanism's: after its scene's inputs (dyn_mech_ani_to_c) */
            const size_t n = strlen(path);
            out->scene_inputs = n > 5 && strcmp(path + n - 5, ".mech") == 0;
            return 0;
        }
        cli_live_free(out);
    }
    return cli_live_build(m, out); /* the page's animation then shows its first run */
}

int cli_live_build_builtins(cli_live *out)
{
    memset(out, 0, sizeof *out);
    /* every built-in model is in the library: an instance runs the one it is told to */
    static const char text[] =
        "#include <dynkit/model.h>\n"
        "static int chosen;\n"
        "__attribute__((export_name(\"dk_live_choose\"))) void dk_live_choose(int i) "
        "{ chosen = i; }\n"
        "const dyn_model *dynkit_model(void) { return dyn_model_at(chosen); }\n";
    char *source = strdup(text);
    if (!source) {
        snprintf(out->why, sizeof out->why, "out of memory");
        return -1;
    }
    return build_source(source, out);
}

/* The module as the page carries it: its zlib stream (cli_zlib_compress, 2.45 times smaller),
 * in base64; the page inflates it with DecompressionStream('deflate'). */
static void json_module(cli_json *j, const cli_live *live)
{
    size_t n = 0;
    unsigned char *z = cli_zlib_compress(live->module, live->size, &n);
    if (!z) {
        j->bad = 1;
        return;
    }
    json_base64(j, z, n);
    free(z);
}

void cli_json_live_module(cli_json *j, const cli_live *live)
{
    json_module(j, live);
}

void cli_live_free(cli_live *live)
{
    free(live->module);
    live->module = NULL;
}

/* The module as base64 (RFC 4648), as a JSON string. */
static void json_base64(cli_json *j, const unsigned char *p, size_t n)
{
    static const char abc[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    cli_json_raw(j, "\"", 1);
    char quad[4];
    for (size_t i = 0; i < n; i += 3) {
        const unsigned v = (unsigned)p[i] << 16 | (i + 1 < n ? (unsigned)p[i + 1] << 8 : 0u) |
                           (i + 2 < n ? (unsigned)p[i + 2] : 0u);
        quad[0] = abc[v >> 18 & 63];
        quad[1] = abc[v >> 12 & 63];
        quad[2] = i + 1 < n ? abc[v >> 6 & 63] : '=';
        quad[3] = i + 2 < n ? abc[v & 63] : '=';
        j->bad |= fwrite(quad, 1, 4, j->out) != 4;
    }
    j->bad |= fputc('"', j->out) == EOF;
}

/* The methods the page offers: the registry's (a map's own only for a map), or only the
 * run's for a model whose runs take a family of their own (noise, delays, integrals). */
static void json_methods(cli_json *j, const dyn_model *m, const dyn_tableau *run_method)
{
    cli_json_begin_array(j);
    const int own = m->n_noise > 0 || m->delay || m->volterra ||
                    dyn_method_find(run_method->name) != run_method;
    if (own) {
        cli_json_begin_array(j);
        cli_json_string(j, run_method->name);
        cli_json_bool(j, dyn_method_is_adaptive(run_method));
        cli_json_end_array(j);
    } else {
        for (int i = 0; i < dyn_method_count(); i++) {
            const dyn_tableau *t = dyn_method_at(i);
            if (dyn_method_is_map(t) == dyn_method_is_map(run_method)) {
                cli_json_begin_array(j);
                cli_json_string(j, t->name);
                cli_json_bool(j, dyn_method_is_adaptive(t));
                cli_json_end_array(j);
            }
        }
    }
    cli_json_end_array(j);
}

static void json_values(cli_json *j, const char *name, const char *unit, double value,
                        double dflt)
{
    cli_json_begin_object(j);
    cli_json_key(j, "name");
    cli_json_string(j, name);
    cli_json_key(j, "unit");
    cli_json_string(j, unit ? unit : "");
    cli_json_key(j, "value");
    cli_json_number(j, value);
    cli_json_key(j, "default");
    cli_json_number(j, dflt);
    cli_json_end_object(j);
}

int cli_json_live(cli_json *j, const cli_live *live, const cli_view *v, const char *spec)
{
    const cli_run *run = &v->run;
    const dyn_model *m = run->model;
    const int digits = j->digits;
    j->digits = 17; /* the settings exactly */
    void *dpar = calloc(1, m->par_size ? m->par_size : 1);
    double *dy0 = calloc((size_t)m->n_states, sizeof *dy0);
    if (!dpar || !dy0) {
        free(dpar);
        free(dy0);
        return 1;
    }
    char err[256];
    dyn_model_default_params(m, dpar, err, sizeof err);
    dyn_model_initial_state(m, run->par, dy0);
    cli_json_begin_object(j);
    if (live->module) { /* else the page's shared module (report --html --live) */
        cli_json_key(j, "module");
        json_module(j, live);
    }
    cli_json_key(j, "spec");
    cli_json_string(j, spec);
    cli_json_key(j, "method");
    cli_json_string(j, run->method->name);
    cli_json_key(j, "methods");
    json_methods(j, m, run->method);
    cli_json_key(j, "t0");
    cli_json_number(j, run->t0);
    cli_json_key(j, "t1");
    cli_json_number(j, run->t1);
    cli_json_key(j, "step");
    cli_json_number(j, run->step);
    cli_json_key(j, "rtol");
    cli_json_number(j, run->rtol);
    cli_json_key(j, "atol");
    cli_json_number(j, run->atol);
    cli_json_key(j, "end");
    cli_json_string(j, run->end == DYN_END_GRID ? "grid" : "exact");
    cli_json_key(j, "at_steps");
    cli_json_bool(j, cli_run_at_steps(run));
    cli_json_key(j, "every");
    cli_json_number(j, (double)(run->every > 1 ? run->every : 1));
    cli_json_key(j, "model_every");
    cli_json_number(j, (double)(m->every > 1 ? m->every : 1));
    cli_json_key(j, "params");
    cli_json_begin_array(j);
    for (int i = 0; i < m->n_params; i++)
        json_values(j, m->params[i].name, m->params[i].unit, dyn_model_get_param(m, run->par, i),
                    dyn_model_get_param(m, dpar, i));
    cli_json_end_array(j);
    cli_json_key(j, "states");
    cli_json_begin_array(j);
    for (int i = 0; i < m->n_states; i++)
        json_values(j, m->states[i].name, m->states[i].unit, run->y0[i], dy0[i]);
    cli_json_end_array(j);
    cli_json_key(j, "scene_inputs"); /* the column after t, the states and the outputs */
    cli_json_bool(j, live->scene_inputs);
    cli_json_key(j, "ani_outputs"); /* there too: the animation's numbers */
    cli_json_bool(j, live->ani_outputs);
    cli_json_key(j, "compare");
    cli_json_begin_array(j);
    for (int k = 0; k < v->n_compare; k++) {
        cli_json_begin_object(j);
        cli_json_key(j, "method");
        cli_json_string(j, v->compare[k].method->name);
        cli_json_key(j, "step");
        cli_json_number(j, v->compare[k].step);
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
    cli_json_end_object(j);
    j->digits = digits;
    free(dpar);
    free(dy0);
    return 0;
}
