/* SPDX-License-Identifier: BSD-3-Clause */
/* --jac-pattern model|probe|none: the sparsity pattern of the Jacobian that a stiff run
 * factors by (docs/stiff.md, "Sparse Jacobians"). model: the model's own (a model file's
 * exact pattern, a C model's declared dyn_model.jac_pattern). probe: found by evaluating f
 * near the initial state (dyn_sparse_probe), for a model without one; the run then takes a
 * copy of the model with that pattern (or the band it shows, when narrow) and forms its
 * Jacobian by differences in groups of columns (Curtis, Powell & Reid). none: dense
 * matrices whatever the model declares. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run/run_parse.h"

/* Points probed, and their seed: fixed, so a run's pattern depends on the model alone. */
#define PROBE_POINTS 3
#define PROBE_SEED 20260907u

/* The narrow band rule of a model file's exact pattern (src/lang/emit_c.c): at least 32
 * states, lower + upper + 1 at most a quarter of them. */
static int narrow_band(int n, int lower, int upper)
{
    return n >= 32 && 4 * (lower + upper + 1) <= n;
}

int cli_run_jac_pattern(const char *command, cli_run *run)
{
    const char *how = run->jac_pattern;
    if (!how || strcmp(how, "model") == 0)
        return CLI_OK;
    if (strcmp(how, "probe") != 0 && strcmp(how, "none") != 0)
        return cli_usage_error(command,
                               "--jac-pattern '%s' is not accepted (accepted: model, the "
                               "model's own; probe, found by evaluating the model; none, "
                               "dense matrices)",
                               how);
    const dyn_model *m = run->model;
    if (strcmp(how, "probe") == 0 && (m->jac_pattern.nnz > 0 || m->jac_banded))
        return cli_usage_error(command,
                               "--jac-pattern probe: model %s has its own %s of the Jacobian; "
                               "probing is for models without one (--jac-pattern none: dense "
                               "matrices)",
                               m->name, m->jac_pattern.nnz > 0 ? "pattern" : "band");
    dyn_model *own = malloc(sizeof *own);
    if (!own) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    *own = *m;
    own->jac_pattern = (dyn_sparse_pattern){0, 0, NULL, NULL};
    own->jacobian_sparse = NULL;
    own->jac_banded = 0;
    own->jac_lower = own->jac_upper = 0;
    own->jacobian_band = NULL;
    if (strcmp(how, "probe") == 0 && dyn_method_is_adaptive(run->method)) {
        const dyn_system sys = {m->rhs, m->n_states, run->par};
        char err[256];
        if (dyn_sparse_probe(&sys, run->t0, run->y0, PROBE_POINTS, PROBE_SEED,
                             &run->probed, err, sizeof err)) {
            free(own);
            cli_error("--jac-pattern probe: %s", err);
            return CLI_FAILED;
        }
        int lower = 0, upper = 0;
        dyn_sparse_pattern_band(&run->probed, &lower, &upper);
        if (narrow_band(m->n_states, lower, upper)) {
            own->jac_banded = 1; /* banded differences (lower + upper + 1 calls of f) */
            own->jac_lower = lower;
            own->jac_upper = upper;
        }
        own->jac_pattern = run->probed;
        if (cli_verbose())
            cli_note("--jac-pattern probe: %d of %d entries of the Jacobian are "
                    "not zero at %d points near the initial state (%d calls of f)",
                    run->probed.nnz, m->n_states * m->n_states, PROBE_POINTS,
                    PROBE_POINTS * (m->n_states + 1));
    }
    run->own_model = own;
    run->model = own;
    return CLI_OK;
}
