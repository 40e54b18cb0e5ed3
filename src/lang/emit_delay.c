/* SPDX-License-Identifier: BSD-3-Clause */
/* The C text of a delay model (XPPAUT's delay(x, tau), `@ delay=`, `x(0)=` a formula of t;
 * dynkit/delay.h): the history pointer kept in one slot of the parameter array, the value
 * of a state lag ago (dk_delay, through dyn_history_value), the history before t0
 * (dk_history), the lags that are constants of the parameters (dk_lags, for the breaking
 * points), and the dyn_delay_model that names them. Written through emit_out.c only, as the
 * rest of the model's text (emit_c.c states the rule). */
#include <string.h>

#include "dynkit/model.h"
#include "lang/lang_internal.h"

/* Whether e is a formula of numbers and parameters only (a constant lag). */
static int is_constant(const node *e)
{
    if (e->kind == N_STATE || e->kind == N_TIME || e->kind == N_FIX || e->kind == N_ALG ||
        e->kind == N_UFUN || e->kind == N_UFUN_D || e->kind == N_DELAY || e->kind == N_ARG ||
        e->kind == N_DFIX || (e->kind == N_FUN && e->op >= F_COUNT))
        return 0;
    for (int i = 0; i < e->nargs; i++)
        if (!is_constant(e->args[i]))
            return 0;
    return 1;
}

/* The constant lags of delay calls in e into lags (at most LAGS_MAX). */
#define LAGS_MAX 8
static void collect(const node *e, const node **lags, int *n)
{
    if (e->kind == N_DELAY && is_constant(e->args[0]) && *n < LAGS_MAX)
        lags[(*n)++] = e->args[0];
    for (int i = 0; i < e->nargs; i++)
        collect(e->args[i], lags, n);
}

static int constant_lags(lang_ctx *c, const node **lags)
{
    const lang_model *m = &c->m;
    int n = 0;
    for (int i = 0; i < m->states.n; i++)
        collect(LVEC_AT(m->states, lang_state, i).rhs, lags, &n);
    for (int i = 0; i < m->fixes.n; i++)
        collect(LVEC_AT(m->fixes, lang_formula, i).expr, lags, &n);
    for (int i = 0; i < m->auxs.n; i++)
        collect(LVEC_AT(m->auxs, lang_formula, i).expr, lags, &n);
    for (int i = 0; i < m->events.n; i++) {
        const lang_event *ev = &LVEC_AT(m->events, lang_event, i);
        collect(ev->cond, lags, &n);
        for (int k = 0; k < ev->nassign; k++)
            collect(ev->assign[k].value, lags, &n);
    }
    return n;
}

void lang_emit_delay_helper(lang_ctx *c, int offset)
{
    LANG_C_CODEF(c,
                 "_Static_assert(sizeof(dyn_history *) <= sizeof(double), \"room for the "
                 "history\");\n"
                 "static inline dyn_history *dk_hist(const double *p)\n{\n"
                 "    dyn_history *h;\n    memcpy(&h, p + %d, sizeof h);\n    return h;\n}\n"
                 "static inline double dk_delay(const double *p, int i, double t, double lag)\n"
                 "{\n    return dyn_history_value(dk_hist(p), i, t, t - lag);\n}\n\n",
                 offset);
}

void lang_emit_delay_guard(lang_ctx *c)
{
    LANG_C_CODEF(c, "    if (!dk_hist(p))\n        return %d;\n", DYN_DELAY_NO_HISTORY);
}

void lang_emit_delay_model(lang_ctx *c, int offset, void (*expr)(lang_ctx *, const node *))
{
    const lang_model *m = &c->m;
    LANG_C_CODEF(c, "static void dk_attach(void *par, dyn_history *h)\n{\n"
                    "    memcpy((double *)par + %d, &h, sizeof h);\n}\n\n",
                 offset);
    int any = 0;
    for (int i = 0; i < m->states.n; i++)
        any |= LVEC_AT(m->states, lang_state, i).history != NULL;
    if (any) {
        LANG_C_CODE(c, "static double dk_history(int i, double t, const void *par, "
                       "const double *y0)\n{\n    const double *p = (const double *)par;\n"
                       "    (void)p;\n    (void)t;\n    switch (i) {\n");
        for (int i = 0; i < m->states.n; i++) {
            const lang_state *s = &LVEC_AT(m->states, lang_state, i);
            if (!s->history)
                continue;
            LANG_C_CODEF(c, "    case %d:\n        return ", i);
            expr(c, s->history);
            LANG_C_CODE(c, ";\n");
        }
        LANG_C_CODE(c, "    default:\n        return y0[i];\n    }\n}\n\n");
    }
    const node *lags[LAGS_MAX];
    const int n = constant_lags(c, lags);
    if (n) {
        LANG_C_CODE(c, "static void dk_lags(const void *par, double *lags)\n{\n"
                       "    const double *p = (const double *)par;\n    (void)p;\n");
        for (int k = 0; k < n; k++) {
            LANG_C_CODEF(c, "    lags[%d] = ", k);
            expr(c, lags[k]);
            LANG_C_CODE(c, ";\n");
        }
        LANG_C_CODE(c, "}\n\n");
    }
    LANG_C_CODE(c, "static const dyn_delay_model dk_delay_model = {\n    .max_delay = ");
    lang_c_num(c, m->max_delay);
    LANG_C_CODE(c, ",\n    .attach = dk_attach,\n    .history = ");
    if (any)
        LANG_C_CODE(c, "dk_history");
    else
        LANG_C_CODE(c, "NULL");
    LANG_C_CODEF(c, ",\n    .n_lags = %d,\n    .lags = ", n);
    if (n)
        LANG_C_CODE(c, "dk_lags");
    else
        LANG_C_CODE(c, "NULL");
    LANG_C_CODE(c, ",\n};\n\n");
}
