/* SPDX-License-Identifier: BSD-3-Clause */
/* bench_colloc — a periodic branch by collocation (dynkit/colloc.h) timed: the Roessler
 * system x' = -y - z, y' = x + a y, z' = b + z (x - c), b = 0.2, c = 5.7, from its Hopf
 * point in a (located here by bisection on the eigenvalues' real part) to a = 0.25 with
 * AUTO-07p's settings of bench/colloc_auto.py (NTST 50, NCOL 4, DS 0.01, DSMAX 0.05), the
 * Floquet multipliers at every point and the period doubling located; then the
 * period-doubled branch from it. Prints one JSON object: the best of `repeats` wall and CPU
 * times of each branch, its points, and the PD points found (a, period, L2 norm). Needs
 * LAPACK's eigenvalues (the multipliers). docs/performance.md, "Periodic orbits". */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_clock.h"
#include "dynkit/colloc.h"
#include "dynkit/lapack.h"
#include "roessler_hopf.h"

static void print_pds(const dyn_po_branch *b)
{
    int first = 1;
    for (int k = 0; k < b->npoints; k++)
        if (strcmp(b->pts[k].label, "PD") == 0) {
            printf("%s{\"a\": %.10g, \"period\": %.10g, \"l2\": %.10g}", first ? "" : ", ",
                   b->pts[k].par, b->pts[k].period, b->pts[k].l2norm);
            first = 0;
        }
}

int main(int argc, char **argv)
{
    const int repeats = argc > 1 ? atoi(argv[1]) : 3;
    double a_h, x0[3], omega = 0;
    if (roessler_hopf_point(&a_h, x0, &omega)) {
        fprintf(stderr, "bench_colloc: LAPACK's eigenvalues failed at the Hopf point\n");
        return 1;
    }
    dyn_po_system sys = {3, roessler, NULL};
    dyn_po_opts o;
    memset(&o, 0, sizeof o);
    o.ntst = 50;
    o.ncol = 4;
    o.ds = 0.01;
    o.dsmin = 1e-5;
    o.dsmax = 0.05;
    o.nmax = 400;
    o.par_min = 0.0;
    o.par_max = 0.25;
    o.eig = &dyn_eig_solver_lapack;
    double best_w[2] = {INFINITY, INFINITY}, best_c[2] = {INFINITY, INFINITY};
    dyn_po_branch keep[2];
    memset(keep, 0, sizeof keep);
    for (int r = 0; r < (repeats > 0 ? repeats : 1); r++) {
        dyn_po_branch b1, b2;
        double w0 = bench_wall_seconds(), c0 = bench_process_cpu_seconds();
        if (dyn_po_from_hopf(&sys, x0, a_h, omega, &o, &b1)) {
            fprintf(stderr, "bench_colloc: the branch failed: %s\n", b1.message);
            return 1;
        }
        double w1 = bench_wall_seconds(), c1 = bench_process_cpu_seconds();
        best_w[0] = fmin(best_w[0], w1 - w0);
        best_c[0] = fmin(best_c[0], c1 - c0);
        const dyn_po_point *pd = NULL;
        for (int k = 0; k < b1.npoints && !pd; k++)
            if (strcmp(b1.pts[k].label, "PD") == 0)
                pd = &b1.pts[k];
        memset(&b2, 0, sizeof b2);
        if (pd) {
            w0 = bench_wall_seconds();
            c0 = bench_process_cpu_seconds();
            dyn_po_from_pd(&sys, pd, &o, &b2);
            w1 = bench_wall_seconds();
            c1 = bench_process_cpu_seconds();
            best_w[1] = fmin(best_w[1], w1 - w0);
            best_c[1] = fmin(best_c[1], c1 - c0);
        }
        dyn_po_branch_free(&keep[0]);
        dyn_po_branch_free(&keep[1]);
        keep[0] = b1;
        keep[1] = b2;
    }
    printf("{\"hopf_a\": %.12g, \"omega\": %.12g,\n \"branch\": {\"wall\": %.6g, \"cpu\": %.6g, "
           "\"points\": %d, \"pd\": [", a_h, omega, best_w[0], best_c[0], keep[0].npoints);
    print_pds(&keep[0]);
    printf("]},\n \"doubled\": {\"wall\": %.6g, \"cpu\": %.6g, \"points\": %d, \"pd\": [",
           best_w[1], best_c[1], keep[1].npoints);
    print_pds(&keep[1]);
    printf("]}}\n");
    dyn_po_branch_free(&keep[0]);
    dyn_po_branch_free(&keep[1]);
    return 0;
}
