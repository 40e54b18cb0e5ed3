/* SPDX-License-Identifier: BSD-3-Clause */
/* The linear algebra of the tool's stiff runs: dense, band or sparse matrices for a model
 * (cli_linear_choose, from its declared band or the pattern of its exact Jacobian); the
 * solver of band matrices, LAPACK's dgbtrf/dgbtrs when the tool is built with the backend
 * dynkit_lapack (backends/lapack), else the library's own (NULL: dyn_band_solver_builtin);
 * the sparse LU, KLU when built with dynkit_klu (backends/klu); the CVODE backend; all of
 * them as the dyn_run_backends of the tool's runs (the library's dyn_run_linear_choose
 * chooses between them). docs/stiff.md, "Large systems", says why. And the eigenvalue
 * solver of linearize: LAPACK's dgeev, or none (docs/analysis.md). */
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

const dyn_run_backends *cli_run_backends(void)
{
    static const dyn_run_backends backends = {
#ifdef DYNKIT_HAVE_LAPACK
        .band = &dyn_band_solver_lapack,
#endif
#ifdef DYNKIT_HAVE_KLU
        .sparse_open = cli_sparse_solver_open,
        .sparse_close = cli_sparse_solver_close,
#endif
#ifdef DYNKIT_HAVE_CVODE
        .cvode = dyn_cvode_run,
#endif
    };
    return &backends;
}

/* dyn_run_backends.cvode_has_klu: asked once, at the first choice of a run's matrices */
static const dyn_run_backends *backends_for_choice(void)
{
#ifdef DYNKIT_HAVE_CVODE
    static dyn_run_backends with_klu;
    static int known;
    if (!known) {
        with_klu = *cli_run_backends();
        with_klu.cvode_has_klu = dyn_cvode_has_klu();
        known = 1;
    }
    return &with_klu;
#else
    return cli_run_backends();
#endif
}

void cli_linear_choose(const dyn_model *m, cli_linear *lin)
{
    dyn_run_linear_choose(m, NULL, backends_for_choice(), lin);
}

void cli_linear_for_run(const cli_run *run, cli_linear *lin)
{
    dyn_run_linear_choose(run->model, run->method, backends_for_choice(), lin);
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
