/* SPDX-License-Identifier: BSD-3-Clause */
/* The solver of band matrices the tool's stiff runs use: LAPACK's dgbtrf/dgbtrs when the
 * tool is built with the backend dynkit_lapack (backends/lapack), else the library's own
 * (NULL: dyn_band_solver_builtin). docs/stiff.md says why both exist. */
#include "cli.h"

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
