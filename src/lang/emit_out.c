/* SPDX-License-Identifier: BSD-3-Clause */
/* The only writer of the generated C text (emit_c.c calls nothing else to write it).
 *
 * The rule (docs/model-files.md, "What the generated C contains"): a byte that came from
 * outside dynkit (the file's path, names, numbers as written, `#:` text, units,
 * descriptions, table contents, anything from the model file or the command line) reaches
 * the C text only through lang_c_str, as a C string literal in which everything but
 * printable ASCII other than " \ ? is an escape. Everything else written is dynkit's own:
 * string literals of the translator's source (LANG_C_CODE accepts nothing else), numbers
 * formatted here (lang_c_num, and LANG_C_CODEF, whose format is a literal that may convert
 * numbers only: %s, %c, %p and %n are refused), identifiers made of a prefix and numbers
 * (never a name from the file), and text already written by these functions (lang_c_take,
 * lang_c_splice). No comment carries anything from outside. The fuzz harness
 * fuzz/fuzz_emit.c and tests/test_lang_emit.c check the result token by token.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lang/lang_internal.h"

static void put(lang_ctx *c, const char *s, size_t n)
{
    if (c->out_len + n + 1 > c->out_cap) {
        size_t cap = c->out_cap ? c->out_cap : 4096;
        if (c->out_len + n + 1 > LANG_MAX_OUTPUT)
            lang_fail(c, (lpos){0, 0}, "the model's C text would be too large (more than %u "
                      "MB)", (unsigned)(LANG_MAX_OUTPUT >> 20));
        while (c->out_len + n + 1 > cap)
            cap *= 2;
        char *o = realloc(c->out, cap);
        if (!o)
            lang_oom(c);
        c->out = o;
        c->out_cap = cap;
    }
    memcpy(c->out + c->out_len, s, n);
    c->out_len += n;
    c->out[c->out_len] = '\0';
}

void lang_c_code_(lang_ctx *c, const char *literal, size_t n) { put(c, literal, n); }

/* Whether fmt converts anything but numbers (a string, a character, a pointer, or %n). */
static int converts_text(const char *fmt)
{
    for (const char *f = fmt; *f; f++) {
        if (*f != '%')
            continue;
        f++;
        if (*f == '%')
            continue;
        while (*f && strchr("-+ #0123456789.*hljztL", *f))
            f++;
        if (!*f || strchr("scpnS", *f))
            return 1;
    }
    return 0;
}

void lang_c_codef_(lang_ctx *c, const char *fmt, ...)
{
    if (converts_text(fmt))
        lang_fail(c, (lpos){0, 0}, "internal error: the C text's format '%s' converts text",
                  fmt);
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (n < 0)
        lang_oom(c);
    if ((size_t)n < sizeof buf) {
        put(c, buf, (size_t)n);
        return;
    }
    char *big = lang_alloc(c, (size_t)n + 1);
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    put(c, big, (size_t)n);
}

/* The one way outside bytes reach the C text: a string literal of s (NULL: ""). Printable
 * ASCII but " \ and ? (trigraphs) as itself, newline as \n, every other byte as a
 * three-digit octal escape (which never takes a following digit). */
void lang_c_str(lang_ctx *c, const char *s)
{
    put(c, "\"", 1);
    const unsigned char *q = (const unsigned char *)(s ? s : "");
    while (*q) {
        const unsigned char *run = q;
        while (*q >= 32 && *q < 127 && *q != '"' && *q != '\\' && *q != '?')
            q++;
        if (q > run)
            put(c, (const char *)run, (size_t)(q - run));
        if (!*q)
            break;
        char b[8];
        if (*q == '"' || *q == '\\' || *q == '?') {
            b[0] = '\\';
            b[1] = (char)*q;
            put(c, b, 2);
        } else if (*q == '\n') {
            put(c, "\\n", 2);
        } else {
            snprintf(b, sizeof b, "\\%03o", *q);
            put(c, b, 4);
        }
        q++;
    }
    put(c, "\"", 1);
}

/* A double as C: %.17g (round-trips), always with a point or exponent, negative values
 * and -0 in parentheses, NAN and HUGE_VAL for the others. */
void lang_c_num(lang_ctx *c, double v)
{
    if (isnan(v)) {
        put(c, "NAN", 3);
        return;
    }
    if (isinf(v)) {
        lang_c_code_(c, v > 0 ? "HUGE_VAL" : "(-HUGE_VAL)", v > 0 ? 8 : 11);
        return;
    }
    char b[48];
    snprintf(b, sizeof b, "%.17g", v);
    if (!strpbrk(b, ".en"))
        strcat(b, ".0");
    const int paren = v < 0 || (v == 0 && signbit(v));
    if (paren)
        put(c, "(", 1);
    put(c, b, strlen(b));
    if (paren)
        put(c, ")", 1);
}


lang_ctext lang_c_take(lang_ctx *c)
{
    lang_ctext t = {lang_strndup(c, c->out ? c->out : "", c->out ? c->out_len : 0),
                    c->out ? c->out_len : 0};
    free(c->out);
    c->out = NULL;
    c->out_len = c->out_cap = 0;
    return t;
}

void lang_c_discard(lang_ctx *c)
{
    free(c->out);
    c->out = NULL;
    c->out_len = c->out_cap = 0;
}

void lang_c_splice(lang_ctx *c, lang_ctext t)
{
    if (t.text)
        put(c, t.text, t.len);
}

void lang_c_solver(lang_ctx *c)
{
    const char *s = lang_alg_solver_text();
    put(c, s, strlen(s));
}
