/* SPDX-License-Identifier: BSD-3-Clause */
/* The formulas of an animation (dynkit/ani.h) evaluated for one frame (frame_eval.c: the
 * meaning the .ode translator's C text gives them). Fixed quantities are computed first, in
 * their dependency order, as the compiled model does. Colours are clamped to [0, 1] as
 * XPPAUT's eval_ani_color does. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lang/ani_internal.h"

enum { FIX_ON_STACK = 256 };

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
    lang_frame x = {m, frame->t, frame->y, frame->outputs, frame->params, fix, 0};
    for (int i = 0; i < nfix; i++)
        fix[i] = NAN;
    for (int i = 0; i < nfix; i++) {
        const int k = m->fix_order[i];
        fix[k] = lang_eval_frame(&x, LVEC_AT(m->fixes, lang_formula, k).expr, NULL);
    }
    for (int i = 0; i < ani->n_items; i++) {
        const ani_item *it = &ani->items[i];
        double *v = values + it->p.offset;
        for (int k = 0; k < it->p.n_values; k++)
            v[k] = lang_eval_frame(&x, it->expr[k], NULL);
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
