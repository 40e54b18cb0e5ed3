/* SPDX-License-Identifier: BSD-3-Clause */
/* Names and order of an .ode model: the resolution of every name in every formula
 * with the nearest known name suggested for an unknown one, what each kind of formula may
 * use (derived parameters and initial values: parameters only; user functions: their
 * arguments, states, parameters and t), the dependency order of fixed temporaries and of
 * derived parameters (a circular definition is refused naming the cycle), recursion of
 * user functions refused, and the `#:` documentation lines attached to their names. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/model.h" /* DYN_POINCARE_* */
#include "dynkit/sde.h"
#include "lang/lang_internal.h"

/* ---- resolution ---- */

/* CTX_PARAMS, CTX_TABLE and CTX_HISTORY: formulas of the parameters only (CTX_TABLE: and
 * of the table's abscissa t; CTX_HISTORY: and of t, a delay model's initial value, its
 * history before t0) */
enum { CTX_RHS, CTX_FUNC, CTX_PARAMS, CTX_TABLE, CTX_HISTORY };

typedef struct rctx {
    int kind;
    const lang_func *func;
    const char *what; /* "a derived parameter", "an initial value", ... */
    int table;        /* CTX_TABLE: the table whose formula this is */
} rctx;

static const char *nearest_symbol(lang_ctx *c, const char *word, const rctx *r, int funcs)
{
    lang_model *m = &c->m;
    int n = 0;
    const int cap = m->nsyms + F_COUNT + LANG_MAX_ARGS + 2;
    const char **names = lang_alloc(c, (size_t)cap * sizeof *names);
    for (int k = 0; k < m->symcap; k++) {
        const lang_sym *s = &m->syms[k];
        if (!s->key || (funcs != (s->kind == SYM_FUNC)))
            continue;
        names[n++] = s->key;
    }
    if (funcs) {
        for (int f = 0; f < F_COUNT; f++)
            names[n++] = lang_fun_name(f);
    } else {
        names[n++] = "t";
        names[n++] = "pi";
        if (r && r->func)
            for (int k = 0; k < r->func->nargs; k++)
                names[n++] = r->func->argnames[k];
    }
    return dyn_lang_nearest(word, names, n);
}

static _Noreturn void unknown(lang_ctx *c, const node *e, const rctx *r, int funcs)
{
    const char *near = nearest_symbol(c, e->name, r, funcs);
    if (near)
        lang_fail(c, e->pos, "unknown %s '%s' (did you mean '%s'?)", funcs ? "function" : "name",
                  e->name, near);
    lang_fail(c, e->pos, "unknown %s '%s'", funcs ? "function" : "name", e->name);
}

/* normal(m, s) and ran(x) (XPPAUT's random numbers, a new one at each step): each call a
 * noise slot of its own, the call rewritten as m + s*slot or x*slot. 1 when e was one. */
static int random_call(lang_ctx *c, node *e, const rctx *r)
{
    const int is_normal = lang_same_name(e->name, "normal"), is_ran = lang_same_name(e->name, "ran");
    if (!is_normal && !is_ran)
        return 0;
    const int want = is_normal ? 2 : 1;
    if (e->nargs != want)
        lang_fail(c, e->pos, "%s takes %d argument%s (%s), not %d", is_normal ? "normal" : "ran",
                  want, want > 1 ? "s" : "", is_normal ? "mean, standard deviation" : "the "
                  "upper end of [0, x)", e->nargs);
    if (r->kind >= CTX_PARAMS && r->kind != CTX_TABLE)
        lang_fail(c, e->pos, "%s cannot use random numbers ('%s'): they change at every step of "
                  "a run", r->what, is_normal ? "normal" : "ran");
    node *slot = lang_node(c, N_NOISE, e->pos);
    slot->op = is_normal ? DYN_NOISE_NORMAL : DYN_NOISE_UNIFORM;
    if (r->kind == CTX_TABLE) {
        /* XPPAUT computes a table once: its numbers are drawn once, in prepare (index < 0:
         * the call's number -1 - index, dyn_table_random) */
        slot->index = -1 - c->m.n_table_draws++;
    } else {
        lang_noise *nz = lvec_push(c, &c->m.noises, sizeof *nz);
        nz->name = is_normal ? "normal" : "ran";
        nz->pos = e->pos;
        nz->kind = slot->op;
        slot->index = c->m.noises.n - 1;
    }
    node **a = e->args;
    node *prod = lang_node(c, N_BIN, e->pos);
    prod->op = OP_MUL;
    prod->nargs = 2;
    prod->args = lang_alloc(c, 2 * sizeof *prod->args);
    prod->args[0] = is_normal ? a[1] : a[0];
    prod->args[1] = slot;
    if (is_ran) {
        *e = *prod;
        return 1;
    }
    node *mean = a[0];
    e->kind = N_BIN;
    e->op = OP_ADD;
    e->name = NULL;
    e->args = lang_alloc(c, 2 * sizeof *e->args);
    e->args[0] = mean;
    e->args[1] = prod;
    prod->paren = 1;
    return 1;
}

static void resolve(lang_ctx *c, node *e, const rctx *r)
{
    if (++c->depth > 4 * LANG_MAX_DEPTH)
        lang_fail(c, e->pos, "expression nested too deeply");
    for (int i = 0; i < e->nargs; i++)
        resolve(c, e->args[i], r);
    c->depth--;
    lang_model *m = &c->m;
    if (e->kind == N_TIME && r->func)
        for (int k = 0; k < r->func->nargs; k++)
            if (lang_same_name("t", r->func->argnames[k])) {
                /* f(t)=...: XPPAUT's t is then the argument */
                e->kind = N_ARG;
                e->index = k;
                return;
            }
    if (e->kind == N_TIME && r->kind == CTX_PARAMS)
        lang_fail(c, e->pos, "%s cannot depend on the time t", r->what);
    if (e->kind == N_NAME) {
        if (r->func)
            for (int k = 0; k < r->func->nargs; k++)
                if (lang_same_name(e->name, r->func->argnames[k])) {
                    e->kind = N_ARG;
                    e->index = k;
                    return;
                }
        const lang_sym *s = lang_lookup(c, e->name);
        if (!s)
            unknown(c, e, r, 0);
        switch (s->kind) {
        case SYM_STATE:
            if (r->kind >= CTX_PARAMS)
                lang_fail(c, e->pos, "%s cannot depend on the state '%s'", r->what, e->name);
            e->kind = N_STATE;
            e->index = s->index;
            return;
        case SYM_PARAM:
            e->kind = N_PARAM;
            e->index = s->index;
            return;
        case SYM_DERIVED:
            e->kind = N_PARAM;
            e->index = m->params.n + s->index;
            return;
        case SYM_NUMBER:
            e->kind = N_NUM;
            e->num = LVEC_AT(m->numbers, lang_param, s->index).value;
            return;
        case SYM_FIX:
            if (r->kind >= CTX_PARAMS)
                lang_fail(c, e->pos, "%s cannot depend on the fixed quantity '%s'", r->what,
                          e->name);
            if (r->kind == CTX_FUNC)
                ((lang_func *)r->func)->uses_fix = 1;
            e->kind = N_FIX;
            e->index = s->index;
            return;
        case SYM_ALG:
            if (r->kind >= CTX_PARAMS)
                lang_fail(c, e->pos,
                          "%s cannot depend on the algebraic variable '%s' (it is "
                          "solved for along the run)",
                          r->what, e->name);
            if (r->kind == CTX_FUNC) /* inlined where it is called, as with a fixed quantity */
                ((lang_func *)r->func)->uses_fix = 1;
            e->kind = N_ALG;
            e->index = s->index;
            return;
        case SYM_NOISE:
            if (r->kind >= CTX_PARAMS)
                lang_fail(c, e->pos, "%s cannot depend on the noise '%s' (it changes at every "
                          "step of a run)", r->what, e->name);
            e->kind = N_NOISE;
            e->index = s->index;
            return;
        case SYM_VOLT:
            if (r->kind >= CTX_PARAMS)
                lang_fail(c, e->pos, "%s cannot depend on an integral int{...}", r->what);
            e->kind = N_VOLT;
            e->index = s->index;
            return;
        case SYM_AUX:
            lang_fail(c, e->pos, "'%s' is an aux output, which XPPAUT does not know inside "
                      "formulas: define it as a fixed quantity '%s_=...' and write 'aux "
                      "%s=%s_'", e->name, e->name, e->name, e->name);
        case SYM_FUNC:
            lang_fail(c, e->pos, "'%s' is a function: call it as %s(...)", e->name, e->name);
        case SYM_TABLE:
            lang_fail(c, e->pos, "'%s' is a table: look a value up with %s(x)", e->name, e->name);
        case SYM_SPECIAL:
            lang_fail(c, e->pos, "'%s' is a network sum: take its element j with %s(j)", e->name,
                      e->name);
        default:
            unknown(c, e, r, 0);
        }
    }
    if (e->kind == N_FUN && random_call(c, e, r))
        return;
    if (e->kind == N_DELAY) {
        if (r->kind != CTX_RHS)
            lang_fail(c, e->pos, "%s cannot use delay(%s, ...): write it in an equation, a "
                      "fixed quantity, an aux output or an event", r->what, e->name);
        const lang_sym *s = lang_lookup(c, e->name);
        if (!s || s->kind != SYM_STATE)
            lang_fail(c, e->pos, "delay(%s, ...): '%s' is %s; delay(x, tau) reads the past of "
                      "a state x", e->name, e->name,
                      s ? lang_sym_kind_name(s->kind) : "not declared");
        e->index = s->index;
        return;
    }
    if (e->kind == N_FUN && !lang_resolve_call(c, e))
        unknown(c, e, r, 1);
    if (e->kind == N_FUN && e->op == F_TABLE) {
        const char *tname = LVEC_AT(m->tables, lang_table, e->index).name;
        if (r->kind == CTX_PARAMS)
            lang_fail(c, e->pos, "%s cannot use the table '%s' (its values come after the "
                      "parameters)", r->what, tname);
        if (r->kind == CTX_TABLE && e->index >= r->table)
            lang_fail(c, e->pos, "the formula of table '%s' uses table '%s', %s",
                      LVEC_AT(m->tables, lang_table, r->table).name, tname,
                      e->index == r->table ? "itself" : "defined after it");
    }
    if (e->kind == N_FUN && e->op == F_SPECIAL) {
        const lang_special *sp = &LVEC_AT(m->specials, lang_special, e->index);
        if (r->kind != CTX_RHS)
            lang_fail(c, e->pos, "%s cannot use the network sum '%s': use it in the equations, "
                      "aux outputs or events", r->what, sp->name);
        const node *j = e->args[0];
        if (j->kind != N_NUM)
            lang_fail(c, j->pos, "the element of network sum '%s' must be a whole number from 0 "
                      "to %d (write %s([j]) in an array line); here it is a formula",
                      sp->name, sp->n - 1, sp->name);
        if (j->num != floor(j->num) || j->num < 0 || j->num >= sp->n)
            lang_fail(c, j->pos, "the element of network sum '%s' must be a whole number from 0 "
                      "to %d (write %s([j]) in an array line); here it is %.15g", sp->name,
                      sp->n - 1, sp->name, j->num);
    }
}

/* A copy of e with the time t replaced by the number t0 (a history's value at t0). */
static node *at_time(lang_ctx *c, const node *e, double t0)
{
    node *r = lang_node(c, e->kind, e->pos);
    *r = *e;
    if (e->kind == N_TIME) {
        r->kind = N_NUM;
        r->num = t0;
        r->nargs = 0;
        return r;
    }
    if (e->nargs) {
        r->args = lang_alloc(c, (size_t)e->nargs * sizeof *r->args);
        for (int i = 0; i < e->nargs; i++)
            r->args[i] = at_time(c, e->args[i], t0);
    }
    return r;
}

/* ---- sums and shifts, unrolled before names are resolved ---- */

/* The value of a constant integer formula (numbers, + - * /, signs), or fail. */
static long const_int(lang_ctx *c, const node *e, const char *what)
{
    double v;
    switch (e->kind) {
    case N_NUM: v = e->num; break;
    case N_NEG: v = -(double)const_int(c, e->args[0], what); break;
    case N_BIN: {
        const double a = (double)const_int(c, e->args[0], what);
        const double b = (double)const_int(c, e->args[1], what);
        if (e->op == OP_ADD)
            v = a + b;
        else if (e->op == OP_SUB)
            v = a - b;
        else if (e->op == OP_MUL)
            v = a * b;
        else if (e->op == OP_DIV && b != 0)
            v = a / b;
        else
            lang_fail(c, e->pos, "%s must be a whole number: numbers, + - * / and i'", what);
        break;
    }
    default:
        lang_fail(c, e->pos, "%s must be a whole number: numbers, + - * / and i'", what);
    }
    if (!(v > -1e7 && v < 1e7))
        lang_fail(c, e->pos, "%s is too large", what);
    if (v != (double)(long)v)
        lang_fail(c, e->pos, "%s must be a whole number, not %.17g (XPPAUT would take its integer part silently)", what, v);
    return (long)v;
}

/* A copy of e with i' = k. */
static node *with_index(lang_ctx *c, node *e, long k)
{
    if (e->kind == N_SUMIDX) {
        node *n = lang_node(c, N_NUM, e->pos);
        n->num = (double)k;
        return n;
    }
    if (e->nargs == 0)
        return e;
    if (++c->copies > LANG_MAX_COPIES)
        lang_fail(c, e->pos, "sums too large to unroll (more than %d copies of their terms)",
                  LANG_MAX_COPIES);
    node *n = lang_node(c, e->kind, e->pos);
    *n = *e;
    n->args = lang_alloc(c, (size_t)e->nargs * sizeof *n->args);
    for (int i = 0; i < e->nargs; i++)
        n->args[i] = with_index(c, e->args[i], k);
    return n;
}

#define SUM_CHUNK 256 /* terms of a sum added left to right before a tree takes over */

static node *sum_node(lang_ctx *c, lpos pos, node *left, node *right)
{
    node *s = lang_node(c, N_BIN, pos);
    s->op = OP_ADD;
    s->nargs = 2;
    s->args = lang_alloc(c, 2 * sizeof *s->args);
    s->args[0] = left;
    s->args[1] = right;
    return s;
}

/* sum(j1,j2)of(f(i')) unrolled to f(j1)+...+f(j2); shift(name,k) is the name declared k
 * places after name among the names of its kind (XPPAUT's shift addresses the variable k
 * places on, and arrays are declared in a row). */
static node *unroll(lang_ctx *c, node *e, int in_sum)
{
    if (++c->depth > 4 * LANG_MAX_DEPTH)
        lang_fail(c, e->pos, "expression nested too deeply");
    if (e->kind == N_SUMIDX && !in_sum)
        lang_fail(c, e->pos, "i' is the index of a sum: sum(j1,j2)of(...i'...)");
    if (e->kind == N_SUM) {
        if (in_sum)
            lang_fail(c, e->pos, "a sum inside a sum (XPPAUT has one index, i')");
        const long a = const_int(c, e->args[0], "the first bound of sum"),
                   b = const_int(c, e->args[1], "the last bound of sum");
        if (b - a >= LANG_MAX_RANGE)
            lang_fail(c, e->pos, "sum(%ld,%ld) too long (at most %d terms)", a, b,
                      LANG_MAX_RANGE);
        /* left to right in chunks of SUM_CHUNK terms (as XPPAUT adds), the chunks' sums
         * added as a balanced tree: the expression stays shallow for the longest sum */
        const long n = b >= a ? b - a + 1 : 0;
        node **chunk = n > 0 ? lang_alloc(c, (size_t)((n + SUM_CHUNK - 1) / SUM_CHUNK) *
                                                 sizeof *chunk)
                             : NULL;
        long n_chunks = 0;
        node *total = NULL;
        for (long k = a; k <= b; k++) {
            node *term = unroll(c, with_index(c, e->args[2], k), 1);
            if ((k - a) % SUM_CHUNK == 0) {
                chunk[n_chunks++] = term;
                continue;
            }
            chunk[n_chunks - 1] = sum_node(c, e->pos, chunk[n_chunks - 1], term);
        }
        for (long width = 1; width < n_chunks; width *= 2)
            for (long i = 0; i + width < n_chunks; i += 2 * width)
                chunk[i] = sum_node(c, e->pos, chunk[i], chunk[i + width]);
        total = n_chunks > 0 ? chunk[0] : NULL;
        c->depth--;
        if (!total) { /* an empty sum */
            node *z = lang_node(c, N_NUM, e->pos);
            z->num = 0.0;
            return z;
        }
        total->paren = 1;
        return total;
    }
    for (int i = 0; i < e->nargs; i++)
        e->args[i] = unroll(c, e->args[i], in_sum);
    c->depth--;
    if (e->kind == N_FUN && lang_same_name(e->name, "shift")) {
        if (e->nargs != 2 || e->args[0]->kind != N_NAME)
            lang_fail(c, e->pos, "shift(name, k) takes a declared name and a whole number");
        const long k = const_int(c, e->args[1], "the offset of shift");
        const lang_sym *s = lang_lookup(c, e->args[0]->name);
        if (!s)
            unknown(c, e->args[0], &(rctx){CTX_RHS, NULL, "a formula", -1}, 0);
        lvec *v = s->kind == SYM_STATE     ? &c->m.states
                  : s->kind == SYM_PARAM   ? &c->m.params
                  : s->kind == SYM_FIX     ? &c->m.fixes
                  : s->kind == SYM_DERIVED ? &c->m.derived
                                           : NULL;
        if (!v)
            lang_fail(c, e->pos, "shift of %s '%s': only states, parameters and fixed "
                      "quantities", lang_sym_kind_name(s->kind), e->args[0]->name);
        const long at = s->index + k;
        if (at < 0 || at >= v->n)
            lang_fail(c, e->pos, "shift(%s,%ld) is outside the %d names of its kind", e->args[0]->name,
                      k, v->n);
        const char *target = s->kind == SYM_STATE ? LVEC_AT(*v, lang_state, at).name
                             : s->kind == SYM_PARAM ? LVEC_AT(*v, lang_param, at).name
                                                    : LVEC_AT(*v, lang_formula, at).name;
        node *n = lang_node(c, N_NAME, e->pos);
        n->name = target;
        return n;
    }
    return e;
}

/* ---- orders ---- */

/* Calls of user functions in e: visit each callee (DFS for recursion). */
static void func_visit(lang_ctx *c, int fi, int *stack, int depth);

static void func_calls(lang_ctx *c, const node *e, int *stack, int depth)
{
    for (int i = 0; i < e->nargs; i++)
        func_calls(c, e->args[i], stack, depth);
    if (e->kind == N_UFUN) {
        lang_func *caller = &LVEC_AT(c->m.funcs, lang_func, stack[depth - 1]);
        func_visit(c, e->index, stack, depth);
        const lang_func *f = &LVEC_AT(c->m.funcs, lang_func, e->index);
        caller->uses_state |= f->uses_state;
        caller->uses_time |= f->uses_time;
    }
    if (e->kind == N_STATE || e->kind == N_TIME) {
        lang_func *caller = &LVEC_AT(c->m.funcs, lang_func, stack[depth - 1]);
        if (e->kind == N_STATE)
            caller->uses_state = 1;
        else
            caller->uses_time = 1;
    }
}

static void func_visit(lang_ctx *c, int fi, int *stack, int depth)
{
    lang_func *f = &LVEC_AT(c->m.funcs, lang_func, fi);
    if (f->mark == 2)
        return;
    if (f->mark == 1) {
        const lang_func *caller = &LVEC_AT(c->m.funcs, lang_func, stack[depth - 1]);
        lang_fail(c, f->pos, "function '%s' calls itself%s%s: recursion is not supported",
                  f->name, caller == f ? "" : " through '", caller == f ? "" : caller->name);
    }
    f->mark = 1;
    stack[depth] = fi;
    func_calls(c, f->body, stack, depth + 1);
    f->mark = 2;
}

/* Dependency order of formulas (fixed temporaries, or derived parameters) by DFS; a cycle is
 * refused with its path. dep_kind: N_FIX or N_PARAM (derived: index - offset). */
typedef struct order_ctx {
    lang_formula *f;
    int n;
    int dep_kind, offset;
    int *out, nout;
    int *path, npath;
    const char *what;
} order_ctx;

static void order_visit(lang_ctx *c, order_ctx *o, int k);

static void order_deps(lang_ctx *c, order_ctx *o, const node *e)
{
    for (int i = 0; i < e->nargs; i++)
        order_deps(c, o, e->args[i]);
    if ((int)e->kind == o->dep_kind && e->index >= o->offset)
        order_visit(c, o, e->index - o->offset);
}

static void order_visit(lang_ctx *c, order_ctx *o, int k)
{
    lang_formula *f = &o->f[k];
    if (f->mark == 2)
        return;
    if (f->mark == 1) {
        /* the cycle: from k's first appearance on the path */
        char buf[400];
        size_t used = 0;
        int from = o->npath - 1;
        while (from > 0 && o->path[from] != k)
            from--;
        for (int i = from; i < o->npath && used + 80 < sizeof buf; i++)
            used += (size_t)snprintf(buf + used, sizeof buf - used, "%s -> ",
                                     o->f[o->path[i]].name);
        snprintf(buf + used, sizeof buf - used, "%s", f->name);
        lang_fail(c, f->pos, "circular definition of %s: %s", o->what, buf);
    }
    f->mark = 1;
    o->path[o->npath++] = k;
    order_deps(c, o, f->expr);
    o->npath--;
    f->mark = 2;
    o->out[o->nout++] = k;
}

static int *order(lang_ctx *c, lvec *v, int dep_kind, int offset, const char *what)
{
    order_ctx o = {v->data, v->n, dep_kind, offset, NULL, 0, NULL, 0, what};
    o.out = lang_alloc(c, (size_t)(v->n + 1) * sizeof(int));
    o.path = lang_alloc(c, (size_t)(v->n + 1) * sizeof(int));
    for (int k = 0; k < v->n; k++)
        o.f[k].mark = 0;
    for (int k = 0; k < v->n; k++)
        order_visit(c, &o, k);
    return o.out;
}

static void fix_calls(lang_ctx *c, const node *e, int *uf)
{
    for (int i = 0; i < e->nargs; i++)
        fix_calls(c, e->args[i], uf);
    if (e->kind == N_UFUN && LVEC_AT(c->m.funcs, lang_func, e->index).uses_fix)
        *uf = 1;
}

/* Calls of functions that read fixed temporaries, replaced by their bodies (a C function
 * cannot see the caller's locals). */
static node *inline_fix_calls(lang_ctx *c, node *e, int depth)
{
    LANG_WORK(c, e->pos);
    if (depth > LANG_MAX_INLINE)
        lang_fail(c, e->pos, "calls nested too deeply to inline");
    for (int i = 0; i < e->nargs; i++)
        e->args[i] = inline_fix_calls(c, e->args[i], depth);
    if (e->kind == N_UFUN) {
        const lang_func *f = &LVEC_AT(c->m.funcs, lang_func, e->index);
        if (f->uses_fix)
            return inline_fix_calls(c, lang_subst(c, f->body, e->args), depth + 1);
    }
    return e;
}

/* ---- functions that read fixed quantities take them as arguments ----
 * A C function cannot see its caller's locals: a function that reads fixed quantities (or
 * algebraic variables), directly or through the functions it calls, takes them as
 * arguments after its own, and every call passes them. Each function stays one C function
 * and each call one call, so the C text grows with the file, not with the number of ways
 * calls nest (f1(u)=f0(f0(u)), f2(u)=f1(f1(u)), ...: 2^k copies when the bodies were
 * expanded where called). Only when a function would take more than LANG_MAX_ARGS
 * arguments are the calls expanded instead (inline_fix_calls, bounded by LANG_MAX_COPIES). */
typedef struct pass_set {
    int n, over, done;
    int kind[LANG_MAX_ARGS], index[LANG_MAX_ARGS]; /* N_FIX or N_ALG, and which */
} pass_set;

static void pass_add(pass_set *s, int kind, int index)
{
    for (int i = 0; i < s->n; i++)
        if (s->kind[i] == kind && s->index[i] == index)
            return;
    if (s->n == LANG_MAX_ARGS) {
        s->over = 1;
        return;
    }
    s->kind[s->n] = kind;
    s->index[s->n++] = index;
}

static void pass_of(lang_ctx *c, pass_set *sets, int f);

/* What e reads that a function must be passed, into s. */
static void pass_collect(lang_ctx *c, pass_set *sets, const node *e, pass_set *s)
{
    for (int i = 0; i < e->nargs; i++)
        pass_collect(c, sets, e->args[i], s);
    if (e->kind == N_FIX || e->kind == N_ALG) {
        pass_add(s, e->kind, e->index);
    } else if (e->kind == N_UFUN && LVEC_AT(c->m.funcs, lang_func, e->index).uses_fix) {
        pass_of(c, sets, e->index);
        const pass_set *g = &sets[e->index];
        s->over |= g->over;
        for (int i = 0; i < g->n; i++)
            pass_add(s, g->kind[i], g->index[i]);
    }
}

/* (functions do not call themselves, directly or not: refused before) */
static void pass_of(lang_ctx *c, pass_set *sets, int f)
{
    if (sets[f].done)
        return;
    sets[f].done = 1;
    pass_collect(c, sets, LVEC_AT(c->m.funcs, lang_func, f).body, &sets[f]);
}

/* e with each call of such a function given what it reads after its own arguments; in the
 * body of function own (own_nargs arguments of its own), what it is passed read as those
 * arguments. */
static node *pass_rewrite(lang_ctx *c, const pass_set *sets, node *e, const pass_set *own,
                          int own_nargs)
{
    if (own && (e->kind == N_FIX || e->kind == N_ALG)) {
        int k = 0;
        while (own->kind[k] != (int)e->kind || own->index[k] != e->index)
            k++;
        node *a = lang_node(c, N_ARG, e->pos);
        a->index = own_nargs + k;
        return a;
    }
    const int call = e->kind == N_UFUN && LVEC_AT(c->m.funcs, lang_func, e->index).uses_fix;
    if (e->nargs == 0 && !call)
        return e;
    const int extra = call ? sets[e->index].n : 0;
    node *n = lang_node(c, e->kind, e->pos);
    *n = *e;
    n->args = lang_alloc(c, (size_t)(e->nargs + extra + 1) * sizeof *n->args);
    for (int i = 0; i < e->nargs; i++)
        n->args[i] = pass_rewrite(c, sets, e->args[i], own, own_nargs);
    for (int i = 0; i < extra; i++) {
        node *x = lang_node(c, sets[e->index].kind[i], e->pos);
        x->index = sets[e->index].index[i];
        n->args[e->nargs + i] = pass_rewrite(c, sets, x, own, own_nargs);
    }
    n->nargs = e->nargs + extra;
    return n;
}

/* Gives the functions that read fixed quantities these as arguments and returns what each
 * is passed, or NULL (nothing changed) when one would take more than LANG_MAX_ARGS. */
static const pass_set *pass_fixes_as_args(lang_ctx *c)
{
    lang_model *m = &c->m;
    const int nf = m->funcs.n;
    pass_set *sets = lang_alloc(c, ((size_t)nf + 1) * sizeof *sets);
    int any = 0;
    for (int f = 0; f < nf; f++) {
        const lang_func *fn = &LVEC_AT(m->funcs, lang_func, f);
        if (!fn->uses_fix)
            continue;
        any = 1;
        pass_of(c, sets, f);
        if (sets[f].over || fn->nargs + sets[f].n > LANG_MAX_ARGS)
            return NULL;
    }
    if (!any)
        return sets;
    for (int f = 0; f < nf; f++) {
        lang_func *fn = &LVEC_AT(m->funcs, lang_func, f);
        if (fn->uses_fix)
            fn->body = pass_rewrite(c, sets, fn->body, &sets[f], fn->nargs);
    }
    for (int f = 0; f < nf; f++) { /* then the arguments (the bodies used the old counts) */
        lang_func *fn = &LVEC_AT(m->funcs, lang_func, f);
        if (!fn->uses_fix || sets[f].n == 0)
            continue;
        const char **names = lang_alloc(c, (size_t)(fn->nargs + sets[f].n) * sizeof *names);
        for (int k = 0; k < fn->nargs; k++)
            names[k] = fn->argnames[k];
        for (int k = 0; k < sets[f].n; k++)
            names[fn->nargs + k] =
                sets[f].kind[k] == N_FIX
                    ? LVEC_AT(m->fixes, lang_formula, sets[f].index[k]).name
                    : LVEC_AT(m->algs, lang_formula, sets[f].index[k]).name;
        fn->argnames = names;
        fn->nargs += sets[f].n;
    }
    return sets;
}

/* A top-level formula's calls by pass_fixes_as_args's rule when it held (sets), else
 * expanded */
static node *fix_calls_of(lang_ctx *c, node *e, const pass_set *sets)
{
    return sets ? pass_rewrite(c, sets, e, NULL, 0) : inline_fix_calls(c, e, 0);
}

/* The block of a network sum's len states or fixed quantities (len 0: every state from name
 * on; states only) that begins at name. */
static int special_block(lang_ctx *c, const lang_special *sp, const char *name, lpos pos,
                         int len, int *kind, int *index)
{
    const lang_sym *u = lang_lookup(c, name);
    if (!u || (u->kind != SYM_STATE && (u->kind != SYM_FIX || len == 0)))
        lang_fail(c, pos, "network sum '%s': '%s' is %s; it sums over %s", sp->name, name,
                  u ? lang_sym_kind_name(u->kind) : "not declared",
                  len ? "states or fixed quantities" : "states");
    const int avail = u->kind == SYM_STATE ? c->m.states.n : c->m.fixes.n;
    if (u->index + len > avail)
        lang_fail(c, pos, "network sum '%s' sums %d %s from '%s' on, and there are only %d",
                  sp->name, len, u->kind == SYM_STATE ? "states" : "fixed quantities", name,
                  avail - u->index);
    *kind = u->kind == SYM_STATE ? N_STATE : N_FIX;
    *index = u->index;
    return len ? len : avail - u->index;
}

/* A table of a network sum, of npts points. */
static int special_table(lang_ctx *c, const lang_special *sp, const char *name, lpos pos,
                         long npts, const char *why)
{
    const lang_sym *t = lang_lookup(c, name);
    if (!t || t->kind != SYM_TABLE)
        lang_fail(c, pos, "network sum '%s': '%s' is %s, not a table", sp->name, name,
                  t ? lang_sym_kind_name(t->kind) : "not declared");
    const lang_table *tb = &LVEC_AT(c->m.tables, lang_table, t->index);
    if (tb->npts != npts)
        lang_fail(c, pos, "network sum '%s': %s, and table '%s' has %ld points", sp->name, why,
                  tb->name, tb->npts);
    return t->index;
}

/* A network sum's tables, the blocks it sums over and fconv's function. */
/* An integrand of int{...}, or the kernel K of int{K#u} (integrals.c) */
static void resolve_volt(lang_ctx *c, node *e, int kernel)
{
    const rctx r = {CTX_RHS, NULL, kernel ? "the kernel of int{K#u}" : "an integrand", -1};
    resolve(c, e, &r);
}

static void resolve_special(lang_ctx *c, lang_special *sp)
{
    const long mn = (long)sp->m * sp->n;
    char why[160];
    if (sp->kind == LANG_SUM_CONV || sp->kind == LANG_SUM_FCONV)
        snprintf(why, sizeof why, "%s with m = %d weighs 2m+1 = %d neighbours",
                 sp->kind == LANG_SUM_CONV ? "conv" : "fconv", sp->m, 2 * sp->m + 1);
    else
        snprintf(why, sizeof why, "%s takes m n = %ld weights", sp->kind == LANG_SUM_MMULT
                                                                    ? "mmult" : "sparse", mn);
    const long npts = sp->kind <= LANG_SUM_FCONV ? 2L * sp->m + 1 : mn;
    sp->table = special_table(c, sp, sp->table_name, sp->table_pos, npts, why);
    if (sp->kind == LANG_SUM_SPARSE)
        sp->index_table = special_table(c, sp, sp->index_name, sp->index_pos, mn,
                                        "sparse takes m n = m times n indices");
    const int len = sp->kind == LANG_SUM_MMULT ? sp->m : sp->kind == LANG_SUM_SPARSE ? 0 : sp->n;
    sp->ulen = special_block(c, sp, sp->root_name, sp->root_pos, len, &sp->root_kind, &sp->root);
    if (sp->kind != LANG_SUM_FCONV)
        return;
    special_block(c, sp, sp->vroot_name, sp->vroot_pos, sp->n, &sp->vroot_kind, &sp->vroot);
    const lang_sym *f = lang_lookup(c, sp->func_name);
    if (!f || f->kind != SYM_FUNC)
        lang_fail(c, sp->func_pos, "network sum '%s': '%s' is %s, not a function", sp->name,
                  sp->func_name, f ? lang_sym_kind_name(f->kind) : "not declared");
    const lang_func *fn = &LVEC_AT(c->m.funcs, lang_func, f->index);
    if (fn->nargs != 2 || fn->uses_fix)
        lang_fail(c, sp->func_pos, "network sum '%s': fconv's function '%s' must take 2 arguments "
                  "(u, v) and read no fixed quantities", sp->name, fn->name);
    sp->func = f->index;
}

/* 1 if e calls a network sum. */
static int special_calls(const node *e)
{
    if (e->kind == N_FUN && e->op == F_SPECIAL)
        return 1;
    for (int i = 0; i < e->nargs; i++)
        if (special_calls(e->args[i]))
            return 1;
    return 0;
}

/* 1 if e calls a table, directly or through the user functions it calls. */
static int table_calls(lang_ctx *c, const node *e)
{
    if (e->kind == N_FUN && e->op == F_TABLE)
        return 1;
    if (e->kind == N_UFUN && LVEC_AT(c->m.funcs, lang_func, e->index).uses_table)
        return 1;
    for (int i = 0; i < e->nargs; i++)
        if (table_calls(c, e->args[i]))
            return 1;
    return 0;
}

/* Calls in a parameters-only formula must not reach states or t. */
static void check_param_calls(lang_ctx *c, const node *e, const char *what)
{
    for (int i = 0; i < e->nargs; i++)
        check_param_calls(c, e->args[i], what);
    if (e->kind == N_UFUN) {
        const lang_func *f = &LVEC_AT(c->m.funcs, lang_func, e->index);
        if (f->uses_state || f->uses_time || f->uses_fix || f->uses_table)
            lang_fail(c, e->pos, "%s cannot call '%s', which depends on %s", what, f->name,
                      f->uses_state  ? "the states"
                      : f->uses_time ? "the time t"
                      : f->uses_fix  ? "fixed quantities"
                                     : "a table");
    }
}

/* e reads parameter k */
static int reads_param(const node *e, int k)
{
    if (!e)
        return 0;
    if (e->kind == N_PARAM && e->index == k)
        return 1;
    for (int i = 0; i < e->nargs; i++)
        if (reads_param(e->args[i], k))
            return 1;
    return 0;
}

/* XPPAUT sets the parameters its globals assign after the assignments of every global that
 * fires in the same cycle (flags.c); dynkit after each global's own: a global that reads a
 * parameter another assigns could see another value when both fire at one instant. */
static void warn_shared_parameters(lang_ctx *c)
{
    const lang_model *m = &c->m;
    for (int i = 0; i < m->events.n; i++) {
        const lang_event *ev = &LVEC_AT(m->events, lang_event, i);
        for (int a = 0; a < ev->nassign; a++) {
            if (ev->assign[a].state >= 0)
                continue;
            const int k = -1 - ev->assign[a].state;
            for (int j = 0; j < m->events.n; j++) {
                const lang_event *other = &LVEC_AT(m->events, lang_event, j);
                for (int b = 0; j != i && b < other->nassign; b++)
                    if (reads_param(other->assign[b].value, k)) {
                        lang_warn(c, other->assign[b].pos,
                                  "this global reads '%s', which the global on line %d "
                                  "assigns: when both fire at one instant, XPPAUT reads the "
                                  "value from before that instant, dynkit the new one if that "
                                  "global comes first in the file", ev->assign[a].name,
                                  ev->pos.line);
                        return;
                    }
            }
        }
    }
}

static const char *display_name(lang_ctx *c, const char *name, lpos pos, const char *option)
{
    if (lang_same_name(name, "t"))
        return NULL;
    const lang_sym *s = lang_lookup(c, name);
    if (s && s->kind == SYM_STATE)
        return LVEC_AT(c->m.states, lang_state, s->index).name;
    if (s && s->kind == SYM_AUX)
        return LVEC_AT(c->m.auxs, lang_formula, s->index).name;
    if (s && s->kind == SYM_ALG)
        lang_fail(c, pos,
                  "option '%s': '%s' is an algebraic variable: name an aux output of "
                  "it (aux %s_=%s)",
                  option, name, name, name);
    /* XPPAUT 6.11 runs such a file and leaves the option out (measured) */
    const char *near = nearest_symbol(c, name, NULL, 0);
    lang_warn(c, pos, "option '%s': '%s' is not a state or an aux output%s%s%s; the option is "
              "ignored, as XPPAUT ignores it", option, name, near ? " (did you mean '" : "",
              near ? near : "", near ? "'?)" : "");
    return NULL;
}

/* The variable of @ poimap: poivar (a state, an aux output, or t for a section), else the
 * first state, as XPPAUT takes it; a name that is none of them is an error (a section of
 * another variable would be written without a word). */
static void poincare_var(lang_ctx *c)
{
    lang_model *m = &c->m;
    if (!m->poivar) {
        if (m->states.n == 0)
            lang_fail(c, m->poimap_pos, "poimap needs a state (the model has none)");
        m->poivar = LVEC_AT(m->states, lang_state, 0).name;
        return;
    }
    const lang_sym *s = lang_lookup(c, m->poivar);
    if (lang_same_name(m->poivar, "t")) {
        if (m->poimap == DYN_POINCARE_EXTREMUM)
            lang_fail(c, m->poivar_pos, "poivar=t: the extrema of poimap=max are a state's");
        m->poivar = "t";
    } else if (s && s->kind == SYM_STATE) {
        m->poivar = LVEC_AT(m->states, lang_state, s->index).name;
    } else if (s && s->kind == SYM_AUX && m->poimap != DYN_POINCARE_EXTREMUM) {
        m->poivar = LVEC_AT(m->auxs, lang_formula, s->index).name;
    } else {
        const char *near = nearest_symbol(c, m->poivar, NULL, 0);
        lang_fail(c, m->poivar_pos, "poivar=%s: name a state%s%s%s%s", m->poivar,
                  m->poimap == DYN_POINCARE_EXTREMUM ? "" : ", an aux output or t",
                  near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "");
    }
}

void lang_alg_uses(lang_ctx *c, const node *e, unsigned char *used, unsigned char *fix_seen,
                   unsigned char *fun_seen)
{
    for (int i = 0; i < e->nargs; i++)
        lang_alg_uses(c, e->args[i], used, fix_seen, fun_seen);
    if (e->kind == N_ALG)
        used[e->index] = 1;
    else if (e->kind == N_FIX && !fix_seen[e->index]) {
        fix_seen[e->index] = 1;
        lang_alg_uses(c, LVEC_AT(c->m.fixes, lang_formula, e->index).expr, used, fix_seen,
                      fun_seen);
    } else if (e->kind == N_UFUN && !fun_seen[e->index]) {
        fun_seen[e->index] = 1;
        lang_alg_uses(c, LVEC_AT(c->m.funcs, lang_func, e->index).body, used, fix_seen, fun_seen);
    }
}

/* A differential-algebraic system: as many 0= equations as algebraic variables (solv),
 * each variable used by some equation; the equations are formulas like the right-hand
 * sides, the initial guesses formulas of the parameters. */
static void check_algebraic(lang_ctx *c, const rctx *rhs)
{
    lang_model *m = &c->m;
    if (m->algs.n == 0 && m->algeqs.n == 0)
        return;
    for (int i = 0; i < m->algeqs.n; i++)
        resolve(c, LVEC_AT(m->algeqs, lang_formula, i).expr, rhs);
    for (int i = 0; i < m->algs.n; i++) {
        lang_formula *f = &LVEC_AT(m->algs, lang_formula, i);
        rctx r = {CTX_PARAMS, NULL, "the initial guess of an algebraic variable", -1};
        resolve(c, f->expr, &r);
        check_param_calls(c, f->expr, "the initial guess of an algebraic variable");
    }
    if (m->algeqs.n != m->algs.n) {
        const lpos at = m->algeqs.n > m->algs.n ? LVEC_AT(m->algeqs, lang_formula, m->algs.n).pos
                                                : LVEC_AT(m->algs, lang_formula, m->algeqs.n).pos;
        lang_fail(c, at,
                  "%d algebraic equation%s (0=...) for %d algebraic variable%s (solv): "
                  "give as many of each",
                  m->algeqs.n, m->algeqs.n == 1 ? "" : "s", m->algs.n, m->algs.n == 1 ? "" : "s");
    }
    if (m->map_eq || m->map_meth)
        lang_fail(c, LVEC_AT(m->algs, lang_formula, 0).pos,
                  "algebraic equations are for differential equations, not discrete maps");
    unsigned char *used = lang_alloc(c, (size_t)m->algs.n + 1);
    unsigned char *fix_seen = lang_alloc(c, (size_t)m->fixes.n + 1);
    unsigned char *fun_seen = lang_alloc(c, (size_t)m->funcs.n + 1);
    for (int i = 0; i < m->algeqs.n; i++)
        lang_alg_uses(c, LVEC_AT(m->algeqs, lang_formula, i).expr, used, fix_seen, fun_seen);
    for (int i = 0; i < m->algs.n; i++)
        if (!used[i]) {
            const lang_formula *f = &LVEC_AT(m->algs, lang_formula, i);
            lang_fail(c, f->pos,
                      "the algebraic variable '%s' appears in no algebraic equation "
                      "(0=...), which must determine it",
                      f->name);
        }
}

void lang_check(lang_ctx *c)
{
    lang_model *m = &c->m;
    for (int i = 0; i < m->funcs.n; i++) {
        lang_func *f = &LVEC_AT(m->funcs, lang_func, i);
        f->body = unroll(c, f->body, 0);
    }
    for (int i = 0; i < m->derived.n; i++) {
        lang_formula *f = &LVEC_AT(m->derived, lang_formula, i);
        f->expr = unroll(c, f->expr, 0);
    }
    for (int i = 0; i < m->fixes.n; i++) {
        lang_formula *f = &LVEC_AT(m->fixes, lang_formula, i);
        f->expr = unroll(c, f->expr, 0);
    }
    for (int i = 0; i < m->states.n; i++) {
        lang_state *st = &LVEC_AT(m->states, lang_state, i);
        st->rhs = unroll(c, st->rhs, 0);
    }
    for (int i = 0; i < m->auxs.n; i++) {
        lang_formula *f = &LVEC_AT(m->auxs, lang_formula, i);
        f->expr = unroll(c, f->expr, 0);
    }
    for (int i = 0; i < m->algeqs.n; i++) {
        lang_formula *f = &LVEC_AT(m->algeqs, lang_formula, i);
        f->expr = unroll(c, f->expr, 0);
    }
    for (int i = 0; i < m->algs.n; i++) {
        lang_formula *f = &LVEC_AT(m->algs, lang_formula, i);
        f->expr = unroll(c, f->expr, 0);
    }
    for (int i = 0; i < m->events.n; i++) {
        lang_event *ev = &LVEC_AT(m->events, lang_event, i);
        ev->cond = unroll(c, ev->cond, 0);
        for (int k = 0; k < ev->nassign; k++)
            ev->assign[k].value = unroll(c, ev->assign[k].value, 0);
    }
    for (int i = 0; i < m->inits.n; i++) {
        lang_init *in = &LVEC_AT(m->inits, lang_init, i);
        in->value = unroll(c, in->value, 0);
    }
    /* user functions first: their bodies, then recursion and what they use */
    for (int i = 0; i < m->funcs.n; i++) {
        lang_func *f = &LVEC_AT(m->funcs, lang_func, i);
        rctx r = {CTX_FUNC, f, "a function", -1};
        resolve(c, f->body, &r);
    }
    int *stack = lang_alloc(c, (size_t)(m->funcs.n + 1) * sizeof(int));
    for (int i = 0; i < m->funcs.n; i++) {
        lang_func *f = &LVEC_AT(m->funcs, lang_func, i);
        if (f->mark == 2)
            continue;
        f->mark = 1;
        stack[0] = i;
        func_calls(c, f->body, stack, 1);
        f->mark = 2;
    }
    /* a second pass: uses_* of callees visited after their callers */
    for (int pass = 0; pass < m->funcs.n; pass++) {
        int changed = 0;
        for (int i = 0; i < m->funcs.n; i++) {
            lang_func *f = &LVEC_AT(m->funcs, lang_func, i);
            int us = f->uses_state, ut = f->uses_time, uf = f->uses_fix;
            const int ub = f->uses_table || table_calls(c, f->body);
            lang_func_uses(c, f->body, &us, &ut);
            fix_calls(c, f->body, &uf);
            changed |= us != f->uses_state || ut != f->uses_time || uf != f->uses_fix ||
                       ub != f->uses_table;
            f->uses_state = us;
            f->uses_time = ut;
            f->uses_fix = uf;
            f->uses_table = ub;
        }
        if (!changed)
            break;
    }
    rctx rhs = {CTX_RHS, NULL, "a formula", -1};
    for (int i = 0; i < m->bdrys.n; i++) {
        lang_formula *f = &LVEC_AT(m->bdrys, lang_formula, i);
        f->expr = unroll(c, f->expr, 0);
        resolve(c, f->expr, &rhs);
        lang_bdry_resolved(c, f);
    }
    for (int i = 0; i < m->derived.n; i++) {
        lang_formula *f = &LVEC_AT(m->derived, lang_formula, i);
        rctx r = {CTX_PARAMS, NULL, "a derived parameter", -1};
        resolve(c, f->expr, &r);
        check_param_calls(c, f->expr, "a derived parameter");
    }
    /* tables: formulas of t and the parameters, computed after the derived parameters;
     * their values follow those in the parameter array */
    int offset = m->params.n + m->derived.n;
    for (int i = 0; i < m->tables.n; i++) {
        lang_table *tb = &LVEC_AT(m->tables, lang_table, i);
        if (tb->expr) {
            tb->expr = unroll(c, tb->expr, 0);
            rctx r = {CTX_TABLE, NULL, "a table's formula", i};
            resolve(c, tb->expr, &r);
            check_param_calls(c, tb->expr, "a table's formula");
        }
        tb->offset = offset;
        offset += (int)tb->npts;
        if (offset - (m->params.n + m->derived.n) > LANG_MAX_TABLE)
            lang_fail(c, tb->pos, "tables of more than %d points in all", LANG_MAX_TABLE);
    }
    /* the sums' arrays live on the stack of the functions that use them (OpenMP threads of
     * sweeps have small stacks): at most LANG_MAX_SUM_STACK doubles in all */
    long sum_stack = 0;
    for (int i = 0; i < m->specials.n; i++) {
        lang_special *sp = &LVEC_AT(m->specials, lang_special, i);
        if (sp->kind != LANG_SUM_GILL) /* its rates are fixed quantities (markov.c) */
            resolve_special(c, sp);
        sum_stack += sp->n + (sp->root_kind == N_FIX ? sp->ulen : 0) +
                 (sp->kind == LANG_SUM_FCONV && sp->vroot_kind == N_FIX ? sp->n : 0);
        if (sum_stack > LANG_MAX_SUM_STACK)
            lang_fail(c, sp->pos, "network sums of more than %d elements in all (with the fixed "
                      "quantities they sum over): sum over states, or fewer", LANG_MAX_SUM_STACK);
    }
    for (int i = 0; i < m->fixes.n; i++) {
        const lang_formula *f = &LVEC_AT(m->fixes, lang_formula, i);
        resolve(c, f->expr, &rhs);
        if (special_calls(f->expr))
            lang_fail(c, f->pos, "the fixed quantity '%s' uses a network sum, which is computed "
                      "after the fixed quantities: use the sum in the equations", f->name);
    }
    for (int i = 0; i < m->states.n; i++)
        resolve(c, LVEC_AT(m->states, lang_state, i).rhs, &rhs);
    lang_volt_resolve(c, resolve_volt);
    for (int i = 0; i < m->auxs.n; i++)
        resolve(c, LVEC_AT(m->auxs, lang_formula, i).expr, &rhs);
    check_algebraic(c, &rhs);
    for (int i = 0; i < m->events.n; i++) {
        lang_event *ev = &LVEC_AT(m->events, lang_event, i);
        resolve(c, ev->cond, &rhs);
        for (int k = 0; k < ev->nassign; k++) {
            lang_assign *a = &ev->assign[k];
            const lang_sym *s = lang_lookup(c, a->name);
            if (!s) {
                node e = {0};
                e.name = a->name;
                e.pos = a->pos;
                unknown(c, &e, &rhs, 0);
            }
            /* XPPAUT's globals assign states and parameters (flags.c): a parameter keeps its
             * new value for the rest of the run (a spike counter) */
            if (s->kind != SYM_STATE && s->kind != SYM_PARAM)
                lang_fail(c, a->pos, "a global assigns states and parameters; '%s' is %s",
                          a->name, lang_sym_kind_name(s->kind));
            a->state = s->kind == SYM_STATE ? s->index : -1 - s->index;
            resolve(c, a->value, &rhs);
        }
        for (int k = 0; k < i; k++)
            if (lang_same_name(LVEC_AT(m->events, lang_event, k).name, ev->name))
                lang_fail(c, ev->pos, "event '%s' is declared twice", ev->name);
    }
    warn_shared_parameters(c);
    for (int i = 0; i < m->inits.n; i++) {
        lang_init *in = &LVEC_AT(m->inits, lang_init, i);
        const lang_sym *s = lang_lookup(c, in->name);
        if (!s || s->kind != SYM_STATE) {
            if (s)
                lang_fail(c, in->pos, "an initial value is for a state; '%s' is %s", in->name,
                          lang_sym_kind_name(s->kind));
            node e = {0};
            e.name = in->name;
            e.pos = in->pos;
            unknown(c, &e, &rhs, 0);
        }
        rctx r = {m->n_delays && in->x0 ? CTX_HISTORY : CTX_PARAMS, NULL, "an initial value",
                  -1};
        resolve(c, in->value, &r);
        check_param_calls(c, in->value, "an initial value");
        lang_state *st = &LVEC_AT(m->states, lang_state, s->index);
        if (m->n_delays && in->x0) { /* XPPAUT: x(0)= is the history too, a formula of t */
            st->history = in->value;
            int us = 0, ut = 0;
            lang_func_uses(c, in->value, &us, &ut);
            if (ut)
                in->value = at_time(c, in->value, m->t0);
        }
        if (st->init) /* XPPAUT takes the last one too, without a word */
            lang_note(c, in->pos,
                      "the initial value of %s is given again (before, on line %d): the "
                      "last one is used, as in XPPAUT",
                      st->name, st->init_pos.line);
        st->init = in->value;
        st->init_pos = in->pos;
    }
    const pass_set *sets = pass_fixes_as_args(c);
    for (int i = 0; i < m->fixes.n; i++) {
        lang_formula *f = &LVEC_AT(m->fixes, lang_formula, i);
        f->expr = fix_calls_of(c, f->expr, sets);
    }
    for (int i = 0; i < m->states.n; i++) {
        lang_state *st = &LVEC_AT(m->states, lang_state, i);
        st->rhs = fix_calls_of(c, st->rhs, sets);
    }
    for (int i = 0; i < m->auxs.n; i++) {
        lang_formula *f = &LVEC_AT(m->auxs, lang_formula, i);
        f->expr = fix_calls_of(c, f->expr, sets);
    }
    for (int i = 0; i < m->volts.n; i++) {
        lang_volt *v = &LVEC_AT(m->volts, lang_volt, i);
        v->integrand = fix_calls_of(c, v->integrand, sets);
    }
    for (int i = 0; i < m->algeqs.n; i++) {
        lang_formula *f = &LVEC_AT(m->algeqs, lang_formula, i);
        f->expr = fix_calls_of(c, f->expr, sets);
    }
    for (int i = 0; i < m->events.n; i++) {
        lang_event *ev = &LVEC_AT(m->events, lang_event, i);
        ev->cond = fix_calls_of(c, ev->cond, sets);
        for (int k = 0; k < ev->nassign; k++)
            ev->assign[k].value = fix_calls_of(c, ev->assign[k].value, sets);
    }
    m->fix_order = order(c, &m->fixes, N_FIX, 0, "fixed quantities");
    m->derived_order = order(c, &m->derived, N_PARAM, m->params.n, "derived parameters");
    lang_noise_classify(c);
    /* documentation lines */
    for (int i = 0; i < m->docs.n; i++) {
        const lang_docline *d = &LVEC_AT(m->docs, lang_docline, i);
        const lang_sym *s = lang_lookup(c, d->name);
        if (!s) {
            const char *near = nearest_symbol(c, d->name, NULL, 0);
            lang_fail(c, d->pos, "'#: %s': not a declared name, nor title, description or "
                      "event%s%s%s", d->name, near ? " (did you mean '" : "",
                      near ? near : "", near ? "'?)" : "");
        }
        lang_doc *to = NULL;
        if (s->kind == SYM_STATE)
            to = &LVEC_AT(m->states, lang_state, s->index).doc;
        else if (s->kind == SYM_PARAM)
            to = &LVEC_AT(m->params, lang_param, s->index).doc;
        else if (s->kind == SYM_AUX)
            to = &LVEC_AT(m->auxs, lang_formula, s->index).doc;
        else
            lang_fail(c, d->pos, "'%s' is %s; units and descriptions are for states, "
                      "parameters and aux outputs", d->name, lang_sym_kind_name(s->kind));
        if (d->doc.unit)
            to->unit = d->doc.unit;
        if (d->doc.description)
            to->description = d->doc.description;
    }
    if (m->xp)
        m->xp = display_name(c, m->xp, m->xp_pos, "xp");
    if (m->yp)
        m->yp = display_name(c, m->yp, m->yp_pos, "yp");
    if (m->poimap)
        poincare_var(c);
}

int lang_resolve_call(lang_ctx *c, node *e)
{
    int arity;
    const int f = lang_fun_lookup(e->name, &arity);
    if (f >= 0) {
        if (arity != e->nargs)
            lang_fail(c, e->pos, "'%s' takes %d argument%s, not %d", e->name, arity,
                      arity == 1 ? "" : "s", e->nargs);
        e->op = f;
        return 1;
    }
    const lang_sym *s = lang_lookup(c, e->name);
    if (s && s->kind == SYM_SPECIAL) {
        if (e->nargs != 1)
            lang_fail(c, e->pos, "network sum '%s' takes 1 argument (the element), not %d",
                      e->name, e->nargs);
        e->op = F_SPECIAL;
        e->index = s->index;
        return 1;
    }
    if (s && s->kind == SYM_TABLE) {
        if (e->nargs != 1)
            lang_fail(c, e->pos, "table '%s' takes 1 argument, not %d", e->name, e->nargs);
        e->op = F_TABLE;
        e->index = s->index;
        return 1;
    }
    if (s && s->kind == SYM_FUNC) {
        const lang_func *fn = &LVEC_AT(c->m.funcs, lang_func, s->index);
        if (fn->nargs != e->nargs)
            lang_fail(c, e->pos, "function '%s' takes %d argument%s, not %d", fn->name,
                      fn->nargs, fn->nargs == 1 ? "" : "s", e->nargs);
        e->kind = N_UFUN;
        e->index = s->index;
        return 1;
    }
    if (s)
        lang_fail(c, e->pos, "'%s' is %s, not a function", e->name, lang_sym_kind_name(s->kind));
    return 0;
}
