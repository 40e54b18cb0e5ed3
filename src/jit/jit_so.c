/* SPDX-License-Identifier: BSD-3-Clause */
/* Loading a compiled model's shared object (POSIX dlopen/dlsym): a private copy opened by
 * descriptor, its ABI stamp and entry point checked, its model checked (jit_check.c); used by
 * the system compiler's backend (jit_cc.c) and dyn_jit_load_shared. */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "jit_internal.h"

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

void jit_so_unload(void *handle) { close_so(handle); }
