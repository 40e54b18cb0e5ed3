/* SPDX-License-Identifier: BSD-3-Clause */
/* bench/bench_clock.h — the clocks of the benchmarks: wall time (CLOCK_MONOTONIC) and the
 * CPU time of the whole process, all threads (CLOCK_PROCESS_CPUTIME_ID), in seconds.
 * CPU time shows what a piece of work costs even when other work shares the cores (wall
 * time then includes the waits for a core). POSIX clock_gettime. */
#ifndef DYNKIT_BENCH_CLOCK_H
#define DYNKIT_BENCH_CLOCK_H

#include <time.h>

static inline double bench_wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline double bench_process_cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif /* DYNKIT_BENCH_CLOCK_H */
