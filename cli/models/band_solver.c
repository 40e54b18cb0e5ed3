/* SPDX-License-Identifier: BSD-3-Clause */
/* The linear algebra of the tool's stiff runs: dense, band or sparse matrices for a model
 * (cli_linear_choose, from its declared band or the pattern of its exact Jacobian); the
 * solver of band matrices, LAPACK's dgbtrf/dgbtrs when the tool is built with the backend
 * dynkit_lapack (backends/lapack), else the library's own (NULL: dyn_band_solver_builtin);
 * the sparse LU, KLU when built with dynkit_klu (backends/klu). docs/stiff.md, "Large
 * systems", says why. And the eigenvalue solver of linearize: LAPACK's dgeev, or none
 * (docs/analysis.md). */
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "dynkit/analysis.h"

#ifdef DYNKIT_HAVE_KLU
#include "dynkit/klu.h"
#endif

#ifdef DYNKIT_HAVE_LAPACK
#include "dynkit/lapack.h"
#endif

#ifdef DYNKIT_HAVE_CVODE
#include "dynkit/cvode.h"
#endif

const dyn_band_solver *cli_band_solver(void)
{
#ifdef DYNKIT_HAVE_LAPACK
    return &dyn_band_solver_lapack;
#else
    return NULL;
#endif
}

const dyn_eig_solver *cli_eig_solver(void)
{
#ifdef DYNKIT_HAVE_LAPACK
    return &dyn_eig_solver_lapack;
#else
    return NULL;
#endif
}

/* A sparse LU pays against the dense one from this many states on, and for a pattern with at
 * most a quarter of the entries (the band of a model file is found when it is narrow, at
 * least as many states: src/lang/emit_c.c). */
#define CLI_SPARSE_MIN_STATES 32

void cli_linear_choose(const dyn_model *m, cli_linear *lin)
{
    const int n = m->n_states, nnz = m->jac_pattern.nnz;
    lin->kind = CLI_LINEAR_DENSE;
    lin->lower = m->jac_lower;
    lin->upper = m->jac_upper;
    lin->nnz = nnz;
    if (m->jac_banded) {
        lin->kind = CLI_LINEAR_BAND;
        snprintf(lin->why, sizeof lin->why,
                 "band matrices: the Jacobian is banded, %d below and %d above the diagonal "
                 "(of %d states)%s",
                 m->jac_lower, m->jac_upper, n,
                 nnz <= 0            ? ", as the model declares"
                 : m->jacobian_band  ? ", as its exact pattern shows"
                                     : ", as its pattern shows");
        return;
    }
    if (nnz <= 0) {
        snprintf(lin->why, sizeof lin->why,
                 "dense matrices: %d states, and the model gives no sparse pattern of its "
                 "Jacobian (a model file's exact one has it from %d states on, with at most a "
                 "quarter of the entries)",
                 n, CLI_SPARSE_MIN_STATES);
        return;
    }
    dyn_sparse_pattern_band(&m->jac_pattern, &lin->lower, &lin->upper);
    if (n < CLI_SPARSE_MIN_STATES || 4.0 * nnz > (double)n * n) {
        snprintf(lin->why, sizeof lin->why,
                 "dense matrices: %d states and %d of %d entries of the Jacobian (a sparse "
                 "LU pays from %d states and a quarter of the entries)",
                 n, nnz, n * n, CLI_SPARSE_MIN_STATES);
        return;
    }
#ifdef DYNKIT_HAVE_KLU
    lin->kind = CLI_LINEAR_SPARSE;
    if (m->jacobian_sparse) {
        snprintf(lin->why, sizeof lin->why,
                 "sparse matrices (KLU): the exact Jacobian has %d of %d entries and is not "
                 "banded (%d below, %d above the diagonal)",
                 nnz, n * n, lin->lower, lin->upper);
        return;
    }
    /* differences in groups of columns: as many calls of f as groups */
    int *group = malloc((size_t)n * sizeof *group);
    const int groups = group ? dyn_sparse_groups(&m->jac_pattern, group) : -1;
    free(group);
    snprintf(lin->why, sizeof lin->why,
             "sparse matrices (KLU): the Jacobian's pattern has %d of %d entries and is not "
             "banded (%d below, %d above the diagonal); its values by differences in %d "
             "groups of columns, %d calls of f instead of %d",
             nnz, n * n, lin->lower, lin->upper, groups, groups, n);
#else
    snprintf(lin->why, sizeof lin->why,
             "dense matrices: the Jacobian has %d of %d entries and is not banded, but "
             "dynkit was built without KLU (libsuitesparse-dev), its sparse LU",
             nnz, n * n);
#endif
}

void cli_linear_for_run(const cli_run *run, cli_linear *lin)
{
    cli_linear_choose(run->model, lin);
    if (lin->kind != CLI_LINEAR_SPARSE || !cli_method_is_cvode(run->method))
        return;
#ifdef DYNKIT_HAVE_CVODE
    const int klu = dyn_cvode_has_klu();
#else
    const int klu = 0;
#endif
    if (klu && run->model->jacobian_sparse)
        return;
    lin->kind = CLI_LINEAR_DENSE;
    snprintf(lin->why, sizeof lin->why,
             "dense matrices: cvode takes sparse matrices with the model's exact sparse "
             "Jacobian and SUNDIALS' KLU, and %s",
             klu ? "this model gives its pattern without the values (rodas4 forms them by "
                   "differences)"
                 : "dynkit's CVODE backend was built without SUNLinSol_KLU");
}

int cli_sparse_solver_open(dyn_sparse_solver *s)
{
#ifdef DYNKIT_HAVE_KLU
    return dyn_klu_init(s);
#else
    (void)s;
    return 1;
#endif
}

void cli_sparse_solver_close(dyn_sparse_solver *s)
{
#ifdef DYNKIT_HAVE_KLU
    dyn_klu_release(s);
#else
    (void)s;
#endif
}
