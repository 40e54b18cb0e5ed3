/* SPDX-License-Identifier: BSD-3-Clause */
/* The solver of band matrices the tool's stiff runs use: LAPACK's dgbtrf/dgbtrs when the
 * tool is built with the backend dynkit_lapack (backends/lapack), else the library's own
 * (NULL: dyn_band_solver_builtin). docs/stiff.md says why both exist. And the eigenvalue
 * solver of linearize: LAPACK's dgeev, or none (docs/analysis.md). */
#include "cli.h"
#include "dynkit/analysis.h"

#ifdef DYNKIT_HAVE_LAPACK
#include "dynkit/lapack.h"
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
