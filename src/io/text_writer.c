/* SPDX-License-Identifier: BSD-3-Clause */
/* Buffered text output (dyn_text_writer, io.h): bytes and shortest round-trip numbers are
 * gathered in a 64 KiB buffer and handed to the stream with one fwrite per full buffer, so
 * writing a table costs the formatting, not one stdio call per number. A short fwrite (a
 * full disk, a closed pipe) is kept and reported by every later call. */
#include <string.h>

#include "dynkit/io.h"
#include "dynkit/ode.h"

void dyn_text_writer_init(dyn_text_writer *w, FILE *out)
{
    w->out = out;
    w->len = 0;
    w->failed = 0;
}

int dyn_text_writer_flush(dyn_text_writer *w)
{
    if (!w->failed && w->len > 0 && fwrite(w->buf, 1, w->len, w->out) != w->len)
        w->failed = 1;
    w->len = 0;
    return w->failed ? DYN_ERR_IO : DYN_OK;
}

int dyn_text_write(dyn_text_writer *w, const char *s, size_t n)
{
    while (n > 0) {
        if (w->len == sizeof w->buf && dyn_text_writer_flush(w) != DYN_OK)
            return DYN_ERR_IO;
        size_t room = sizeof w->buf - w->len;
        size_t k = n < room ? n : room;
        memcpy(w->buf + w->len, s, k);
        w->len += k;
        s += k;
        n -= k;
    }
    return w->failed ? DYN_ERR_IO : DYN_OK;
}

int dyn_text_write_double(dyn_text_writer *w, double x)
{
    if (sizeof w->buf - w->len < DYN_DOUBLE_CHARS && dyn_text_writer_flush(w) != DYN_OK)
        return DYN_ERR_IO;
    w->len += (size_t)dyn_format_double(x, w->buf + w->len);
    return w->failed ? DYN_ERR_IO : DYN_OK;
}
