/* SPDX-License-Identifier: BSD-3-Clause */
/* The formulas of an animation (dynkit/ani.h) evaluated for one frame by walking their trees,
 * with the meaning the .ode translator's C text gives them (emit_c.c), so that a formula in
 * an .ani file and the same formula compiled from the .ode file give the same numbers:
 * XPPAUT's priorities are already in the tree; heav(x) = x < 0 ? 0 : 1, sign(0) = 0,
 * mod(x,y) = fmod(x,y) plus y when negative (XPPAUT's pmod), flr = floor, max/min as
 * x>y?x:y and x<y?x:y, x^2 = x*x, comparisons, &, | and not give 1 or 0,
 * if(c)then(a)else(b) is a when c is not 0. Fixed quantities are computed first, in their
 * dependency order, as the compiled model does; user functions are called with their
 * arguments. Colours are clamped to [0, 1] as XPPAUT's eval_ani_color does. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lang/ani_internal.h"

enum { EVAL_MAX_DEPTH = 4000, FIX_ON_STACK = 256 };

typedef struct ectx {
    const dyn_ani *a;
    const dyn_ani_frame *f;
    const double *fix;
    int depth;
} ectx;

/* args: the arguments of the function whose body e belongs to, or NULL in an animation's
 * own formula (then N_ARG k is the k-th output). */
static double ev(ectx *x, const node *e, const double *args)
{
    if (++x->depth > EVAL_MAX_DEPTH) {
        x->depth--;
        return NAN;
    }
    double r = NAN, a, b;
    switch (e->kind) {
    case N_NUM: r = e->num; break;
    case N_TIME: r = x->f->t; break;
    case N_STATE: r = x->f->y ? x->f->y[e->index] : NAN; break;
    case N_PARAM: r = x->f->params ? x->f->params[e->index] : NAN; break;
    case N_FIX: r = x->fix ? x->fix[e->index] : NAN; break;
    case N_ARG:
        r = args ? args[e->index] : (x->f->outputs ? x->f->outputs[e->index] : NAN);
        break;
    case N_NEG: r = -ev(x, e->args[0], args); break;
    case N_NOT: r = ev(x, e->args[0], args) == 0.0 ? 1.0 : 0.0; break;
    case N_IF:
        r = ev(x, e->args[0], args) != 0.0 ? ev(x, e->args[1], args) : ev(x, e->args[2], args);
        break;
    case N_BIN:
        a = ev(x, e->args[0], args);
        if (e->op == OP_AND && !(a != 0.0)) {
            r = 0.0;
            break;
        }
        if (e->op == OP_OR && a != 0.0) {
            r = 1.0;
            break;
        }
        b = ev(x, e->args[1], args);
        r = lang_apply_bin(e->op, a, b);
        break;
    case N_FUN:
        a = ev(x, e->args[0], args);
        b = e->nargs > 1 ? ev(x, e->args[1], args) : 0.0;
        r = lang_apply_fun(e->op, a, b);
        break;
    case N_UFUN: {
        const lang_func *fn = &LVEC_AT(x->a->c->m.funcs, lang_func, e->index);
        double v[LANG_MAX_ARGS + 1] = {0};
        for (int i = 0; i < e->nargs && i < LANG_MAX_ARGS; i++)
            v[i] = ev(x, e->args[i], args);
        r = ev(x, fn->body, v);
        break;
    }
    default: break;
    }
    x->depth--;
    return r;
}

int ani_varies(const dyn_ani *a, const node *e)
{
    switch (e->kind) {
    case N_TIME:
    case N_STATE:
    case N_FIX:
    case N_ARG: return 1;
    case N_UFUN: {
        const lang_func *fn = &LVEC_AT(a->c->m.funcs, lang_func, e->index);
        if (fn->uses_state || fn->uses_time || fn->uses_fix)
            return 1;
        break;
    }
    default: break;
    }
    for (int i = 0; i < e->nargs; i++)
        if (ani_varies(a, e->args[i]))
            return 1;
    return 0;
}

int dyn_ani_eval(const dyn_ani *ani, const dyn_ani_frame *frame, double *values)
{
    if (!ani || !frame || !values)
        return 0;
    const lang_model *m = &ani->c->m;
    const int nfix = ani->from_ode ? m->fixes.n : 0;
    double on_stack[FIX_ON_STACK];
    double *fix = nfix <= FIX_ON_STACK ? on_stack : malloc((size_t)nfix * sizeof *fix);
    if (!fix)
        return 1;
    ectx x = {ani, frame, fix, 0};
    for (int i = 0; i < nfix; i++)
        fix[i] = NAN;
    for (int i = 0; i < nfix; i++) {
        const int k = m->fix_order[i];
        fix[k] = ev(&x, LVEC_AT(m->fixes, lang_formula, k).expr, NULL);
    }
    for (int i = 0; i < ani->n_items; i++) {
        const ani_item *it = &ani->items[i];
        double *v = values + it->p.offset;
        for (int k = 0; k < it->p.n_values; k++)
            v[k] = ev(&x, it->expr[k], NULL);
        if (it->p.color < 0) {
            double *col = &v[it->p.n_values - 1];
            if (*col > 1.0)
                *col = 1.0;
            else if (*col < 0.0)
                *col = 0.0;
            /* NaN stays NaN: the page draws it with the foreground colour */
        }
    }
    if (fix != on_stack)
        free(fix);
    return 0;
}

char *dyn_ani_vtext(const char *text, double value, char *buf, size_t size)
{
    if (!buf || size == 0)
        return buf;
    snprintf(buf, size, "%s%g", text ? text : "", value);
    return buf;
}
