/* SPDX-License-Identifier: BSD-3-Clause */
/* Symbolic derivatives of .ode expressions for the analytic Jacobian, with the
 * simplifications that keep the emitted code lean (0*x, 1*x, x+0, x-0, x/1, x^1, constant
 * folding), and the evaluation of constant expressions (parameter values, default initial
 * states) with XPPAUT's meaning of each function (heav(0) = 1, sign(0) = 0,
 * mod(x,y) = fmod(x,y) made non-negative by adding y, as its pmod; max and min as
 * x>y?x:y and x<y?x:y). Derivatives of the piecewise functions are their derivatives almost
 * everywhere: heav, sign, flr, ceil, comparisons, not, & and | have zero derivative; abs
 * has sign(x); max, min and if(c)then(a)else(b) the derivative of the branch taken; mod(a,b)
 * has 1 in a and -k = (mod(a,b) - a)/b in b. Fixed temporaries enter by the chain rule
 * through their own derivatives (locals of the Jacobian), user functions through their
 * partial derivatives (functions of their own), or inline when they use the states
 * directly. */
#include <math.h>
#include <string.h>

#include "lang/lang_internal.h"

node *lang_num(lang_ctx *c, double v)
{
    node **shared = v == 0.0 && !signbit(v) ? &c->zero : v == 1.0 ? &c->one : NULL;
    if (shared && *shared)
        return *shared;
    node *e = lang_node(c, N_NUM, (lpos){0, 0});
    if (shared)
        *shared = e;
    e->num = v;
    return e;
}

int lang_is_num(const node *e, double v) { return e->kind == N_NUM && e->num == v && !e->name; }

static int is_const(const node *e) { return e->kind == N_NUM; }

static node *mk(lang_ctx *c, node_kind k, int op, int nargs, node *a, node *b, node *d)
{
    node *e = lang_node(c, k, (lpos){0, 0});
    e->op = op;
    e->nargs = nargs;
    e->args = lang_alloc(c, (size_t)(nargs ? nargs : 1) * sizeof *e->args);
    if (nargs > 0)
        e->args[0] = a;
    if (nargs > 1)
        e->args[1] = b;
    if (nargs > 2)
        e->args[2] = d;
    return e;
}

/* ---- evaluation ---- */

double lang_eval(lang_ctx *c, const node *e, const double *args, const double *pvals)
{
    double a = 0, b = 0;
    if (++c->depth > 8 * LANG_MAX_DEPTH)
        lang_fail(c, e->pos, "expression nested too deeply to evaluate");
    double r = NAN;
    switch (e->kind) {
    case N_NUM: r = e->num; break;
    case N_PARAM: r = pvals ? pvals[e->index] : NAN; break;
    case N_ARG: r = args ? args[e->index] : NAN; break;
    case N_NEG: r = -lang_eval(c, e->args[0], args, pvals); break;
    case N_NOT: r = lang_eval(c, e->args[0], args, pvals) == 0.0 ? 1.0 : 0.0; break;
    case N_IF:
        r = lang_eval(c, e->args[0], args, pvals) != 0.0 ? lang_eval(c, e->args[1], args, pvals)
                                                         : lang_eval(c, e->args[2], args, pvals);
        break;
    case N_BIN:
        a = lang_eval(c, e->args[0], args, pvals);
        b = lang_eval(c, e->args[1], args, pvals);
        r = lang_apply_bin(e->op, a, b);
        break;
    case N_FUN:
        a = lang_eval(c, e->args[0], args, pvals);
        if (e->nargs > 1)
            b = lang_eval(c, e->args[1], args, pvals);
        r = lang_apply_fun(e->op, a, b);
        break;
    case N_UFUN: {
        const lang_func *f = &LVEC_AT(c->m.funcs, lang_func, e->index);
        double v[LANG_MAX_ARGS];
        for (int i = 0; i < e->nargs && i < LANG_MAX_ARGS; i++)
            v[i] = lang_eval(c, e->args[i], args, pvals);
        r = lang_eval(c, f->body, v, pvals);
        break;
    }
    default: break;
    }
    c->depth--;
    return r;
}

/* ---- simplifying constructors ---- */

static node *fold(lang_ctx *c, node *e)
{
    if (e->kind == N_FUN && e->op >= F_COUNT) /* tables: their values come at run time */
        return e;
    for (int i = 0; i < e->nargs; i++)
        if (!is_const(e->args[i]))
            return e;
    return lang_num(c, lang_eval(c, e, NULL, NULL));
}

static node *neg(lang_ctx *c, node *a)
{
    if (is_const(a))
        return lang_num(c, -a->num);
    if (a->kind == N_NEG)
        return a->args[0];
    return mk(c, N_NEG, 0, 1, a, NULL, NULL);
}

static node *add(lang_ctx *c, node *a, node *b)
{
    if (lang_is_num(a, 0.0))
        return b;
    if (lang_is_num(b, 0.0))
        return a;
    if (b->kind == N_NEG)
        return fold(c, mk(c, N_BIN, OP_SUB, 2, a, b->args[0], NULL));
    return fold(c, mk(c, N_BIN, OP_ADD, 2, a, b, NULL));
}

static node *sub(lang_ctx *c, node *a, node *b)
{
    if (lang_is_num(b, 0.0))
        return a;
    if (lang_is_num(a, 0.0))
        return neg(c, b);
    if (b->kind == N_NEG)
        return add(c, a, b->args[0]);
    return fold(c, mk(c, N_BIN, OP_SUB, 2, a, b, NULL));
}

static node *mul(lang_ctx *c, node *a, node *b)
{
    if (lang_is_num(a, 0.0) || lang_is_num(b, 0.0))
        return lang_num(c, 0.0);
    if (lang_is_num(a, 1.0))
        return b;
    if (lang_is_num(b, 1.0))
        return a;
    if (lang_is_num(a, -1.0))
        return neg(c, b);
    if (lang_is_num(b, -1.0))
        return neg(c, a);
    if (a->kind == N_NEG && b->kind == N_NEG)
        return mul(c, a->args[0], b->args[0]);
    if (a->kind == N_NEG)
        return neg(c, mul(c, a->args[0], b));
    if (b->kind == N_NEG)
        return neg(c, mul(c, a, b->args[0]));
    return fold(c, mk(c, N_BIN, OP_MUL, 2, a, b, NULL));
}

static node *dvd(lang_ctx *c, node *a, node *b)
{
    if (lang_is_num(a, 0.0))
        return lang_num(c, 0.0);
    if (lang_is_num(b, 1.0))
        return a;
    if (a->kind == N_NEG)
        return neg(c, dvd(c, a->args[0], b));
    return fold(c, mk(c, N_BIN, OP_DIV, 2, a, b, NULL));
}

static node *pw(lang_ctx *c, node *a, node *b)
{
    if (lang_is_num(b, 1.0))
        return a;
    if (lang_is_num(b, 0.0))
        return lang_num(c, 1.0);
    return fold(c, mk(c, N_BIN, OP_POW, 2, a, b, NULL));
}

static node *fun(lang_ctx *c, int f, node *a, node *b)
{
    return fold(c, mk(c, N_FUN, f, b ? 2 : 1, a, b, NULL));
}

static node *cond(lang_ctx *c, node *test, node *a, node *b)
{
    if (is_const(a) && is_const(b) && (a->num == b->num || (isnan(a->num) && isnan(b->num))))
        return a;
    if (is_const(test))
        return test->num != 0.0 ? a : b;
    return mk(c, N_IF, 0, 3, test, a, b);
}

node *lang_add(lang_ctx *c, node *a, node *b) { return add(c, a, b); }
node *lang_sub(lang_ctx *c, node *a, node *b) { return sub(c, a, b); }
node *lang_mul(lang_ctx *c, node *a, node *b) { return mul(c, a, b); }
node *lang_div(lang_ctx *c, node *a, node *b) { return dvd(c, a, b); }
node *lang_neg(lang_ctx *c, node *a) { return neg(c, a); }
node *lang_fun1(lang_ctx *c, int f, node *a) { return fun(c, f, a, NULL); }

/* ---- derivatives ---- */

/* body with its arguments replaced by args (for inlining a call) */
node *lang_subst(lang_ctx *c, node *body, node **args)
{
    LANG_WORK(c, body->pos);
    if (body->kind == N_ARG)
        return args[body->index];
    if (body->nargs == 0)
        return body;
    if (++c->copies > LANG_MAX_COPIES)
        lang_fail(c, body->pos, "calls of functions nest too deeply to expand (more than %d "
                  "copies of their formulas)", LANG_MAX_COPIES);
    node *e = lang_node(c, body->kind, body->pos);
    *e = *body;
    e->args = lang_alloc(c, (size_t)body->nargs * sizeof *e->args);
    for (int i = 0; i < body->nargs; i++)
        e->args[i] = lang_subst(c, body->args[i], args);
    return e;
}

static node *d(lang_ctx *c, node *e, lang_dvar *v);

static node *d_fun(lang_ctx *c, node *e, lang_dvar *v)
{
    /* a network sum depends on the states through its block, not through its argument */
    if (e->op == F_SPECIAL)
        lang_fail(c, e->pos, "network sums ('special') have no analytic derivative here");
    node *a = e->args[0], *b = e->nargs > 1 ? e->args[1] : NULL;
    node *da = d(c, a, v);
    node *db = b ? d(c, b, v) : NULL;
    const int only_a = lang_is_num(da, 0.0);
    if (only_a && (!db || lang_is_num(db, 0.0)))
        return lang_num(c, 0.0);
    switch (e->op) {
    case F_TABLE: { /* piecewise linear: the slope of the segment at a */
        node *slope = mk(c, N_FUN, F_TABLE_SLOPE, 1, a, NULL, NULL);
        slope->index = e->index;
        return mul(c, slope, da);
    }
    case F_TABLE_SLOPE: return lang_num(c, 0.0);
    case F_SIN: return mul(c, fun(c, F_COS, a, NULL), da);
    case F_COS: return neg(c, mul(c, fun(c, F_SIN, a, NULL), da));
    case F_TAN: {
        node *co = fun(c, F_COS, a, NULL);
        return dvd(c, da, mul(c, co, co));
    }
    case F_ASIN: return dvd(c, da, fun(c, F_SQRT, sub(c, lang_num(c, 1.0), mul(c, a, a)), NULL));
    case F_ACOS:
        return neg(c, dvd(c, da, fun(c, F_SQRT, sub(c, lang_num(c, 1.0), mul(c, a, a)), NULL)));
    case F_ATAN: return dvd(c, da, add(c, lang_num(c, 1.0), mul(c, a, a)));
    case F_ATAN2:
        return dvd(c, sub(c, mul(c, b, da), mul(c, a, db)), add(c, mul(c, a, a), mul(c, b, b)));
    case F_SINH: return mul(c, fun(c, F_COSH, a, NULL), da);
    case F_COSH: return mul(c, fun(c, F_SINH, a, NULL), da);
    case F_TANH: {
        node *th = fun(c, F_TANH, a, NULL);
        return mul(c, sub(c, lang_num(c, 1.0), mul(c, th, th)), da);
    }
    case F_EXP: return mul(c, fun(c, F_EXP, a, NULL), da);
    case F_LN: return dvd(c, da, a);
    case F_LOG10: return dvd(c, da, mul(c, a, lang_num(c, 2.30258509299404568402)));
    case F_SQRT: return dvd(c, da, mul(c, lang_num(c, 2.0), fun(c, F_SQRT, a, NULL)));
    case F_ABS: return mul(c, fun(c, F_SIGN, a, NULL), da);
    case F_HEAV:
    case F_SIGN:
    case F_FLR:
    case F_CEIL: return lang_num(c, 0.0);
    case F_MOD:
        if (lang_is_num(db, 0.0))
            return da;
        return add(c, da, mul(c, dvd(c, sub(c, fun(c, F_MOD, a, b), a), b), db));
    case F_MAX: return cond(c, mk(c, N_BIN, OP_GT, 2, a, b, NULL), da, db);
    case F_MIN: return cond(c, mk(c, N_BIN, OP_LT, 2, a, b, NULL), da, db);
    case F_ERF:
    case F_ERFC: {
        node *g = mul(c, lang_num(c, 1.12837916709551257390),
                      fun(c, F_EXP, neg(c, mul(c, a, a)), NULL));
        node *r = mul(c, g, da);
        return e->op == F_ERF ? r : neg(c, r);
    }
    default: return lang_num(c, NAN);
    }
}

static node *d_bin(lang_ctx *c, node *e, lang_dvar *v)
{
    node *a = e->args[0], *b = e->args[1];
    if (e->op >= OP_GT || e->op == OP_AND || e->op == OP_OR)
        return lang_num(c, 0.0);
    node *da = d(c, a, v), *db = d(c, b, v);
    switch (e->op) {
    case OP_ADD: return add(c, da, db);
    case OP_SUB: return sub(c, da, db);
    case OP_MUL: return add(c, mul(c, da, b), mul(c, a, db));
    case OP_DIV: return sub(c, dvd(c, da, b), dvd(c, mul(c, a, db), mul(c, b, b)));
    case OP_POW:
        if (lang_is_num(db, 0.0)) {
            if (lang_is_num(da, 0.0))
                return lang_num(c, 0.0);
            return mul(c, mul(c, b, pw(c, a, sub(c, b, lang_num(c, 1.0)))), da);
        }
        if (lang_is_num(da, 0.0))
            return mul(c, mul(c, e, fun(c, F_LN, a, NULL)), db);
        return mul(c, e, add(c, mul(c, db, fun(c, F_LN, a, NULL)), dvd(c, mul(c, b, da), a)));
    default: return lang_num(c, 0.0);
    }
}

static node *d_ufun(lang_ctx *c, node *e, lang_dvar *v)
{
    const lang_func *f = &LVEC_AT(c->m.funcs, lang_func, e->index);
    if (v->kind == N_STATE && f->uses_state) {
        /* the body reads the states itself: differentiate it inline */
        if (++v->inline_depth > LANG_MAX_INLINE)
            lang_fail(c, e->pos, "calls of '%s' nested too deeply to differentiate", f->name);
        node *r = d(c, lang_subst(c, f->body, e->args), v);
        v->inline_depth--;
        return r;
    }
    node *sum = lang_num(c, 0.0);
    for (int k = 0; k < e->nargs; k++) {
        node *dk = d(c, e->args[k], v);
        if (lang_is_num(dk, 0.0))
            continue;
        node *p = lang_node(c, N_UFUN_D, e->pos);
        p->index = e->index;
        p->op = k;
        p->nargs = e->nargs;
        p->args = e->args;
        if (v->used)
            v->used[e->index * LANG_MAX_ARGS + k] = 1;
        sum = add(c, sum, mul(c, p, dk));
    }
    return sum;
}

static node *d(lang_ctx *c, node *e, lang_dvar *v)
{
    LANG_WORK(c, e->pos);
    if (++c->depth > 8 * LANG_MAX_DEPTH)
        lang_fail(c, e->pos, "expression nested too deeply to differentiate");
    node *r;
    switch (e->kind) {
    case N_STATE:
    case N_ARG:
    case N_ALG: r = lang_num(c, (int)e->kind == v->kind && e->index == v->index ? 1.0 : 0.0); break;
    case N_FIX:
        r = (v->kind == N_STATE || v->kind == N_ALG) && v->fixd && v->fixd[e->index]
                ? v->fixd[e->index]
                : lang_num(c, 0.0);
        break;
    case N_NEG: r = neg(c, d(c, e->args[0], v)); break;
    case N_BIN: r = d_bin(c, e, v); break;
    case N_FUN: r = d_fun(c, e, v); break;
    case N_UFUN: r = d_ufun(c, e, v); break;
    case N_IF: r = cond(c, e->args[0], d(c, e->args[1], v), d(c, e->args[2], v)); break;
    default: r = lang_num(c, 0.0); break; /* numbers, parameters, t, not */
    }
    c->depth--;
    return r;
}

node *lang_deriv(lang_ctx *c, const node *e, const lang_dvar *v)
{
    lang_dvar w = *v;
    return d(c, (node *)e, &w);
}

void lang_func_uses(lang_ctx *c, const node *e, int *state, int *time)
{
    for (int i = 0; i < e->nargs; i++)
        lang_func_uses(c, e->args[i], state, time);
    if (e->kind == N_STATE)
        *state = 1;
    else if (e->kind == N_TIME)
        *time = 1;
    else if (e->kind == N_DELAY)
        *state = *time = 1;
    else if (e->kind == N_UFUN) {
        const lang_func *f = &LVEC_AT(c->m.funcs, lang_func, e->index);
        *state |= f->uses_state;
        *time |= f->uses_time;
    }
}
