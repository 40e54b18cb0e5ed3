/* SPDX-License-Identifier: BSD-3-Clause */
/* The C text of a delay model (XPPAUT's delay(x, tau), `@ delay=`, `x(0)=` a formula of t;
 * dynkit/delay.h): the history pointer kept in one slot of the parameter array, the value
 * of a state lag ago (dk_delay, through dyn_history_value), the history before t0
 * (dk_history), the lags that are constants of the parameters (dk_lags, for the breaking
 * points), and the dyn_delay_model that names them. Written through emit_out.c only, as the
 * rest of the model's text (emit_c.c states the rule). */
#include <math.h>
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

/* Every formula that may read delay(): equations, fixed quantities, aux outputs, events. */
typedef void (*visit_fn)(const node *e, void *ctx);
static void each_formula(const lang_model *m, visit_fn fn, void *ctx)
{
    for (int i = 0; i < m->states.n; i++)
        fn(LVEC_AT(m->states, lang_state, i).rhs, ctx);
    for (int i = 0; i < m->fixes.n; i++)
        fn(LVEC_AT(m->fixes, lang_formula, i).expr, ctx);
    for (int i = 0; i < m->auxs.n; i++)
        fn(LVEC_AT(m->auxs, lang_formula, i).expr, ctx);
    for (int i = 0; i < m->events.n; i++) {
        const lang_event *ev = &LVEC_AT(m->events, lang_event, i);
        fn(ev->cond, ctx);
        for (int k = 0; k < ev->nassign; k++)
            fn(ev->assign[k].value, ctx);
    }
}

/* The constant lags of delay calls (at most LAGS_MAX). */
#define LAGS_MAX 8
typedef struct lag_list {
    const node *call[LAGS_MAX]; /* the delay() calls */
    int n;
} lag_list;

static void collect(const node *e, void *ctx)
{
    lag_list *l = ctx;
    if (e->kind == N_DELAY && is_constant(e->args[0]) && l->n < LAGS_MAX)
        l->call[l->n++] = e;
    for (int i = 0; i < e->nargs; i++)
        collect(e->args[i], ctx);
}

/* The states that delay() reads (one flag each). */
static void mark_delayed(const node *e, void *ctx)
{
    unsigned char *delayed = ctx;
    if (e->kind == N_DELAY)
        delayed[e->index] = 1;
    for (int i = 0; i < e->nargs; i++)
        mark_delayed(e->args[i], ctx);
}

/* The first delay() call met (in each_formula's order), to place a note at. */
static void first_call(const node *e, void *ctx)
{
    const node **first = ctx;
    if (*first)
        return;
    if (e->kind == N_DELAY) {
        *first = e;
        return;
    }
    for (int i = 0; i < e->nargs; i++)
        first_call(e->args[i], ctx);
}

void lang_emit_delay_prepare(lang_ctx *c, void (*expr)(lang_ctx *, const node *))
{
    const lang_model *m = &c->m;
    lag_list lags = {{0}, 0};
    each_formula(m, collect, &lags);
    for (int k = 0; k < lags.n; k++) {
        const node *d = lags.call[k];
        LANG_C_CODE(c, "    {\n        const double lag = ");
        expr(c, d->args[0]);
        LANG_C_CODE(c, ";\n        if (!(lag >= 0.0)");
        if (m->max_delay > 0) {
            LANG_C_CODE(c, " || lag > ");
            lang_c_num(c, m->max_delay);
        }
        if (m->max_delay > 0) {
            LANG_C_CODEF(c, ") {\n            snprintf(err, errlen, \"delay(%%s, ...) on line %d: "
                            "the lag is %%g with these parameters; it must be a number from 0 "
                            "to the maximal delay %%g (the file's @ delay=)\", ",
                         d->pos.line);
            lang_c_str(c, d->name);
            LANG_C_CODE(c, ", lag, ");
            lang_c_num(c, m->max_delay);
        } else {
            LANG_C_CODEF(c, ") {\n            snprintf(err, errlen, \"delay(%%s, ...) on line %d: "
                            "the lag is %%g with these parameters; it must be a number >= 0 "
                            "(the file has no @ delay=, which would also bound it)\", ",
                         d->pos.line);
            lang_c_str(c, d->name);
            LANG_C_CODE(c, ", lag");
        }
        LANG_C_CODE(c, ");\n            return 1;\n        }\n    }\n");
    }
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
    /* the history: x(0)='s formula, else 0 as XPPAUT 6.11 reads it (measured: `init x=1`
     * alone gives x = 0 before t0; docs/model-files.md, "Delay equations") */
    unsigned char *delayed = lang_alloc(c, (size_t)m->states.n + 1);
    each_formula(m, mark_delayed, delayed);
    for (int i = 0; i < m->states.n; i++) {
        const lang_state *s = &LVEC_AT(m->states, lang_state, i);
        if (delayed[i] && !s->history)
            lang_warn(c, s->pos,
                      "%s is read by delay() and only 'init' gives its value: before "
                      "t0 it is 0, as in XPPAUT; write %s(0)=VALUE (or a formula of t) to give "
                      "its history",
                      s->name, s->name);
    }
    /* XPPAUT allocates no history without `@ delay=` (its maximal delay, default 0), and its
     * delay(x, lag) then returns the current x (measured with xppaut 6.11: y'=-delay(y,1),
     * y(0)=1 gives y(2)=e^-2); dynkit keeps the history and uses the lag, and says so once */
    const node *call = NULL;
    each_formula(m, first_call, &call);
    if (call && !(m->max_delay > 0))
        lang_warn(c, call->pos,
                  "the file sets %s: XPPAUT then reads every delay(x, lag) as the "
                  "current x; dynkit keeps the history and uses the lag (write '@ delay=M', "
                  "the longest lag, to bound the history as XPPAUT does)",
                  m->max_delay_given ? "'@ delay=0', XPPAUT's default, which keeps no history"
                                     : "no '@ delay='");
    LANG_C_CODE(c, "static double dk_history(int i, double t, const void *par, "
                   "const double *y0)\n{\n    const double *p = (const double *)par;\n"
                   "    (void)p;\n    (void)t;\n    (void)y0;\n    switch (i) {\n");
    for (int i = 0; i < m->states.n; i++) {
        const lang_state *s = &LVEC_AT(m->states, lang_state, i);
        if (!s->history)
            continue;
        LANG_C_CODEF(c, "    case %d:\n        return ", i);
        expr(c, s->history);
        LANG_C_CODE(c, ";\n");
    }
    LANG_C_CODE(c, "    default:\n        return 0.0;\n    }\n}\n\n");
    lag_list lags = {{0}, 0};
    each_formula(m, collect, &lags);
    const int n = lags.n;
    if (n) {
        LANG_C_CODE(c, "static void dk_lags(const void *par, double *lags)\n{\n"
                       "    const double *p = (const double *)par;\n    (void)p;\n");
        for (int k = 0; k < n; k++) {
            LANG_C_CODEF(c, "    lags[%d] = ", k);
            expr(c, lags.call[k]->args[0]);
            LANG_C_CODE(c, ";\n");
        }
        LANG_C_CODE(c, "}\n\n");
    }
    LANG_C_CODE(c, "static const dyn_delay_model dk_delay_model = {\n    .max_delay = ");
    lang_c_num(c, m->max_delay);
    LANG_C_CODE(c, ",\n    .attach = dk_attach,\n    .history = dk_history");
    LANG_C_CODEF(c, ",\n    .n_lags = %d,\n    .lags = ", n);
    if (n)
        LANG_C_CODE(c, "dk_lags");
    else
        LANG_C_CODE(c, "NULL");
    LANG_C_CODE(c, ",\n};\n\n");
}
