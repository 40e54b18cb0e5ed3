/* SPDX-License-Identifier: BSD-3-Clause */
/* The units of a mechanism's formulas (docs/mechanisms.md, "Units"): a small algebra of
 * dimensions over the seven SI base units (BIPM, The International System of Units, 9th
 * ed., 2019: m, kg, s, A, K, mol, cd, with the derived units of its table 4; rad and sr
 * are 1), each declared unit read into exponents, and every formula's unit inferred from
 * those of its parameters, coordinates, speeds and t. A sum, a comparison or the two sides
 * of a constraint whose units differ, a function such as sin or exp of a quantity with a
 * unit, and a formula whose place asks for a unit (a position in m, a mass in kg, a force in
 * N, ...) that it does not have are errors at FILE:LINE:COL naming both units. Lenient where
 * units are not declared: a name without a unit, a user function, a table make the unit
 * unknown and nothing is checked through it; a number takes the unit its sum needs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mbs/mbs_internal.h"

enum { NBASE = 7 };
static const char *const base_names[NBASE] = {"kg", "m", "s", "A", "K", "mol", "cd"};

/* U_NUMBER: a number written in the formula, of the unit its sum needs; U_SCALED: a
 * quantity of unit e times such a number (l/2, -20*t): its unit is not declared, so it
 * takes the unit of what it is added to or compared with (lenient) */
typedef enum { U_UNKNOWN, U_NUMBER, U_SCALED, U_KNOWN } ukind;

typedef struct unit {
    ukind kind;
    double e[NBASE];
} unit;

static const unit unknown = {U_UNKNOWN, {0}};
static const unit number = {U_NUMBER, {0}};

/* ---- reading a declared unit ---- */

typedef struct named_unit {
    const char *sym;
    double e[NBASE]; /* kg m s A K mol cd */
} named_unit;

static const named_unit named[] = {
    {"1", {0}},         {"rad", {0}},        {"sr", {0}},           {"deg", {0}},
    {"kg", {1}},        {"g", {1}},          {"m", {0, 1}},         {"s", {0, 0, 1}},
    {"A", {0, 0, 0, 1}}, {"K", {0, 0, 0, 0, 1}}, {"mol", {0, 0, 0, 0, 0, 1}},
    {"cd", {0, 0, 0, 0, 0, 0, 1}}, {"min", {0, 0, 1}}, {"h", {0, 0, 1}},
    {"Hz", {0, 0, -1}}, {"N", {1, 1, -2}},   {"Pa", {1, -1, -2}},   {"J", {1, 2, -2}},
    {"W", {1, 2, -3}},  {"C", {0, 0, 1, 1}}, {"V", {1, 2, -3, -1}}, {"ohm", {1, 2, -3, -2}},
    {"F", {-1, -2, 4, 2}}, {"T", {1, 0, -2, -1}}, {"Wb", {1, 2, -2, -1}},
    {"H", {1, 2, -2, -2}}, {"rpm", {0, 0, -1}}, {"l", {0, 3}}, {"L", {0, 3}},
};

enum { UNIT_MAX_DEPTH = 200 }; /* parentheses, as expressions' nesting */

typedef struct ureader {
    const char *p, *start;
    int bad, depth;
    const char *why, *at; /* the first error and where it is */
    char near[16];        /* an unknown symbol's nearest known one */
} ureader;

static void fail_at(ureader *r, const char *at, const char *why)
{
    if (!r->bad) {
        r->why = why;
        r->at = at;
    }
    r->bad = 1;
}

static void skip_blanks(ureader *r)
{
    while (*r->p == ' ' || *r->p == '\t')
        r->p++;
}

static unit read_product(ureader *r);

/* the known symbol nearest to the len letters at s (by dyn_lang_nearest), into near */
static void nearest_symbol(ureader *r, const char *s, size_t len)
{
    const char *names[sizeof named / sizeof *named];
    const int n = (int)(sizeof named / sizeof *named);
    for (int i = 0; i < n; i++)
        names[i] = named[i].sym;
    char word[64];
    snprintf(word, sizeof word, "%.*s", (int)(len < 63 ? len : 63), s);
    const char *near = dyn_lang_nearest(word, names, n);
    snprintf(r->near, sizeof r->near, "%s", near ? near : "");
}

static unit read_atom(ureader *r)
{
    unit u = {U_KNOWN, {0}};
    skip_blanks(r);
    if (*r->p == '(') {
        if (++r->depth > UNIT_MAX_DEPTH) {
            fail_at(r, r->p, "parentheses nested deeper than 200 levels");
            return u;
        }
        const char *open = r->p++;
        u = read_product(r);
        r->depth--;
        skip_blanks(r);
        if (*r->p == ')')
            r->p++;
        else
            fail_at(r, r->bad ? r->p : open, "'(' without its ')'");
    } else {
        size_t len = 0;
        while ((r->p[len] >= 'a' && r->p[len] <= 'z') || (r->p[len] >= 'A' && r->p[len] <= 'Z'))
            len++;
        if (len == 0 && r->p[0] == '1')
            len = 1;
        int found = 0;
        for (size_t i = 0; i < sizeof named / sizeof *named && len && !found; i++)
            if (strlen(named[i].sym) == len && strncmp(named[i].sym, r->p, len) == 0) {
                memcpy(u.e, named[i].e, sizeof u.e);
                found = 1;
            }
        if (!len)
            fail_at(r, r->p, "expected a unit's symbol, '1' or '('");
        else if (!found) {
            nearest_symbol(r, r->p, len);
            fail_at(r, r->p, "unknown unit symbol");
        }
        r->p += len;
    }
    skip_blanks(r);
    if (*r->p == '^' && !r->bad) {
        char *end;
        r->p++;
        const double k = strtod(r->p, &end);
        if (end == r->p || !isfinite(k) || fabs(k) > 1e6)
            fail_at(r, r->p, "expected a power after '^' (a number such as 2, -1 or 0.5)");
        r->p = end;
        for (int i = 0; i < NBASE; i++)
            u.e[i] *= k;
    }
    return u;
}

/* factors separated by blanks, '*' or '.', each '/' dividing by the next factor */
static unit read_product(ureader *r)
{
    unit u = read_atom(r);
    for (;;) {
        skip_blanks(r);
        const char c = *r->p;
        if (c == '\0' || c == ')' || r->bad)
            return u;
        int divide = 0;
        if (c == '/' || c == '*' || c == '.') {
            divide = c == '/';
            r->p++;
        }
        const unit v = read_atom(r);
        for (int i = 0; i < NBASE; i++)
            u.e[i] += divide ? -v.e[i] : v.e[i];
    }
}

static unit read_unit(ureader *r)
{
    skip_blanks(r);
    if (!*r->p) {
        fail_at(r, r->p, "an empty unit (write [1] for a number, or leave the brackets out)");
        return unknown;
    }
    unit u = read_product(r);
    if (!r->bad && *r->p)
        fail_at(r, r->p, "')' without its '('");
    return r->bad ? unknown : u;
}

int mbs_unit_error(lang_ctx *c, const char *text, int *offset, const char **why)
{
    ureader r = {text, text, 0, 0, NULL, NULL, ""};
    read_unit(&r);
    if (!r.bad)
        return 0;
    *offset = (int)(r.at - text);
    if (r.near[0])
        *why = lang_printf(c, "%s '%.*s' (did you mean '%s'?)", r.why,
                           (int)strspn(r.at, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"),
                           r.at, r.near);
    else if (strcmp(r.why, "unknown unit symbol") == 0)
        *why = lang_printf(c, "%s '%.*s'", r.why, (int)strspn(r.at, "abcdefghijklmnopqrstuvwxyz"
                                                                   "ABCDEFGHIJKLMNOPQRSTUVWXYZ"),
                           r.at);
    else
        *why = r.why;
    return 1;
}

/* a declared unit's dimensions, or unknown (none declared; a unit that does not read was
 * refused where it was written, mbs_unit_error) */
static unit declared(const char *text)
{
    if (!text)
        return unknown;
    ureader r = {text, text, 0, 0, NULL, NULL, ""};
    return read_unit(&r);
}

/* ---- writing one ---- */

static const char *show(lang_ctx *c, unit u)
{
    if (u.kind == U_NUMBER || u.kind == U_UNKNOWN)
        return "a number";
    static const struct {
        const char *sym;
        double e[NBASE];
    } common[] = {{"N", {1, 1, -2}}, {"N m", {1, 2, -2}}, {"W", {1, 2, -3}}, {"Pa", {1, -1, -2}}};
    for (size_t k = 0; k < sizeof common / sizeof *common; k++)
        if (!memcmp(common[k].e, u.e, sizeof u.e))
            return common[k].sym;
    const char *num = "", *den = "";
    int nden = 0;
    for (int i = 0; i < NBASE; i++) {
        const double x = fabs(u.e[i]);
        if (u.e[i] == 0)
            continue;
        const char *one = x == 1 ? base_names[i] : lang_printf(c, "%s^%g", base_names[i], x);
        if (u.e[i] > 0)
            num = lang_printf(c, "%s%s%s", num, *num ? " " : "", one);
        else {
            den = lang_printf(c, "%s%s%s", den, *den ? " " : "", one);
            nden++;
        }
    }
    if (!*num && !*den)
        return "1";
    if (!*den)
        return num;
    return lang_printf(c, "%s/%s%s%s", *num ? num : "1", nden > 1 ? "(" : "", den,
                       nden > 1 ? ")" : "");
}

/* ---- inference ---- */

typedef struct uctx {
    lang_ctx *c;
    mbs_model *mb;
    unit *fix, *par;            /* memo of the fixed quantities and derived parameters */
    unsigned char *fix_state, *par_state; /* 0 not seen, 1 in progress, 2 done */
    const unit *arg;            /* the units of a function's arguments (N_ARG), or NULL */
    int nargs;
} uctx;

static int same(unit a, unit b) { return !memcmp(a.e, b.e, sizeof a.e); }
static int dimensionless(unit u) { return u.kind != U_KNOWN || same(u, number); }

static unit infer(uctx *x, const node *e);

/* the unit of a sum (or comparison, or the two sides of a constraint) of a and b at pos */
static unit agree(uctx *x, unit a, unit b, lpos pos, const char *what)
{
    if (a.kind == U_UNKNOWN || b.kind == U_UNKNOWN)
        return unknown;
    if (a.kind == U_NUMBER || (a.kind == U_SCALED && b.kind == U_KNOWN))
        return b;
    if (b.kind == U_NUMBER || (b.kind == U_SCALED && a.kind == U_KNOWN))
        return a;
    if (a.kind == U_SCALED) /* both: the unit of neither is declared */
        return same(a, b) ? a : unknown;
    if (!same(a, b))
        lang_fail(x->c, pos, "the units do not add up: %s in %s and in %s", what,
                  show(x->c, a), show(x->c, b));
    return a;
}

static unit scaled(unit u, double k)
{
    for (int i = 0; i < NBASE && (u.kind == U_KNOWN || u.kind == U_SCALED); i++)
        u.e[i] *= k;
    return u;
}

static int constant(const node *e, double *v)
{
    if (e->kind == N_NUM) {
        *v = e->num;
        return 1;
    }
    if (e->kind == N_NEG && constant(e->args[0], v)) {
        *v = -*v;
        return 1;
    }
    return 0;
}

static unit function(uctx *x, const node *e)
{
    unit a = e->nargs > 0 ? infer(x, e->args[0]) : number;
    unit b = e->nargs > 1 ? infer(x, e->args[1]) : number;
    switch ((fun_id)e->op) {
    case F_SIN: case F_COS: case F_TAN: case F_ASIN: case F_ACOS: case F_ATAN: case F_SINH:
    case F_COSH: case F_TANH: case F_EXP: case F_LN: case F_LOG10: case F_ERF: case F_ERFC:
        if (!dimensionless(a))
            lang_fail(x->c, e->args[0]->pos, "the units do not add up: %s of a quantity in %s "
                      "(its argument must be a number: 1 or rad)", e->name ? e->name : "a "
                      "function", show(x->c, a));
        return a.kind == U_UNKNOWN ? unknown : number;
    case F_ATAN2:
        agree(x, a, b, e->pos, "atan2's arguments are");
        return a.kind == U_UNKNOWN || b.kind == U_UNKNOWN ? unknown : number;
    case F_SQRT:
        return scaled(a, 0.5);
    case F_ABS: case F_FLR: case F_CEIL:
        return a;
    case F_MAX: case F_MIN: case F_MOD:
        return agree(x, a, b, e->pos, "the arguments are");
    case F_SIGN: case F_HEAV:
        return a.kind == U_UNKNOWN ? unknown : number;
    default:
        return unknown;
    }
}

static unit binary(uctx *x, const node *e)
{
    const unit a = infer(x, e->args[0]), b = infer(x, e->args[1]);
    switch ((bin_op)e->op) {
    case OP_ADD:
    case OP_SUB:
        return agree(x, a, b, e->pos, "the terms are");
    case OP_GT: case OP_LT: case OP_GE: case OP_LE: case OP_EQ: case OP_NE:
        return agree(x, a, b, e->pos, "the sides of the comparison are").kind == U_UNKNOWN
                   ? unknown : number;
    case OP_MUL:
    case OP_DIV: {
        if (a.kind == U_UNKNOWN || b.kind == U_UNKNOWN)
            return unknown;
        if (a.kind == U_NUMBER && b.kind == U_NUMBER)
            return number;
        unit u = {a.kind == U_KNOWN && b.kind == U_KNOWN ? U_KNOWN : U_SCALED, {0}};
        for (int i = 0; i < NBASE; i++)
            u.e[i] = a.e[i] + (e->op == OP_DIV ? -b.e[i] : b.e[i]);
        return u;
    }
    case OP_POW: {
        double k;
        if (a.kind == U_UNKNOWN || a.kind == U_NUMBER)
            return a;
        if (same(a, number))
            return a.kind == U_KNOWN ? (unit){U_KNOWN, {0}} : a;
        return constant(e->args[1], &k) ? scaled(a, k) : unknown;
    }
    default:
        return a.kind == U_UNKNOWN || b.kind == U_UNKNOWN ? unknown : number;
    }
}

static unit memo(uctx *x, unit *at, unsigned char *state, const node *e)
{
    if (*state == 2)
        return *at;
    if (*state == 1)
        return unknown; /* a cycle: lang_check reports it */
    *state = 1;
    *at = e ? infer(x, e) : unknown;
    *state = 2;
    return *at;
}

static unit infer_node(uctx *x, const node *e);

/* as deep as the derivatives may go (a chain of fixed quantities included) */
static unit infer(uctx *x, const node *e)
{
    if (++x->c->depth > 8 * LANG_MAX_DEPTH)
        lang_fail(x->c, e->pos, "formula nested too deeply through the quantities it reads "
                  "(more than %d levels)", 8 * LANG_MAX_DEPTH);
    const unit u = infer_node(x, e);
    x->c->depth--;
    return u;
}

static unit infer_node(uctx *x, const node *e)
{
    lang_model *m = &x->c->m;
    switch (e->kind) {
    case N_NUM:
        return number;
    case N_TIME:
        return (unit){U_KNOWN, {0, 0, 1}};
    case N_STATE:
        return declared(LVEC_AT(m->states, lang_state, e->index).doc.unit);
    case N_PARAM:
        if (e->index < m->params.n)
            return declared(LVEC_AT(m->params, lang_param, e->index).doc.unit);
        if (e->index - m->params.n < m->derived.n) {
            const int k = e->index - m->params.n;
            const lang_formula *f = &LVEC_AT(m->derived, lang_formula, k);
            if (f->doc.unit)
                return declared(f->doc.unit);
            return memo(x, &x->par[k], &x->par_state[k], f->expr);
        }
        return unknown;
    case N_FIX: {
        const lang_formula *f = &LVEC_AT(m->fixes, lang_formula, e->index);
        if (f->doc.unit)
            return declared(f->doc.unit);
        return memo(x, &x->fix[e->index], &x->fix_state[e->index], f->expr);
    }
    case N_ARG:
        return x->arg && e->index < x->nargs ? x->arg[e->index] : unknown;
    case N_NEG:
        return infer(x, e->args[0]);
    case N_BIN:
        return binary(x, e);
    case N_FUN:
        return function(x, e);
    case N_IF:
        infer(x, e->args[0]);
        return agree(x, infer(x, e->args[1]), infer(x, e->args[2]), e->pos,
                     "the branches are");
    default:
        return unknown;
    }
}

/* ---- the places that ask for a unit ---- */

/* where a formula begins (the position of a binary operation is its operator's) */
static lpos start_of(const node *e)
{
    while ((e->kind == N_BIN || e->kind == N_IF) && e->nargs > 0)
        e = e->args[0];
    return e->pos;
}

static unit of_input(uctx *x, int k)
{
    if (k < 0)
        return unknown;
    return memo(x, &x->fix[k], &x->fix_state[k], LVEC_AT(x->c->m.fixes, lang_formula, k).expr);
}

static void expect(uctx *x, int k, const char *want, const char *what)
{
    if (k < 0)
        return;
    const unit u = of_input(x, k), w = declared(want);
    /* a formula in 1 or rad (unitless coordinates of a sketch) is taken anywhere; one that
     * scales a quantity (l/2) has that quantity's unit */
    if ((u.kind == U_KNOWN || u.kind == U_SCALED) && w.kind == U_KNOWN && !same(u, w) &&
        !same(u, number))
        lang_fail(x->c, start_of(LVEC_AT(x->c->m.fixes, lang_formula, k).expr),
                  "the units do not add up: %s is in %s, not in %s", what, show(x->c, u),
                  show(x->c, w));
}

/* whether e reads a parameter, coordinate, speed, derived parameter or fixed quantity
 * whose unit is known (all of them are inferred by then) */
static int reads_a_unit(uctx *x, const node *e)
{
    const lang_model *m = &x->c->m;
    unit u = unknown;
    if (e->kind == N_STATE)
        u = declared(LVEC_AT(m->states, lang_state, e->index).doc.unit);
    else if (e->kind == N_PARAM || e->kind == N_FIX)
        u = infer(x, e);
    if (u.kind == U_KNOWN)
        return 1;
    for (int i = 0; i < e->nargs; i++)
        if (e->args[i] && reads_a_unit(x, e->args[i]))
            return 1;
    return 0;
}

/* a spring's law F(x, v) in N or its energy G(x) in J, with x in m and v in m/s: the
 * function's formula, at its start, when it reads a name with a unit (a law of x, v and
 * numbers alone, in a file without units, is not checked) */
static void expect_law(uctx *x, int fi, const char *want, const char *what)
{
    if (fi < 0)
        return;
    const lang_func *fn = &LVEC_AT(x->c->m.funcs, lang_func, fi);
    if (!fn->body || !reads_a_unit(x, fn->body))
        return;
    static const unit args[2] = {{U_KNOWN, {0, 1}}, {U_KNOWN, {0, 1, -1}}};
    x->arg = args;
    x->nargs = fn->nargs < 2 ? fn->nargs : 2;
    const unit u = infer(x, fn->body), w = declared(want);
    x->arg = NULL;
    x->nargs = 0;
    if (u.kind == U_KNOWN && !same(u, w) && !same(u, number))
        lang_fail(x->c, start_of(fn->body), "the units do not add up: %s is in %s, not in %s "
                  "(x in m, v in m/s)", what, show(x->c, u), want);
}

/* a vector (a position, a force, ...): each component in the unit, and none in 1 (a
 * formula that reads a name with a unit) beside one in the unit */
static void expect3(uctx *x, const int k[3], const char *want, const char *what)
{
    for (int i = 0; i < 3; i++)
        expect(x, k[i], want, what);
    const unit w = declared(want);
    int in_unit = 0;
    for (int i = 0; i < 3; i++) {
        const unit u = of_input(x, k[i]);
        in_unit |= (u.kind == U_KNOWN || u.kind == U_SCALED) && same(u, w) && !same(w, number);
    }
    for (int i = 0; i < 3 && in_unit; i++) {
        if (k[i] < 0)
            continue;
        const unit u = of_input(x, k[i]);
        const node *e = LVEC_AT(x->c->m.fixes, lang_formula, k[i]).expr;
        if (u.kind != U_UNKNOWN && same(u, number) && reads_a_unit(x, e))
            lang_fail(x->c, start_of(e), "the units do not add up: component %c of %s is in 1, "
                      "beside components in %s: each component of it is in %s", "xyz"[i],
                      what, show(x->c, w), show(x->c, w));
    }
}

void mbs_check_units(lang_ctx *c, mbs_model *mb)
{
    lang_model *m = &c->m;
    uctx x = {c, mb, NULL, NULL, NULL, NULL, NULL, 0};
    const size_t nf = (size_t)m->fixes.n + 1, nd = (size_t)m->derived.n + 1;
    x.fix = lang_alloc(c, nf * sizeof *x.fix);
    x.par = lang_alloc(c, nd * sizeof *x.par);
    x.fix_state = lang_alloc(c, nf);
    x.par_state = lang_alloc(c, nd);
    memset(x.fix_state, 0, nf);
    memset(x.par_state, 0, nd);
    /* every declared unit reads (those of doc lines #: NAME [UNIT] too; the others were
     * refused where they were written) */
    for (int i = 0; i < m->docs.n; i++) {
        const lang_docline *d = &LVEC_AT(m->docs, lang_docline, i);
        int off;
        const char *why;
        if (d->doc.unit && mbs_unit_error(c, d->doc.unit, &off, &why))
            lang_fail(c, d->pos, "%s in the unit of '%s': %s", why, d->name, MBS_UNIT_SYMBOLS);
    }
    /* the two sides of each constraint first: named so */
    for (int i = 0; i < mb->cons.n; i++) {
        const mbs_constraint *k = &LVEC_AT(mb->cons, mbs_constraint, i);
        const node *e = k->expr >= 0 && !k->sym ? LVEC_AT(m->fixes, lang_formula, k->expr).expr
                                                : NULL;
        if (e && e->kind == N_BIN && e->op == OP_SUB)
            agree(&x, infer(&x, e->args[0]), infer(&x, e->args[1]), start_of(e->args[1]),
                  lang_printf(c, "the sides of %s '%s' are", k->prescribed >= 0 ? "prescribe" :
                              "constraint", k->name));
    }
    /* every formula on its own: its sums and functions */
    for (int k = 0; k < m->derived.n; k++)
        memo(&x, &x.par[k], &x.par_state[k], LVEC_AT(m->derived, lang_formula, k).expr);
    for (int k = 0; k < m->fixes.n; k++)
        of_input(&x, k);
    for (int k = 0; k < m->auxs.n; k++)
        if (LVEC_AT(m->auxs, lang_formula, k).expr)
            infer(&x, LVEC_AT(m->auxs, lang_formula, k).expr);
    /* the places that ask for a unit */
    expect3(&x, mb->gravity, "m/s^2", "gravity");
    for (int i = 0; i < mb->bodies.n; i++) {
        const mbs_body *b = &LVEC_AT(mb->bodies, mbs_body, i);
        expect(&x, b->mass, "kg", lang_printf(c, "the mass of '%s'", b->name));
        for (int j = 0; j < 6 && !b->point; j++)
            expect(&x, b->inertia[j], "kg m^2", lang_printf(c, "the inertia of '%s'", b->name));
        if (!b->point && b->about[0] >= 0)
            expect3(&x, b->about, "m", lang_printf(c, "the point the inertia of '%s' is about",
                                                   b->name));
        if (b->joint == MBS_NO_JOINT)
            expect3(&x, b->at, "m", lang_printf(c, "the position of '%s'", b->name));
        for (int j = 0; j < b->nrot; j++)
            expect(&x, b->angle[j], "rad", lang_printf(c, "a rotation angle of '%s'", b->name));
    }
    for (int i = 0; i < mb->springs.n; i++) {
        const mbs_spring *s = &LVEC_AT(mb->springs, mbs_spring, i);
        const char *of = lang_printf(c, "of spring '%s'", s->name);
        expect(&x, s->k, "N/m", lang_printf(c, "the stiffness k %s", of));
        expect(&x, s->l0, "m", lang_printf(c, "the rest length l0 %s", of));
        expect(&x, s->c, "N s/m", lang_printf(c, "the damping c %s", of));
        expect3(&x, s->a.p, "m", lang_printf(c, "an end %s", of));
        expect3(&x, s->b.p, "m", lang_printf(c, "an end %s", of));
        expect_law(&x, s->law, "N", lang_printf(c, "the law %s(x, v) %s", s->law_name, of));
        expect_law(&x, s->energy, "J", lang_printf(c, "the energy %s(x) %s", s->energy_name,
                                                   of));
    }
    for (int i = 0; i < mb->loads.n; i++) {
        const mbs_load *l = &LVEC_AT(mb->loads, mbs_load, i);
        expect3(&x, l->f, l->torque ? "N m" : "N",
                lang_printf(c, "%s '%s'", l->torque ? "torque" : "force", l->name));
        if (!l->torque)
            expect3(&x, l->at, "m", lang_printf(c, "the point of force '%s'", l->name));
    }
    for (int i = 0; i < mb->cons.n; i++) {
        mbs_constraint *k = &LVEC_AT(mb->cons, mbs_constraint, i);
        if (k->expr < 0 || k->sym)
            continue; /* a wheel's, derived */
        if (!k->unit && k->prescribed < 0) {
            /* no declared unit: the one its formula has, when that is known (a loop in m
             * gives its multiplier in N), also through numbers without a unit (r*sin(th));
             * an angle or a number keeps the rule of the first coordinate (mbs_derive.c,
             * force_unit) */
            const unit u = infer(&x, LVEC_AT(m->fixes, lang_formula, k->expr).expr);
            if ((u.kind == U_KNOWN || u.kind == U_SCALED) && !same(u, number))
                k->unit = show(c, u);
            continue;
        }
        if (k->prescribed >= 0)
            expect(&x, k->expr,
                   LVEC_AT(mb->coords, mbs_coord, k->prescribed).unit,
                   lang_printf(c, "the motion prescribed to '%s'",
                               LVEC_AT(mb->coords, mbs_coord, k->prescribed).name));
        else if (k->unit && declared(k->unit).kind == U_KNOWN)
            expect(&x, k->expr, k->unit, lang_printf(c, "constraint '%s'", k->name));
    }
}
