/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/sweep_mpi.h — a sweep split over the ranks of an MPI job (optional: library
 * dynkit_sweep_mpi, built when CMake finds MPI, e.g. Debian's libopenmpi-dev).
 *
 * Rank r of K runs the runs i with i mod K = r (interleaved, so that runs whose cost grows
 * along the table are shared evenly), each rank on its own OpenMP threads
 * (dyn_sweep_run); rank 0 then receives every rank's rows and statuses and holds the
 * whole table. Each run is computed exactly as in one process, and rows are only copied,
 * never combined, so rank 0's table is the same bits as dyn_sweep_run's in one process,
 * for any number of ranks and threads. */
#ifndef DYNKIT_SWEEP_MPI_H
#define DYNKIT_SWEEP_MPI_H

#include "dynkit/sweep.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Run s over the ranks of MPI_COMM_WORLD (MPI initialised by the caller, with at least
 * MPI_THREAD_FUNNELED). Every rank passes the same sweep and arrays of n_runs rows; on
 * rank 0 results and status receive the whole table (the other ranks' arrays hold their
 * own runs only). Runs s->skip marks are left alone on every rank. Returns on every rank:
 * DYN_OK, DYN_CANCELLED when a rank was cancelled (its unfinished runs have
 * DYN_SWEEP_NOT_RUN), or an error of dyn_sweep_run or DYN_ERR_IO (MPI failed), with a
 * message in err. */
int dyn_sweep_mpi_run(const dyn_sweep *s, double *results, int *status, char *err,
                      size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_SWEEP_MPI_H */
