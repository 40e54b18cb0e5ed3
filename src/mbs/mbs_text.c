/* SPDX-License-Identifier: BSD-3-Clause */
/* The equations of motion of a mechanism as readable text (dynkit derive): M, F and the
 * constraints' rows and convective terms, each a formula in the file's names with XPPAUT's
 * operators (parenthesized where its priorities need it), so that it can be read back by
 * an .ode file or by SymPy (with ^ as **). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h"
#include "mbs/mbs_internal.h"

typedef struct tbuf {
    lang_ctx *c;
    char *s;
    size_t n, cap;
} tbuf;

static void put(tbuf *b, const char *s)
{
    const size_t k = strlen(s);
    if (b->n + k + 1 > b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 4096;
        while (cap < b->n + k + 1)
            cap *= 2;
        char *t = lang_alloc(b->c, cap);
        if (b->n)
            memcpy(t, b->s, b->n);
        b->s = t;
        b->cap = cap;
    }
    memcpy(b->s + b->n, s, k + 1);
    b->n += k;
}

static int prio(const node *e)
{
    if (e->kind == N_BIN)
        return lang_op_priority(e->op);
    if (e->kind == N_NEG || e->kind == N_NOT)
        return 5;
    if (e->kind == N_NUM && (e->num < 0 || signbit(e->num)))
        return 5;
    return 9;
}

static void text(tbuf *b, const node *e);

static void sub(tbuf *b, const node *e, int need)
{
    const int p = prio(e) < need;
    if (p)
        put(b, "(");
    text(b, e);
    if (p)
        put(b, ")");
}

static void text(tbuf *b, const node *e)
{
    lang_model *m = &b->c->m;
    switch (e->kind) {
    case N_NUM: put(b, dyn_shortest(e->num).s); break;
    case N_TIME: put(b, "t"); break;
    case N_STATE: put(b, LVEC_AT(m->states, lang_state, e->index).name); break;
    case N_PARAM:
        put(b, e->index < m->params.n
                   ? LVEC_AT(m->params, lang_param, e->index).name
                   : LVEC_AT(m->derived, lang_formula, e->index - m->params.n).name);
        break;
    case N_FIX: {
        const lang_formula *f = &LVEC_AT(m->fixes, lang_formula, e->index);
        if (strncmp(f->name, "mbs_", 4) == 0)
            sub(b, f->expr, 9); /* a formula of the file without a name of its own */
        else
            put(b, f->name);
        break;
    }
    case N_NEG:
        put(b, "-");
        sub(b, e->args[0], 6);
        break;
    case N_NOT:
        put(b, "not ");
        sub(b, e->args[0], 9);
        break;
    case N_BIN: {
        const int p = lang_op_priority(e->op);
        if (e->op == OP_ADD && e->args[1]->kind == N_NEG) { /* a+-b as a-b */
            sub(b, e->args[0], p);
            put(b, "-");
            sub(b, e->args[1]->args[0], p + 1);
            break;
        }
        sub(b, e->args[0], e->op == OP_POW ? 9 : p);
        put(b, lang_op_text(e->op));
        sub(b, e->args[1], e->op == OP_ADD || e->op == OP_MUL ? p : e->op == OP_POW ? 9 : p + 1);
        break;
    }
    case N_FUN:
    case N_UFUN:
        put(b, e->kind == N_UFUN ? LVEC_AT(m->funcs, lang_func, e->index).name
               : e->op < F_COUNT ? lang_fun_name(e->op)
                                 : LVEC_AT(m->tables, lang_table, e->index).name);
        put(b, "(");
        for (int i = 0; i < e->nargs; i++) {
            if (i)
                put(b, ", ");
            text(b, e->args[i]);
        }
        put(b, ")");
        break;
    case N_IF:
        put(b, "if(");
        text(b, e->args[0]);
        put(b, ")then(");
        text(b, e->args[1]);
        put(b, ")else(");
        text(b, e->args[2]);
        put(b, ")");
        break;
    default: put(b, "?"); break;
    }
}

static void line(tbuf *b, const char *label, const node *e)
{
    put(b, label);
    put(b, " = ");
    text(b, e);
    put(b, "\n");
}

const char *mbs_formula_text(lang_ctx *c, const node *e)
{
    tbuf b = {c, NULL, 0, 0};
    text(&b, e);
    return b.s;
}

/* the kinematic equations of declared speeds, a line each */
static void rates(tbuf *b, const mbs_model *mb)
{
    for (int i = 0; i < mb->coords.n && mb->speeds.n; i++) {
        const mbs_coord *q = &LVEC_AT(mb->coords, mbs_coord, i);
        put(b, lang_printf(b->c, "%s'", q->name));
        put(b, " = ");
        text(b, LVEC_AT(b->c->m.fixes, lang_formula, q->kin).expr);
        put(b, "\n");
    }
}

char *mbs_text(lang_ctx *c, const mbs_model *mb)
{
    tbuf b = {c, NULL, 0, 0};
    lang_model *m = &c->m;
    const int n = mb->coords.n, nc = mb->cons.n;
    /* with declared speeds u the rows and columns are the speeds' */
    const int by_u = mb->speeds.n > 0;
    const char *acc = by_u ? "u'" : "q''";
    put(&b, lang_printf(c, "%s: equations of motion by TMT, M %s = F + D' lambda%s%s\n", m->name,
                        acc, nc ? (by_u ? ", D u' + c = 0" : ", D q'' + c = 0") : "",
                        by_u ? ", q' = W(q) u" : ""));
    if (mb->regularized)
        put(&b, lang_printf(c, "M below is singular at the initial state (it moves no mass in "
                               "a direction the constraints fix): the model solves (M + D'D) "
                               "%s = F + D' (lambda - b) in its place, with b = c + 2 a h + "
                               "a^2 f (Baumgarte's rate a, h and f for holonomic constraints "
                               "only; docs/mechanisms.md, \"The method\")\n",
                            acc));
    put(&b, "coordinates q:");
    for (int i = 0; i < n; i++)
        put(&b, lang_printf(c, " %s", LVEC_AT(mb->coords, mbs_coord, i).name));
    put(&b, "; speeds:");
    for (int i = 0; i < n; i++)
        put(&b, lang_printf(c, " %s", LVEC_AT(mb->coords, mbs_coord, i).speed));
    put(&b, "\n\n");
    if (by_u) {
        put(&b, "kinematic equations:\n");
        rates(&b, mb);
        put(&b, "\n");
    }
#define NAME(i)                                                                                    \
    (by_u ? LVEC_AT(mb->coords, mbs_coord, i).speed : LVEC_AT(mb->coords, mbs_coord, i).name)
    for (int i = 0; i < n; i++)
        for (int k = 0; k <= i; k++)
            line(&b, lang_printf(c, "M[%s,%s]", NAME(i), NAME(k)), mb->M[i * n + k]);
    for (int i = 0; i < n; i++)
        line(&b, lang_printf(c, "F[%s]", NAME(i)), mb->F[i]);
    for (int r = 0; r < nc; r++) {
        const mbs_constraint *k = &LVEC_AT(mb->cons, mbs_constraint, r);
        put(&b, lang_printf(c, "\nconstraint %s (%s)\n", k->name,
                            mb->con_speeds[r] ? "on the speeds" : "of the positions"));
        for (int j = 0; j < n; j++)
            line(&b, lang_printf(c, "D[%s,%s]", k->name, NAME(j)), mb->con_D[r * n + j]);
        line(&b, lang_printf(c, "c[%s]", k->name), mb->con_c[r]);
    }
#undef NAME
    int header = 0;
    for (int i = 0; i < m->fixes.n; i++) {
        const lang_formula *f = &LVEC_AT(m->fixes, lang_formula, i);
        if (strncmp(f->name, "mbs_", 4) == 0)
            continue;
        if (!header++)
            put(&b, "\nwhere\n");
        line(&b, f->name, f->expr);
    }
    char *out = malloc(b.n + 1);
    if (!out)
        lang_oom(c);
    memcpy(out, b.s ? b.s : "", b.n + 1);
    return out;
}
