/* SPDX-License-Identifier: BSD-3-Clause */
/* Small helpers shared by the tests: bitwise comparison of doubles, a workspace big enough
 * for every registered method, and an output callback that records the samples it sees. */
#ifndef DYNKIT_TEST_UTIL_H
#define DYNKIT_TEST_UTIL_H

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/ode.h"

/* Doubles of workspace that fit every method in these tests (stages + 3) * n. */
#define TEST_WORK 512
/* Largest number of states of a test problem. */
#define TEST_MAX_N 12

/* The i-th registered method if it is an explicit Runge-Kutta table (what the fixed-step
 * driver runs), else NULL: other kinds of solver get tests of their own. */
static inline const dyn_tableau *fixed_method_at(int i)
{
    const dyn_tableau *m = dyn_method_at(i);
    return m && m->kind == DYN_KIND_EXPLICIT_RK ? m : NULL;
}

/* 1 if a and b have the same bits (so -0 != +0, and a NaN equals only itself). */
static inline int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Largest |a_i - b_i|. */
static inline double max_abs_diff(const double *a, const double *b, int n)
{
    double worst = 0.0;
    for (int i = 0; i < n; i++)
        worst = fmax(worst, fabs(a[i] - b[i]));
    return worst;
}

/* Euclidean norm of a - b. */
static inline double norm_diff(const double *a, const double *b, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrt(s);
}

/* An output callback that records sample indices, times and states (dyn_output_fn).
 * stop_at >= 0 makes it return non-zero when it sees sample index stop_at. */
#define TEST_MAX_SAMPLES 4096
typedef struct sample_log {
    long count;
    long k[TEST_MAX_SAMPLES];
    double t[TEST_MAX_SAMPLES];
    double y[TEST_MAX_SAMPLES][TEST_MAX_N];
    int n;
    long stop_at;
    int overflow;
} sample_log;

static inline void sample_log_init(sample_log *log, int n)
{
    memset(log, 0, sizeof *log);
    log->n = n;
    log->stop_at = -1;
}

static inline int sample_log_output(long k, double t, const double *y, void *ctx)
{
    sample_log *log = ctx;
    if (log->count >= TEST_MAX_SAMPLES) {
        log->overflow = 1;
        return 1;
    }
    log->k[log->count] = k;
    log->t[log->count] = t;
    memcpy(log->y[log->count], y, (size_t)log->n * sizeof *y);
    log->count++;
    return k == log->stop_at;
}

/* Print a line that tells which case failed (used by CHECK below). */
static inline void test_note(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

/* Assert cond (cmocka must be included first); on failure print the formatted note saying
 * which case failed, then fail with the condition's text. */
#define CHECK(cond, ...)                                                                     \
    do {                                                                                     \
        if (!(cond)) {                                                                       \
            test_note(__VA_ARGS__);                                                          \
            fail_msg("%s:%d: %s", __FILE__, __LINE__, #cond);                                \
        }                                                                                    \
    } while (0)

#endif
