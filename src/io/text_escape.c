/* SPDX-License-Identifier: BSD-3-Clause */
/* Text from outside (file names, lines of files, names and units in them) made safe for a
 * terminal (dynkit/io.h): the one escaper of every message of the library and the tool.
 * Printable ASCII and well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates,
 * nothing above U+10FFFF) are kept; every other byte is written \xNN: the C0 and C1 control
 * functions of ECMA-48 (ESC, BEL, CSI U+009B, which some terminals obey), DEL, and bytes
 * that are not UTF-8. */
#include <stdio.h>
#include <string.h>

#include "dynkit/io.h"

long dyn_utf8_next(const unsigned char **p)
{
    const unsigned char *s = *p;
    const unsigned c = s[0];
    int len;
    long v, min;
    if (c < 0x80) {
        *p = s + 1;
        return (long)c;
    }
    if (c >= 0xC2 && c <= 0xDF)
        len = 2, v = c & 0x1F, min = 0x80;
    else if (c >= 0xE0 && c <= 0xEF)
        len = 3, v = c & 0x0F, min = 0x800;
    else if (c >= 0xF0 && c <= 0xF4)
        len = 4, v = c & 0x07, min = 0x10000;
    else {
        *p = s + 1;
        return DYN_UTF8_REPLACEMENT;
    }
    for (int k = 1; k < len; k++) {
        if ((s[k] & 0xC0) != 0x80) { /* also stops at the terminating NUL */
            *p = s + 1;
            return DYN_UTF8_REPLACEMENT;
        }
        v = (v << 6) | (s[k] & 0x3F);
    }
    if (v < min || v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF)) {
        *p = s + 1;
        return DYN_UTF8_REPLACEMENT;
    }
    *p = s + len;
    return v;
}

const char *dyn_terminal_text(const char *s, int lines, char *buf, size_t size)
{
    if (!buf || size == 0)
        return buf;
    if (size < 4) {
        buf[0] = '\0';
        return buf;
    }
    size_t used = 0, cut = 0; /* cut: where "..." fits after the text kept */
    const unsigned char *p = (const unsigned char *)(s ? s : "");
    while (*p) {
        if (used + 4 <= size)
            cut = used;
        const unsigned char *start = p;
        const long v = dyn_utf8_next(&p);
        const size_t len = (size_t)(p - start);
        /* kept: printable characters, and tab and line feed when asked */
        const int keep = (v >= 0x20 && v != 0x7F && !(v >= 0x80 && v <= 0x9F) &&
                          !(v == DYN_UTF8_REPLACEMENT && len == 1)) ||
                         (lines && (v == '\t' || v == '\n'));
        const size_t need = keep ? len : 4 * len;
        if (used + need + 1 > size) { /* no room for it and the NUL */
            memcpy(buf + cut, "...", 4);
            return buf;
        }
        if (keep) {
            memcpy(buf + used, start, len);
            used += len;
        } else {
            for (size_t k = 0; k < len; k++)
                used += (size_t)snprintf(buf + used, size - used, "\\x%02X", start[k]);
        }
    }
    buf[used] = '\0';
    return buf;
}

const char *dyn_text_escaped(const char *s, char *buf, size_t size)
{
    return dyn_terminal_text(s, 0, buf, size);
}
