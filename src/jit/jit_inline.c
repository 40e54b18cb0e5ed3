/* SPDX-License-Identifier: BSD-3-Clause */
/* The embedded headers put into a model's text in memory, for libtcc when the cache (where
 * the headers directory lives) cannot be written: each `#include` of a dynkit header is
 * replaced by the header's text, as the preprocessor would read it (C11 6.10.2), framed by
 * `#line` directives (C11 6.10.4) so that a diagnostic still names the user's file and line,
 * or the header's. The headers' include guards make repeated inclusions empty, as with
 * files. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jit_internal.h"

#define MAX_DEPTH 16 /* the headers nest 4 deep; a cycle stops here */

typedef struct text_buf {
    char *p;
    size_t len, cap;
    int bad; /* out of memory */
} text_buf;

static void put(text_buf *b, const char *s, size_t n)
{
    if (b->bad)
        return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 1 << 16;
        while (cap < b->len + n + 1)
            cap *= 2;
        char *p = realloc(b->p, cap);
        if (!p) {
            b->bad = 1;
            return;
        }
        b->p = p;
        b->cap = cap;
    }
    memcpy(b->p + b->len, s, n);
    b->len += n;
    b->p[b->len] = '\0';
}

static const char *skip_blanks(const char *s, const char *end)
{
    while (s < end && (*s == ' ' || *s == '\t'))
        s++;
    return s;
}

/* s..end a line: after "#", blanks and `word`, a pointer past it, else NULL */
static const char *directive(const char *s, const char *end, const char *word)
{
    s = skip_blanks(s, end);
    if (s == end || *s != '#')
        return NULL;
    s = skip_blanks(s + 1, end);
    const size_t n = strlen(word);
    if ((size_t)(end - s) < n || memcmp(s, word, n) != 0)
        return NULL;
    return s + n;
}

/* the embedded header a line `#include <dynkit/NAME>` (or "dynkit/NAME") names, else NULL */
static const dyn_jit_header *included_header(const char *s, const char *end)
{
    s = directive(s, end, "include");
    if (!s)
        return NULL;
    s = skip_blanks(s, end);
    if (s == end || (*s != '<' && *s != '"'))
        return NULL;
    const char close = *s == '<' ? '>' : '"';
    s++;
    if ((size_t)(end - s) < 7 || memcmp(s, "dynkit/", 7) != 0)
        return NULL;
    s += 7;
    const char *stop = memchr(s, close, (size_t)(end - s));
    if (!stop)
        return NULL;
    for (int i = 0; i < dyn_jit_header_count; i++) {
        const char *name = dyn_jit_headers[i].name;
        if (strlen(name) == (size_t)(stop - s) && memcmp(name, s, (size_t)(stop - s)) == 0)
            return &dyn_jit_headers[i];
    }
    return NULL;
}

/* a line `#line N "NAME"`: *line = N and the literal (quotes included) into *name, *name_len
 * (left as they were without one); 1, or 0 when the line is no #line */
static int line_directive(const char *s, const char *end, long *line, const char **name,
                          size_t *name_len)
{
    s = directive(s, end, "line");
    if (!s)
        return 0;
    char *after;
    char digits[24];
    const char *d = skip_blanks(s, end);
    size_t n = (size_t)(end - d) < sizeof digits - 1 ? (size_t)(end - d) : sizeof digits - 1;
    memcpy(digits, d, n);
    digits[n] = '\0';
    const long v = strtol(digits, &after, 10);
    if (after == digits)
        return 0;
    *line = v;
    const char *q = skip_blanks(d + (after - digits), end);
    if (q < end && *q == '"') {
        const char *c = q + 1;
        while (c < end && *c != '"')
            c += (*c == '\\' && c + 1 < end) ? 2 : 1;
        if (c < end) {
            *name = q;
            *name_len = (size_t)(c + 1 - q);
        }
    }
    return 1;
}

static void expand(text_buf *b, const char *text, size_t len, const char *name, size_t name_len,
                   int depth)
{
    long line = 1;
    const char *s = text, *end = text + len;
    while (s < end && !b->bad) {
        const char *nl = memchr(s, '\n', (size_t)(end - s));
        const char *eol = nl ? nl : end;
        const dyn_jit_header *h = depth < MAX_DEPTH ? included_header(s, eol) : NULL;
        if (h) {
            char head[200], tail[64];
            const int hn = snprintf(head, sizeof head, "#line 1 \"dynkit/%s\"\n", h->name);
            put(b, head, (size_t)hn);
            expand(b, (const char *)h->data, h->size, head + 8, (size_t)hn - 9, depth + 1);
            const int tn = snprintf(tail, sizeof tail, "#line %ld ", line + 1);
            put(b, tail, (size_t)tn);
            put(b, name, name_len);
            put(b, "\n", 1);
            line++;
        } else {
            put(b, s, (size_t)(eol - s));
            put(b, "\n", 1);
            if (!line_directive(s, eol, &line, &name, &name_len))
                line++;
        }
        s = nl ? nl + 1 : end;
    }
}

char *jit_headers_inline(const char *text)
{
    text_buf b = {0};
    static const char unnamed[] = "\"model.c\"";
    expand(&b, text, strlen(text), unnamed, sizeof unnamed - 1, 0);
    if (b.bad) {
        free(b.p);
        return NULL;
    }
    return b.p;
}
