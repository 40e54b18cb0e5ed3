/* SPDX-License-Identifier: BSD-3-Clause */
/* bench/bench_util.h — what several benchmarks share besides their clocks (bench_clock.h):
 * the median of repeated timings, and a whole file read into memory. */
#ifndef DYNKIT_BENCH_UTIL_H
#define DYNKIT_BENCH_UTIL_H

#include <stdio.h>
#include <stdlib.h>

static inline int bench_cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* the median of v[0..n) (n > 0), sorting v in place: v[0] is then the minimum */
static inline double bench_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* the file's bytes and a terminating 0 (free them), their count in *len; NULL when it
 * cannot be read */
static inline char *bench_read_text(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *s = NULL;
    long n = -1;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0)
        s = malloc((size_t)n + 1);
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
        free(s);
        s = NULL;
    }
    fclose(f);
    if (s) {
        s[n] = '\0';
        *len = (size_t)n;
    }
    return s;
}

#endif /* DYNKIT_BENCH_UTIL_H */
