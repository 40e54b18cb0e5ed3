/* SPDX-License-Identifier: BSD-3-Clause */
/* The jit layer's public functions (dynkit/jit.h): choice of the backend, loading a C file,
 * loading a shared object with the check of its model ABI, and the check of the dyn_model a
 * compiled model returns. */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "jit_internal.h"

const char *dyn_jit_backend_name(int backend)
{
    switch (backend) {
    case DYN_JIT_AUTO: return "auto";
    case DYN_JIT_CC: return "cc";
    case DYN_JIT_TCC: return "tcc";
    default: return "unknown";
    }
}

int dyn_jit_backend_available(dyn_jit_backend backend)
{
#ifdef DYNKIT_HAVE_TCC
    if (backend == DYN_JIT_TCC)
        return 1;
#endif
    return backend == DYN_JIT_CC || backend == DYN_JIT_AUTO;
}

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
    char text[800];
    snprintf(text, sizeof text,
             "%s: compiled with libtcc instead, whose code runs up to 3 times slower", why);
    jit_note(out->note, sizeof out->note, text);
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
    if (rc == 3 && automatic) { /* the compiler's time limit, named in out->note */
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

/* ---- the model a compiled unit returns ---- */

static int check_vars(const dyn_var *v, int n, const char *what, const char *where, char *err,
                      size_t errlen)
{
    if (n < 0)
        return jit_fail(err, errlen, "%s: dynkit_model() returned a model with n_%s = %d", where,
                        what, n);
    if (n > 0 && !v)
        return jit_fail(err, errlen,
                        "%s: dynkit_model() returned a model with n_%s = %d but no %s array", where,
                        what, n, what);
    for (int i = 0; i < n; i++)
        if (!v[i].name || !v[i].name[0])
            return jit_fail(err, errlen, "%s: %s %d of the model has no name", where, what, i);
    return 0;
}

int jit_check_model(const dyn_model *m, const char *where, char *err, size_t errlen)
{
    if (!m)
        return jit_fail(err, errlen, "%s: dynkit_model() returned NULL instead of a model", where);
    if (!m->name || !m->name[0])
        return jit_fail(err, errlen, "%s: the model has no name (dyn_model.name)", where);
    if (m->n_states <= 0)
        return jit_fail(err, errlen,
                        "%s: the model '%s' has n_states = %d (it needs at least one state)", where,
                        m->name, m->n_states);
    if (!m->rhs)
        return jit_fail(err, errlen, "%s: the model '%s' has no right-hand side (dyn_model.rhs)",
                        where, m->name);
    if (!m->y0 && !m->initial_state)
        return jit_fail(err, errlen,
                        "%s: the model '%s' has no initial state (dyn_model.y0 or initial_state)",
                        where, m->name);
    if (check_vars(m->states, m->n_states, "states", where, err, errlen) ||
        check_vars(m->outputs, m->n_outputs, "outputs", where, err, errlen) ||
        check_vars(m->inputs, m->n_inputs, "inputs", where, err, errlen))
        return 1;
    if (m->n_outputs > 0 && !m->compute_outputs)
        return jit_fail(err, errlen, "%s: the model '%s' has %d outputs but no compute_outputs",
                        where, m->name, m->n_outputs);
    if (m->n_inputs > 0 && !m->set_input)
        return jit_fail(err, errlen, "%s: the model '%s' has %d inputs but no set_input", where,
                        m->name, m->n_inputs);
    if (m->n_params < 0 || (m->n_params > 0 && !m->params))
        return jit_fail(err, errlen, "%s: the model '%s' has n_params = %d but no params array",
                        where, m->name, m->n_params);
    for (int i = 0; i < m->n_params; i++) {
        const dyn_param *p = &m->params[i];
        if (!p->name || !p->name[0])
            return jit_fail(err, errlen, "%s: parameter %d of the model '%s' has no name", where, i,
                            m->name);
        if (m->par_size < sizeof(double) || p->offset > m->par_size - sizeof(double) ||
            p->offset % _Alignof(double) != 0)
            return jit_fail(err, errlen,
                            "%s: parameter '%s' of the model '%s' lies outside its parameter "
                            "struct (offset %zu, par_size %zu): set par_size = sizeof(the "
                            "struct) and offset = offsetof(the struct, member)",
                            where, p->name, m->name, p->offset, m->par_size);
    }
    if (m->n_events < 0 || (m->n_events > 0 && !m->events))
        return jit_fail(err, errlen, "%s: the model '%s' has n_events = %d but no events array",
                        where, m->name, m->n_events);
    for (int i = 0; i < m->n_events; i++)
        if (!m->events[i].name || !m->events[i].name[0] || !m->events[i].g)
            return jit_fail(err, errlen,
                            "%s: event %d of the model '%s' has no name or no function g", where, i,
                            m->name);
    if (m->jac_banded && (m->jac_lower < 0 || m->jac_upper < 0 || m->jac_lower >= m->n_states ||
                          m->jac_upper >= m->n_states))
        return jit_fail(err, errlen,
                        "%s: the model '%s' declares a band of its Jacobian with jac_lower = %d, "
                        "jac_upper = %d (accepted: 0 to n_states - 1 = %d)",
                        where, m->name, m->jac_lower, m->jac_upper, m->n_states - 1);
    if (m->n_noise < 0 || (m->n_noise > 0 && !m->noise_kinds) ||
        (m->n_noise > 0 && (m->noise_offset % sizeof(double) != 0 ||
                            m->noise_offset > m->par_size ||
                            (m->par_size - m->noise_offset) / sizeof(double) <
                                (size_t)m->n_noise)) ||
        m->noise_class < DYN_NOISE_GENERAL || m->noise_class > DYN_NOISE_COMMUTATIVE)
        return jit_fail(err, errlen,
                        "%s: the model '%s' declares %d noise slots that do not fit its parameter "
                        "struct (noise_offset %zu, par_size %zu, noise_kinds %s, noise_class %d)",
                        where, m->name, m->n_noise, m->noise_offset, m->par_size,
                        m->noise_kinds ? "given" : "NULL", m->noise_class);
    for (int i = 0; i < m->n_noise; i++)
        if (m->noise_kinds[i] < DYN_NOISE_WIENER || m->noise_kinds[i] > DYN_NOISE_UNIFORM)
            return jit_fail(err, errlen, "%s: noise slot %d of the model '%s' has kind %d "
                            "(accepted: 0 wiener, 1 normal, 2 uniform)", where, i, m->name,
                            m->noise_kinds[i]);
    const int sde_method = m->method && m->n_noise > 0 && strcmp(m->method, "rkmil") == 0;
    if (m->method && !sde_method && !dyn_method_find(m->method))
        return jit_fail(err, errlen,
                        "%s: the model '%s' names an unknown default method (dyn_model.method = "
                        "\"%s\"; e.g. \"dp45\" or \"rk4\", or NULL for " DYN_MODEL_METHOD ")",
                        where, m->name, m->method);
    if (!isfinite(m->t0) || !isfinite(m->t1) || !(m->t1 > m->t0) || !isfinite(m->step) ||
        m->step < 0 || (m->step == 0 && m->samples != DYN_SAMPLES_STEPS))
        return jit_fail(err, errlen,
                        "%s: the model '%s' has a bad default run (t0 = %g, t1 = %g, step = %g): "
                        "set dyn_model.t0 < t1 and step > 0 (the sample interval of adaptive "
                        "methods)",
                        where, m->name, m->t0, m->t1, m->step);
    return 0;
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

/* A loaded shared object: the dlopen handle, and the descriptor of the private copy it was
 * loaded from (kept open while it is loaded, so that no other object gets its name). */
typedef struct loaded_so {
    void *dl;
    int fd;
} loaded_so;

static void close_so(loaded_so *s)
{
    if (s->dl)
        dlclose(s->dl);
    if (s->fd >= 0)
        close(s->fd);
    free(s);
}

static int load_so(const char *path, int fd, const char *where, dyn_jit_model *out, char *err,
                   size_t errlen)
{
    if (fd >= 0 && access("/proc/self/fd", X_OK) != 0) { /* no /proc: the checked path */
        close(fd);
        fd = -1;
    }
    /* dlopen searches the library path for a name without '/': a file is meant */
    char full[1024];
    int n = fd >= 0               ? snprintf(full, sizeof full, "/proc/self/fd/%d", fd)
            : strchr(path, '/') ? snprintf(full, sizeof full, "%s", path)
                                : snprintf(full, sizeof full, "./%s", path);
    loaded_so *so = n < 0 || (size_t)n >= sizeof full ? NULL : malloc(sizeof *so);
    if (!so) {
        if (fd >= 0)
            close(fd);
        return jit_fail(err, errlen, n < 0 || (size_t)n >= sizeof full ? "path too long: %s"
                                                                         : "out of memory (%s)",
                        path);
    }
    so->fd = fd;
    dlerror();
    void *h = so->dl = dlopen(full, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        close_so(so);
        const char *e = dlerror();
        if (e && strstr(e, "undefined symbol"))
            return jit_fail(err, errlen,
                            "cannot load the model %s: %s (a function the model calls is "
                            "neither in it, nor in libm, nor exported by this program: a "
                            "program that loads models links dynkit with ENABLE_EXPORTS / "
                            "-rdynamic, or links libdynkit.so)",
                            where, e);
        return jit_fail(err, errlen, "cannot load the model %s: %s", where,
                        e ? e : "unknown error");
    }
    const unsigned *abi = (const unsigned *)dlsym(h, "dynkit_model_abi");
    if (!abi) {
        close_so(so);
        return jit_fail(err, errlen,
                        "%s does not record a model ABI (the symbol dynkit_model_abi, which "
                        "dynkit adds when it compiles a model): this dynkit reads ABI %d: "
                        "recompile it with dynkit",
                        where, DYN_MODEL_ABI);
    }
    if (*abi != (unsigned)DYN_MODEL_ABI) {
        unsigned got = *abi;
        close_so(so);
        return jit_fail(err, errlen,
                        "%s was built for model ABI %u, this dynkit reads ABI %d: recompile it",
                        where, got, DYN_MODEL_ABI);
    }
    /* object pointer to function pointer: through memcpy, as POSIX dlsym intends */
    void *sym = dlsym(h, DYN_MODEL_ENTRY);
    dyn_model_entry_fn entry;
    if (!sym) {
        close_so(so);
        return jit_fail(err, errlen,
                        "%s does not define the entry point %s() (model.h: "
                        "const dyn_model *dynkit_model(void))",
                        where, DYN_MODEL_ENTRY);
    }
    memcpy(&entry, &sym, sizeof entry);
    const dyn_model *m = entry();
    if (jit_check_model(m, where, err, errlen) != 0) {
        close_so(so);
        return 1;
    }
    out->model = m;
    out->handle = so;
    out->backend = DYN_JIT_CC;
    snprintf(out->so_path, sizeof out->so_path, "%s", path);
    return 0;
}

int jit_load_so(const char *path, int fd, const char *where, dyn_jit_model *out, char *err,
                size_t errlen)
{
    memset(out, 0, sizeof *out);
    return load_so(path, fd, where, out, err, errlen); /* which closes fd when it fails */
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
        close_so(m->handle);
    m->handle = NULL;
    m->model = NULL;
}
