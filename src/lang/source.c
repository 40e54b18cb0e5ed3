/* SPDX-License-Identifier: BSD-3-Clause */
/* Source lines of an .ode file: physical lines, continuation with a final `\`, and the
 * expansion of XPPAUT's array shorthand (manual, "Structure of ODE files"):
 *   x[1..4]'=-x[j]+[j]        one line per j, `[j1..j2]` becomes j, `[expr in j]` its value
 *   %[1..4] ... %             every line of the block once per j
 * Each character of a logical line keeps the place it came from, so an error in an
 * expanded or continued line points at the file's own line and column. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lang/lang_internal.h"

void lang_lbuf_put(lang_ctx *c, lang_lbuf *b, char ch, lpos p)
{
    if (b->len + 1 >= b->cap) {
        const int cap = b->cap ? 2 * b->cap : 128;
        if (cap > 4 * LANG_MAX_LINE + 16)
            lang_fail(c, p, "line too long (more than %d characters)", LANG_MAX_LINE);
        char *t = lang_alloc(c, (size_t)cap);
        lpos *q = lang_alloc(c, (size_t)cap * sizeof *q);
        if (b->len) {
            memcpy(t, b->text, (size_t)b->len);
            memcpy(q, b->pos, (size_t)b->len * sizeof *q);
        }
        b->text = t;
        b->pos = q;
        b->cap = cap;
    }
    b->text[b->len] = ch;
    b->pos[b->len] = p;
    b->len++;
    b->text[b->len] = '\0';
}

static lang_line lbuf_line(lang_ctx *c, lang_lbuf *b, lpos end)
{
    lang_line l;
    if (!b->text)
        lang_lbuf_put(c, b, ' ', end), b->len = 0, b->text[0] = '\0';
    if (b->len > LANG_MAX_LINE)
        lang_fail(c, b->pos[0], "line too long (more than %d characters)", LANG_MAX_LINE);
    b->pos[b->len] = end; /* lang_lbuf_put keeps room for one more */
    b->text[b->len] = '\0';
    l.text = b->text;
    l.len = b->len;
    l.pos = b->pos;
    return l;
}

/* ---- the integer expressions of [..] ---- */

typedef struct ixp {
    lang_ctx *c;
    const lang_line *l;
    int i, end;
    long j;
    int depth;
} ixp;

static void ix_blank(ixp *x)
{
    while (x->i < x->end && (x->l->text[x->i] == ' ' || x->l->text[x->i] == '\t'))
        x->i++;
}

static long long ix_sum(ixp *x);

static long long ix_atom(ixp *x)
{
    ix_blank(x);
    if (x->i >= x->end)
        lang_fail(x->c, x->l->pos[x->i], "missing index expression in [ ]");
    const char ch = x->l->text[x->i];
    if (++x->depth > 50)
        lang_fail(x->c, x->l->pos[x->i], "index expression nested too deeply");
    long long v;
    if (ch == '-') {
        x->i++;
        v = -ix_atom(x);
    } else if (ch == '+') {
        x->i++;
        v = ix_atom(x);
    } else if (ch == '(') {
        x->i++;
        v = ix_sum(x);
        ix_blank(x);
        if (x->i >= x->end || x->l->text[x->i] != ')')
            lang_fail(x->c, x->l->pos[x->i], "missing ')' in the index expression");
        x->i++;
    } else if (ch == 'j' || ch == 'J') {
        x->i++;
        v = x->j;
    } else if (isdigit((unsigned char)ch)) {
        v = 0;
        while (x->i < x->end && isdigit((unsigned char)x->l->text[x->i])) {
            v = v * 10 + (x->l->text[x->i] - '0');
            if (v > 1000000000)
                lang_fail(x->c, x->l->pos[x->i], "index too large");
            x->i++;
        }
    } else {
        lang_fail(x->c, x->l->pos[x->i],
                  "unexpected '%c' in an index: [ ] holds integers, j, + - * and ( )", ch);
    }
    x->depth--;
    if (v > 1000000000 || v < -1000000000)
        lang_fail(x->c, x->l->pos[x->i > 0 ? x->i - 1 : 0], "index too large");
    return v;
}

static long long ix_prod(ixp *x)
{
    long long v = ix_atom(x);
    for (;;) {
        ix_blank(x);
        if (x->i < x->end && x->l->text[x->i] == '*') {
            x->i++;
            v *= ix_atom(x);
            if (v > 1000000000 || v < -1000000000)
                lang_fail(x->c, x->l->pos[x->i - 1], "index too large");
        } else {
            return v;
        }
    }
}

static long long ix_sum(ixp *x)
{
    long long v = ix_prod(x);
    for (;;) {
        ix_blank(x);
        if (x->i < x->end && (x->l->text[x->i] == '+' || x->l->text[x->i] == '-')) {
            const char op = x->l->text[x->i++];
            const long long w = ix_prod(x);
            v = op == '+' ? v + w : v - w;
        } else {
            return v;
        }
    }
}

/* The value of the integer expression between [ and ] (offsets a..b, exclusive). */
static long ix_value(lang_ctx *c, const lang_line *l, int a, int b, long j)
{
    ixp x = {c, l, a, b, j, 0};
    const long long v = ix_sum(&x);
    ix_blank(&x);
    if (x.i != b)
        lang_fail(c, l->pos[x.i], "unexpected '%c' in an index: [ ] holds integers, j, + - * "
                  "and ( )", l->text[x.i]);
    return (long)v;
}

/* Offset of the matching ']' of the '[' at i, or -1. */
static int close_bracket(const lang_line *l, int i)
{
    for (int k = i + 1; k < l->len; k++) {
        if (l->text[k] == ']')
            return k;
        if (l->text[k] == '[')
            return -1;
    }
    return -1;
}

/* Find a range [j1..j2] in the line: 1 and its offsets, else 0. */
static int find_range(lang_ctx *c, const lang_line *l, int *open, int *close, long *j1,
                      long *j2)
{
    for (int i = 0; i < l->len; i++) {
        if (l->text[i] != '[')
            continue;
        const int k = close_bracket(l, i);
        if (k < 0)
            lang_fail(c, l->pos[i], "'[' without a matching ']'");
        const char *dots = NULL;
        for (int q = i + 1; q + 1 < k; q++)
            if (l->text[q] == '.' && l->text[q + 1] == '.') {
                dots = l->text + q;
                break;
            }
        if (!dots) {
            i = k;
            continue;
        }
        const int d = (int)(dots - l->text);
        *j1 = ix_value(c, l, i + 1, d, 0);
        *j2 = ix_value(c, l, d + 2, k, 0);
        *open = i;
        *close = k;
        if (*j2 < *j1)
            lang_fail(c, l->pos[i], "empty array range [%ld..%ld]", *j1, *j2);
        if (*j2 - *j1 + 1 > LANG_MAX_RANGE)
            lang_fail(c, l->pos[i], "array range [%ld..%ld] too long (at most %d elements)",
                      *j1, *j2, LANG_MAX_RANGE);
        return 1;
    }
    return 0;
}

/* One copy of line l for the index j: the range (if any, at open..close) becomes j, and
 * every other [expr] its value. */
static lang_line expand_one(lang_ctx *c, lang_lbuf *scratch, const lang_line *l, long j, int open,
                            int close, int with_j)
{
    lang_lbuf b = *scratch; /* reused: a line is consumed before the next one is made */
    b.len = 0;
    char num[32];
    for (int i = 0; i < l->len; i++) {
        const char ch = l->text[i];
        if (ch != '[') {
            lang_lbuf_put(c, &b, ch, l->pos[i]);
            continue;
        }
        const int k = close_bracket(l, i);
        if (k < 0)
            lang_fail(c, l->pos[i], "'[' without a matching ']'");
        long v;
        if (i == open) {
            v = j;
            (void)close;
        } else {
            for (int q = i + 1; q + 1 < k; q++)
                if (l->text[q] == '.' && l->text[q + 1] == '.')
                    lang_fail(c, l->pos[i], "a second array range in one line (one [j1..j2] "
                              "per line, or a %%[j1..j2] block)");
            if (!with_j)
                for (int q = i + 1; q < k; q++)
                    if (l->text[q] == 'j' || l->text[q] == 'J')
                        lang_fail(c, l->pos[q], "[j] outside an array line (x[1..n]'=... or "
                                  "a %%[1..n] block)");
            v = ix_value(c, l, i + 1, k, j);
        }
        const int suffix = i > 0 && lang_is_ident_char((unsigned char)l->text[i - 1]);
        if (suffix && v < 0)
            lang_fail(c, l->pos[i], "index %ld of a name is negative (j = %ld)", v, j);
        const int n = snprintf(num, sizeof num, v < 0 ? "(%ld)" : "%ld", v);
        for (int q = 0; q < n; q++)
            lang_lbuf_put(c, &b, num[q], l->pos[i]);
        i = k;
    }
    lang_line r = lbuf_line(c, &b, l->pos[l->len]);
    *scratch = b;
    return r;
}

/* ---- driver ---- */

typedef struct lines_state {
    lang_line_fn fn;
    void *ctx;
    long expanded;
    int stop;
    /* a %[j1..j2] block being collected */
    int in_block;
    long b1, b2;
    lpos block_pos;
    lvec block; /* lang_line */
    lang_lbuf scratch; /* the expanded line */
} lines_state;

static int first_char(const lang_line *l, int *at)
{
    int i = 0;
    while (i < l->len && (l->text[i] == ' ' || l->text[i] == '\t'))
        i++;
    if (at)
        *at = i;
    return i < l->len ? (unsigned char)l->text[i] : 0;
}

static void emit(lang_ctx *c, lines_state *s, const lang_line *l)
{
    if (s->stop)
        return;
    if (++s->expanded > LANG_MAX_EXPANDED)
        lang_fail(c, l->pos[0], "too many lines after expanding arrays (more than %d)",
                  LANG_MAX_EXPANDED);
    if (s->fn(c, l, s->ctx))
        s->stop = 1;
}

static void logical_line(lang_ctx *c, lines_state *s, const lang_line *l)
{
    int at;
    const int ch = first_char(l, &at);
    if (ch != '#' && ch != '"') /* before [m] of int[m]{...} could be read as an index */
        lang_volt_line(c, l);
    if (c->no_arrays) { /* [ ] holds units (src/mbs) */
        emit(c, s, l);
        return;
    }
    if (s->in_block) {
        if (ch == '%') {
            /* the end of the block: each line once per j */
            s->in_block = 0;
            for (long j = s->b1; j <= s->b2 && !s->stop; j++)
                for (int k = 0; k < s->block.n && !s->stop; k++) {
                    const lang_line *bl = &LVEC_AT(s->block, lang_line, k);
                    const int bc = first_char(bl, NULL);
                    if (bc == '#' || bc == '"' || bc == 0) {
                        emit(c, s, bl);
                        continue;
                    }
                    lang_line e = expand_one(c, &s->scratch, bl, j, -1, -1, 1);
                    emit(c, s, &e);
                }
            s->block.n = 0;
            return;
        }
        lang_line *keep = lvec_push(c, &s->block, sizeof(lang_line));
        keep->len = l->len;
        keep->text = lang_strndup(c, l->text, (size_t)l->len);
        keep->pos = lang_alloc(c, ((size_t)l->len + 1) * sizeof *keep->pos);
        memcpy(keep->pos, l->pos, ((size_t)l->len + 1) * sizeof *keep->pos);
        return;
    }
    if (ch == '#' || ch == '"' || ch == 0) {
        emit(c, s, l);
        return;
    }
    if (ch == '%') {
        int open, close;
        long j1, j2;
        int k = at + 1;
        while (k < l->len && (l->text[k] == ' ' || l->text[k] == '\t'))
            k++;
        if (k >= l->len || l->text[k] != '[') {
            /* "% text": XPPAUT reads a '%' line that opens no block as a comment */
            return;
        }
        if (!find_range(c, l, &open, &close, &j1, &j2))
            lang_fail(c, l->pos[at], "'%%' starts an array block: %%[j1..j2]");
        s->in_block = 1;
        s->b1 = j1;
        s->b2 = j2;
        s->block_pos = l->pos[at];
        return;
    }
    int open, close;
    long j1, j2;
    if (!find_range(c, l, &open, &close, &j1, &j2)) {
        if (memchr(l->text, '[', (size_t)l->len)) {
            /* b100'=-flux[100]: constant indices */
            lang_line e = expand_one(c, &s->scratch, l, 0, -1, -1, 0);
            emit(c, s, &e);
            return;
        }
        emit(c, s, l);
        return;
    }
    for (long j = j1; j <= j2 && !s->stop; j++) {
        lang_line e = expand_one(c, &s->scratch, l, j, open, close, 1);
        emit(c, s, &e);
    }
}

void lang_lines(lang_ctx *c, lang_line_fn fn, void *ctx)
{
    lines_state s = {0};
    s.fn = fn;
    s.ctx = ctx;
    lang_lbuf b = {0};
    int continued = 0;
    for (int ln = 0; ln < c->nlines && !s.stop; ln++) {
        const size_t a = c->line_start[ln];
        size_t e = a;
        while (e < c->len && c->text[e] != '\n')
            e++;
        size_t last = e;
        while (last > a && (c->text[last - 1] == '\r' || c->text[last - 1] == ' ' ||
                            c->text[last - 1] == '\t'))
            last--;
        const int cont = last > a && c->text[last - 1] == '\\';
        if (cont)
            last--;
        else
            last = e;
        if (!continued)
            b.len = 0; /* the buffer is reused: lines are consumed one by one */
        for (size_t k = a; k < last; k++) {
            char ch = c->text[k];
            const lpos p = {ln + 1, (int)(k - a) + 1};
            if (ch == '\0')
                lang_fail(c, p, "NUL character in the file");
            if (ch == '\r')
                ch = ' ';
            if (ln == 0 && k < 3 && c->len >= 3 && memcmp(c->text, "\xef\xbb\xbf", 3) == 0)
                ch = ' '; /* a UTF-8 byte order mark */
            lang_lbuf_put(c, &b, ch, p);
        }
        continued = cont;
        if (cont && ln + 1 < c->nlines)
            continue;
        const lpos end = {ln + 1, (int)(last - a) + 1};
        lang_line l = lbuf_line(c, &b, end);
        logical_line(c, &s, &l);
        continued = 0;
    }
    if (s.in_block && !s.stop)
        lang_fail(c, s.block_pos, "array block %%[%ld..%ld] without its closing '%%' line",
                  s.b1, s.b2);
}
