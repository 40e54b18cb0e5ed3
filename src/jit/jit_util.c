/* SPDX-License-Identifier: BSD-3-Clause */
/* Small helpers of every file of the jit layer: messages into the caller's buffer, the
 * model's note, a monotonic clock (POSIX clock_gettime). They call nothing of the layer. */
#define _POSIX_C_SOURCE 200809L
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "jit_internal.h"

int jit_fail(char *err, size_t errlen, const char *fmt, ...)
{
    if (err && errlen > 0) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return 1;
}

double jit_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void jit_note(char *note, size_t size, const char *text)
{
    if (!note || size == 0)
        return;
    size_t used = strlen(note);
    if (used + 1 < size)
        snprintf(note + used, size - used, "%s%s", used ? "; " : "", text);
}
