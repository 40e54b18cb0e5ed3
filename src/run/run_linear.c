/* SPDX-License-Identifier: BSD-3-Clause */
/* The matrices of a stiff run (dynkit/run.h, dyn_run_linear_choose): dense, band (the
 * model's band, declared or found in the pattern of its exact Jacobian) or sparse (a pattern
 * that is not banded, when a sparse LU is among the backends), and why, in words;
 * docs/stiff.md, "Large systems", says why each pays where it does. */
#include <stdio.h>
#include <stdlib.h>

#include "dynkit/run.h"

void dyn_run_linear_choose(const dyn_model *m, const dyn_tableau *method,
                           const dyn_run_backends *b, dyn_linear_choice *lin)
{
    const int n = m->n_states, nnz = m->jac_pattern.nnz;
    lin->kind = DYN_LINEAR_DENSE;
    lin->lower = m->jac_lower;
    lin->upper = m->jac_upper;
    lin->nnz = nnz;
    if (m->jac_banded) {
        lin->kind = DYN_LINEAR_BAND;
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
                 n, DYN_SPARSE_MIN_STATES);
        return;
    }
    dyn_sparse_pattern_band(&m->jac_pattern, &lin->lower, &lin->upper);
    if (n < DYN_SPARSE_MIN_STATES || 4.0 * nnz > (double)n * n) {
        snprintf(lin->why, sizeof lin->why,
                 "dense matrices: %d states and %d of %d entries of the Jacobian (a sparse "
                 "LU pays from %d states and a quarter of the entries)",
                 n, nnz, n * n, DYN_SPARSE_MIN_STATES);
        return;
    }
    if (!b || !b->sparse_open) {
        snprintf(lin->why, sizeof lin->why,
                 "dense matrices: the Jacobian has %d of %d entries and is not banded, but "
                 "dynkit was built without KLU (libsuitesparse-dev), its sparse LU",
                 nnz, n * n);
        return;
    }
    if (method && method == dyn_run_method_cvode() && !(b->cvode_has_klu && m->jacobian_sparse)) {
        snprintf(lin->why, sizeof lin->why,
                 "dense matrices: cvode takes sparse matrices with the model's exact sparse "
                 "Jacobian and SUNDIALS' KLU, and %s",
                 b->cvode_has_klu ? "this model gives its pattern without the values (rodas4 "
                                    "forms them by differences)"
                                  : "dynkit's CVODE backend was built without SUNLinSol_KLU");
        return;
    }
    lin->kind = DYN_LINEAR_SPARSE;
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
}
