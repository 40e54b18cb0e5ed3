/* SPDX-License-Identifier: BSD-3-Clause */
/* lapack_eig.c — dyn_eig_solver over LAPACK's dgeev (balancing, reduction to Hessenberg
 * form, the shifted QR algorithm; eigenvalues only), through the Fortran interface of the
 * reference LAPACK. The matrix is handed over row-major as it is: read column-major it is
 * A^T, which has the same eigenvalues. The workspace is asked of dgeev (lwork = -1) and
 * allocated per call. */
#include <stdio.h>
#include <stdlib.h>

#include "dynkit/lapack.h"

extern void dgeev_(const char *jobvl, const char *jobvr, const int *n, double *a, const int *lda,
                   double *wr, double *wi, double *vl, const int *ldvl, double *vr, const int *ldvr,
                   double *work, const int *lwork, int *info, unsigned long jobvl_len,
                   unsigned long jobvr_len);

static int lapack_eigenvalues(int n, double *a, double *re, double *im, char *err, size_t errlen)
{
    const int one = 1, query = -1;
    double size = 0.0, dummy = 0.0;
    int info = 0;
    dgeev_("N", "N", &n, a, &n, re, im, &dummy, &one, &dummy, &one, &size, &query, &info, 1, 1);
    int lwork = info == 0 && size >= 3.0 * n ? (int)size : 4 * n + 1;
    double *work = malloc((size_t)lwork * sizeof *work);
    if (!work) {
        snprintf(err, errlen, "out of memory for dgeev's workspace (%d doubles)", lwork);
        return -1;
    }
    dgeev_("N", "N", &n, a, &n, re, im, &dummy, &one, &dummy, &one, work, &lwork, &info, 1, 1);
    free(work);
    if (info != 0) {
        if (info > 0)
            snprintf(err, errlen,
                     "dgeev: the QR algorithm did not converge (%d eigenvalues not found)", info);
        else
            snprintf(err, errlen, "dgeev: argument %d was invalid", -info);
        return -1;
    }
    return 0;
}

const dyn_eig_solver dyn_eig_solver_lapack = {"lapack dgeev", lapack_eigenvalues};
