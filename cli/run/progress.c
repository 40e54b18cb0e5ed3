/* SPDX-License-Identifier: BSD-3-Clause */
/* Progress display for long runs: after one second, a line on stderr updated in place,
 * only when stderr is a terminal (never in pipes, files or CI logs). */
#define _POSIX_C_SOURCE 200809L
#include <time.h>
#include <unistd.h>

#include "cli.h"

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void cli_progress_start(cli_progress *p, int quiet)
{
    p->enabled = !quiet && isatty(fileno(stderr));
    p->start = now_seconds();
    p->shown = 0;
    p->last = 0.0;
}

int cli_progress_update(double t, double fraction, void *ctx)
{
    cli_progress *p = ctx;
    double elapsed = now_seconds() - p->start;
    if (elapsed < 1.0)
        return 0;
    double remaining = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    fprintf(stderr, "\r  %5.1f%%  t = %-12.6g s  elapsed %.1f s, about %.1f s left ",
            100.0 * fraction, t, elapsed, remaining);
    p->shown = 1;
    return 0;
}

void cli_progress_text(cli_progress *p, const char *text)
{
    if (!p->enabled)
        return;
    const double t = now_seconds(), elapsed = t - p->start;
    if (elapsed < 1.0 || t - p->last < 0.1)
        return;
    p->last = t;
    fprintf(stderr, "\r\033[K  %s  elapsed %.1f s", text, elapsed);
    p->shown = 1;
}

void cli_progress_finish(cli_progress *p)
{
    if (p->shown)
        fputs("\r\033[K", stderr);
    p->shown = 0;
}
