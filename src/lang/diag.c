/* SPDX-License-Identifier: BSD-3-Clause */
/* Diagnostics and memory of the .ode translator: the arena every pass allocates from, the
 * error exit (FILE:LINE:COL, the source line and a caret, like a C compiler's message) and
 * the notes of a successful translation (dynkit/lang.h). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h"
#include "lang/lang_internal.h"

struct lang_block {
    lang_block *next;
    size_t used, size; /* bytes of the data below */
    max_align_t data[];
};

enum { LANG_CHUNK = 1 << 16, LANG_BIG = 1 << 12 };

static lang_block *new_block(lang_ctx *c, size_t size)
{
    if (c->bytes + size > LANG_MAX_MEMORY)
        lang_fail(c, (lpos){0, 0}, "the model is too large to translate (more than %u MB of "
                  "memory)", (unsigned)(LANG_MAX_MEMORY >> 20));
    lang_block *b = malloc(sizeof *b + size);
    if (!b)
        lang_oom(c);
    b->used = 0;
    b->size = size;
    c->bytes += size;
    return b;
}

/* Zeroed memory from the arena: small pieces from 64 KB chunks, large ones alone. */
void *lang_alloc(lang_ctx *c, size_t n)
{
    if (n > ((size_t)1 << 40))
        lang_oom(c);
    n = (n + sizeof(max_align_t) - 1) / sizeof(max_align_t) * sizeof(max_align_t);
    if (n == 0)
        n = sizeof(max_align_t);
    lang_block *b;
    if (n > LANG_BIG) {
        b = new_block(c, n);
        if (c->blocks) { /* keep the current chunk first */
            b->next = c->blocks->next;
            c->blocks->next = b;
        } else {
            b->next = NULL;
            c->blocks = b;
        }
        b->used = n;
    } else {
        b = c->blocks;
        if (!b || b->size - b->used < n) {
            b = new_block(c, LANG_CHUNK);
            b->next = c->blocks;
            c->blocks = b;
        }
    }
    void *p = (char *)b->data + (n > LANG_BIG ? 0 : b->used);
    if (n <= LANG_BIG)
        b->used += n;
    memset(p, 0, n);
    return p;
}

char *lang_strndup(lang_ctx *c, const char *s, size_t n)
{
    char *d = lang_alloc(c, n + 1);
    memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

char *lang_strdup(lang_ctx *c, const char *s) { return lang_strndup(c, s, strlen(s)); }

char *lang_printf(lang_ctx *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        lang_oom(c);
    char *s = lang_alloc(c, (size_t)n + 1);
    va_start(ap, fmt);
    vsnprintf(s, (size_t)n + 1, fmt, ap);
    va_end(ap);
    return s;
}

void lang_free_all(lang_ctx *c)
{
    while (c->blocks) {
        lang_block *b = c->blocks;
        c->blocks = b->next;
        free(b);
    }
}

void *lvec_push(lang_ctx *c, lvec *v, size_t elem)
{
    if (v->n == v->cap) {
        const int cap = v->cap ? 2 * v->cap : 8;
        void *data = lang_alloc(c, (size_t)cap * elem);
        if (v->n)
            memcpy(data, v->data, (size_t)v->n * elem);
        v->data = data; /* the old block stays in the arena until the end */
        v->cap = cap;
    }
    char *slot = (char *)v->data + (size_t)v->n * elem;
    v->n++;
    memset(slot, 0, elem);
    return slot;
}

static void copy_trunc(char *dst, size_t size, const char *src, size_t n)
{
    if (n >= size)
        n = size - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

_Noreturn void lang_oom(lang_ctx *c)
{
    c->status = 1;
    dyn_lang_diag *d = c->diag;
    if (d) {
        d->line = d->col = 0;
        snprintf(d->message, sizeof d->message, "out of memory while translating the model");
        d->excerpt[0] = '\0';
    }
    longjmp(*c->fail, 1);
}

_Noreturn void lang_work_exceeded(lang_ctx *c, lpos p)
{
    lang_fail(c, p, "the formulas expand to more than %ld terms (the bound of the "
              "translator's work: calls of functions that read the states are expanded "
              "where they are differentiated, and so are all calls when a function would "
              "take more than %d arguments with the fixed quantities it reads); write the "
              "nested calls as fixed quantities, each computed once",
              LANG_MAX_WORK, LANG_MAX_ARGS);
}

_Noreturn void lang_fail(lang_ctx *c, lpos p, const char *fmt, ...)
{
    c->status = 2;
    dyn_lang_diag *d = c->diag;
    if (d) {
        d->line = p.line;
        d->col = p.col;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(d->message, sizeof d->message, fmt, ap);
        va_end(ap);
        d->excerpt[0] = '\0';
        if (p.line >= 1 && p.line <= c->nlines) {
            const size_t a = c->line_start[p.line - 1];
            size_t b = a;
            while (b < c->len && c->text[b] != '\n' && c->text[b] != '\r')
                b++;
            copy_trunc(d->excerpt, sizeof d->excerpt, c->text + a, b - a);
            /* control characters would move the caret: show them as blanks */
            for (char *s = d->excerpt; *s; s++)
                if ((unsigned char)*s < 32)
                    *s = ' ';
        }
    }
    longjmp(*c->fail, 1);
}

void lang_note(lang_ctx *c, lpos p, const char *fmt, ...)
{
    if (!c->note)
        return;
    char msg[600];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    c->note(c->path, p.line, msg, c->note_ctx);
}

void lang_warn(lang_ctx *c, lpos p, const char *fmt, ...)
{
    if (!c->note)
        return;
    char msg[600];
    const int k = snprintf(msg, sizeof msg, "%s", DYN_LANG_WARNING);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg + k, sizeof msg - (size_t)k, fmt, ap);
    va_end(ap);
    c->note(c->path, p.line, msg, c->note_ctx);
}

/* The columns a terminal gives the first n bytes of excerpt once escaped (one per
 * character: dyn_terminal_text keeps UTF-8 characters whole and writes other bytes as
 * four). */
static size_t shown_width(const char *excerpt, size_t n)
{
    char prefix[sizeof ((dyn_lang_diag *)0)->excerpt], shown[4 * sizeof prefix + 1];
    copy_trunc(prefix, sizeof prefix, excerpt, n);
    dyn_terminal_text(prefix, 1, shown, sizeof shown);
    size_t width = 0;
    for (const unsigned char *p = (const unsigned char *)shown; *p; p++)
        width += (*p & 0xC0) != 0x80;
    return width;
}

char *dyn_lang_diag_format(const dyn_lang_diag *d, char *buf, size_t size)
{
    if (!buf || size == 0)
        return buf;
    buf[0] = '\0';
    if (!d)
        return buf;
    /* the file's name, the message and the line quote outside text: escaped for a terminal
     * by the one escaper (dyn_terminal_text), so no control byte of them reaches it raw */
    char path[4 * sizeof d->path + 1], message[4 * sizeof d->message + 1];
    char excerpt[4 * sizeof d->excerpt + 1];
    dyn_terminal_text(d->path, 0, path, sizeof path);
    dyn_terminal_text(d->message, 1, message, sizeof message);
    dyn_terminal_text(d->excerpt, 1, excerpt, sizeof excerpt);
    size_t used = 0;
    int n;
    if (d->line > 0)
        n = snprintf(buf, size, "%s:%d:%d: error: %s\n", path, d->line, d->col, message);
    else
        n = snprintf(buf, size, "%s: error: %s\n", path, message);
    if (n < 0 || (size_t)n >= size)
        return buf;
    used = (size_t)n;
    if (d->line > 0 && d->excerpt[0]) {
        n = snprintf(buf + used, size - used, "  %s\n", excerpt);
        if (n < 0 || (size_t)n >= size - used)
            return buf;
        used += (size_t)n;
        const size_t col = d->col > 0 ? (size_t)d->col : 1;
        const size_t elen = strlen(d->excerpt);
        const size_t width = shown_width(d->excerpt, col - 1 < elen ? col - 1 : elen) +
                             (col - 1 > elen ? col - 1 - elen : 0);
        if (used + width + 4 < size) {
            buf[used++] = ' ';
            buf[used++] = ' ';
            for (size_t i = 0; i < width; i++)
                buf[used++] = i < elen && d->excerpt[i] == '\t' ? '\t' : ' ';
            buf[used++] = '^';
            buf[used++] = '\n';
            buf[used] = '\0';
        }
    }
    return buf;
}
