/* SPDX-License-Identifier: BSD-3-Clause */
/* A program of one's own on dynkit::sweep (find_package(dynkit)): docs/sweeps.md's example,
 * the pendulum's first turning point over 50 initial speeds; prints that of run 49 (the same
 * on any number of threads). Built with -DSWEEP_USER_MPI on dynkit::sweep_mpi, the same
 * sweep split over the ranks of an MPI job (dynkit/sweep_mpi.h); rank 0 prints. */
#include <stdio.h>

#include <dynkit/dynkit.h>
#include <dynkit/sweep.h>
#ifdef SWEEP_USER_MPI
#include <mpi.h>

#include <dynkit/sweep_mpi.h>
#endif

int main(void)
{
#ifdef SWEEP_USER_MPI
    int provided, rank;
    MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
#endif
    const dyn_model *m = dyn_model_find("pendulum");
    dyn_sweep_var dphi;
    dyn_reduce red[4];
    int nr;
    char err[256];
    if (dyn_sweep_var_find(m, "dphi", &dphi, err, sizeof err) ||
        dyn_reduce_parse(m, "event:turn,max:height", red, 4, &nr, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    double values[50], results[50 * 2];
    int status[50];
    for (int i = 0; i < 50; i++)
        values[i] = dyn_linspace_at(0.1, 1.9, 50, i);
    dyn_sweep s = {0};
    s.model = m;
    s.n_vars = 1, s.vars = &dphi, s.n_runs = 50, s.values = values;
    s.method = dyn_method_find("dop853");
    s.rtol = s.atol = 1e-12;
    s.t0 = 0, s.t1 = 5, s.step = 0.01;
    s.n_reduce = nr, s.reduce = red;
#ifdef SWEEP_USER_MPI
    const int rc = dyn_sweep_mpi_run(&s, results, status, err, sizeof err);
    MPI_Finalize();
    if (rank != 0)
        return rc != DYN_OK;
#else
    const int rc = dyn_sweep_run(&s, results, status, err, sizeof err);
#endif
    if (rc != DYN_OK || status[49] != DYN_OK) {
        fprintf(stderr, "sweep failed: %s\n", err);
        return 1;
    }
    printf("%.15g\n", results[49 * 2 + 0]);
    return 0;
}
