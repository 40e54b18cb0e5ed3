/* SPDX-License-Identifier: BSD-3-Clause */
/* Escaping of outside text for XML (SVG, HTML), for JSON inside HTML's <script> and for a
 * terminal (escape.h): W3C XML 1.0 sec. 2.2 (Char) and 2.4, RFC 8259 sec. 7, RFC 3629
 * (UTF-8), HTML's script data state (WHATWG HTML, 13.2.5.4), ECMA-48's C0 and C1 control
 * functions. */
#include <string.h>

#include "dynkit/io.h"
#include "util/escape.h"

#define REPLACEMENT DYN_UTF8_REPLACEMENT

/* The character that starts at *p (the library's UTF-8 reader, dynkit/io.h). */
static long next_char(const unsigned char **p) { return dyn_utf8_next(p); }

/* Character v in UTF-8. */
static int put_utf8(FILE *out, long v)
{
    unsigned char b[4];
    int n;
    if (v < 0x80)
        b[0] = (unsigned char)v, n = 1;
    else if (v < 0x800)
        b[0] = (unsigned char)(0xC0 | (v >> 6)), b[1] = (unsigned char)(0x80 | (v & 0x3F)), n = 2;
    else if (v < 0x10000)
        b[0] = (unsigned char)(0xE0 | (v >> 12)), b[1] = (unsigned char)(0x80 | ((v >> 6) & 0x3F)),
        b[2] = (unsigned char)(0x80 | (v & 0x3F)), n = 3;
    else
        b[0] = (unsigned char)(0xF0 | (v >> 18)), b[1] = (unsigned char)(0x80 | ((v >> 12) & 0x3F)),
        b[2] = (unsigned char)(0x80 | ((v >> 6) & 0x3F)), b[3] = (unsigned char)(0x80 | (v & 0x3F)),
        n = 4;
    return fwrite(b, 1, (size_t)n, out) != (size_t)n;
}

int cli_xml_escaped(FILE *out, const char *s)
{
    int bad = 0;
    const unsigned char *p = (const unsigned char *)s;
    while (p && *p && !bad) {
        long v = next_char(&p);
        switch (v) {
        case '<': bad = fputs("&lt;", out) < 0; break;
        case '>': bad = fputs("&gt;", out) < 0; break;
        case '&': bad = fputs("&amp;", out) < 0; break;
        case '"': bad = fputs("&quot;", out) < 0; break;
        case '\'': bad = fputs("&#39;", out) < 0; break;
        case '\t':
        case '\n':
        case '\r': bad = fprintf(out, "&#%ld;", v) < 0; break;
        default:
            /* XML 1.0's Char: no other control character, no U+FFFE or U+FFFF */
            if (v < 0x20 || v == 0x7F || v == 0xFFFE || v == 0xFFFF)
                v = REPLACEMENT;
            bad = put_utf8(out, v);
        }
    }
    return bad;
}

int cli_json_escaped(FILE *out, const char *s)
{
    int bad = fputc('"', out) == EOF;
    const unsigned char *p = (const unsigned char *)(s ? s : "");
    while (*p && !bad) {
        const long v = next_char(&p);
        switch (v) {
        case '"': bad = fputs("\\\"", out) < 0; break;
        case '\\': bad = fputs("\\\\", out) < 0; break;
        case '\n': bad = fputs("\\n", out) < 0; break;
        case '\t': bad = fputs("\\t", out) < 0; break;
        case '\r': bad = fputs("\\r", out) < 0; break;
        default:
            if (v < 0x20 || v == '<' || v == '>' || v == '&' || v == 0x2028 || v == 0x2029 ||
                v == REPLACEMENT)
                bad = fprintf(out, "\\u%04lx", v) < 0;
            else
                bad = put_utf8(out, v);
        }
    }
    return bad | (fputc('"', out) == EOF);
}

const char *cli_terminal_text(const char *s, int lines, char *buf, size_t size)
{
    return dyn_terminal_text(s, lines, buf, size);
}
