/* SPDX-License-Identifier: BSD-3-Clause */
/* A sweep split over MPI ranks (dynkit/sweep_mpi.h): each rank runs the runs i = rank mod
 * size with dyn_sweep_run, then rank 0 gathers the rows (MPI_Gatherv of each rank's rows
 * and statuses, in the rank's run order) and puts them in place. Rows are copied, never
 * combined, so the table is the same bits as one process's (MPI 3.1 standard, sec. 5.5). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mpi.h>

#include "dynkit/sweep_mpi.h"

int dyn_sweep_mpi_run(const dyn_sweep *s, double *results, int *status, char *err,
                      size_t errlen)
{
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    const long n = s->n_runs;
    const int nr = s->n_reduce;
    /* this rank's runs: i mod size == rank, not skipped */
    unsigned char *skip = malloc((size_t)n + 1);
    if (!skip) {
        snprintf(err, errlen, "out of memory");
        return DYN_ERR_CAPACITY;
    }
    for (long i = 0; i < n; i++)
        skip[i] = (i % size != rank) || (s->skip && s->skip[i]);
    dyn_sweep local = *s;
    local.skip = skip;
    int rc = dyn_sweep_run(&local, results, status, err, errlen);
    /* the worst outcome of all ranks: an error beats cancelled beats ok */
    int code = rc == DYN_OK ? 0 : rc == DYN_CANCELLED ? 1 : 2, worst = code;
    MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (worst == 2) {
        free(skip);
        if (rc == DYN_OK || rc == DYN_CANCELLED) {
            snprintf(err, errlen, "the sweep failed on another rank");
            return DYN_ERR_ARG;
        }
        return rc;
    }
    /* pack this rank's rows: statuses as doubles after the reductions (exact for ints) */
    const int width = nr + 1;
    long mine = 0;
    for (long i = 0; i < n; i++)
        mine += !skip[i];
    double *pack = malloc(((size_t)mine * (size_t)width + 1) * sizeof *pack);
    int *counts = rank == 0 ? malloc((size_t)size * sizeof *counts) : NULL;
    int *displs = rank == 0 ? malloc((size_t)size * sizeof *displs) : NULL;
    int ok = pack && (rank != 0 || (counts && displs));
    int all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (!all_ok || (long)mine * width > 2147483647L) {
        free(pack);
        free(counts);
        free(displs);
        free(skip);
        snprintf(err, errlen, "out of memory for gathering the rows");
        return DYN_ERR_CAPACITY;
    }
    long k = 0;
    for (long i = 0; i < n; i++) {
        if (skip[i])
            continue;
        if (nr > 0)
            memcpy(pack + k * width, results + (size_t)i * (size_t)nr,
                   (size_t)nr * sizeof *pack);
        pack[k * width + nr] = (double)status[i];
        k++;
    }
    const int count = (int)(mine * width);
    MPI_Gather(&count, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD);
    double *all = NULL;
    long total = 0;
    if (rank == 0) {
        for (int r = 0; r < size; r++) {
            displs[r] = (int)total;
            total += counts[r];
        }
        all = malloc(((size_t)total + 1) * sizeof *all);
    }
    int have = rank != 0 || all != NULL, every = 0;
    MPI_Allreduce(&have, &every, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    int mrc = MPI_SUCCESS;
    if (every)
        mrc = MPI_Gatherv(pack, count, MPI_DOUBLE, all, counts, displs, MPI_DOUBLE, 0,
                          MPI_COMM_WORLD);
    if (rank == 0 && every && mrc == MPI_SUCCESS) {
        /* rank r's rows are its runs in order: i = r, r + size, ... not skipped by s */
        for (int r = 1; r < size; r++) {
            const double *p = all + displs[r];
            for (long i = r; i < n; i += size) {
                if (s->skip && s->skip[i])
                    continue;
                if (nr > 0)
                    memcpy(results + (size_t)i * (size_t)nr, p, (size_t)nr * sizeof *p);
                status[i] = (int)p[nr];
                p += width;
            }
        }
    }
    free(all);
    free(pack);
    free(counts);
    free(displs);
    free(skip);
    if (!every || mrc != MPI_SUCCESS) {
        snprintf(err, errlen, every ? "MPI_Gatherv failed" : "out of memory for the table");
        return every ? DYN_ERR_IO : DYN_ERR_CAPACITY;
    }
    if (worst == 1) {
        snprintf(err, errlen, "the sweep was cancelled");
        return DYN_CANCELLED;
    }
    return DYN_OK;
}
