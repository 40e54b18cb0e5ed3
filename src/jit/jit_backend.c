/* SPDX-License-Identifier: BSD-3-Clause */
/* The compiler backends this build has (dynkit/jit.h): their names and which are available
 * (libtcc when built with DYNKIT_HAVE_TCC). Asked by jit.c and the backends alike. */
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
