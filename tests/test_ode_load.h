/* SPDX-License-Identifier: BSD-3-Clause */
/* test_ode_load.h — an .ode text translated by src/lang, compiled through the jit into a
 * given cache directory and loaded with its default parameters: the set-up the model-file
 * suites share. Needs cmocka and test_util.h (CHECK) included first. */
#ifndef DYNKIT_TEST_ODE_LOAD_H
#define DYNKIT_TEST_ODE_LOAD_H

#include <string.h>

#include "dynkit/dynkit.h"
#include "dynkit/jit.h"
#include "dynkit/lang.h"

/* A loaded model and its default parameters. */
typedef struct loaded {
    dyn_jit_model jm;
    const dyn_model *m;
    double par[64];
} loaded;

static inline void test_ode_load(const char *text, const char *cache_dir, loaded *L)
{
    char *c_src = NULL;
    dyn_lang_diag d;
    char buf[4096];
    const int rc = dyn_ode_to_c("m.ode", text, strlen(text), &c_src, &d, NULL, NULL);
    CHECK(rc == 0, "%s", dyn_lang_diag_format(&d, buf, sizeof buf));
    dyn_jit_opts opts = {0};
    opts.cache_dir = cache_dir;
    char err[4096];
    const int jrc = dyn_jit_load_source(c_src, strlen(c_src), "m.ode", &opts, &L->jm, err,
                                        sizeof err);
    CHECK(jrc == 0, "%s\n%s", err, c_src);
    free(c_src);
    L->m = L->jm.model;
    assert_true(L->m->par_size <= sizeof L->par);
    memset(L->par, 0, sizeof L->par);
    char perr[256];
    CHECK(dyn_model_default_params(L->m, L->par, perr, sizeof perr) == 0, "%s", perr);
}

#endif
