/* SPDX-License-Identifier: BSD-3-Clause */
/* family.h — section 2b of the benchmark suite: right-hand-side calls at equal error over
 * families of problems (16 van der Pol orbits, 5 Kepler orbits, the Arenstorf orbit)
 * instead of one orbit, where the error at t1 swings from one tolerance to the next and a
 * ratio of calls at one level is mostly noise. Two tables: dynkit's pairs against the
 * peers' methods of the same order on the van der Pol orbits (with a target row for each
 * pair), and each pair's step-size controller against other settings on every problem (the
 * measurements behind the defaults in docs/solvers.md, "Each pair's controller").
 */
#ifndef DYNKIT_BENCH_FAMILY_H
#define DYNKIT_BENCH_FAMILY_H

#include <dynkit/solve.h>

#include "suite.h"

typedef struct family_env {
    int quick;           /* few problems and tolerances: checks only */
    const char *csv_dir; /* write wp-family.csv there, or NULL */
    /* the solvers the adaptive section runs on sys: dynkit's pairs and the enabled peers
     * (diagnostic and header-only rows are left out here); returns how many */
    int (*collect)(const bench_sys *sys, bench_solver *out, int max);
    /* dynkit's pair `method` with the controller settings of ctl, labelled; returns 0 or 1 */
    int (*variant)(const bench_sys *sys, const char *method, const dyn_solve_opts *ctl,
                   const char *label, bench_solver *out, int max);
    /* a row of the targets table; a failed check */
    void (*target)(int met, const char *task, const char *what, const char *goal,
                   const char *value);
    void (*check)(int ok, const char *message);
} family_env;

void family_section(const family_env *env);

#endif
