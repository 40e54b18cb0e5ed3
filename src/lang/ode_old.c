/* SPDX-License-Identifier: BSD-3-Clause */
/* XPPAUT's first .ode format, which XPPAUT still reads when the file's first line is a
 * positive number (XPPAUT's form_ode.c, its "old style" compiler; each rule checked against
 * xppaut 6.11 -silent in tests/xppaut/oldformat/). The first line gives the count of
 * equations: the variables' and the auxiliary quantities'. Each line is then known by the
 * first letter of its first word (case-insensitive; the rest of the word is not read):
 *   v NAME=VALUE,...   variables and their initial values (values default to 0)
 *   f NAME,...         fixed quantities
 *   p NAME=VALUE,...   parameters          n NAME=VALUE,...  numbers (hidden parameters)
 *   u NAME N FORMULA   a function of N arguments, named arg1 ... argN in FORMULA
 *   o FORMULA          one right-hand side: the k-th `o` line belongs to the k-th of the
 *                      variables, then the fixed quantities, then the auxiliary quantities
 *   i FORMULA          an `o` line whose variable is given by an integral equation,
 *                      x(t) = FORMULA (`volt` of the current format)
 *   k NAME MU FORMULA  a kernel: NAME in an `o` or `i` line is int[MU]{FORMULA}
 *   a NAME,...         names of the auxiliary quantities (else AUX1, AUX2, ...)
 *   g / t / w          global, table, wiener: as in the current format
 *   @ (first column)   options           x  a named set (ignored, as `set` is)
 *   s, h               XPPAUT's own help (nothing to read)     d  the end of the file
 * Lines of any other first character are ignored, as XPPAUT ignores them (comments). An
 * `o` line beyond the count ends the reading, as in XPPAUT. Markov states (m, r), boundary
 * conditions (b) and option files (c) are refused by letter.
 *
 * Each line is rewritten as the statements of the current format with every character
 * keeping its place in the file, and read by the current format's parser (ode_parse.c), so
 * a message points at the file's own line and column. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "lang/lang_internal.h"

/* a physical line of the file (ln: 0-based) */
typedef struct pline {
    const char *s;
    int len, ln;
} pline;

/* a span [from, to) of a physical line */
typedef struct span {
    int ln, from, to;
} span;

/* k NAME MU FORMULA: NAME in a right-hand side is the integral int[MU]{FORMULA} */
typedef struct kernel {
    span name, mu, formula;
} kernel;

typedef struct oldf {
    lang_ctx *c;
    lang_line_fn fn;
    void *ctx;
    int stop; /* the file's text ends here */
    long neq;
    lvec vars, fixes, auxnames; /* span (the names) */
    lvec rhs;                   /* span (the formula) of each `o` or `i` line */
    lvec rhs_word;              /* lpos: the place of its first word */
    lvec rhs_int;               /* int: 1 for an `i` line (an integral equation) */
    lvec kernels;               /* kernel: the `k` lines */
} oldf;

static lpos at(const pline *p, int k)
{
    return (lpos){p->ln + 1, k + 1};
}

static int blank(int ch)
{
    return ch == ' ' || ch == '\t';
}

/* words the translation writes: every character at the place p */
static void put_word(lang_ctx *c, lang_lbuf *b, const char *s, lpos p)
{
    while (*s)
        lang_lbuf_put(c, b, *s++, p);
}

static pline physical(lang_ctx *c, int ln)
{
    pline p;
    const size_t a = c->line_start[ln];
    size_t e = a;
    while (e < c->len && c->text[e] != '\n')
        e++;
    p.s = c->text + a;
    p.len = (int)(e - a);
    p.ln = ln;
    if (p.len > LANG_MAX_LINE)
        lang_fail(c, at(&p, 0), "line too long (more than %d characters)", LANG_MAX_LINE);
    for (int k = 0; k < p.len; k++)
        if (p.s[k] == '\0')
            lang_fail(c, at(&p, k), "NUL character in the file");
    return p;
}

static void put_span(lang_ctx *c, lang_lbuf *b, span sp)
{
    const pline p = physical(c, sp.ln);
    for (int k = sp.from; k < sp.to; k++)
        lang_lbuf_put(c, b, p.s[k] == '\r' ? ' ' : p.s[k], at(&p, k));
}

/* A right-hand side: the names of kernels (`k` lines) written as their integrals. */
static void put_formula(oldf *o, lang_lbuf *b, span sp)
{
    lang_ctx *c = o->c;
    const pline p = physical(c, sp.ln);
    int k = sp.from;
    while (k < sp.to) {
        if (!lang_is_ident_start((unsigned char)p.s[k]) ||
            (k > sp.from && lang_is_ident_char((unsigned char)p.s[k - 1]))) {
            put_span(c, b, (span){sp.ln, k, k + 1});
            k++;
            continue;
        }
        int e = k + 1;
        while (e < sp.to && lang_is_ident_char((unsigned char)p.s[e]))
            e++;
        const kernel *kn = NULL;
        for (int i = 0; i < o->kernels.n && !kn; i++) {
            const kernel *q = &LVEC_AT(o->kernels, kernel, i);
            const pline qp = physical(c, q->name.ln);
            if (q->name.to - q->name.from == e - k &&
                strncasecmp(qp.s + q->name.from, p.s + k, (size_t)(e - k)) == 0)
                kn = q;
        }
        if (!kn) {
            put_span(c, b, (span){sp.ln, k, e});
        } else {
            put_word(c, b, "int[", at(&p, k));
            put_span(c, b, kn->mu);
            put_word(c, b, "]{", at(&p, k));
            put_span(c, b, kn->formula);
            lang_lbuf_put(c, b, '}', at(&p, e - 1));
        }
        k = e;
    }
}

/* hand the statement written in b to the current format's parser; end: its end's place */
static void flush(oldf *o, lang_lbuf *b, lpos end)
{
    lang_ctx *c = o->c;
    lang_lbuf_put(c, b, '\0', end);
    b->len--;
    b->pos[b->len] = end;
    lang_line l = {b->text, b->len, b->pos};
    lang_volt_line(c, &l); /* its integrals int{...}, as source.c reads a line's */
    (void)o->fn(c, &l, o->ctx); /* never a `done`: the translation writes none */
    b->len = 0;
}

static int line_end(const pline *p)
{
    int e = p->len;
    while (e > 0 && (p->s[e - 1] == '\r' || blank(p->s[e - 1])))
        e--;
    return e;
}

/* The next item of a declaration list from *k (XPPAUT's rule: NAME or NAME=VALUE,
 * separated by commas or blanks, blanks allowed around '='): the name's span, the value's
 * (to == from when none) and the place of '='. Returns 0 when the list is done. */
static int next_item(const pline *p, int end, int *k, span *name, span *value, int *eq)
{
    int i = *k;
    while (i < end && (blank(p->s[i]) || p->s[i] == ','))
        i++;
    if (i >= end)
        return 0;
    int j = i + 1;
    while (j < end && p->s[j] != '=' && p->s[j] != ',' && !blank(p->s[j]))
        j++;
    *name = (span){p->ln, i, j};
    *value = (span){p->ln, j, j};
    *eq = -1;
    while (j < end && blank(p->s[j]))
        j++;
    if (j < end && p->s[j] == '=') {
        *eq = j++;
        while (j < end && blank(p->s[j]))
            j++;
        const int v = j;
        while (j < end && p->s[j] != ',' && !blank(p->s[j]))
            j++;
        *value = (span){p->ln, v, j};
    }
    *k = j;
    return 1;
}

/* p / n / v / w lines: one statement of the current format per item */
static void declarations(oldf *o, const pline *p, int from, int kind, lpos kpos)
{
    lang_ctx *c = o->c;
    const int end = line_end(p);
    lang_lbuf b = {0};
    span name, value;
    int eq, k = from;
    while (next_item(p, end, &k, &name, &value, &eq)) {
        if (kind == 'v' || kind == 'f') {
            *(span *)lvec_push(c, kind == 'v' ? &o->vars : &o->fixes, sizeof(span)) = name;
            if (kind == 'f' || eq < 0)
                continue; /* a variable starts at 0; a fixed quantity's value is its formula */
        }
        put_word(c, &b, kind == 'p' ? "par " : kind == 'n' ? "number " : kind == 'w' ? "wiener "
                                                                                    : "init ",
                 kpos);
        put_span(c, &b, name);
        if (eq >= 0 && kind != 'w') {
            lang_lbuf_put(c, &b, '=', at(p, eq));
            put_span(c, &b, value);
        }
        flush(o, &b, at(p, k));
    }
}

/* u NAME N FORMULA: NAME(arg1,...,argN)=FORMULA */
static void function(oldf *o, const pline *p, int from)
{
    lang_ctx *c = o->c;
    const int end = line_end(p);
    int i = from;
    while (i < end && blank(p->s[i]))
        i++;
    const int n0 = i;
    while (i < end && !blank(p->s[i]))
        i++;
    const int n1 = i;
    while (i < end && blank(p->s[i]))
        i++;
    const int a0 = i;
    while (i < end && !blank(p->s[i]))
        i++;
    const int a1 = i;
    if (n0 == n1 || a0 == a1)
        lang_fail(c, at(p, a0), "expected 'u NAME N FORMULA' (a function of N arguments, named "
                  "arg1 ... argN in its formula)");
    char num[16];
    int len = a1 - a0 < 15 ? a1 - a0 : 15;
    memcpy(num, p->s + a0, (size_t)len);
    num[len] = '\0';
    char *stop;
    const long narg = strtol(num, &stop, 10);
    if (*stop || narg < 1 || narg > LANG_MAX_ARGS)
        lang_fail(c, at(p, a0), "the number of arguments of '%.*s' must be a whole number from "
                  "1 to %d, not '%.*s'", n1 - n0, p->s + n0, LANG_MAX_ARGS, a1 - a0, p->s + a0);
    int f1 = a1;
    while (f1 < end && p->s[f1] != '$')
        f1++;
    lang_lbuf b = {0};
    put_span(c, &b, (span){p->ln, n0, n1});
    lang_lbuf_put(c, &b, '(', at(p, a0));
    for (long k = 1; k <= narg; k++)
        put_word(c, &b, lang_printf(c, k > 1 ? ",arg%ld" : "arg%ld", k), at(p, a0));
    put_word(c, &b, ")=", at(p, a0));
    put_span(c, &b, (span){p->ln, a1, f1});
    flush(o, &b, at(p, f1));
}

/* k NAME MU FORMULA (the formula up to a '$' or the end) */
static void kernel_line(oldf *o, const pline *p, int from)
{
    const int end = line_end(p);
    span w[2];
    int i = from;
    for (int n = 0; n < 2; n++) {
        while (i < end && blank(p->s[i]))
            i++;
        w[n] = (span){p->ln, i, i};
        while (i < end && !blank(p->s[i]))
            i++;
        w[n].to = i;
    }
    int f0 = i, f1;
    while (f0 < end && (blank(p->s[f0]) || p->s[f0] == '$'))
        f0++;
    for (f1 = f0; f1 < end && p->s[f1] != '$'; f1++)
        ;
    if (w[0].from == w[0].to || w[1].from == w[1].to || f0 == f1)
        lang_fail(o->c, at(p, f0), "expected 'k NAME MU FORMULA' (a kernel: NAME in a "
                  "formula is the integral int[MU]{FORMULA})");
    kernel *k = lvec_push(o->c, &o->kernels, sizeof *k);
    k->name = w[0];
    k->mu = w[1];
    k->formula = (span){p->ln, f0, f1};
}

/* g / t: the same statement as in the current format, under its current keyword */
static void same_statement(oldf *o, const pline *p, int from, const char *keyword, lpos kpos)
{
    lang_lbuf b = {0};
    put_word(o->c, &b, keyword, kpos);
    lang_lbuf_put(o->c, &b, ' ', kpos);
    const int end = line_end(p);
    put_span(o->c, &b, (span){p->ln, from, end});
    flush(o, &b, at(p, end));
}

/* The equations, once the counts are known: variables, fixed quantities, then auxiliary
 * quantities, in the order of their `o` lines. */
static void equations(oldf *o)
{
    lang_ctx *c = o->c;
    const int nv = o->vars.n, nf = o->fixes.n, no = o->rhs.n;
    const lpos first = {1, 1};
    if (nv > o->neq)
        lang_fail(c, first, "the first line gives %ld equations, fewer than the %d variables "
                  "declared in 'v' lines", o->neq, nv);
    if (no != o->neq + nf)
        lang_fail(c, first, "the first line gives %ld equations (variables and auxiliary "
                  "quantities): with %d fixed quantit%s the file needs %ld 'o' lines, and has "
                  "%d", o->neq, nf, nf == 1 ? "y" : "ies", o->neq + nf, no);
    lang_lbuf b = {0};
    for (int k = 0; k < no; k++) {
        const span f = LVEC_AT(o->rhs, span, k);
        const lpos w = LVEC_AT(o->rhs_word, lpos, k);
        if (k < nv && LVEC_AT(o->rhs_int, int, k)) {
            put_word(c, &b, "volt ", w);
            put_span(c, &b, LVEC_AT(o->vars, span, k));
            lang_lbuf_put(c, &b, '=', w);
        } else if (k < nv) {
            put_span(c, &b, LVEC_AT(o->vars, span, k));
            put_word(c, &b, "'=", w);
        } else if (k < nv + nf) {
            put_span(c, &b, LVEC_AT(o->fixes, span, k - nv));
            lang_lbuf_put(c, &b, '=', w);
        } else {
            const int a = k - nv - nf;
            put_word(c, &b, "aux ", w);
            if (a < o->auxnames.n)
                put_span(c, &b, LVEC_AT(o->auxnames, span, a));
            else
                put_word(c, &b, lang_printf(c, "AUX%d", a + 1), w);
            lang_lbuf_put(c, &b, '=', w);
        }
        put_formula(o, &b, f);
        flush(o, &b, (lpos){f.ln + 1, f.to + 1});
    }
}

static void refuse(lang_ctx *c, lpos p, char kind, const char *what)
{
    lang_fail(c, p, "'%c' lines of XPPAUT's first format (%s) are not supported", kind, what);
}

/* one line after the first; sets o->stop at the end of the file's text */
static void old_line(oldf *o, const pline *p)
{
    lang_ctx *c = o->c;
    if (p->len > 0 && p->s[0] == '@') {
        same_statement(o, p, 1, "@", at(p, 0));
        return;
    }
    const int end = line_end(p);
    int w0 = 0;
    while (w0 < end && (blank(p->s[w0]) || p->s[w0] == ','))
        w0++;
    if (w0 >= end)
        return;
    int w1 = w0;
    while (w1 < end && !blank(p->s[w1]) && p->s[w1] != ',')
        w1++;
    const int after = w1 < end ? w1 + 1 : w1; /* past the word's delimiter */
    const lpos wpos = at(p, w0);
    const int kind = tolower((unsigned char)p->s[w0]);
    switch (kind) {
    case 'd':
        o->stop = 1;
        return;
    case 's':
    case 'h':
        return;
    case 'p':
    case 'n':
    case 'v':
    case 'f':
    case 'w':
        declarations(o, p, after, kind, wpos);
        return;
    case 'u':
        function(o, p, after);
        return;
    case 'g':
        same_statement(o, p, after, "global", wpos);
        return;
    case 't':
        same_statement(o, p, after, "table", wpos);
        return;
    case 'a': {
        span name, value;
        int eq, k = after;
        while (next_item(p, end, &k, &name, &value, &eq)) {
            if (eq >= 0)
                lang_fail(c, at(p, eq), "an 'a' line names the auxiliary quantities (their "
                          "formulas are 'o' lines), found '='");
            *(span *)lvec_push(c, &o->auxnames, sizeof(span)) = name;
        }
        return;
    }
    case 'i':
    case 'o': {
        if (o->rhs.n >= o->neq + o->fixes.n) {
            lang_warn(c, wpos, "an 'o' line beyond the first line's count (%ld equation%s, "
                      "%d fixed quantit%s): the rest of the file is not read, as XPPAUT does "
                      "not read it", o->neq, o->neq == 1 ? "" : "s", o->fixes.n,
                      o->fixes.n == 1 ? "y" : "ies");
            o->stop = 1;
            return;
        }
        int f = after;
        while (f < end && blank(p->s[f]))
            f++;
        if (f >= end)
            lang_fail(c, at(p, end), "expected a right-hand side after '%.*s'", w1 - w0,
                      p->s + w0);
        *(span *)lvec_push(c, &o->rhs, sizeof(span)) = (span){p->ln, f, end};
        *(lpos *)lvec_push(c, &o->rhs_word, sizeof(lpos)) = wpos;
        *(int *)lvec_push(c, &o->rhs_int, sizeof(int)) = kind == 'i';
        return;
    }
    case 'x':
        lang_note(c, wpos, "'x' (a named set of values chosen from XPPAUT's menus) is accepted "
                  "and ignored: the default run does not use it");
        return;
    case 'm':
    case 'r':
        refuse(c, wpos, (char)kind, "Markov states");
        break;
    case 'k':
        kernel_line(o, p, after);
        return;
    case 'b':
        refuse(c, wpos, 'b', "boundary conditions of a boundary-value problem");
        break;
    case 'c':
        refuse(c, wpos, 'c', "an option file; put the options in '@' lines");
        break;
    default:
        if (isalpha(kind))
            lang_warn(c, wpos, "'%.*s': XPPAUT's first format has no '%c' lines; the line is "
                      "ignored, as XPPAUT ignores it", w1 - w0, p->s + w0, kind);
        else if (kind == '@')
            lang_warn(c, wpos, "an '@' line of XPPAUT's first format starts in the first "
                      "column; this one is ignored, as XPPAUT ignores it");
        return;
    }
}

int lang_old_format(lang_ctx *c, lang_line_fn fn, void *ctx)
{
    if (c->nlines < 1)
        return 0;
    const pline first = physical(c, 0);
    int k = 0;
    if (first.len >= 3 && memcmp(first.s, "\xef\xbb\xbf", 3) == 0)
        k = 3; /* a UTF-8 byte order mark, as source.c skips it */
    while (k < first.len && isspace((unsigned char)first.s[k]))
        k++;
    if (k < first.len && first.s[k] == '+')
        k++;
    long neq = 0;
    const int d0 = k;
    while (k < first.len && isdigit((unsigned char)first.s[k]) && neq <= LANG_MAX_SYMBOLS)
        neq = 10 * neq + (first.s[k++] - '0');
    if (k == d0 || neq <= 0)
        return 0;
    if (neq > LANG_MAX_SYMBOLS)
        lang_fail(c, at(&first, d0), "the first line's count of equations is larger than %d",
                  LANG_MAX_SYMBOLS);
    lang_note(c, at(&first, d0), "the first line is a number: the file is in XPPAUT's first "
              "format, with %ld equations", neq);
    oldf o = {0};
    o.c = c;
    o.fn = fn;
    o.ctx = ctx;
    o.neq = neq;
    for (int ln = 1; ln < c->nlines && !o.stop; ln++) {
        const pline p = physical(c, ln);
        old_line(&o, &p);
    }
    equations(&o);
    return 1;
}
