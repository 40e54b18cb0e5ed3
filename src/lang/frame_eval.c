/* SPDX-License-Identifier: BSD-3-Clause */
/* A formula of a model evaluated for one frame (a time, the states, the outputs, the
 * parameters and the fixed quantities' values) by walking its tree, with the meaning the
 * .ode translator's C text gives it (emit_c.c), so that a formula evaluated here and the same
 * formula compiled give the same numbers: XPPAUT's priorities are already in the tree;
 * heav(x) = x < 0 ? 0 : 1, sign(0) = 0, mod(x,y) = fmod(x,y) plus y when negative (XPPAUT's
 * pmod), flr = floor, max/min as x>y?x:y and x<y?x:y, x^2 = x*x, comparisons, &, | and not
 * give 1 or 0, if(c)then(a)else(b) is a when c is not 0; user functions are called with
 * their arguments. Used by the animations (ani_eval.c) and the mechanisms' pictures
 * (src/mbs/mbs_scene.c). */
#include <math.h>

#include "lang/lang_internal.h"

enum { EVAL_MAX_DEPTH = 4000 };

double lang_eval_frame(lang_frame *x, const node *e, const double *args)
{
    if (++x->depth > EVAL_MAX_DEPTH) {
        x->depth--;
        return NAN;
    }
    double r = NAN, a, b;
    switch (e->kind) {
    case N_NUM: r = e->num; break;
    case N_TIME: r = x->t; break;
    case N_STATE: r = x->y ? x->y[e->index] : NAN; break;
    case N_PARAM: r = x->params ? x->params[e->index] : NAN; break;
    case N_FIX: r = x->fix ? x->fix[e->index] : NAN; break;
    case N_ARG:
        r = args ? args[e->index] : (x->outputs ? x->outputs[e->index] : NAN);
        break;
    case N_NEG: r = -lang_eval_frame(x, e->args[0], args); break;
    case N_NOT: r = lang_eval_frame(x, e->args[0], args) == 0.0 ? 1.0 : 0.0; break;
    case N_IF:
        r = lang_eval_frame(x, e->args[0], args) != 0.0 ? lang_eval_frame(x, e->args[1], args) : lang_eval_frame(x, e->args[2], args);
        break;
    case N_BIN:
        a = lang_eval_frame(x, e->args[0], args);
        if (e->op == OP_AND && !(a != 0.0)) {
            r = 0.0;
            break;
        }
        if (e->op == OP_OR && a != 0.0) {
            r = 1.0;
            break;
        }
        b = lang_eval_frame(x, e->args[1], args);
        r = lang_apply_bin(e->op, a, b);
        break;
    case N_FUN:
        a = lang_eval_frame(x, e->args[0], args);
        b = e->nargs > 1 ? lang_eval_frame(x, e->args[1], args) : 0.0;
        r = lang_apply_fun(e->op, a, b);
        break;
    case N_UFUN: {
        const lang_func *fn = &LVEC_AT(x->m->funcs, lang_func, e->index);
        double v[LANG_MAX_ARGS + 1] = {0};
        for (int i = 0; i < e->nargs && i < LANG_MAX_ARGS; i++)
            v[i] = lang_eval_frame(x, e->args[i], args);
        r = lang_eval_frame(x, fn->body, v);
        break;
    }
    default: break;
    }
    x->depth--;
    return r;
}

