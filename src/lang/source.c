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

/* ---- lists with a range per item ---- */

/* A statement that takes a list of items separated by commas (par, number, init, by their
 * first letter as XPPAUT reads them, wiener, solv): the offset after its first word, else
 * -1. */
static int list_statement(const lang_line *l, int at)
{
    int k = at;
    while (k < l->len && (isalnum((unsigned char)l->text[k]) || l->text[k] == '-' ||
                          l->text[k] == '_'))
        k++;
    if (k == at || k == l->len || (l->text[k] != ' ' && l->text[k] != '\t'))
        return -1;
    int next = k;
    while (next < l->len && (l->text[next] == ' ' || l->text[next] == '\t'))
        next++;
    if (next == l->len || l->text[next] == '=')
        return -1;
    const int a = tolower((unsigned char)l->text[at]);
    const size_t n = (size_t)(k - at);
    char w[8] = "";
    if (n < sizeof w)
        for (size_t q = 0; q < n; q++)
            w[q] = (char)tolower((unsigned char)l->text[at + (int)q]);
    if (a == 'p' || a == 'n' || a == 'i' || strcmp(w, "wiener") == 0 || strcmp(w, "w") == 0 ||
        strcmp(w, "solv") == 0 || strcmp(w, "solve") == 0)
        return k;
    return -1;
}

/* The part [a, b) of line l as a line of its own. */
static lang_line sub_line(const lang_line *l, int a, int b)
{
    lang_line r = {l->text + a, b - a, l->pos + a};
    return r;
}

/* The end of the item of a list that starts at a (a comma outside brackets, or the end). */
static int item_end(const lang_line *l, int a)
{
    int b = a, depth = 0;
    for (; b < l->len && !(depth == 0 && l->text[b] == ','); b++)
        depth += l->text[b] == '(' || l->text[b] == '[' ? 1
                 : l->text[b] == ')' || l->text[b] == ']' ? -1 : 0;
    return b;
}

/* Whether a list statement's items are expanded each over its own range: when more than one
 * item holds a range, or one does and no other item has brackets (`par a[1..2]=3, k=1`
 * declares k once); not when another item reads the range's j (`init u[1..3]=1,v[j]=2`). */
static int list_per_item(lang_ctx *c, const lang_line *l, int items_from)
{
    if (!memchr(l->text, '.', (size_t)l->len))
        return 0;
    int ranges = 0, other_brackets = 0;
    for (int a = items_from; a < l->len;) {
        const int b = item_end(l, a);
        const lang_line item = sub_line(l, a, b);
        int open, close;
        long j1, j2;
        if (find_range(c, &item, &open, &close, &j1, &j2))
            ranges++;
        else
            other_brackets |= memchr(item.text, '[', (size_t)item.len) != NULL;
        a = b < l->len ? b + 1 : b;
    }
    return ranges > 1 || (ranges == 1 && !other_brackets);
}

/* A list statement with array ranges in several items (`init u[3..4]=1.05,v[3..4]=1.05`):
 * each item expanded over its own range, the items joined into one line of the statement
 * (list_per_item says when). */
static void expand_list(lang_ctx *c, lang_lbuf *scratch, lang_lbuf *acc, const lang_line *l,
                        int items_from, lang_line *out)
{
    acc->len = 0;
    for (int i = 0; i < items_from; i++)
        lang_lbuf_put(c, acc, l->text[i], l->pos[i]);
    int ranges = 0, first_range = -1;
    for (int a = items_from; a < l->len;) {
        const int b = item_end(l, a);
        const lang_line item = sub_line(l, a, b);
        int open = -1, close = -1;
        long j1 = 0, j2 = 0;
        const int ranged = find_range(c, &item, &open, &close, &j1, &j2);
        if (ranged && ranges++ == 0)
            first_range = a;
        const int brackets = memchr(item.text, '[', (size_t)item.len) != NULL;
        for (long j = j1; j <= j2; j++) {
            const lang_line e =
                brackets ? expand_one(c, scratch, &item, j, open, close, ranged) : item;
            if (acc->len > items_from)
                lang_lbuf_put(c, acc, ',', e.pos[0]);
            for (int k = 0; k < e.len; k++)
                lang_lbuf_put(c, acc, e.text[k], e.pos[k]);
        }
        a = b < l->len ? b + 1 : b;
    }
    if (ranges > 1)
        lang_warn(c, l->pos[first_range],
                  "each item of this list is set over its whole array range; XPPAUT sets only "
                  "the first element of each range but the last in such a line: give each "
                  "range a line of its own for a file both programs read alike");
    *out = lbuf_line(c, acc, l->pos[l->len]);
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
    lang_lbuf list;    /* a list statement's items, each expanded over its range */
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
    const int items_from = list_statement(l, at);
    if (items_from >= 0 && list_per_item(c, l, items_from)) {
        lang_line e;
        expand_list(c, &s->scratch, &s->list, l, items_from, &e);
        emit(c, s, &e);
        return;
    }
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
