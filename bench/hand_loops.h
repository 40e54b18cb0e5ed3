/* SPDX-License-Identifier: BSD-3-Clause */
/* The hand-written reference loop of the benchmarks: textbook RK4 with the right-hand side
 * inlined and n a compile-time constant, k1..k4 then y += h/6 (k1 + 2 k2 + 2 k3 + k4).
 * The systems timed are autonomous, so the stage times are not formed. HAND_UNROLL unrolls
 * the loops over the states completely (n is a constant): gcc -O2 does not by itself, and
 * a reference must be the fastest loop one can write at the flags of the comparison.
 * HAND_RK4(NAME, N, PAR_T, EVAL) defines
 *   static void NAME(const void *par, const double *y0, double h, long steps, double *yout)
 * with EVAL(y, dydt, par) the right-hand side written as a macro or inline function. */
#ifndef DYNKIT_BENCH_HAND_LOOPS_H
#define DYNKIT_BENCH_HAND_LOOPS_H

#include <string.h>

#if defined(__clang__)
#define HAND_UNROLL _Pragma("clang loop unroll(full)")
#elif defined(__GNUC__)
#define HAND_UNROLL _Pragma("GCC unroll 16")
#else
#define HAND_UNROLL
#endif

#define HAND_RK4(NAME, N, PAR_T, EVAL)                                                             \
    static __attribute__((noinline)) void NAME(const void *vpar, const double *y0, double h,       \
                                               long steps, double *yout)                           \
    {                                                                                              \
        const PAR_T *par = vpar;                                                                   \
        double y[N], Y[N], k1[N], k2[N], k3[N], k4[N];                                             \
        memcpy(y, y0, sizeof y);                                                                   \
        const double h2 = 0.5 * h, h6 = h / 6.0;                                                   \
        for (long step = 0; step < steps; step++) {                                                \
            EVAL(y, k1, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                Y[q] = y[q] + h2 * k1[q];                                                          \
            EVAL(Y, k2, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                Y[q] = y[q] + h2 * k2[q];                                                          \
            EVAL(Y, k3, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                Y[q] = y[q] + h * k3[q];                                                           \
            EVAL(Y, k4, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                y[q] += h6 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]);                          \
        }                                                                                          \
        memcpy(yout, y, sizeof y);                                                                 \
    }

#endif
