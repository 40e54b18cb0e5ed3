/* SPDX-License-Identifier: BSD-3-Clause */
/* wp_front.h — the cost of a solver at a given error, read off its work-precision points:
 * the Pareto front (points sorted by cost, each kept when its error is below that of every
 * cheaper point), linear in log-log between neighbours. Shared by the work-precision
 * sections of the suite (suite.c) and the families of problems (family.c).
 */
#ifndef DYNKIT_BENCH_WP_FRONT_H
#define DYNKIT_BENCH_WP_FRONT_H

/* Cost at error level e from n points (err[i], cost[i]), of which those with ok[i] == 0 (ok
 * may be NULL), a non-positive error or cost are skipped; NAN outside the errors the front
 * covers. n at most WP_FRONT_MAX. */
#define WP_FRONT_MAX 64
double wp_front_cost_at(int n, const double *err, const double *cost, const int *ok, double e);

#endif
