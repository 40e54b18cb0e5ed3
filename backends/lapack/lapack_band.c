/* SPDX-License-Identifier: BSD-3-Clause */
/* lapack_band.c — dyn_band_solver over LAPACK's dgbtrf (band LU with partial pivoting) and
 * dgbtrs (its solve, no transpose), called through the Fortran interface of the reference
 * LAPACK (arguments by reference, 1-based pivots kept as LAPACK returns them: the pivots
 * are private to the solver). The storage is the same as the library's (dynkit/ode.h), so
 * nothing is copied. */
#include "dynkit/lapack.h"

/* Fortran LAPACK (the hidden string-length argument of trans, a single character) */
extern void dgbtrf_(const int *m, const int *n, const int *kl, const int *ku, double *ab,
                    const int *ldab, int *ipiv, int *info);
extern void dgbtrs_(const char *trans, const int *n, const int *kl, const int *ku,
                    const int *nrhs, const double *ab, const int *ldab, const int *ipiv,
                    double *b, const int *ldb, int *info, unsigned long trans_len);

static int lapack_factor(int n, int lower, int upper, double *ab, int ldab, int *piv)
{
    int info = 0;
    dgbtrf_(&n, &n, &lower, &upper, ab, &ldab, piv, &info);
    return info; /* < 0 cannot happen with valid sizes; > 0: an exactly zero pivot */
}

static void lapack_solve(int n, int lower, int upper, const double *ab, int ldab,
                         const int *piv, double *b)
{
    const int one = 1;
    int info = 0;
    dgbtrs_("N", &n, &lower, &upper, &one, ab, &ldab, piv, b, &n, &info, 1);
}

const dyn_band_solver dyn_band_solver_lapack = {"lapack", lapack_factor, lapack_solve};
