/* SPDX-License-Identifier: BSD-3-Clause */
/* The C text of an .ode model: a translation unit that defines
 * `const dyn_model *dynkit_model(void)` (dynkit/model.h), compiled by the jit layer.
 *
 * A model file is data. Nothing from outside (the path, names, numbers as written, `#:`
 * text, units, descriptions, table contents, options) is written here except through
 * lang_c_str (emit_out.c), as an escaped string literal: code comes only from string
 * literals of this file (LANG_C_CODE), numbers this translator formats (LANG_C_CODEF,
 * lang_c_num), and identifiers made of a prefix and numbers, never from a name of the
 * file; no comment holds anything from outside. emit_out.c is the only writer of the text
 * (docs/model-files.md, "What the generated C contains").
 *
 * Conventions (docs/model-files.md): states are y[i] in the order of their equations;
 * the parameter struct is an array of doubles p[], the parameters in the order of the file
 * then the derived parameters (computed by prepare); fixed temporaries are const locals
 * v_K (K: the quantity's number) computed in dependency order where needed; user functions
 * are static functions u_F(a_0..., t, y, p) (F: the function's number), their partial
 * derivatives udK_F; XPPAUT's functions are static inline helpers dk_*. A
 * `#line N "file"` precedes the code of each source line, so a compiler's message points
 * at the model's own line. Nothing mutable at file scope: the model is re-entrant.
 */
#include <limits.h>
#include <setjmp.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lang/lang_internal.h"

/* #line N "PATH" before the code of a source line: the path only as an escaped string */
static void line_dir(lang_ctx *c, lpos p)
{
    if (p.line <= 0)
        return;
    LANG_C_CODEF(c, "#line %d ", p.line);
    lang_c_str(c, c->path);
    LANG_C_CODE(c, "\n");
}

static int noise_offset(const lang_model *m);
static int volt_offset(const lang_model *m);
static int seed_offset(const lang_model *m);

/* The literal ident when cond holds, else NULL */
#define CODE_OR_NULL(c, cond, ident) \
    ((cond) ? LANG_C_CODE((c), ident) : LANG_C_CODE((c), "NULL"))

/* ---- expressions ---- */

typedef struct ectx {
    const lang_func *func; /* the function whose body this is, or NULL */
    int has_state;         /* y and t are in scope */
} ectx;

/* The C function of a built-in function (all of XPPAUT's names are C's or a dk_ helper's) */
static void c_fun(lang_ctx *c, int f)
{
    switch (f) {
    case F_SIN: LANG_C_CODE(c, "sin"); break;
    case F_COS: LANG_C_CODE(c, "cos"); break;
    case F_TAN: LANG_C_CODE(c, "tan"); break;
    case F_ASIN: LANG_C_CODE(c, "asin"); break;
    case F_ACOS: LANG_C_CODE(c, "acos"); break;
    case F_ATAN: LANG_C_CODE(c, "atan"); break;
    case F_ATAN2: LANG_C_CODE(c, "atan2"); break;
    case F_SINH: LANG_C_CODE(c, "sinh"); break;
    case F_COSH: LANG_C_CODE(c, "cosh"); break;
    case F_TANH: LANG_C_CODE(c, "tanh"); break;
    case F_EXP: LANG_C_CODE(c, "exp"); break;
    case F_LN: LANG_C_CODE(c, "log"); break;
    case F_LOG10: LANG_C_CODE(c, "log10"); break;
    case F_SQRT: LANG_C_CODE(c, "sqrt"); break;
    case F_ABS: LANG_C_CODE(c, "fabs"); break;
    case F_HEAV: LANG_C_CODE(c, "dk_heav"); break;
    case F_SIGN: LANG_C_CODE(c, "dk_sign"); break;
    case F_MOD: LANG_C_CODE(c, "dk_mod"); break;
    case F_FLR: LANG_C_CODE(c, "floor"); break;
    case F_CEIL: LANG_C_CODE(c, "ceil"); break;
    case F_MAX: LANG_C_CODE(c, "dk_max"); break;
    case F_MIN: LANG_C_CODE(c, "dk_min"); break;
    case F_ERF: LANG_C_CODE(c, "erf"); break;
    case F_ERFC: LANG_C_CODE(c, "erfc"); break;
    default: lang_fail(c, (lpos){0, 0}, "internal error: no C function for %d", f);
    }
}

/* A comparison's C operator */
static void c_cmp(lang_ctx *c, int op)
{
    switch (op) {
    case OP_GT: LANG_C_CODE(c, ") > ("); break;
    case OP_LT: LANG_C_CODE(c, ") < ("); break;
    case OP_GE: LANG_C_CODE(c, ") >= ("); break;
    case OP_LE: LANG_C_CODE(c, ") <= ("); break;
    case OP_EQ: LANG_C_CODE(c, ") == ("); break;
    default: LANG_C_CODE(c, ") != ("); break;
    }
}

enum {
    H_HEAV = 1, H_SIGN = 2, H_MOD = 4, H_MAX = 8, H_MIN = 16, H_NOT = 32, H_SQ = 64, H_POW = 128,
    H_TABLE = 256, H_CONV = 512
};

/* fused: per function, slot 0 the function, slot 1 + k its partial derivative in k */
static void mark_func(lang_ctx *c, int f, int slot)
{
    c->fused[(size_t)f * (LANG_MAX_ARGS + 1) + (size_t)slot] = 1;
}

static int func_marked(const lang_ctx *c, int f, int slot)
{
    return c->fused[(size_t)f * (LANG_MAX_ARGS + 1) + (size_t)slot];
}

static void expr(lang_ctx *c, const node *e, const ectx *x);

/* The spacing of a table's abscissas (1 for a table of one point, never used then). */
static double table_dx(const lang_table *tb)
{
    return tb->npts > 1 ? (tb->hi - tb->lo) / (double)(tb->npts - 1) : 1.0;
}

static void call_args(lang_ctx *c, const node *e, const ectx *x)
{
    for (int i = 0; i < e->nargs; i++) {
        expr(c, e->args[i], x);
        LANG_C_CODE(c, ", ");
    }
    if (x->has_state)
        LANG_C_CODE(c, "t, y, p)");
    else
        LANG_C_CODE(c, "0.0, (const double *)0, p)");
}

static void expr(lang_ctx *c, const node *e, const ectx *x)
{
    LANG_WORK(c, e->pos);
    if (++c->depth > 16 * LANG_MAX_DEPTH)
        lang_fail(c, e->pos, "expression too deep to write as C");
    lang_model *m = &c->m;
    switch (e->kind) {
    case N_NUM: lang_c_num(c, e->num); break;
    case N_TIME: LANG_C_CODE(c, "t"); break;
    case N_STATE: LANG_C_CODEF(c, "y[%d]", e->index); break;
    case N_PARAM:
        if (m->param_input && e->index < m->params.n && m->param_input[e->index] >= 0 &&
            (x->has_state || x->func))
            LANG_C_CODEF(c, "dk_input(p, t, %d, %d)", m->param_input[e->index], e->index);
        else
            LANG_C_CODEF(c, "p[%d]", e->index);
        break;
    case N_FIX: LANG_C_CODEF(c, "v_%d", e->index); break;
    case N_ALG: LANG_C_CODEF(c, "w[%d]", e->index); break;
    case N_NOISE:
        if (e->index < 0) /* a table's random number, at its point k (emit_table_values) */
            LANG_C_CODEF(c, "dyn_table_random((uint64_t)p[%d] | (uint64_t)p[%d] << 32, %d, k, %d)",
                         seed_offset(m), seed_offset(m) + 1, -1 - e->index, e->op);
        else
            LANG_C_CODEF(c, "p[%d]", noise_offset(m) + e->index);
        break;
    case N_VOLT: /* index -1: the time of the integral, in the slot after the integrals */
        LANG_C_CODEF(c, "p[%d]", volt_offset(m) + (e->index < 0 ? m->volts.n : e->index));
        break;
    case N_DFIX:
        LANG_C_CODEF(c, "dv%d_%d", e->op, e->index);
        break;
    case N_ARG: LANG_C_CODEF(c, "a_%d", e->index); break;
    case N_NEG:
        LANG_C_CODE(c, "(-");
        expr(c, e->args[0], x);
        LANG_C_CODE(c, ")");
        break;
    case N_NOT:
        c->helpers |= H_NOT;
        LANG_C_CODE(c, "dk_not(");
        expr(c, e->args[0], x);
        LANG_C_CODE(c, ")");
        break;
    case N_IF:
        LANG_C_CODE(c, "((");
        expr(c, e->args[0], x);
        LANG_C_CODE(c, ") != 0.0 ? (");
        expr(c, e->args[1], x);
        LANG_C_CODE(c, ") : (");
        expr(c, e->args[2], x);
        LANG_C_CODE(c, "))");
        break;
    case N_BIN: {
        const node *a = e->args[0], *b = e->args[1];
        switch (e->op) {
        case OP_ADD:
        case OP_SUB:
        case OP_MUL:
        case OP_DIV:
            LANG_C_CODE(c, "(");
            expr(c, a, x);
            if (e->op == OP_ADD)
                LANG_C_CODE(c, " + ");
            else if (e->op == OP_SUB)
                LANG_C_CODE(c, " - ");
            else if (e->op == OP_MUL)
                LANG_C_CODE(c, " * ");
            else
                LANG_C_CODE(c, " / ");
            expr(c, b, x);
            LANG_C_CODE(c, ")");
            break;
        case OP_POW:
            if (b->kind == N_NUM && b->num == 2.0) {
                c->helpers |= H_SQ;
                LANG_C_CODE(c, "dk_sq(");
                expr(c, a, x);
                LANG_C_CODE(c, ")");
            } else {
                c->helpers |= H_POW;
                LANG_C_CODE(c, "dk_pow(");
                expr(c, a, x);
                LANG_C_CODE(c, ", ");
                expr(c, b, x);
                LANG_C_CODE(c, ")");
            }
            break;
        case OP_AND:
        case OP_OR:
            LANG_C_CODE(c, "((");
            expr(c, a, x);
            if (e->op == OP_AND)
                LANG_C_CODE(c, ") != 0.0 && (");
            else
                LANG_C_CODE(c, ") != 0.0 || (");
            expr(c, b, x);
            LANG_C_CODE(c, ") != 0.0 ? 1.0 : 0.0)");
            break;
        default:
            LANG_C_CODE(c, "((");
            expr(c, a, x);
            c_cmp(c, e->op);
            expr(c, b, x);
            LANG_C_CODE(c, ") ? 1.0 : 0.0)");
            break;
        }
        break;
    }
    case N_FUN:
        if (e->op == F_SPECIAL) { /* computed before the statements (emit_fixes) */
            LANG_C_CODEF(c, "sp_%d[%d]", e->index, (int)e->args[0]->num);
            break;
        }
        if (e->op == F_TABLE || e->op == F_TABLE_SLOPE) {
            const lang_table *tb = &LVEC_AT(m->tables, lang_table, e->index);
            c->helpers |= H_TABLE;
            if (e->op == F_TABLE)
                LANG_C_CODE(c, "dk_table");
            else
                LANG_C_CODE(c, "dk_table_slope");
            LANG_C_CODEF(c, "(p + %d, %ld, ", tb->offset, tb->npts);
            lang_c_num(c, tb->lo);
            LANG_C_CODE(c, ", ");
            lang_c_num(c, table_dx(tb));
            LANG_C_CODE(c, ", ");
            expr(c, e->args[0], x);
            LANG_C_CODE(c, ")");
            break;
        }
        c->helpers |= e->op == F_HEAV  ? H_HEAV
                      : e->op == F_SIGN ? H_SIGN
                      : e->op == F_MOD  ? H_MOD
                      : e->op == F_MAX  ? H_MAX
                      : e->op == F_MIN  ? H_MIN
                                        : 0;
        c_fun(c, e->op);
        LANG_C_CODE(c, "(");
        for (int i = 0; i < e->nargs; i++) {
            if (i)
                LANG_C_CODE(c, ", ");
            expr(c, e->args[i], x);
        }
        LANG_C_CODE(c, ")");
        break;
    case N_DELAY:
        LANG_C_CODEF(c, "dk_delay(p, %d, t, ", e->index);
        expr(c, e->args[0], x);
        LANG_C_CODE(c, ")");
        break;
    case N_UFUN:
        mark_func(c, e->index, 0);
        LANG_C_CODEF(c, "u_%d(", e->index);
        call_args(c, e, x);
        break;
    case N_UFUN_D:
        mark_func(c, e->index, 1 + e->op);
        LANG_C_CODEF(c, "ud%d_%d(", e->op, e->index);
        call_args(c, e, x);
        break;
    default: LANG_C_CODE(c, "NAN"); break;
    }
    c->depth--;
}

/* ---- fixed temporaries (and network sums) needed by a set of expressions ---- */

/* needed: one flag per fixed quantity, then one per network sum */
static void need(lang_ctx *c, const node *e, unsigned char *needed)
{
    LANG_WORK(c, e->pos);
    for (int i = 0; i < e->nargs; i++)
        need(c, e->args[i], needed);
    if (e->kind == N_FIX && !needed[e->index]) {
        needed[e->index] = 1;
        need(c, LVEC_AT(c->m.fixes, lang_formula, e->index).expr, needed);
    }
    if (e->kind == N_FUN && e->op == F_SPECIAL && !needed[c->m.fixes.n + e->index]) {
        const lang_special *sp = &LVEC_AT(c->m.specials, lang_special, e->index);
        needed[c->m.fixes.n + e->index] = 1;
        for (int b = 0; b < 2; b++) { /* the blocks of u and (fconv) v */
            const int kind = b ? sp->vroot_kind : sp->root_kind, first = b ? sp->vroot : sp->root;
            const int len = b ? (sp->kind == LANG_SUM_FCONV ? sp->n : 0) : sp->ulen;
            for (int k = 0; kind == N_FIX && k < len; k++)
                if (!needed[first + k]) {
                    needed[first + k] = 1;
                    need(c, LVEC_AT(c->m.fixes, lang_formula, first + k).expr, needed);
                }
        }
    }
}

/* The block of len elements of network sum i (v: fconv's second block), states from first
 * on (y + first) or fixed quantities, then a local array spu_I (spv_I) of their values
 * written here. */
static void block_decl(lang_ctx *c, int i, int v, int kind, int first, int len)
{
    if (kind == N_STATE)
        return;
    if (v)
        LANG_C_CODEF(c, "    const double spv_%d[%d] = {", i, len);
    else
        LANG_C_CODEF(c, "    const double spu_%d[%d] = {", i, len);
    for (int k = 0; k < len; k++)
        LANG_C_CODEF(c, k ? ", v_%d" : "v_%d", first + k);
    LANG_C_CODE(c, "};\n");
}

/* The block as a C array expression (y + first, or the local of block_decl) */
static void block_ref(lang_ctx *c, int i, int v, int kind, int first)
{
    if (kind == N_STATE)
        LANG_C_CODEF(c, "(y + %d)", first);
    else if (v)
        LANG_C_CODEF(c, "spv_%d", i);
    else
        LANG_C_CODEF(c, "spu_%d", i);
}

/* The network sums flagged in needed, after the fixed quantities: sp_I[j] for each j. */
static void emit_specials(lang_ctx *c, const unsigned char *needed)
{
    const lang_model *m = &c->m;
    for (int i = 0; i < m->specials.n; i++) {
        if (!needed[m->fixes.n + i])
            continue;
        const lang_special *sp = &LVEC_AT(m->specials, lang_special, i);
        line_dir(c, sp->pos);
        block_decl(c, i, 0, sp->root_kind, sp->root, sp->ulen);
        if (sp->kind == LANG_SUM_GILL) {
            lang_emit_gill(c, i, sp, noise_offset(m));
            continue;
        }
        const lang_table *tb = &LVEC_AT(m->tables, lang_table, sp->table);
        if (sp->kind == LANG_SUM_CONV || sp->kind == LANG_SUM_FCONV)
            c->helpers |= H_CONV;
        LANG_C_CODEF(c, "    double sp_%d[%d];\n", i, sp->n);
        if (sp->kind == LANG_SUM_CONV) {
            LANG_C_CODEF(c, "    dk_conv(sp_%d, %d, %d, %d, p + %d, ", i, sp->n, sp->m, sp->type,
                         tb->offset);
            block_ref(c, i, 0, sp->root_kind, sp->root);
            LANG_C_CODE(c, ");\n");
            continue;
        }
        if (sp->kind == LANG_SUM_MMULT || sp->kind == LANG_SUM_SPARSE) {
            /* mmult: w[i + m j] u(i); sparse: w[j m + i] u(l[j m + i]) (indices checked by
             * prepare) */
            const int sparse = sp->kind == LANG_SUM_SPARSE;
            LANG_C_CODEF(c, "    for (int j = 0; j < %d; j++) {\n        double s = 0.0;\n"
                            "        for (int i = 0; i < %d; i++)\n",
                         sp->n, sp->m);
            if (sparse)
                LANG_C_CODEF(c, "            s += (p + %d)[j * %d + i] * ", tb->offset, sp->m);
            else
                LANG_C_CODEF(c, "            s += (p + %d)[i + %d * j] * ", tb->offset, sp->m);
            block_ref(c, i, 0, sp->root_kind, sp->root);
            if (sparse)
                LANG_C_CODEF(c, "[(long)(p + %d)[j * %d + i]];\n",
                             LVEC_AT(m->tables, lang_table, sp->index_table).offset, sp->m);
            else
                LANG_C_CODE(c, "[i];\n");
            LANG_C_CODEF(c, "        sp_%d[j] = s;\n    }\n", i);
            continue;
        }
        /* fconv: f(u(j+i), v(j)) in place of u(j+i) */
        block_decl(c, i, 1, sp->vroot_kind, sp->vroot, sp->n);
        mark_func(c, sp->func, 0);
        LANG_C_CODEF(c, "    for (int j = 0; j < %d; j++) {\n        double s = 0.0;\n"
                        "        for (int i = -%d; i <= %d; i++)\n"
                        "            s += (p + %d)[%d + i] * u_%d(dk_conv_at(",
                     sp->n, sp->m, sp->m, tb->offset, sp->m, sp->func);
        block_ref(c, i, 0, sp->root_kind, sp->root);
        LANG_C_CODEF(c, ", %d, j + i, %d), ", sp->n, sp->type);
        block_ref(c, i, 1, sp->vroot_kind, sp->vroot);
        LANG_C_CODEF(c, "[j], t, y, p);\n        sp_%d[j] = s;\n    }\n", i);
    }
}

static void emit_fixes(lang_ctx *c, const unsigned char *needed)
{
    const ectx x = {NULL, 1};
    for (int i = 0; i < c->m.fixes.n; i++) {
        const int k = c->m.fix_order[i];
        if (!needed[k])
            continue;
        const lang_formula *f = &LVEC_AT(c->m.fixes, lang_formula, k);
        line_dir(c, f->pos);
        LANG_C_CODEF(c, "    const double v_%d = ", k);
        expr(c, f->expr, &x);
        LANG_C_CODE(c, ";\n");
    }
    emit_specials(c, needed);
}

static unsigned char *needed_by(lang_ctx *c, node *const *roots, int n)
{
    unsigned char *needed = lang_alloc(c, (size_t)c->m.fixes.n + (size_t)c->m.specials.n + 1);
    for (int i = 0; i < n; i++)
        if (roots[i])
            need(c, roots[i], needed);
    return needed;
}

/* ---- differential-algebraic systems ----
 * The algebraic variables w solve the 0= equations r(t, y, w) = 0 (XPPAUT's solv and 0=)
 * at every evaluation of the right-hand side (so that the branch followed is tracked along
 * the run) and wherever else they are read, by the solver of alg_solver.c. Their slots in
 * p, after the tables: the last solution, the initial guesses, each variable's scale (the
 * largest magnitude so far), the earliest time solved, the time and the state of the last
 * solution. An evaluation at or before that earliest time (the start of every run, also a
 * second run from the same parameters) starts from the guesses. */

/* Index in p of the first slot of the algebraic variables. */
static int alg_offset(const lang_model *m)
{
    int k = m->params.n + m->derived.n;
    for (int i = 0; i < m->tables.n; i++)
        k += (int)LVEC_AT(m->tables, lang_table, i).npts;
    return k;
}

static int has_alg(const node *e)
{
    if (e->kind == N_ALG)
        return 1;
    for (int i = 0; i < e->nargs; i++)
        if (has_alg(e->args[i]))
            return 1;
    return 0;
}

/* Whether roots, or the fixed quantities they need, read an algebraic variable. */
static int needs_alg(lang_ctx *c, node *const *roots, int n, const unsigned char *needed)
{
    if (c->m.algs.n == 0)
        return 0;
    for (int i = 0; i < n; i++)
        if (roots[i] && has_alg(roots[i]))
            return 1;
    for (int k = 0; k < c->m.fixes.n; k++)
        if (needed[k] && has_alg(LVEC_AT(c->m.fixes, lang_formula, k).expr))
            return 1;
    return 0;
}

/* What a function does when the algebraic equations have no solution (emit_alg_solve) */
enum { ALG_FAIL_RHS, ALG_FAIL_STATUS, ALG_FAIL_NAN };

/* w at (t, y) into a local array; on failure fail's statement. In the right-hand side
 * (ALG_FAIL_RHS), the solution and its point are the next start. */
static void emit_alg_solve(lang_ctx *c, int fail)
{
    LANG_C_CODE(c, "    double w[DK_ALG_M];\n    if (dk_alg_solve(t, y, p, w))\n        ");
    if (fail == ALG_FAIL_RHS) /* derivatives that are not finite, so that an adaptive method
                               * tries a shorter step, as after any trial state that is not
                               * finite */
        LANG_C_CODE(c, "{\n        for (int i = 0; i < DK_ALG_N; i++)\n"
                       "            dydt[i] = NAN;\n        return 0;\n    }\n"
                       "    dk_alg_keep(t, y, par, w);\n");
    else if (fail == ALG_FAIL_STATUS)
        LANG_C_CODE(c, "return DK_ALG_FAILED;\n");
    else
        LANG_C_CODE(c, "return NAN;\n");
}

/* The constants of alg_solver.c's text: sizes, slots in p, limits. */
static void emit_alg_constants(lang_ctx *c)
{
    const lang_model *m = &c->m;
    const int na = m->algs.n, n = m->states.n, off = alg_offset(m);
    LANG_C_CODEF(c,
         "#define DK_ALG_M %d /* algebraic variables */\n#define DK_ALG_N %d /* states */\n"
         "#define DK_ALG_W %d /* p: the last solution */\n"
         "#define DK_ALG_G %d /* the initial guesses */\n"
         "#define DK_ALG_S %d /* the largest magnitudes so far */\n"
         "#define DK_ALG_T %d /* the earliest time solved */\n"
         "#define DK_ALG_TP %d /* the time of the last solution */\n"
         "#define DK_ALG_YP %d /* its state */\n"
         "#define DK_ALG_PATH %d /* continuation along a segment (up to 4096 states) */\n"
         "#define DK_ALG_FAILED %d /* no solution near the branch (dynkit/lang.h) */\n\n",
         na, n, off, off + na, off + 2 * na, off + 3 * na, off + 3 * na + 1, off + 3 * na + 2,
         n <= 4096, DYN_LANG_ALG_FAILED);
}

/* ---- pieces of the model ---- */

static void helpers(lang_ctx *c)
{
    const unsigned h = c->helpers;
    if (h & H_HEAV)
        LANG_C_CODE(c, "static inline double dk_heav(double x) { return x < 0.0 ? 0.0 : 1.0; }\n");
    if (h & H_SIGN)
        LANG_C_CODE(c, "static inline double dk_sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? "
                 "-1.0 : 0.0); }\n");
    if (h & H_MOD)
        LANG_C_CODE(c, "static inline double dk_mod(double x, double y)\n"
                 "{\n    double z = fmod(x, y);\n    if (z < 0.0)\n        z += y;\n"
                 "    return z;\n}\n");
    if (h & H_MAX)
        LANG_C_CODE(c, "static inline double dk_max(double x, double y) { return x > y ? x : y; }\n");
    if (h & H_MIN)
        LANG_C_CODE(c, "static inline double dk_min(double x, double y) { return x < y ? x : y; }\n");
    if (h & H_NOT)
        LANG_C_CODE(c, "static inline double dk_not(double x) { return x == 0.0 ? 1.0 : 0.0; }\n");
    if (h & H_SQ)
        LANG_C_CODE(c, "static inline double dk_sq(double x) { return x * x; }\n");
    if (h & H_POW)
        LANG_C_CODE(c, "static inline double dk_pow(double x, double y) { return y == 2.0 ? x * x : "
                 "pow(x, y); }\n");
    if (h & H_CONV) /* XPPAUT's conv: sum w[m+i] u(j+i), u beyond its ends 0, wrapped, or
                     * mirrored at both ends; as XPPAUT 6.11 (measured: docs/model-files.md),
                     * 0 from 2n away on (mirrored) and below -2n (wrapped) */
        LANG_C_CODE(c, "static inline double dk_conv_at(const double *u, int n, int q, int type)\n"
                 "{\n    if (q >= 0 && q < n)\n        return u[q];\n"
                 "    if (type == 0 || (type == 1 && (q <= -2 * n || q >= 2 * n)) || q < -2 * n)\n"
                 "        return 0.0;\n    if (n == 1)\n        return type == 2 ? u[0] : 0.0;\n"
                 "    const int period = type == 2 ? n : 2 * (n - 1);\n    q %= period;\n"
                 "    if (q < 0)\n        q += period;\n"
                 "    return u[q < n ? q : period - q];\n}\n"
                 "static inline void dk_conv(double *out, int n, int m, int type, "
                 "const double *w, "
                 "const double *u)\n{\n    for (int j = 0; j < n; j++) {\n"
                 "        double s = 0.0;\n        for (int i = -m; i <= m; i++)\n"
                 "            s += w[m + i] * dk_conv_at(u, n, j + i, type);\n"
                 "        out[j] = s;\n    }\n}\n");
    if (h & H_TABLE) /* XPPAUT's lookup: linear, extrapolated by the end segments */
        LANG_C_CODE(c, "static inline long dk_table_at(long n, double lo, double dx, double x)\n"
                 "{\n    const double k = floor((x - lo) / dx);\n"
                 "    return !(k > 0.0) ? 0 : k > (double)(n - 2) ? n - 2 : (long)k;\n}\n"
                 "static inline double dk_table(const double *v, long n, double lo, double dx, "
                 "double x)\n{\n    if (n < 2)\n        return v[0];\n"
                 "    const long i = dk_table_at(n, lo, dx, x);\n"
                 "    return v[i] + (v[i + 1] - v[i]) * (x - (lo + (double)i * dx)) / dx;\n}\n"
                 "static inline double dk_table_slope(const double *v, long n, double lo, "
                 "double dx, double x)\n{\n    if (n < 2)\n        return 0.0;\n"
                 "    const long i = dk_table_at(n, lo, dx, x);\n"
                 "    return (v[i + 1] - v[i]) / dx;\n}\n");
    if (h)
        LANG_C_CODE(c, "\n");
}

/* user function fi, u_FI(a_0, ..., t, y, p), or its partial derivative udK_FI */
static void func_proto(lang_ctx *c, const lang_func *f, int fi, int partial)
{
    if (partial < 0)
        LANG_C_CODEF(c, "static double u_%d(", fi);
    else
        LANG_C_CODEF(c, "static double ud%d_%d(", partial, fi);
    for (int k = 0; k < f->nargs; k++)
        LANG_C_CODEF(c, "double a_%d, ", k);
    LANG_C_CODE(c, "double t, const double *y, const double *p)");
}

/* ---- the whole unit ---- */

typedef struct jac_plan {
    unsigned char *used;  /* partials of user functions used (funcs * LANG_MAX_ARGS) */
    node **partial;       /* their bodies */
    lang_ctext text;      /* the Jacobian's C text */
    lang_ctext before;    /* the main text, while the Jacobian's is written */
    int writing;          /* 1 while the Jacobian's text is written */
    int band_bad_i, band_bad_j; /* an entry outside the declared band (-1: none) */
    int nnz;              /* the sparse pattern (CSC, every diagonal entry in it) */
    int *colptr, *rowind;
} jac_plan;

/* A band is taken from the exact Jacobian's pattern (no declaration needed) when it is
 * narrow: at least LANG_BAND_MIN_STATES states and a band of at most a quarter of them. A
 * band LU then costs about 2 n lower (lower + upper) operations against n^3/3 dense, and
 * the smaller models keep their dense matrices (docs/stiff.md, "Large systems"). */
#define LANG_BAND_MIN_STATES 32

/* The pattern of the columns' entries with every diagonal entry, into j (CSC). */
static void sparse_pattern(lang_ctx *c, jac_plan *j, node ***entry, int n)
{
    int nnz = 0;
    for (int jj = 0; jj < n; jj++)
        for (int i = 0; i < n; i++)
            nnz += entry[jj][i] || i == jj;
    j->nnz = nnz;
    j->colptr = lang_alloc(c, ((size_t)n + 1) * sizeof *j->colptr);
    j->rowind = lang_alloc(c, (size_t)nnz * sizeof *j->rowind);
    int k = 0;
    for (int jj = 0; jj < n; jj++) {
        j->colptr[jj] = k;
        for (int i = 0; i < n; i++)
            if (entry[jj][i] || i == jj)
                j->rowind[k++] = i;
    }
    j->colptr[n] = k;
}

/* Whether the pattern is written with the model: at least LANG_BAND_MIN_STATES states and at
 * most a quarter of the entries (the rule by which the tool takes sparse matrices,
 * cli_linear_choose); a smaller or denser Jacobian stays dense, and the text of its
 * entries is not written a second time. */
static int pattern_kept(const jac_plan *j, int n)
{
    return n >= LANG_BAND_MIN_STATES && 4.0 * j->nnz <= (double)n * n;
}

/* Without a declared band: the pattern's band when it is narrow (LANG_BAND_MIN_STATES). */
static void find_band(lang_model *m, const jac_plan *j, int n)
{
    if (m->has_band || n < LANG_BAND_MIN_STATES)
        return;
    int lo = 0, up = 0;
    for (int jj = 0; jj < n; jj++)
        for (int k = j->colptr[jj]; k < j->colptr[jj + 1]; k++) {
            const int d = j->rowind[k] - jj;
            lo = d > lo ? d : lo;
            up = -d > up ? -d : up;
        }
    if (4 * (lo + up + 1) > n)
        return;
    m->has_band = m->band_found = 1;
    m->band_lo = lo;
    m->band_up = up;
}

static void plan_partials(lang_ctx *c, jac_plan *j)
{
    lang_model *m = &c->m;
    const int nf = m->funcs.n;
    j->partial = lang_alloc(c, ((size_t)nf + 1) * LANG_MAX_ARGS * sizeof *j->partial);
    for (int changed = 1; changed;) {
        changed = 0;
        for (int f = 0; f < nf; f++)
            for (int k = 0; k < LANG_MAX_ARGS; k++) {
                const int id = f * LANG_MAX_ARGS + k;
                if (!j->used[id] || j->partial[id])
                    continue;
                lang_func *fn = &LVEC_AT(m->funcs, lang_func, f);
                lang_dvar v = {N_ARG, k, NULL, j->used, 0};
                j->partial[id] = lang_deriv(c, fn->body, &v);
                changed = 1;
            }
    }
}

/* The definitions of the user functions and partial derivatives the text calls (a
 * definition may call more: until none is new). */
static void emit_function_defs(lang_ctx *c, const jac_plan *j, unsigned char *done)
{
    lang_model *m = &c->m;
    for (int changed = 1; changed;) {
        changed = 0;
        for (int f = 0; f < m->funcs.n; f++) {
            const lang_func *fn = &LVEC_AT(m->funcs, lang_func, f);
            const ectx x = {fn, 1};
            for (int k = -1; k < fn->nargs; k++) {
                const size_t id = (size_t)f * (LANG_MAX_ARGS + 1) + (size_t)(k + 1);
                if (!func_marked(c, f, k + 1) || done[id])
                    continue;
                const node *body = k < 0 ? fn->body
                                   : j->partial ? j->partial[f * LANG_MAX_ARGS + k]
                                                : NULL;
                done[id] = 1;
                changed = 1;
                if (!body)
                    continue;
                LANG_C_CODE(c, "\n");
                line_dir(c, fn->pos);
                func_proto(c, fn, f, k);
                LANG_C_CODE(c, "\n{\n    (void)t;\n    (void)y;\n    (void)p;\n");
                for (int a = 0; a < fn->nargs; a++)
                    LANG_C_CODEF(c, "    (void)a_%d;\n", a);
                LANG_C_CODE(c, "    return ");
                expr(c, body, &x);
                LANG_C_CODE(c, ";\n}\n");
            }
        }
    }
}

static void emit_function_protos(lang_ctx *c)
{
    lang_model *m = &c->m;
    int any = 0;
    for (int f = 0; f < m->funcs.n; f++) {
        const lang_func *fn = &LVEC_AT(m->funcs, lang_func, f);
        for (int k = -1; k < fn->nargs; k++)
            if (func_marked(c, f, k + 1)) {
                if (!any)
                    LANG_C_CODE(c, "/* user functions and their partial derivatives */\n");
                any = 1;
                func_proto(c, fn, f, k);
                LANG_C_CODE(c, ";\n");
            }
    }
    if (any)
        LANG_C_CODE(c, "\n");
}

static void emit_rhs(lang_ctx *c)
{
    lang_model *m = &c->m;
    node **roots = lang_alloc(c, (size_t)m->states.n * sizeof *roots);
    for (int i = 0; i < m->states.n; i++)
        roots[i] = LVEC_AT(m->states, lang_state, i).rhs;
    unsigned char *needed = needed_by(c, roots, m->states.n);
    LANG_C_CODE(c, "static int dk_rhs(double t, const double *y, double *dydt, void *par)\n{\n"
             "    const double *p = (const double *)par;\n    (void)t;\n    (void)y;\n"
             "    (void)p;\n");
    if (m->n_delays)
        lang_emit_delay_guard(c);
    if (m->algs.n) /* also when no derivative reads them: the branch is tracked here */
        emit_alg_solve(c, ALG_FAIL_RHS);
    emit_fixes(c, needed);
    const ectx x = {NULL, 1};
    for (int i = 0; i < m->states.n; i++) {
        const lang_state *s = &LVEC_AT(m->states, lang_state, i);
        line_dir(c, s->pos);
        LANG_C_CODEF(c, "    dydt[%d] = ", i);
        expr(c, s->rhs, &x);
        LANG_C_CODE(c, ";\n");
    }
    LANG_C_CODE(c, "    return 0;\n}\n\n");
}

static void emit_outputs(lang_ctx *c)
{
    lang_model *m = &c->m;
    if (m->auxs.n == 0)
        return;
    node **roots = lang_alloc(c, (size_t)m->auxs.n * sizeof *roots);
    for (int i = 0; i < m->auxs.n; i++)
        roots[i] = LVEC_AT(m->auxs, lang_formula, i).expr;
    unsigned char *needed = needed_by(c, roots, m->auxs.n);
    LANG_C_CODE(c, "static int dk_outputs(double t, const double *y, const void *par, double *out)\n"
             "{\n    const double *p = (const double *)par;\n    (void)t;\n    (void)y;\n"
             "    (void)p;\n");
    if (m->n_delays)
        lang_emit_delay_guard(c);
    if (needs_alg(c, roots, m->auxs.n, needed))
        emit_alg_solve(c, ALG_FAIL_STATUS);
    emit_fixes(c, needed);
    const ectx x = {NULL, 1};
    for (int i = 0; i < m->auxs.n; i++) {
        const lang_formula *f = &LVEC_AT(m->auxs, lang_formula, i);
        line_dir(c, f->pos);
        LANG_C_CODEF(c, "    out[%d] = ", i);
        expr(c, f->expr, &x);
        LANG_C_CODE(c, ";\n");
    }
    LANG_C_CODE(c, "    return 0;\n}\n\n");
}

/* In prepare: each table's values into p, from its formula of t at the abscissas
 * lo + k dx (with the parameters just set), or from its file's numbers. */
static void emit_table_values(lang_ctx *c)
{
    const lang_model *m = &c->m;
    const ectx x = {NULL, 0};
    for (int i = 0; i < m->tables.n; i++) {
        const lang_table *tb = &LVEC_AT(m->tables, lang_table, i);
        line_dir(c, tb->pos);
        if (!tb->expr) {
            LANG_C_CODEF(c, "    memcpy(p + %d, dk_table_file%d, sizeof dk_table_file%d);\n", tb->offset,
                 i, i);
            continue;
        }
        LANG_C_CODEF(c, "    for (long k = 0; k < %ld; k++) {\n        const double t = ", tb->npts);
        lang_c_num(c, tb->lo);
        LANG_C_CODE(c, " + ");
        lang_c_num(c, table_dx(tb));
        LANG_C_CODEF(c, " * (double)k;\n        (void)t;\n        p[%d + k] = ", tb->offset);
        expr(c, tb->expr, &x);
        LANG_C_CODEF(c, ";\n        if (!isfinite(p[%d + k])) {\n            snprintf(err, errlen, "
                "\"table '%%s' is not finite at t = %%g (%%g)\", ",
             tb->offset);
        lang_c_str(c, tb->name);
        LANG_C_CODEF(c, ", t, p[%d + k]);\n            return 1;\n        }\n    }\n", tb->offset);
    }
}

/* Tables read from files in m. */
static int table_files(const lang_model *m)
{
    int k = 0;
    for (int i = 0; i < m->tables.n; i++)
        k += LVEC_AT(m->tables, lang_table, i).expr == NULL;
    return k;
}

/* Doubles of the parameter array: parameters, derived parameters, the tables' values, the
 * algebraic variables' slots. */
/* the doubles of the parameter array before the input table (a dyn_input_table) */
static int input_offset(const lang_model *m)
{
    return alg_offset(m) + (m->algs.n ? 3 * m->algs.n + 2 + m->states.n : 0);
}

#define LANG_INPUT_DOUBLES 8 /* room for a dyn_input_table */

/* the noise slots (dynkit/sde.h) come last */
static int noise_offset(const lang_model *m)
{
    return input_offset(m) + (m->n_inputs ? LANG_INPUT_DOUBLES : 0);
}

/* Index in p of a delay model's history pointer (one slot, after the noise slots). */
static int delay_offset(const lang_model *m) { return noise_offset(m) + m->noises.n; }

/* Index in p of the Volterra integrals' values (integrals.c), after the delay's slot. */
static int volt_offset(const lang_model *m) { return delay_offset(m) + (m->n_delays ? 1 : 0); }

/* the seed of the tables' random numbers: two doubles (its low and high 32 bits) */
static int seed_offset(const lang_model *m)
{
    return volt_offset(m) + (lang_volt_model(m) ? m->volts.n + 1 : 0);
}

static int par_doubles(const lang_model *m) { return seed_offset(m) + (m->n_table_draws ? 2 : 0); }

static void state_expr(lang_ctx *c, const node *e)
{
    const ectx x = {NULL, 1};
    expr(c, e, &x);
}

static void fixes_for(lang_ctx *c, node *const *roots, int n)
{
    emit_fixes(c, needed_by(c, roots, n));
}

static void history_expr(lang_ctx *c, const node *e)
{
    const ectx x = {NULL, 0};
    expr(c, e, &x);
}

/* The inputs: reading one (dk_input), attaching a table (dk_set_input), their names. */
static void emit_inputs(lang_ctx *c)
{
    const lang_model *m = &c->m;
    if (!m->n_inputs)
        return;
    LANG_C_CODEF(c,
                 "_Static_assert(sizeof(dyn_input_table) <= %d * sizeof(double), \"room for "
                 "the input table\");\n"
                 "static inline double dk_input(const double *p, double t, int k, int i)\n{\n"
                 "    dyn_input_table it;\n    memcpy(&it, p + %d, sizeof it);\n"
                 "    return dyn_input_table_at(&it, t, k, p[i]);\n}\n\n"
                 "static int dk_set_input(void *par, const double *table, long rows, "
                 "dyn_interp interp, char *err, size_t errlen)\n{\n    dyn_input_table it;\n"
                 "    if (dyn_input_table_set(&it, table, rows, %d, interp, err, errlen))\n"
                 "        return 1;\n    memcpy((double *)par + %d, &it, sizeof it);\n"
                 "    return 0;\n}\n\n",
                 LANG_INPUT_DOUBLES, input_offset(m), m->n_inputs, input_offset(m));
}

static void emit_input_vars(lang_ctx *c)
{
    const lang_model *m = &c->m;
    if (!m->n_inputs)
        return;
    LANG_C_CODE(c, "static const dyn_var dk_inputs_vars[] = {\n");
    for (int k = 0; k < m->n_inputs; k++) {
        const lang_param *p = &LVEC_AT(m->params, lang_param, m->input_param[k]);
        LANG_C_CODE(c, "    {");
        lang_c_str(c, p->name);
        LANG_C_CODE(c, ", ");
        lang_c_str(c, p->doc.unit);
        LANG_C_CODE(c, ", ");
        lang_c_str(c, p->doc.description);
        LANG_C_CODE(c, "},\n");
    }
    LANG_C_CODE(c, "};\n");
}

/* In prepare, after the tables: each index of a sparse sum must point into its block. */
static void emit_sparse_checks(lang_ctx *c)
{
    const lang_model *m = &c->m;
    for (int i = 0; i < m->specials.n; i++) {
        const lang_special *sp = &LVEC_AT(m->specials, lang_special, i);
        if (sp->kind != LANG_SUM_SPARSE)
            continue;
        const lang_table *l = &LVEC_AT(m->tables, lang_table, sp->index_table);
        line_dir(c, sp->pos);
        LANG_C_CODEF(c, "    for (long k = 0; k < %ld; k++)\n        if (!(p[%d + k] >= 0.0 && "
                "p[%d + k] < %d.0)) {\n            snprintf(err, errlen, \"network sum '%%s': "
                "index %%ld of table '%%s' is %%g, not one of the %d states from '%%s' on (0 "
                "to %d)\", ",
             l->npts, l->offset, l->offset, sp->ulen, sp->ulen, sp->ulen - 1);
        lang_c_str(c, sp->name);
        LANG_C_CODE(c, ", k, ");
        lang_c_str(c, l->name);
        LANG_C_CODEF(c, ", p[%d + k], ", l->offset);
        lang_c_str(c, sp->root_name);
        LANG_C_CODE(c, ");\n            return 1;\n        }\n");
    }
}

/* The numbers of the tables read from files, as arrays for prepare to copy. */
static void emit_table_files(lang_ctx *c)
{
    const lang_model *m = &c->m;
    for (int i = 0; i < m->tables.n; i++) {
        const lang_table *tb = &LVEC_AT(m->tables, lang_table, i);
        if (tb->expr)
            continue;
        LANG_C_CODEF(c, "static const double dk_table_file%d[%ld] = {", i, tb->npts);
        for (long k = 0; k < tb->npts; k++) {
            if (k % 4)
                LANG_C_CODE(c, ", ");
            else if (k)
                LANG_C_CODE(c, ",\n    ");
            else
                LANG_C_CODE(c, "\n    ");
            lang_c_num(c, tb->values[k]);
        }
        LANG_C_CODE(c, "};\n\n");
    }
}

/* In prepare: the algebraic variables' initial guesses (also their first start and their
 * first scale), and no time solved yet. */
static void emit_alg_guesses(lang_ctx *c)
{
    const lang_model *m = &c->m;
    const int na = m->algs.n;
    const ectx x = {NULL, 0};
    for (int i = 0; i < na; i++) {
        const lang_formula *f = &LVEC_AT(m->algs, lang_formula, i);
        line_dir(c, f->pos);
        LANG_C_CODEF(c, "    p[DK_ALG_G + %d] = ", i);
        expr(c, f->expr, &x);
        LANG_C_CODEF(c,
             ";\n    if (!isfinite(p[DK_ALG_G + %d])) {\n        snprintf(err, errlen, \"the "
             "initial guess of algebraic variable '%%s' is not finite (%%g)\", ",
             i);
        lang_c_str(c, f->name);
        LANG_C_CODEF(c,
             ", p[DK_ALG_G + %d]);\n        return 1;\n    }\n    p[DK_ALG_W + %d] = "
             "p[DK_ALG_G + %d];\n    p[DK_ALG_S + %d] = fabs(p[DK_ALG_G + %d]);\n",
             i, i, i, i, i);
    }
    if (na)
        LANG_C_CODE(c, "    p[DK_ALG_T] = INFINITY;\n    p[DK_ALG_TP] = 0.0;\n");
}

static void emit_prepare(lang_ctx *c)
{
    lang_model *m = &c->m;
    const int np = m->params.n;
    LANG_C_CODE(c, "static int dk_prepare(void *par, char *err, size_t errlen)\n{\n"
             "    double *p = (double *)par;\n    (void)p;\n");
    if (np > 0) {
        LANG_C_CODE(c, "    static const char *const names[] = {");
        for (int i = 0; i < np; i++) {
            if (i)
                LANG_C_CODE(c, ", ");
            lang_c_str(c, LVEC_AT(m->params, lang_param, i).name);
        }
        LANG_C_CODEF(c, "};\n    for (int i = 0; i < %d; i++)\n        if (!isfinite(p[i])) {\n"
                "            snprintf(err, errlen, \"parameter '%%s' is not finite (%%g)\", "
                "names[i], p[i]);\n            return 1;\n        }\n",
             np);
    }
    const ectx x = {NULL, 0};
    for (int i = 0; i < m->derived.n; i++) {
        const int k = m->derived_order[i];
        const lang_formula *f = &LVEC_AT(m->derived, lang_formula, k);
        line_dir(c, f->pos);
        LANG_C_CODEF(c, "    p[%d] = ", np + k);
        expr(c, f->expr, &x);
        LANG_C_CODE(c, ";\n");
        LANG_C_CODEF(c, "    if (!isfinite(p[%d])) {\n        snprintf(err, errlen, \"derived parameter "
                "'%%s' is not finite (%%g)\", ",
             np + k);
        lang_c_str(c, f->name);
        LANG_C_CODEF(c, ", p[%d]);\n        return 1;\n    }\n", np + k);
    }
    emit_table_values(c);
    emit_sparse_checks(c);
    emit_alg_guesses(c);
    if (m->n_delays)
        lang_emit_delay_prepare(c, history_expr);
    LANG_C_CODE(c, "    (void)err;\n    (void)errlen;\n    return 0;\n}\n\n");
}

static int init_needs_params(const node *e)
{
    if (!e)
        return 0;
    if (e->kind == N_PARAM || e->kind == N_UFUN)
        return 1;
    for (int i = 0; i < e->nargs; i++)
        if (init_needs_params(e->args[i]))
            return 1;
    return 0;
}

static int emit_initial(lang_ctx *c, const double *y0)
{
    lang_model *m = &c->m;
    int any = 0;
    for (int i = 0; i < m->states.n; i++)
        any |= init_needs_params(LVEC_AT(m->states, lang_state, i).init);
    if (!any)
        return 0;
    LANG_C_CODE(c, "static void dk_initial_state(const void *par, double *y0)\n{\n"
             "    const double *p = (const double *)par;\n    (void)p;\n");
    const ectx x = {NULL, 0};
    for (int i = 0; i < m->states.n; i++) {
        const lang_state *s = &LVEC_AT(m->states, lang_state, i);
        if (init_needs_params(s->init)) {
            line_dir(c, s->init_pos);
            LANG_C_CODEF(c, "    y0[%d] = ", i);
            expr(c, s->init, &x);
        } else {
            LANG_C_CODEF(c, "    y0[%d] = ", i);
            lang_c_num(c, y0[i]);
        }
        LANG_C_CODE(c, ";\n");
    }
    LANG_C_CODE(c, "}\n\n");
    return 1;
}

/* Jacobian: the fixed temporaries, then one block per column j with the derivatives of the
 * fixed temporaries with respect to y[j] (locals dvJ_K) and the non-zero entries. */
/* The derivatives of the needed fixed quantities with respect to v's variable, in their
 * order, into out (NULL: zero), and for the derivatives after them into v->fixd: the
 * number, or a reference dv<column>_K to the local the Jacobian's text writes. */
static void derive_fixes(lang_ctx *c, lang_dvar *v, const unsigned char *needed, node **out)
{
    const lang_model *m = &c->m;
    for (int q = 0; q < m->fixes.n; q++) {
        const int k = m->fix_order[q];
        if (!needed[k])
            continue;
        node *dk = lang_deriv(c, LVEC_AT(m->fixes, lang_formula, k).expr, v);
        if (lang_is_num(dk, 0.0))
            continue;
        out[k] = dk;
        if (dk->kind == N_NUM) {
            v->fixd[k] = dk;
        } else {
            node *ref = lang_node(c, N_DFIX, (lpos){0, 0});
            ref->index = k;
            ref->op = v->index;
            v->fixd[k] = ref;
        }
    }
}

static void emit_jacobian(lang_ctx *c, jac_plan *j)
{
    lang_model *m = &c->m;
    const int n = m->states.n;
    node **roots = lang_alloc(c, (size_t)n * sizeof *roots);
    for (int i = 0; i < n; i++)
        roots[i] = LVEC_AT(m->states, lang_state, i).rhs;
    unsigned char *needed = needed_by(c, roots, n);
    node **fixd = lang_alloc(c, ((size_t)m->fixes.n + 1) * sizeof *fixd);
    /* compute everything first (the partials of user functions must be known before the
     * functions are written), then write */
    typedef struct col {
        node **fixd;  /* derivative of each needed fix (NULL: zero) */
        node **entry; /* d f_i / d y_j (NULL: zero) */
    } col;
    col *cols = lang_alloc(c, (size_t)n * sizeof *cols);
    for (int jj = 0; jj < n; jj++) {
        memset(fixd, 0, ((size_t)m->fixes.n + 1) * sizeof *fixd);
        cols[jj].fixd = lang_alloc(c, ((size_t)m->fixes.n + 1) * sizeof(node *));
        cols[jj].entry = lang_alloc(c, (size_t)n * sizeof(node *));
        lang_dvar v = {N_STATE, jj, fixd, j->used, 0};
        derive_fixes(c, &v, needed, cols[jj].fixd);
        for (int i = 0; i < n; i++) {
            node *e = lang_deriv(c, roots[i], &v);
            cols[jj].entry[i] = lang_is_num(e, 0.0) ? NULL : e;
        }
    }
    plan_partials(c, j);
    /* the functions' text comes before the Jacobian's: write it into a buffer of its own */
    j->before = lang_c_take(c);
    j->writing = 1;
    /* the fixed temporaries the derivatives use (not all those of the right-hand side) */
    unsigned char *jneed = lang_alloc(c, (size_t)m->fixes.n + 1);
    for (int jj = 0; jj < n; jj++) {
        for (int i = 0; i < n; i++)
            if (cols[jj].entry[i])
                need(c, cols[jj].entry[i], jneed);
        for (int k = 0; k < m->fixes.n; k++)
            if (cols[jj].fixd[k])
                need(c, cols[jj].fixd[k], jneed);
    }
    {
        node ***entries = lang_alloc(c, (size_t)n * sizeof *entries);
        for (int jj = 0; jj < n; jj++)
            entries[jj] = cols[jj].entry;
        sparse_pattern(c, j, entries, n);
        find_band(m, j, n);
    }
    /* entries outside a declared band: the declaration is wrong (reported by the caller,
     * as an error, not as a Jacobian that could not be formed) */
    j->band_bad_i = j->band_bad_j = -1;
    for (int jj = 0; jj < n && m->has_band && j->band_bad_i < 0; jj++)
        for (int i = 0; i < n; i++)
            if (cols[jj].entry[i] && (i - jj > m->band_lo || jj - i > m->band_up)) {
                j->band_bad_i = i;
                j->band_bad_j = jj;
                break;
            }
    /* dk_jacobian (dense, row-major), for a sparse pattern without a band dk_jacobian_sparse
     * (the pattern's values), and with a band dk_jacobian_band (the band in DYN_BAND_AT
     * storage): the same entries */
    const int ld = m->band_lo + m->band_up + 1;
    /* kind 0: dense; 1: sparse (the pattern's values in order); 2: band */
    for (int kind = 0; kind <= 1 + (m->has_band && j->band_bad_i < 0); kind++) {
        const int band = kind == 2;
        if (kind == 1 && (m->has_band || !pattern_kept(j, n)))
            continue; /* the band's function, or the dense one, serves */
        if (band)
            LANG_C_CODE(c, "static int dk_jacobian_band");
        else if (kind == 1)
            LANG_C_CODE(c, "static int dk_jacobian_sparse");
        else
            LANG_C_CODE(c, "static int dk_jacobian");
        LANG_C_CODE(c, "(double t, const double *y, double *J, void *par)\n{\n"
                       "    const double *p = (const double *)par;\n    (void)t;\n    (void)y;\n"
                       "    (void)p;\n");
        emit_fixes(c, jneed);
        if (kind == 1) { /* a diagonal entry that is zero: the pattern holds it anyway */
            for (int jj = 0; jj < n; jj++)
                if (!cols[jj].entry[jj])
                    for (int k = j->colptr[jj]; k < j->colptr[jj + 1]; k++)
                        if (j->rowind[k] == jj)
                            LANG_C_CODEF(c, "    J[%d] = 0.0;\n", k);
        } else {
            LANG_C_CODEF(c, "    for (int k = 0; k < %d; k++)\n        J[k] = 0.0;\n",
                         band ? n * ld : n * n);
        }
        const ectx x = {NULL, 1};
        for (int jj = 0; jj < n; jj++) {
            int any = 0;
            for (int i = 0; i < n; i++)
                any |= cols[jj].entry[i] != NULL;
            if (!any)
                continue;
            LANG_C_CODEF(c, "    { /* d/d y[%d] */\n", jj);
            for (int q = 0; q < m->fixes.n; q++) {
                const int k = m->fix_order[q];
                const node *dk = cols[jj].fixd[k];
                if (!dk || dk->kind == N_NUM)
                    continue;
                const lang_formula *f = &LVEC_AT(m->fixes, lang_formula, k);
                line_dir(c, f->pos);
                LANG_C_CODEF(c, "        const double dv%d_%d = ", jj, k);
                expr(c, dk, &x);
                LANG_C_CODE(c, ";\n");
                LANG_C_CODEF(c, "        (void)dv%d_%d;\n", jj, k);
            }
            int k = j->colptr[jj];
            for (int i = 0; i < n; i++) {
                if (!cols[jj].entry[i]) {
                    k += i == jj;
                    continue;
                }
                line_dir(c, LVEC_AT(m->states, lang_state, i).pos);
                LANG_C_CODEF(c, "        J[%d] = ", band ? jj * ld + m->band_up + i - jj
                                                   : kind == 1 ? k
                                                               : i * n + jj);
                k++;
                expr(c, cols[jj].entry[i], &x);
                LANG_C_CODE(c, ";\n");
            }
            LANG_C_CODE(c, "    }\n");
        }
        LANG_C_CODE(c, "    return 0;\n}\n\n");
    }
    /* keep the Jacobian's text in the arena until it is appended */
    j->text = lang_c_take(c);
    lang_c_splice(c, j->before);
    j->writing = 0;
}

/* ---- the declared band, checked from the structure of the equations ---- */

/* The lowest and highest state index an expression reads (lo > hi: none), through fixed
 * temporaries and user functions (each worked out once). */
typedef struct state_span {
    int lo, hi;
} state_span;

typedef struct span_memo {
    state_span *fix, *fun;
    unsigned char *fix_done, *fun_done;
    state_span alg; /* the states the algebraic equations read, together */
    int alg_done;   /* 0, 1 while it is computed, 2 */
} span_memo;

static state_span span_join(state_span a, state_span b)
{
    if (b.lo < a.lo)
        a.lo = b.lo;
    if (b.hi > a.hi)
        a.hi = b.hi;
    return a;
}

static state_span span_of(lang_ctx *c, const node *e, span_memo *mm)
{
    state_span s = {INT_MAX, INT_MIN};
    for (int i = 0; i < e->nargs; i++)
        s = span_join(s, span_of(c, e->args[i], mm));
    if (e->kind == N_STATE) {
        s = span_join(s, (state_span){e->index, e->index});
    } else if (e->kind == N_ALG) { /* solved from all the equations together */
        if (mm->alg_done == 0) {
            mm->alg_done = 1;
            state_span a = {INT_MAX, INT_MIN};
            for (int i = 0; i < c->m.algeqs.n; i++)
                a = span_join(a, span_of(c, LVEC_AT(c->m.algeqs, lang_formula, i).expr, mm));
            mm->alg = a;
            mm->alg_done = 2;
        }
        if (mm->alg_done == 2)
            s = span_join(s, mm->alg);
    } else if (e->kind == N_FIX) {
        if (!mm->fix_done[e->index]) {
            mm->fix_done[e->index] = 1;
            mm->fix[e->index] = span_of(c, LVEC_AT(c->m.fixes, lang_formula, e->index).expr, mm);
        }
        s = span_join(s, mm->fix[e->index]);
    } else if (e->kind == N_FUN && e->op == F_SPECIAL) {
        const lang_special *sp = &LVEC_AT(c->m.specials, lang_special, e->index);
        for (int k = 0; k < sp->ulen; k++) {
            const node ref = {.kind = sp->root_kind, .index = sp->root + k};
            s = span_join(s, span_of(c, &ref, mm));
        }
        for (int k = 0; sp->kind == LANG_SUM_FCONV && k < sp->n; k++) {
            const node vref = {.kind = sp->vroot_kind, .index = sp->vroot + k};
            s = span_join(s, span_of(c, &vref, mm));
        }
    } else if (e->kind == N_UFUN || e->kind == N_UFUN_D) {
        if (!mm->fun_done[e->index]) {
            mm->fun_done[e->index] = 1;
            mm->fun[e->index] = span_of(c, LVEC_AT(c->m.funcs, lang_func, e->index).body, mm);
        }
        s = span_join(s, mm->fun[e->index]);
    }
    return s;
}

/* The exact Jacobian of the algebraic equations, J[i M + k] = d r_i / d w_k, from the
 * derivatives of their formulas (deriv.c) as for the right-hand side's: its columns, with
 * the derivatives of the fixed quantities in each. */
typedef struct alg_jac {
    node **entry; /* entry[k * M + i] (NULL: zero) */
    node **fixd;  /* fixd[k * (fixes + 1) + f] (NULL: zero) */
} alg_jac;

/* After a derivative that could not be formed (the error exit back in c->fail's hands):
 * an error other than one in the file (out of memory) goes on to the caller; otherwise a
 * note with the reason between before and after, the diagnostic cleared and the partial
 * derivatives of functions forgotten, so that differences take over. */
static void derivative_failed(lang_ctx *c, jac_plan *jp, const char *before, const char *after)
{
    if (c->status != 2)
        longjmp(*c->fail, 1);
    c->status = 0;
    lpos at = {c->diag->line, c->diag->col};
    lang_note(c, at, "%s%s%s", before, c->diag->message, after);
    c->diag->message[0] = '\0';
    c->diag->line = c->diag->col = 0;
    c->diag->excerpt[0] = '\0';
    memset(jp->used, 0, ((size_t)c->m.funcs.n + 1) * LANG_MAX_ARGS);
    jp->partial = NULL;
}

/* Fills aj and returns 1, or 0 (with a note) when a formula has no analytic derivative
 * (a network sum): Newton's method then takes differences. */
static int alg_jacobian_entries(lang_ctx *c, jac_plan *jp, const unsigned char *needed, alg_jac *aj)
{
    lang_model *m = &c->m;
    const int na = m->algs.n, nf = m->fixes.n;
    jmp_buf fail;
    jmp_buf *outer = c->fail;
    const long work = c->work;
    c->fail = &fail;
    if (setjmp(fail) == 0) {
        aj->entry = lang_alloc(c, (size_t)na * (size_t)na * sizeof *aj->entry);
        aj->fixd = lang_alloc(c, (size_t)na * ((size_t)nf + 1) * sizeof *aj->fixd);
        node **fixd = lang_alloc(c, ((size_t)nf + 1) * sizeof *fixd);
        for (int k = 0; k < na; k++) {
            memset(fixd, 0, ((size_t)nf + 1) * sizeof *fixd);
            lang_dvar v = {N_ALG, k, fixd, jp->used, 0};
            derive_fixes(c, &v, needed, aj->fixd + (size_t)k * ((size_t)nf + 1));
            for (int i = 0; i < na; i++) {
                node *e = lang_deriv(c, LVEC_AT(m->algeqs, lang_formula, i).expr, &v);
                aj->entry[(size_t)k * (size_t)na + (size_t)i] = lang_is_num(e, 0.0) ? NULL : e;
            }
        }
        plan_partials(c, jp);
        c->fail = outer;
        return 1;
    }
    c->fail = outer;
    c->work = work;
    if (c->m.band_found) /* the band found in a pattern that is not kept */
        c->m.has_band = c->m.band_found = 0;
    derivative_failed(c, jp, "the algebraic equations' Jacobian by differences: ", "");
    return 0;
}

/* C text of a bound on the magnitudes that enter e, for the rounding error of computing
 * it: sums and differences add the bounds of their terms, products and quotients combine
 * them (|u| |v|, |u| / |v|), a negation keeps its operand's, anything else is its own
 * magnitude. eps times it bounds the rounding of e within a small factor (Wilkinson's
 * running error bound, to first order). */
static void emit_bound(lang_ctx *c, const node *e, const ectx *x)
{
    LANG_WORK(c, e->pos);
    if (e->kind == N_NEG) {
        emit_bound(c, e->args[0], x);
        return;
    }
    if (e->kind == N_FIX) { /* its bound, a local written before (emit_fix_bounds) */
        LANG_C_CODEF(c, "b_%d", e->index);
        return;
    }
    if (e->kind == N_UFUN) { /* the body with the arguments in place */
        const lang_func *fn = &LVEC_AT(c->m.funcs, lang_func, e->index);
        if (++c->depth > LANG_MAX_INLINE)
            lang_fail(c, e->pos, "calls of '%s' nested too deeply to bound", fn->name);
        emit_bound(c, lang_subst(c, fn->body, e->args), x);
        c->depth--;
        return;
    }
    if (e->kind == N_IF) {
        LANG_C_CODE(c, "((");
        expr(c, e->args[0], x);
        LANG_C_CODE(c, ") != 0.0 ? ");
        emit_bound(c, e->args[1], x);
        LANG_C_CODE(c, " : ");
        emit_bound(c, e->args[2], x);
        LANG_C_CODE(c, ")");
        return;
    }
    if (e->kind == N_BIN &&
        (e->op == OP_ADD || e->op == OP_SUB || e->op == OP_MUL || e->op == OP_DIV)) {
        LANG_C_CODE(c, "(");
        if (e->op == OP_DIV) {
            emit_bound(c, e->args[0], x);
            LANG_C_CODE(c, " / fabs(");
            expr(c, e->args[1], x);
            LANG_C_CODE(c, ")");
        } else {
            emit_bound(c, e->args[0], x);
            if (e->op == OP_MUL)
                LANG_C_CODE(c, " * ");
            else
                LANG_C_CODE(c, " + ");
            emit_bound(c, e->args[1], x);
        }
        LANG_C_CODE(c, ")");
        return;
    }
    LANG_C_CODE(c, "fabs(");
    expr(c, e, x);
    LANG_C_CODE(c, ")");
}

/* dk_alg_residual (r from the 0= equations, and the bounds of their rounding), the exact
 * dk_alg_jacobian when it can be formed, then the solver (alg_solver.c). */
static void emit_alg_functions(lang_ctx *c, jac_plan *jp)
{
    lang_model *m = &c->m;
    const int na = m->algs.n, nf = m->fixes.n;
    if (na == 0)
        return;
    node **roots = lang_alloc(c, (size_t)na * sizeof *roots);
    for (int i = 0; i < na; i++)
        roots[i] = LVEC_AT(m->algeqs, lang_formula, i).expr;
    unsigned char *needed = needed_by(c, roots, na);
    const ectx x = {NULL, 1};
    /* r, and when rb is not NULL the bounds of their rounding (emit_bound) */
    LANG_C_CODE(c, "static void dk_alg_residual(double t, const double *y, const double *p, "
             "const double *w, double *r, double *rb)\n{\n    (void)t;\n    (void)y;\n"
             "    (void)p;\n    (void)w;\n");
    emit_fixes(c, needed);
    for (int i = 0; i < na; i++) {
        const lang_formula *f = &LVEC_AT(m->algeqs, lang_formula, i);
        line_dir(c, f->pos);
        LANG_C_CODEF(c, "    r[%d] = ", i);
        expr(c, f->expr, &x);
        LANG_C_CODE(c, ";\n");
    }
    LANG_C_CODE(c, "    if (!rb)\n        return;\n");
    for (int q = 0; q < m->fixes.n; q++) { /* the fixed quantities' bounds */
        const int k = m->fix_order[q];
        if (!needed[k])
            continue;
        const lang_formula *f = &LVEC_AT(m->fixes, lang_formula, k);
        LANG_C_CODEF(c, "    const double b_%d = ", k);
        emit_bound(c, f->expr, &x);
        LANG_C_CODEF(c, ";\n    (void)b_%d;\n", k);
    }
    for (int i = 0; i < na; i++) {
        const lang_formula *f = &LVEC_AT(m->algeqs, lang_formula, i);
        line_dir(c, f->pos);
        LANG_C_CODEF(c, "    rb[%d] = ", i);
        emit_bound(c, f->expr, &x);
        LANG_C_CODE(c, ";\n");
    }
    LANG_C_CODE(c, "}\n\n");
    alg_jac aj;
    const int exact = alg_jacobian_entries(c, jp, needed, &aj);
    if (exact) {
        unsigned char *jneed = lang_alloc(c, (size_t)nf + 1);
        for (size_t q = 0; q < (size_t)na * (size_t)na; q++)
            if (aj.entry[q])
                need(c, aj.entry[q], jneed);
        for (size_t q = 0; q < (size_t)na * ((size_t)nf + 1); q++)
            if (aj.fixd[q])
                need(c, aj.fixd[q], jneed);
        LANG_C_CODE(c, "/* r and J = dr/dw, exact */\n"
                 "static void dk_alg_jacobian(double t, const double *y, const double *p, "
                 "double *w, const double *s, double *r, double *rb, double *J)\n{\n"
                 "    (void)s;\n    dk_alg_residual(t, y, p, w, r, rb);\n");
        emit_fixes(c, jneed);
        LANG_C_CODEF(c, "    for (int k = 0; k < %d; k++)\n        J[k] = 0.0;\n", na * na);
        for (int k = 0; k < na; k++) {
            LANG_C_CODEF(c, "    { /* d/d w[%d] */\n", k);
            for (int q = 0; q < nf; q++) {
                const int f = m->fix_order[q];
                const node *df = aj.fixd[(size_t)k * ((size_t)nf + 1) + (size_t)f];
                if (!df || df->kind == N_NUM)
                    continue;
                const lang_formula *fx = &LVEC_AT(m->fixes, lang_formula, f);
                line_dir(c, fx->pos);
                LANG_C_CODEF(c, "        const double dv%d_%d = ", k, f);
                expr(c, df, &x);
                LANG_C_CODEF(c, ";\n        (void)dv%d_%d;\n", k, f);
            }
            for (int i = 0; i < na; i++) {
                const node *e = aj.entry[(size_t)k * (size_t)na + (size_t)i];
                if (!e)
                    continue;
                line_dir(c, LVEC_AT(m->algeqs, lang_formula, i).pos);
                LANG_C_CODEF(c, "        J[%d] = ", i * na + k);
                expr(c, e, &x);
                LANG_C_CODE(c, ";\n");
            }
            LANG_C_CODE(c, "    }\n");
        }
        LANG_C_CODE(c, "}\n\n");
    }
    LANG_C_CODEF(c,
         "#define DK_ALG_EXACT_JACOBIAN %d\n#line 1 \"<dynkit: the solver of the algebraic "
         "equations>\"\n",
         exact);
    lang_c_solver(c);
}

/* Without the analytic Jacobian (more than LANG_MAX_JAC_STATES states): every right-hand
 * side must read only states inside the declared band. A state read is taken as a
 * dependence (a conservative check: x - x would count). */
static void check_band_by_structure(lang_ctx *c)
{
    lang_model *m = &c->m;
    span_memo mm;
    const size_t nf = (size_t)m->fixes.n + 1, nu = (size_t)m->funcs.n + 1;
    mm.fix = lang_alloc(c, nf * sizeof *mm.fix);
    mm.fun = lang_alloc(c, nu * sizeof *mm.fun);
    mm.fix_done = lang_alloc(c, nf); /* zeroed */
    mm.fun_done = lang_alloc(c, nu);
    mm.alg_done = 0;
    if (m->algs.n) { /* the equations' states first; what was memoized on the way may miss
                      * them: forgotten */
        const node alg = {.kind = N_ALG};
        (void)span_of(c, &alg, &mm);
        memset(mm.fix_done, 0, nf);
        memset(mm.fun_done, 0, nu);
    }
    for (int i = 0; i < m->states.n; i++) {
        const state_span s = span_of(c, LVEC_AT(m->states, lang_state, i).rhs, &mm);
        if (s.lo > s.hi)
            continue;
        const int j = i - s.lo > m->band_lo ? s.lo : s.hi - i > m->band_up ? s.hi : -1;
        if (j >= 0)
            lang_fail(c, m->band_pos,
                      "bandlo=%d, bandup=%d do not hold: %s' reads %s, %d place%s %s the "
                      "diagonal (the band of the Jacobian must contain every state each "
                      "right-hand side uses)",
                      m->band_lo, m->band_up, LVEC_AT(m->states, lang_state, i).name,
                      LVEC_AT(m->states, lang_state, j).name, abs(i - j),
                      abs(i - j) == 1 ? "" : "s", j < i ? "below" : "above");
    }
}

static void emit_events(lang_ctx *c)
{
    lang_model *m = &c->m;
    const ectx x = {NULL, 1};
    for (int i = 0; i < m->events.n; i++) {
        const lang_event *ev = &LVEC_AT(m->events, lang_event, i);
        node *root = ev->cond;
        unsigned char *needed = needed_by(c, &root, 1);
        LANG_C_CODEF(c, "static double dk_event%d(double t, const double *y, void *par)\n{\n"
                "    const double *p = (const double *)par;\n    (void)t;\n    (void)y;\n"
                "    (void)p;\n",
             i);
        if (needs_alg(c, &root, 1, needed))
            emit_alg_solve(c, ALG_FAIL_NAN);
        emit_fixes(c, needed);
        line_dir(c, ev->pos);
        LANG_C_CODE(c, "    return ");
        expr(c, ev->cond, &x);
        LANG_C_CODE(c, ";\n}\n\n");
        if (!ev->nassign)
            continue;
        /* XPPAUT applies a global's assignments in sequence: each sees the ones before */
        LANG_C_CODEF(c, "static int dk_reset%d(double t, double *y, void *par)\n{\n"
                "    const double *p = (const double *)par;\n    (void)t;\n    (void)p;\n",
             i);
        /* a parameter (XPPAUT's spike counter) is set after the global's assignments, which
         * all read its old value (flags.c), and the derived parameters follow it */
        int n_par = 0;
        for (int k = 0; k < ev->nassign; k++)
            if (ev->assign[k].state < 0)
                LANG_C_CODEF(c, "    double dk_par%d = 0.0;\n", n_par++);
        n_par = 0;
        for (int k = 0; k < ev->nassign; k++) {
            const lang_assign *a = &ev->assign[k];
            root = a->value;
            needed = needed_by(c, &root, 1);
            LANG_C_CODE(c, "    {\n");
            if (needs_alg(c, &root, 1, needed))
                emit_alg_solve(c, ALG_FAIL_STATUS);
            emit_fixes(c, needed);
            line_dir(c, a->pos);
            if (a->state >= 0)
                LANG_C_CODEF(c, "        y[%d] = ", a->state);
            else
                LANG_C_CODEF(c, "        dk_par%d = ", n_par++);
            expr(c, a->value, &x);
            LANG_C_CODE(c, ";\n    }\n");
        }
        if (n_par) {
            LANG_C_CODE(c, "    double *pw = (double *)par;\n");
            n_par = 0;
            for (int k = 0; k < ev->nassign; k++)
                if (ev->assign[k].state < 0)
                    LANG_C_CODEF(c, "    pw[%d] = dk_par%d;\n", -1 - ev->assign[k].state,
                                 n_par++);
            const ectx px = {NULL, 0};
            for (int k = 0; k < m->derived.n; k++) {
                const int d = m->derived_order[k];
                const lang_formula *f = &LVEC_AT(m->derived, lang_formula, d);
                LANG_C_CODEF(c, "    pw[%d] = ", m->params.n + d);
                expr(c, f->expr, &px);
                LANG_C_CODE(c, ";\n");
            }
        }
        LANG_C_CODE(c, "    return 0;\n}\n\n");
    }
}

/* the states' (dk_states) or the outputs' (dk_outputs_vars) names and documentation */
static void vars(lang_ctx *c, lvec *v, int states)
{
    if (states)
        LANG_C_CODE(c, "static const dyn_var dk_states[] = {\n");
    else
        LANG_C_CODE(c, "static const dyn_var dk_outputs_vars[] = {\n");
    for (int i = 0; i < v->n; i++) {
        const char *name;
        const lang_doc *d;
        if (states) {
            const lang_state *s = &LVEC_AT(*v, lang_state, i);
            name = s->name;
            d = &s->doc;
        } else {
            const lang_formula *f = &LVEC_AT(*v, lang_formula, i);
            name = f->name;
            d = &f->doc;
        }
        LANG_C_CODE(c, "    {");
        lang_c_str(c, name);
        LANG_C_CODE(c, ", ");
        lang_c_str(c, d->unit);
        LANG_C_CODE(c, ", ");
        lang_c_str(c, d->description);
        LANG_C_CODE(c, "},\n");
    }
    LANG_C_CODE(c, "};\n");
}

/* The Jacobian, computed first (it decides the partials of user functions to write). One
 * too large to write is left out with a note (the stiff methods then use differences); the
 * model stays. Returns 1 when it was written. */
static int try_jacobian(lang_ctx *c, jac_plan *jp)
{
    jmp_buf jac_fail;
    jmp_buf *outer = c->fail;
    const long work = c->work; /* a Jacobian given up gives its work back to the rest */
    c->copies = 0;
    c->fail = &jac_fail;
    if (setjmp(jac_fail) == 0) {
        emit_jacobian(c, jp);
        c->fail = outer;
        return 1;
    }
    c->fail = outer;
    c->work = work;
    if (c->m.band_found) /* the band found in a pattern that is not kept */
        c->m.has_band = c->m.band_found = 0;
    derivative_failed(c, jp,
                      "no analytic Jacobian: ", "; the stiff methods use finite differences");
    if (jp->writing) { /* failed while writing: back to the main text */
        lang_c_discard(c);
        lang_c_splice(c, jp->before);
        jp->writing = 0;
    }
    jp->text = (lang_ctext){NULL, 0};
    return 0;
}

char *lang_emit_c(lang_ctx *c)
{
    lang_model *m = &c->m;
    const int n = m->states.n, np = m->params.n, nd = m->derived.n;
    /* default values: parameters, then derived ones; initial states */
    double *pv = lang_alloc(c, ((size_t)np + nd + 1) * sizeof *pv);
    for (int i = 0; i < np; i++)
        pv[i] = LVEC_AT(m->params, lang_param, i).value;
    for (int i = 0; i < nd; i++) {
        const int k = m->derived_order[i];
        pv[np + k] = lang_eval(c, LVEC_AT(m->derived, lang_formula, k).expr, NULL, pv);
    }
    double *y0 = lang_alloc(c, (size_t)n * sizeof *y0);
    for (int i = 0; i < n; i++) {
        const node *in = LVEC_AT(m->states, lang_state, i).init;
        y0[i] = in ? lang_eval(c, in, NULL, pv) : 0.0;
    }
    jac_plan jp = {0};
    jp.used = lang_alloc(c, ((size_t)m->funcs.n + 1) * LANG_MAX_ARGS);
    c->fused = lang_alloc(c, ((size_t)m->funcs.n + 1) * (LANG_MAX_ARGS + 1));
    if (m->has_band && (m->band_lo >= n || m->band_up >= n))
        lang_fail(c, m->band_pos,
                  "bandlo=%d, bandup=%d: a bandwidth of the Jacobian must be below the number "
                  "of states, %d",
                  m->band_lo, m->band_up, n);
    if (m->n_delays && m->algs.n)
        lang_fail(c, LVEC_AT(m->algs, lang_formula, 0).pos,
                  "algebraic equations in a model with delay(): not supported together");
    int with_jac = n <= LANG_MAX_JAC_STATES && m->algs.n == 0 && !m->no_jacobian &&
                   !m->n_delays;
    if (m->algs.n)
        lang_note(c, LVEC_AT(m->algs, lang_formula, 0).pos,
                  "no analytic Jacobian: the algebraic variables are solved for numerically; "
                  "the stiff methods use finite differences");
    if (with_jac) {
        with_jac = try_jacobian(c, &jp);
        if (with_jac && jp.band_bad_i >= 0)
            lang_fail(c, m->band_pos,
                      "bandlo=%d, bandup=%d do not hold: d(%s')/d(%s) is not zero, %d place%s "
                      "%s the diagonal (the band of the Jacobian must contain every state each "
                      "right-hand side uses)",
                      m->band_lo, m->band_up,
                      LVEC_AT(m->states, lang_state, jp.band_bad_i).name,
                      LVEC_AT(m->states, lang_state, jp.band_bad_j).name,
                      abs(jp.band_bad_i - jp.band_bad_j),
                      abs(jp.band_bad_i - jp.band_bad_j) == 1 ? "" : "s",
                      jp.band_bad_i > jp.band_bad_j ? "below" : "above");
    } else if (m->algs.n == 0 && !m->no_jacobian) {
        lang_note(c, (lpos){0, 0}, "%d states: no analytic Jacobian (at most %d); the stiff "
                  "methods use finite differences", n, LANG_MAX_JAC_STATES);
    }
    if (m->has_band && !with_jac)
        check_band_by_structure(c); /* the band is then formed by banded differences */

    emit_inputs(c);
    emit_alg_functions(c, &jp);
    emit_rhs(c);
    emit_outputs(c);
    lang_emit_jump(c, noise_offset(m), fixes_for);
    emit_table_files(c);
    emit_prepare(c);
    const int has_init = emit_initial(c, y0);
    lang_c_splice(c, jp.text);
    emit_events(c);
    if (m->bdrys.n)
        lang_emit_bdry(c, state_expr);
    if (m->n_delays)
        lang_emit_delay_model(c, delay_offset(m), history_expr);
    if (lang_volt_model(m))
        lang_emit_volterra(c, volt_offset(m), state_expr, fixes_for);

    /* data */
    LANG_C_CODE(c, "#line 1 \"<dynkit: the model's tables>\"\n");
    vars(c, &m->states, 1);
    LANG_C_CODE(c, "static const double dk_y0[] = {");
    for (int i = 0; i < n; i++) {
        if (i)
            LANG_C_CODE(c, ", ");
        lang_c_num(c, y0[i]);
    }
    LANG_C_CODE(c, "};\n");
    if (np) {
        LANG_C_CODE(c, "static const dyn_param dk_params[] = {\n");
        for (int i = 0; i < np; i++) {
            const lang_param *p = &LVEC_AT(m->params, lang_param, i);
            LANG_C_CODE(c, "    {");
            lang_c_str(c, p->name);
            LANG_C_CODE(c, ", ");
            lang_c_str(c, p->doc.unit);
            LANG_C_CODE(c, ", ");
            lang_c_str(c, p->doc.description);
            LANG_C_CODEF(c, ", %d * sizeof(double), ", i);
            lang_c_num(c, p->value);
            LANG_C_CODE(c, "},\n");
        }
        LANG_C_CODE(c, "};\n");
    }
    if (m->auxs.n)
        vars(c, &m->auxs, 0);
    if (with_jac && pattern_kept(&jp, n)) { /* the exact Jacobian's pattern, CSC */
        LANG_C_CODE(c, "static const int dk_jac_colptr[] = {");
        for (int k = 0; k <= n; k++)
        {
            LANG_C_CODEF(c, "%d, ", jp.colptr[k]);
            if (k % 16 == 15)
                LANG_C_CODE(c, "\n");
        }
        LANG_C_CODE(c, "};\nstatic const int dk_jac_rowind[] = {");
        for (int k = 0; k < jp.nnz; k++)
        {
            LANG_C_CODEF(c, "%d, ", jp.rowind[k]);
            if (k % 16 == 15)
                LANG_C_CODE(c, "\n");
        }
        LANG_C_CODE(c, "};\n");
    }
    emit_input_vars(c);
    if (m->events.n) {
        LANG_C_CODE(c, "static const dyn_event dk_events[] = {\n");
        for (int i = 0; i < m->events.n; i++) {
            const lang_event *ev = &LVEC_AT(m->events, lang_event, i);
            LANG_C_CODE(c, "    {");
            lang_c_str(c, ev->name);
            LANG_C_CODE(c, ", ");
            const char *desc = ev->description;
            if (!desc && ev->is_global)
                desc = lang_printf(c, "XPPAUT global on line %d: resets the state", ev->pos.line);
            lang_c_str(c, desc);
            LANG_C_CODEF(c, ", dk_event%d, %d, %d, ", i, ev->direction, ev->terminal);
            if (ev->nassign)
                LANG_C_CODEF(c, "dk_reset%d},\n", i);
            else
                LANG_C_CODE(c, "NULL},\n");
        }
        LANG_C_CODE(c, "};\n");
    }
    if (m->noises.n) {
        LANG_C_CODE(c, "static const int dk_noise_kinds[] = {");
        for (int i = 0; i < m->noises.n; i++) {
            if (i)
                LANG_C_CODE(c, ", ");
            LANG_C_CODEF(c, "%d", LVEC_AT(m->noises, lang_noise, i).kind);
        }
        LANG_C_CODE(c, "};\n");
    }
    /* 0 and NULL when the file names none: DYN_MODEL_RTOL, DYN_MODEL_ATOL, DYN_MODEL_METHOD */
    const double rtol = m->rtol > 0 ? m->rtol : 0.0;
    const double atol = m->atol > 0 ? m->atol : 0.0;
    LANG_C_CODE(c, "\nstatic const dyn_model dk_model = {\n    .name = ");
    lang_c_str(c, m->name);
    LANG_C_CODE(c, ",\n    .title = ");
    lang_c_str(c, m->title);
    LANG_C_CODE(c, ",\n    .description = ");
    lang_c_str(c, m->description);
    LANG_C_CODEF(c, ",\n    .n_states = %d,\n    .states = dk_states,\n    .y0 = dk_y0,\n"
                    "    .n_params = %d,\n    .params = ",
                 n, np);
    CODE_OR_NULL(c, np, "dk_params");
    LANG_C_CODEF(c, ",\n    .par_size = %d * sizeof(double),\n    .n_outputs = %d,\n"
                    "    .outputs = ",
                 par_doubles(m) > 0 ? par_doubles(m) : 1, m->auxs.n);
    CODE_OR_NULL(c, m->auxs.n, "dk_outputs_vars");
    LANG_C_CODE(c, ",\n    .rhs = dk_rhs,\n    .compute_outputs = ");
    CODE_OR_NULL(c, m->auxs.n, "dk_outputs");
    LANG_C_CODE(c, ",\n    .prepare = dk_prepare,\n    .warn = NULL,\n");
    LANG_C_CODE(c, "    .t0 = ");
    lang_c_num(c, m->t0);
    LANG_C_CODE(c, ",\n    .t1 = ");
    lang_c_num(c, m->t0 + m->total);
    LANG_C_CODE(c, ",\n    .step = ");
    lang_c_num(c, m->dt);
    LANG_C_CODE(c, ",\n    .method = ");
    if (m->noises.n)
        lang_c_str(c, lang_noise_method(c));
    else if (m->method)
        lang_c_str(c, m->method);
    else
        LANG_C_CODE(c, "NULL");
    LANG_C_CODEF(c, ",\n    .n_inputs = %d,\n    .inputs = ", m->n_inputs);
    CODE_OR_NULL(c, m->n_inputs, "dk_inputs_vars");
    LANG_C_CODE(c, ",\n    .set_input = ");
    CODE_OR_NULL(c, m->n_inputs, "dk_set_input");
    LANG_C_CODE(c, ",\n    .jacobian = ");
    CODE_OR_NULL(c, with_jac, "dk_jacobian");
    LANG_C_CODEF(c, ",\n    .n_events = %d,\n    .events = ", m->events.n);
    CODE_OR_NULL(c, m->events.n, "dk_events");
    LANG_C_CODE(c, ",\n    .samples = DYN_SAMPLES_GRID,\n    .initial_state = ");
    CODE_OR_NULL(c, has_init, "dk_initial_state");
    LANG_C_CODE(c, ",\n");
    LANG_C_CODE(c, "    .rtol = ");
    lang_c_num(c, rtol);
    LANG_C_CODE(c, ",\n    .atol = ");
    lang_c_num(c, atol);
    LANG_C_CODE(c, ",\n    .phase_x = ");
    if (m->xp)
        lang_c_str(c, m->xp);
    else
        LANG_C_CODE(c, "NULL");
    LANG_C_CODE(c, ",\n    .phase_y = ");
    if (m->yp)
        lang_c_str(c, m->yp);
    else
        LANG_C_CODE(c, "NULL");
    LANG_C_CODE(c, ",\n    .time_unit = ");
    if (m->time_unit && *m->time_unit)
        lang_c_str(c, m->time_unit);
    else
        LANG_C_CODE(c, "NULL");
    LANG_C_CODE(c, ",\n    .phase_window = {");
    for (int k = 0; k < 4; k++) {
        if (k)
            LANG_C_CODE(c, ", ");
        lang_c_num(c, m->window[k]);
    }
    LANG_C_CODE(c, "}");
    if (m->poimap) {
        LANG_C_CODEF(c, ",\n    .poincare = {%d, ", m->poimap);
        lang_c_str(c, m->poivar);
        LANG_C_CODE(c, ", ");
        lang_c_num(c, m->poipln);
        LANG_C_CODEF(c, ", %d, %d}", m->poisgn, m->poistop);
    }
    LANG_C_CODE(c, ",\n    .source = ");
    lang_c_str(c, c->path);
    LANG_C_CODE(c, ",\n    .t_trans = ");
    lang_c_num(c, m->trans);
    LANG_C_CODEF(c, ",\n    .every = %ld,\n    .bound = ", m->nout);
    lang_c_num(c, m->bound);
    if (with_jac && pattern_kept(&jp, n)) {
        LANG_C_CODEF(c, ",\n    .jac_pattern = {%d, %d, dk_jac_colptr, dk_jac_rowind}", n,
                     jp.nnz);
        if (!m->has_band)
            LANG_C_CODE(c, ",\n    .jacobian_sparse = dk_jacobian_sparse");
    }
    if (m->has_band) {
        LANG_C_CODEF(c, ",\n    .jac_banded = 1,\n    .jac_lower = %d,\n    .jac_upper = %d,\n"
                        "    .jacobian_band = ",
                     m->band_lo, m->band_up);
        CODE_OR_NULL(c, with_jac, "dk_jacobian_band");
    }
    if (m->noises.n)
        LANG_C_CODEF(c, ",\n    .n_noise = %d,\n    .noise_kinds = dk_noise_kinds,\n"
                        "    .noise_offset = %d * sizeof(double),\n    .noise_class = %d",
                     m->noises.n, noise_offset(m), m->noise_class);
    if (m->n_delays)
        LANG_C_CODE(c, ",\n    .delay = &dk_delay_model");
    if (lang_volt_model(m))
        LANG_C_CODE(c, ",\n    .volterra = &dk_volterra_model");
    if (m->markovs.n)
        LANG_C_CODE(c, ",\n    .jump = dk_jump");
    if (m->bdrys.n)
        LANG_C_CODEF(c, ",\n    .n_bdry = %d,\n    .bdry = dk_bdry,\n    .bdry_text = dk_bdry_text",
                     m->bdrys.n);
    if (lang_bdry_has_hom(m))
        LANG_C_CODE(c, ",\n    .hom = &dk_hom");
    if (m->events.n)
        LANG_C_CODE(c, ",\n    .xppaut_globals = 1");
    if (m->n_table_draws)
        LANG_C_CODEF(c, ",\n    .seed_offset = %d * sizeof(double)", seed_offset(m));
    LANG_C_CODE(c, ",\n};\n\nconst dyn_model *dynkit_model(void) { return &dk_model; }\n");
    /* the functions the text calls, then what comes before it all */
    const lang_ctext main_text = lang_c_take(c);
    unsigned char *done = lang_alloc(c, ((size_t)m->funcs.n + 1) * (LANG_MAX_ARGS + 1));
    emit_function_defs(c, &jp, done);
    const lang_ctext defs = lang_c_take(c);
    /* the file's path and name are in .source and .name (string literals), not here */
    LANG_C_CODE(c, "/* C text generated by dynkit from a model file (dk_model.source names it; "
                   "see \"The .ode\n * format\" in docs/model-files.md). Edit the model file, "
                   "not this text. */\n"
                   "#include <math.h>\n#include <stddef.h>\n#include <stdio.h>\n");
    if (table_files(m) || m->n_inputs || m->n_delays)
        LANG_C_CODE(c, "#include <string.h>\n");
    LANG_C_CODE(c, "\n#include <dynkit/model.h>\n");
    if (m->n_delays)
        LANG_C_CODE(c, "#include <dynkit/delay.h>\n");
    if (lang_volt_model(m))
        LANG_C_CODE(c, "#include <dynkit/volterra.h>\n");
    if (m->n_table_draws)
        LANG_C_CODE(c, "#include <dynkit/sde.h>\n");
    if (m->n_inputs)
        LANG_C_CODE(c, "#include <dynkit/input.h>\n\n");
    else
        LANG_C_CODE(c, "\n");
    if (m->algs.n)
        emit_alg_constants(c);
    helpers(c);
    if (m->n_delays)
        lang_emit_delay_helper(c, delay_offset(m));
    emit_function_protos(c);
    lang_c_splice(c, defs);
    if (defs.len)
        LANG_C_CODE(c, "\n");
    lang_c_splice(c, main_text);
    char *r = c->out;
    c->out = NULL;
    return r;
}
