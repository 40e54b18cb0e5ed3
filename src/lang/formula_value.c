/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_lang_formula_value (dynkit/lang.h): the value of one formula of named numbers, as a
 * model file's `init` and `par` lines take them (the .ode expression syntax of
 * expr_parse.c, XPPAUT's functions and operators, evaluated by lang_eval), for the values
 * given on a command line (--init dpsi=200-W*cos(0.3)). */
#include <fenv.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/lang.h"
#include "lang/lang_internal.h"

typedef struct named {
    const char *const *names;
    int n;
} named;

/* Names to the values' indices and calls to XPPAUT's functions; anything else fails. */
static void resolve(lang_ctx *c, node *e, const named *v)
{
    if (++c->depth > 4 * LANG_MAX_DEPTH)
        lang_fail(c, e->pos, "the formula is nested too deeply");
    for (int i = 0; i < e->nargs; i++)
        resolve(c, e->args[i], v);
    c->depth--;
    switch (e->kind) {
    case N_NUM:
    case N_NEG:
    case N_NOT:
    case N_BIN:
    case N_IF: return;
    case N_NAME:
        for (int k = 0; k < v->n; k++)
            if (lang_same_name(e->name, v->names[k])) {
                e->kind = N_PARAM;
                e->index = k;
                return;
            }
        {
            const char *near = dyn_lang_nearest(e->name, v->names, v->n);
            lang_fail(c, e->pos, "'%s' is no parameter of the model%s%s%s", e->name,
                      near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "");
        }
    case N_TIME: lang_fail(c, e->pos, "the value cannot depend on the time t");
    case N_FUN:
        if (lang_resolve_call(c, e))
            return;
        lang_fail(c, e->pos, "'%s' is no function of the formulas (XPPAUT's functions: sin, "
                  "cos, exp, ln, sqrt, abs, heav, max, min, ...)", e->name);
    default: lang_fail(c, e->pos, "a formula of numbers and parameters is expected here");
    }
}

/* The formula's value, after the setjmp of its caller (which lang_fail jumps to): kept out of
 * that function so that no value of it lives across the jump. */
static double evaluate(lang_ctx *c, const char *text, size_t len, const char *const *names,
                       int n, const double *values)
{
    /* the formula as one line of a file: each character at its column */
    size_t *start = lang_alloc(c, sizeof *start); /* the context's, past a jump too */
    *start = 0;
    c->line_start = start;
    c->nlines = 1;
    lang_line line;
    line.text = lang_strndup(c, text, len);
    line.len = (int)len;
    line.pos = lang_alloc(c, (len + 1) * sizeof *line.pos);
    for (size_t i = 0; i <= len; i++)
        line.pos[i] = (lpos){1, (int)i + 1};
    lang_lexer lx = {c, &line, 0, (int)len};
    node *e = lang_parse_expr(&lx);
    lang_expect_end(&lx, "the formula");
    const named v = {names, n};
    resolve(c, e, &v);
    /* what is no double is refused, as a number on the command line is: a step that
     * overflowed or underflowed (1e-300/1e300 would be 0) */
    feclearexcept(FE_OVERFLOW | FE_UNDERFLOW);
    const double x = lang_eval(c, e, NULL, values);
    if (!isfinite(x))
        lang_fail(c, (lpos){1, 1}, "the value is not finite (%g)", x);
    if (fetestexcept(FE_OVERFLOW | FE_UNDERFLOW))
        lang_fail(c, (lpos){1, 1}, "a step of the formula is beyond the range of doubles "
                  "(it overflowed or underflowed)");
    return x;
}

int dyn_lang_formula_value(const char *text, const char *const *names, const double *values,
                           int n, double *value, dyn_lang_diag *diag)
{
    dyn_lang_diag scratch;
    if (!diag)
        diag = &scratch;
    memset(diag, 0, sizeof *diag);
    if (!text || !value || n < 0 || (n > 0 && (!names || !values))) {
        strcpy(diag->message, "no formula or no place for its value (a NULL argument)");
        return 2;
    }
    const size_t len = strlen(text);
    if (len > LANG_MAX_LINE) {
        strcpy(diag->message, "the formula is too long");
        return 2;
    }
    lang_ctx *c = lang_ctx_new("", text, len, NULL, 0, diag);
    if (!c) {
        strcpy(diag->message, "out of memory");
        return 1;
    }
    jmp_buf fail;
    c->fail = &fail;
    if (setjmp(fail)) {
        const int status = c->status ? c->status : 2;
        lang_ctx_free(c, NULL);
        return status;
    }
    *value = evaluate(c, text, len, names, n, values);
    lang_ctx_free(c, NULL);
    return 0;
}
