/* SPDX-License-Identifier: BSD-3-Clause */
/* The C text of an .ode model: a translation unit that defines
 * `const dyn_model *dynkit_model(void)` (dynkit/model.h), compiled by the jit layer.
 *
 * Conventions (docs/model-files.md): states are y[i] in the order of their equations;
 * the parameter struct is an array of doubles p[], the parameters in the order of the file
 * then the derived parameters (computed by prepare); fixed temporaries are const locals
 * v_NAME computed in dependency order where needed; user functions are static functions
 * u_NAME(a_ARG..., t, y, p), their partial derivatives udK_NAME; XPPAUT's functions are
 * static inline helpers dk_*; every user name carries a prefix, so none can clash with C or
 * libm. A `#line N "file"` precedes the code of each source line, so a compiler's message
 * points at the model's own line. Nothing mutable at file scope: the model is re-entrant.
 */
#include <limits.h>
#include <setjmp.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lang/lang_internal.h"

/* ---- output buffer ---- */

static void put(lang_ctx *c, const char *s, size_t n)
{
    if (c->out_len + n + 1 > c->out_cap) {
        size_t cap = c->out_cap ? c->out_cap : 4096;
        if (c->out_len + n + 1 > LANG_MAX_OUTPUT)
            lang_fail(c, (lpos){0, 0}, "the model's C text would be too large (more than %u "
                      "MB)", (unsigned)(LANG_MAX_OUTPUT >> 20));
        while (c->out_len + n + 1 > cap)
            cap *= 2;
        char *o = realloc(c->out, cap);
        if (!o)
            lang_oom(c);
        c->out = o;
        c->out_cap = cap;
    }
    memcpy(c->out + c->out_len, s, n);
    c->out_len += n;
    c->out[c->out_len] = '\0';
}

static void puts_(lang_ctx *c, const char *s) { put(c, s, strlen(s)); }

static void outf(lang_ctx *c, const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (n < 0)
        lang_oom(c);
    if ((size_t)n < sizeof buf) {
        put(c, buf, (size_t)n);
        return;
    }
    char *big = lang_alloc(c, (size_t)n + 1);
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    put(c, big, (size_t)n);
}

/* A C string literal of s (NULL: ""); runs of plain characters are written at once. */
static void str_lit(lang_ctx *c, const char *s)
{
    puts_(c, "\"");
    const unsigned char *q = (const unsigned char *)(s ? s : "");
    while (*q) {
        const unsigned char *run = q;
        while (*q && *q >= 32 && *q < 127 && *q != '"' && *q != '\\' && *q != '?')
            q++;
        if (q > run)
            put(c, (const char *)run, (size_t)(q - run));
        if (!*q)
            break;
        char b[8];
        if (*q == '"' || *q == '\\' || *q == '?') {
            b[0] = '\\';
            b[1] = (char)*q;
            put(c, b, 2);
        } else if (*q == '\n') {
            puts_(c, "\\n");
        } else {
            snprintf(b, sizeof b, "\\%03o", *q);
            puts_(c, b);
        }
        q++;
    }
    puts_(c, "\"");
}

static void line_dir(lang_ctx *c, lpos p)
{
    if (p.line <= 0)
        return;
    if (!c->path_lit) { /* the path as a C string, once */
        char *saved = c->out;
        const size_t len = c->out_len, cap = c->out_cap;
        c->out = NULL;
        c->out_len = c->out_cap = 0;
        c->out_saved2 = saved;
        str_lit(c, c->path);
        c->path_lit = lang_strdup(c, c->out);
        free(c->out);
        c->out = saved;
        c->out_len = len;
        c->out_cap = cap;
        c->out_saved2 = NULL;
    }
    outf(c, "#line %d %s\n", p.line, c->path_lit);
}

static void num_lit(lang_ctx *c, double v)
{
    if (isnan(v)) {
        puts_(c, "NAN");
        return;
    }
    if (isinf(v)) {
        puts_(c, v > 0 ? "HUGE_VAL" : "(-HUGE_VAL)");
        return;
    }
    char b[40];
    snprintf(b, sizeof b, "%.17g", v);
    if (!strpbrk(b, ".en"))
        strcat(b, ".0");
    if (v < 0 || (v == 0 && signbit(v)))
        outf(c, "(%s)", b);
    else
        puts_(c, b);
}

/* ---- expressions ---- */

typedef struct ectx {
    const lang_func *func; /* the function whose body this is, or NULL */
    int has_state;         /* y and t are in scope */
} ectx;

static const char *c_fun(int f)
{
    switch (f) {
    case F_LN: return "log";
    case F_ABS: return "fabs";
    case F_HEAV: return "dk_heav";
    case F_SIGN: return "dk_sign";
    case F_MOD: return "dk_mod";
    case F_FLR: return "floor";
    case F_MAX: return "dk_max";
    case F_MIN: return "dk_min";
    default: return lang_fun_name(f);
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
        puts_(c, ", ");
    }
    puts_(c, x->has_state ? "t, y, p)" : "0.0, (const double *)0, p)");
}

static void expr(lang_ctx *c, const node *e, const ectx *x)
{
    if (++c->depth > 16 * LANG_MAX_DEPTH)
        lang_fail(c, e->pos, "expression too deep to write as C");
    lang_model *m = &c->m;
    switch (e->kind) {
    case N_NUM: num_lit(c, e->num); break;
    case N_TIME: puts_(c, "t"); break;
    case N_STATE: outf(c, "y[%d]", e->index); break;
    case N_PARAM:
        if (m->param_input && e->index < m->params.n && m->param_input[e->index] >= 0 &&
            (x->has_state || x->func))
            outf(c, "dk_input(p, t, %d, %d)", m->param_input[e->index], e->index);
        else
            outf(c, "p[%d]", e->index);
        break;
    case N_FIX: outf(c, "v_%s", LVEC_AT(m->fixes, lang_formula, e->index).name); break;
    case N_ALG: outf(c, "w[%d]", e->index); break;
    case N_DFIX:
        outf(c, "dv%d_%s", e->op, LVEC_AT(m->fixes, lang_formula, e->index).name);
        break;
    case N_ARG: outf(c, "a_%s", x->func ? x->func->argnames[e->index] : "?"); break;
    case N_NEG:
        puts_(c, "(-");
        expr(c, e->args[0], x);
        puts_(c, ")");
        break;
    case N_NOT:
        c->helpers |= H_NOT;
        puts_(c, "dk_not(");
        expr(c, e->args[0], x);
        puts_(c, ")");
        break;
    case N_IF:
        puts_(c, "((");
        expr(c, e->args[0], x);
        puts_(c, ") != 0.0 ? (");
        expr(c, e->args[1], x);
        puts_(c, ") : (");
        expr(c, e->args[2], x);
        puts_(c, "))");
        break;
    case N_BIN: {
        const node *a = e->args[0], *b = e->args[1];
        switch (e->op) {
        case OP_ADD:
        case OP_SUB:
        case OP_MUL:
        case OP_DIV:
            puts_(c, "(");
            expr(c, a, x);
            puts_(c, e->op == OP_ADD ? " + " : e->op == OP_SUB ? " - " : e->op == OP_MUL ? " * "
                                                                                        : " / ");
            expr(c, b, x);
            puts_(c, ")");
            break;
        case OP_POW:
            if (b->kind == N_NUM && b->num == 2.0) {
                c->helpers |= H_SQ;
                puts_(c, "dk_sq(");
                expr(c, a, x);
                puts_(c, ")");
            } else {
                c->helpers |= H_POW;
                puts_(c, "dk_pow(");
                expr(c, a, x);
                puts_(c, ", ");
                expr(c, b, x);
                puts_(c, ")");
            }
            break;
        case OP_AND:
        case OP_OR:
            puts_(c, "((");
            expr(c, a, x);
            puts_(c, e->op == OP_AND ? ") != 0.0 && (" : ") != 0.0 || (");
            expr(c, b, x);
            puts_(c, ") != 0.0 ? 1.0 : 0.0)");
            break;
        default:
            puts_(c, "((");
            expr(c, a, x);
            outf(c, ") %s (", lang_op_text(e->op));
            expr(c, b, x);
            puts_(c, ") ? 1.0 : 0.0)");
            break;
        }
        break;
    }
    case N_FUN:
        if (e->op == F_SPECIAL) { /* computed before the statements (emit_fixes) */
            outf(c, "sp_%s[%d]", LVEC_AT(m->specials, lang_special, e->index).name,
                 (int)e->args[0]->num);
            break;
        }
        if (e->op == F_TABLE || e->op == F_TABLE_SLOPE) {
            const lang_table *tb = &LVEC_AT(m->tables, lang_table, e->index);
            c->helpers |= H_TABLE;
            outf(c, "%s(p + %d, %ld, ", e->op == F_TABLE ? "dk_table" : "dk_table_slope",
                 tb->offset, tb->npts);
            num_lit(c, tb->lo);
            puts_(c, ", ");
            num_lit(c, table_dx(tb));
            puts_(c, ", ");
            expr(c, e->args[0], x);
            puts_(c, ")");
            break;
        }
        c->helpers |= e->op == F_HEAV  ? H_HEAV
                      : e->op == F_SIGN ? H_SIGN
                      : e->op == F_MOD  ? H_MOD
                      : e->op == F_MAX  ? H_MAX
                      : e->op == F_MIN  ? H_MIN
                                        : 0;
        outf(c, "%s(", c_fun(e->op));
        for (int i = 0; i < e->nargs; i++) {
            if (i)
                puts_(c, ", ");
            expr(c, e->args[i], x);
        }
        puts_(c, ")");
        break;
    case N_UFUN:
        mark_func(c, e->index, 0);
        outf(c, "u_%s(", LVEC_AT(m->funcs, lang_func, e->index).name);
        call_args(c, e, x);
        break;
    case N_UFUN_D:
        mark_func(c, e->index, 1 + e->op);
        outf(c, "ud%d_%s(", e->op, LVEC_AT(m->funcs, lang_func, e->index).name);
        call_args(c, e, x);
        break;
    default: puts_(c, "NAN"); break;
    }
    c->depth--;
}

/* ---- fixed temporaries (and network sums) needed by a set of expressions ---- */

/* needed: one flag per fixed quantity, then one per network sum */
static void need(lang_ctx *c, const node *e, unsigned char *needed)
{
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

/* A network sum's block of len elements as a C array expression: y + first for states, or
 * a local array PREFIX_NAME of the fixed quantities' values (written first). */
static const char *special_block(lang_ctx *c, const lang_special *sp, int kind, int first,
                                 int len, const char *prefix)
{
    if (kind == N_STATE)
        return lang_printf(c, "y + %d", first);
    outf(c, "    const double %s_%s[%d] = {", prefix, sp->name, len);
    for (int k = 0; k < len; k++)
        outf(c, "%sv_%s", k ? ", " : "", LVEC_AT(c->m.fixes, lang_formula, first + k).name);
    puts_(c, "};\n");
    return lang_printf(c, "%s_%s", prefix, sp->name);
}

/* The network sums flagged in needed, after the fixed quantities: sp_NAME[j] for each j. */
static void emit_specials(lang_ctx *c, const unsigned char *needed)
{
    const lang_model *m = &c->m;
    for (int i = 0; i < m->specials.n; i++) {
        if (!needed[m->fixes.n + i])
            continue;
        const lang_special *sp = &LVEC_AT(m->specials, lang_special, i);
        const lang_table *tb = &LVEC_AT(m->tables, lang_table, sp->table);
        if (sp->kind == LANG_SUM_CONV || sp->kind == LANG_SUM_FCONV)
            c->helpers |= H_CONV;
        line_dir(c, sp->pos);
        const char *u = special_block(c, sp, sp->root_kind, sp->root, sp->ulen, "spu");
        outf(c, "    double sp_%s[%d];\n", sp->name, sp->n);
        if (sp->kind == LANG_SUM_CONV) {
            outf(c, "    dk_conv(sp_%s, %d, %d, %d, p + %d, %s);\n", sp->name, sp->n, sp->m,
                 sp->type, tb->offset, u);
            continue;
        }
        if (sp->kind == LANG_SUM_MMULT || sp->kind == LANG_SUM_SPARSE) {
            /* mmult: w[i + m j] u(i); sparse: w[j m + i] u(l[j m + i]) (indices checked by
             * prepare) */
            const int sparse = sp->kind == LANG_SUM_SPARSE;
            outf(c, "    for (int j = 0; j < %d; j++) {\n        double s = 0.0;\n"
                    "        for (int i = 0; i < %d; i++)\n",
                 sp->n, sp->m);
            if (sparse)
                outf(c, "            s += (p + %d)[j * %d + i] * (%s)[(long)(p + %d)[j * %d + i]];\n",
                     tb->offset, sp->m, u,
                     LVEC_AT(m->tables, lang_table, sp->index_table).offset, sp->m);
            else
                outf(c, "            s += (p + %d)[i + %d * j] * (%s)[i];\n", tb->offset, sp->m,
                     u);
            outf(c, "        sp_%s[j] = s;\n    }\n", sp->name);
            continue;
        }
        /* fconv: f(u(j+i), v(j)) in place of u(j+i) */
        const char *v = special_block(c, sp, sp->vroot_kind, sp->vroot, sp->n, "spv");
        mark_func(c, sp->func, 0);
        outf(c, "    for (int j = 0; j < %d; j++) {\n        double s = 0.0;\n"
                "        for (int i = -%d; i <= %d; i++)\n"
                "            s += (p + %d)[%d + i] * u_%s(dk_conv_at(%s, %d, j + i, %d), (%s)[j], "
                "t, y, p);\n        sp_%s[j] = s;\n    }\n",
             sp->n, sp->m, sp->m, tb->offset, sp->m,
             LVEC_AT(m->funcs, lang_func, sp->func).name, u, sp->n, sp->type, v, sp->name);
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
        outf(c, "    const double v_%s = ", f->name);
        expr(c, f->expr, &x);
        puts_(c, ";\n");
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

/* w at (t, y) into a local array; on failure the statement fail. In the right-hand side
 * (keep), the solution and its point are the next start. */
static void emit_alg_solve(lang_ctx *c, const char *fail, int keep)
{
    outf(c, "    double w[DK_ALG_M];\n    if (dk_alg_solve(t, y, p, w))\n        %s\n", fail);
    if (keep)
        puts_(c, "    dk_alg_keep(t, y, par, w);\n");
}

/* The constants of alg_solver.c's text: sizes, slots in p, limits. */
static void emit_alg_constants(lang_ctx *c)
{
    const lang_model *m = &c->m;
    const int na = m->algs.n, n = m->states.n, off = alg_offset(m);
    outf(c,
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
        puts_(c, "static inline double dk_heav(double x) { return x < 0.0 ? 0.0 : 1.0; }\n");
    if (h & H_SIGN)
        puts_(c, "static inline double dk_sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? "
                 "-1.0 : 0.0); }\n");
    if (h & H_MOD)
        puts_(c, "static inline double dk_mod(double x, double y)\n"
                 "{\n    double z = fmod(x, y);\n    if (z < 0.0)\n        z += y;\n"
                 "    return z;\n}\n");
    if (h & H_MAX)
        puts_(c, "static inline double dk_max(double x, double y) { return x > y ? x : y; }\n");
    if (h & H_MIN)
        puts_(c, "static inline double dk_min(double x, double y) { return x < y ? x : y; }\n");
    if (h & H_NOT)
        puts_(c, "static inline double dk_not(double x) { return x == 0.0 ? 1.0 : 0.0; }\n");
    if (h & H_SQ)
        puts_(c, "static inline double dk_sq(double x) { return x * x; }\n");
    if (h & H_POW)
        puts_(c, "static inline double dk_pow(double x, double y) { return y == 2.0 ? x * x : "
                 "pow(x, y); }\n");
    if (h & H_CONV) /* XPPAUT's conv: sum w[m+i] u(j+i), u beyond its ends 0, wrapped, or
                     * mirrored at both ends; as XPPAUT 6.11 (measured: docs/model-files.md),
                     * 0 from 2n away on (mirrored) and below -2n (wrapped) */
        puts_(c, "static inline double dk_conv_at(const double *u, int n, int q, int type)\n"
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
        puts_(c, "static inline long dk_table_at(long n, double lo, double dx, double x)\n"
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
        puts_(c, "\n");
}

static void func_proto(lang_ctx *c, const lang_func *f, int partial)
{
    if (partial < 0)
        outf(c, "static double u_%s(", f->name);
    else
        outf(c, "static double ud%d_%s(", partial, f->name);
    for (int k = 0; k < f->nargs; k++)
        outf(c, "double a_%s, ", f->argnames[k]);
    puts_(c, "double t, const double *y, const double *p)");
}

/* ---- the whole unit ---- */

typedef struct jac_plan {
    unsigned char *used;  /* partials of user functions used (funcs * LANG_MAX_ARGS) */
    node **partial;       /* their bodies */
    char *text;           /* the Jacobian's C text */
    size_t text_len;
    int band_bad_i, band_bad_j; /* an entry outside the declared band (-1: none) */
} jac_plan;

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
                puts_(c, "\n");
                line_dir(c, fn->pos);
                func_proto(c, fn, k);
                puts_(c, "\n{\n    (void)t;\n    (void)y;\n    (void)p;\n");
                for (int a = 0; a < fn->nargs; a++)
                    outf(c, "    (void)a_%s;\n", fn->argnames[a]);
                puts_(c, "    return ");
                expr(c, body, &x);
                puts_(c, ";\n}\n");
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
                    puts_(c, "/* user functions and their partial derivatives */\n");
                any = 1;
                func_proto(c, fn, k);
                puts_(c, ";\n");
            }
    }
    if (any)
        puts_(c, "\n");
}

/* The text written so far, moved into the arena; the output starts empty. */
static char *take_text(lang_ctx *c, size_t *len)
{
    char *s = lang_strndup(c, c->out ? c->out : "", c->out ? c->out_len : 0);
    *len = c->out ? c->out_len : 0;
    free(c->out);
    c->out = NULL;
    c->out_len = c->out_cap = 0;
    return s;
}

static void emit_rhs(lang_ctx *c)
{
    lang_model *m = &c->m;
    node **roots = lang_alloc(c, (size_t)m->states.n * sizeof *roots);
    for (int i = 0; i < m->states.n; i++)
        roots[i] = LVEC_AT(m->states, lang_state, i).rhs;
    unsigned char *needed = needed_by(c, roots, m->states.n);
    puts_(c, "static int dk_rhs(double t, const double *y, double *dydt, void *par)\n{\n"
             "    const double *p = (const double *)par;\n    (void)t;\n    (void)y;\n"
             "    (void)p;\n");
    if (m->algs.n) /* also when no derivative reads them: the branch is tracked here. No
                    * solution: derivatives that are not finite, so that an adaptive method
                    * tries a shorter step, as after any trial state that is not finite */
        emit_alg_solve(c,
                       "{\n        for (int i = 0; i < DK_ALG_N; i++)\n"
                       "            dydt[i] = NAN;\n        return 0;\n    }",
                       1);
    emit_fixes(c, needed);
    const ectx x = {NULL, 1};
    for (int i = 0; i < m->states.n; i++) {
        const lang_state *s = &LVEC_AT(m->states, lang_state, i);
        line_dir(c, s->pos);
        outf(c, "    dydt[%d] = ", i);
        expr(c, s->rhs, &x);
        puts_(c, ";\n");
    }
    puts_(c, "    return 0;\n}\n\n");
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
    puts_(c, "static int dk_outputs(double t, const double *y, const void *par, double *out)\n"
             "{\n    const double *p = (const double *)par;\n    (void)t;\n    (void)y;\n"
             "    (void)p;\n");
    if (needs_alg(c, roots, m->auxs.n, needed))
        emit_alg_solve(c, "return DK_ALG_FAILED;", 0);
    emit_fixes(c, needed);
    const ectx x = {NULL, 1};
    for (int i = 0; i < m->auxs.n; i++) {
        const lang_formula *f = &LVEC_AT(m->auxs, lang_formula, i);
        line_dir(c, f->pos);
        outf(c, "    out[%d] = ", i);
        expr(c, f->expr, &x);
        puts_(c, ";\n");
    }
    puts_(c, "    return 0;\n}\n\n");
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
            outf(c, "    memcpy(p + %d, dk_table_file%d, sizeof dk_table_file%d);\n", tb->offset,
                 i, i);
            continue;
        }
        outf(c, "    for (long k = 0; k < %ld; k++) {\n        const double t = ", tb->npts);
        num_lit(c, tb->lo);
        puts_(c, " + ");
        num_lit(c, table_dx(tb));
        outf(c, " * (double)k;\n        (void)t;\n        p[%d + k] = ", tb->offset);
        expr(c, tb->expr, &x);
        outf(c, ";\n        if (!isfinite(p[%d + k])) {\n            snprintf(err, errlen, "
                "\"table '%%s' is not finite at t = %%g (%%g)\", ",
             tb->offset);
        str_lit(c, tb->name);
        outf(c, ", t, p[%d + k]);\n            return 1;\n        }\n    }\n", tb->offset);
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

static int par_doubles(const lang_model *m)
{
    return input_offset(m) + (m->n_inputs ? LANG_INPUT_DOUBLES : 0);
}

/* The inputs: reading one (dk_input), attaching a table (dk_set_input), their names. */
static void emit_inputs(lang_ctx *c)
{
    const lang_model *m = &c->m;
    if (!m->n_inputs)
        return;
    outf(c, "_Static_assert(sizeof(dyn_input_table) <= %d * sizeof(double), \"room for the "
            "input table\");\n"
            "static inline double dk_input(const double *p, double t, int k, int i)\n{\n"
            "    dyn_input_table it;\n    memcpy(&it, p + %d, sizeof it);\n"
            "    return dyn_input_table_at(&it, t, k, p[i]);\n}\n\n"
            "static int dk_set_input(void *par, const double *table, long rows, dyn_interp "
            "interp, char *err, size_t errlen)\n{\n    dyn_input_table it;\n"
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
    puts_(c, "static const dyn_var dk_inputs_vars[] = {\n");
    for (int k = 0; k < m->n_inputs; k++) {
        const lang_param *p = &LVEC_AT(m->params, lang_param, m->input_param[k]);
        puts_(c, "    {");
        str_lit(c, p->name);
        puts_(c, ", ");
        str_lit(c, p->doc.unit);
        puts_(c, ", ");
        str_lit(c, p->doc.description);
        puts_(c, "},\n");
    }
    puts_(c, "};\n");
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
        outf(c, "    for (long k = 0; k < %ld; k++)\n        if (!(p[%d + k] >= 0.0 && "
                "p[%d + k] < %d.0)) {\n            snprintf(err, errlen, \"network sum '%%s': "
                "index %%ld of table '%%s' is %%g, not one of the %d states from '%%s' on (0 "
                "to %d)\", ",
             l->npts, l->offset, l->offset, sp->ulen, sp->ulen, sp->ulen - 1);
        str_lit(c, sp->name);
        puts_(c, ", k, ");
        str_lit(c, l->name);
        outf(c, ", p[%d + k], ", l->offset);
        str_lit(c, sp->root_name);
        puts_(c, ");\n            return 1;\n        }\n");
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
        outf(c, "static const double dk_table_file%d[%ld] = {", i, tb->npts);
        for (long k = 0; k < tb->npts; k++) {
            puts_(c, k % 4 ? ", " : k ? ",\n    " : "\n    ");
            num_lit(c, tb->values[k]);
        }
        puts_(c, "};\n\n");
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
        outf(c, "    p[DK_ALG_G + %d] = ", i);
        expr(c, f->expr, &x);
        outf(c,
             ";\n    if (!isfinite(p[DK_ALG_G + %d])) {\n        snprintf(err, errlen, \"the "
             "initial guess of algebraic variable '%%s' is not finite (%%g)\", ",
             i);
        str_lit(c, f->name);
        outf(c,
             ", p[DK_ALG_G + %d]);\n        return 1;\n    }\n    p[DK_ALG_W + %d] = "
             "p[DK_ALG_G + %d];\n    p[DK_ALG_S + %d] = fabs(p[DK_ALG_G + %d]);\n",
             i, i, i, i, i);
    }
    if (na)
        puts_(c, "    p[DK_ALG_T] = INFINITY;\n    p[DK_ALG_TP] = 0.0;\n");
}

static void emit_prepare(lang_ctx *c)
{
    lang_model *m = &c->m;
    const int np = m->params.n;
    puts_(c, "static int dk_prepare(void *par, char *err, size_t errlen)\n{\n"
             "    double *p = (double *)par;\n    (void)p;\n");
    if (np > 0) {
        puts_(c, "    static const char *const names[] = {");
        for (int i = 0; i < np; i++) {
            if (i)
                puts_(c, ", ");
            str_lit(c, LVEC_AT(m->params, lang_param, i).name);
        }
        outf(c, "};\n    for (int i = 0; i < %d; i++)\n        if (!isfinite(p[i])) {\n"
                "            snprintf(err, errlen, \"parameter '%%s' is not finite (%%g)\", "
                "names[i], p[i]);\n            return 1;\n        }\n",
             np);
    }
    const ectx x = {NULL, 0};
    for (int i = 0; i < m->derived.n; i++) {
        const int k = m->derived_order[i];
        const lang_formula *f = &LVEC_AT(m->derived, lang_formula, k);
        line_dir(c, f->pos);
        outf(c, "    p[%d] = ", np + k);
        expr(c, f->expr, &x);
        puts_(c, ";\n");
        outf(c, "    if (!isfinite(p[%d])) {\n        snprintf(err, errlen, \"derived parameter "
                "'%%s' is not finite (%%g)\", ",
             np + k);
        str_lit(c, f->name);
        outf(c, ", p[%d]);\n        return 1;\n    }\n", np + k);
    }
    emit_table_values(c);
    emit_sparse_checks(c);
    emit_alg_guesses(c);
    puts_(c, "    (void)err;\n    (void)errlen;\n    return 0;\n}\n\n");
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
    puts_(c, "static void dk_initial_state(const void *par, double *y0)\n{\n"
             "    const double *p = (const double *)par;\n    (void)p;\n");
    const ectx x = {NULL, 0};
    for (int i = 0; i < m->states.n; i++) {
        const lang_state *s = &LVEC_AT(m->states, lang_state, i);
        if (init_needs_params(s->init)) {
            line_dir(c, s->init_pos);
            outf(c, "    y0[%d] = ", i);
            expr(c, s->init, &x);
        } else {
            outf(c, "    y0[%d] = ", i);
            num_lit(c, y0[i]);
        }
        puts_(c, ";\n");
    }
    puts_(c, "}\n\n");
    return 1;
}

/* Jacobian: the fixed temporaries, then one block per column j with the derivatives of the
 * fixed temporaries with respect to y[j] (locals dvJ_NAME) and the non-zero entries. */
/* The derivatives of the needed fixed quantities with respect to v's variable, in their
 * order, into out (NULL: zero), and for the derivatives after them into v->fixd: the
 * number, or a reference dv<column>_NAME to the local the Jacobian's text writes. */
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
    char *saved = c->out;
    size_t saved_len = c->out_len, saved_cap = c->out_cap;
    c->out_saved = saved;
    c->out_saved_len = saved_len;
    c->out_saved_cap = saved_cap;
    c->out = NULL;
    c->out_len = c->out_cap = 0;
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
    /* dk_jacobian (dense, row-major) and, with a declared band, dk_jacobian_band (the band
     * in DYN_BAND_AT storage): the same entries */
    const int ld = m->band_lo + m->band_up + 1;
    for (int band = 0; band <= (m->has_band && j->band_bad_i < 0); band++) {
        outf(c, "static int dk_jacobian%s(double t, const double *y, double *J, void *par)\n{\n"
                "    const double *p = (const double *)par;\n    (void)t;\n    (void)y;\n"
                "    (void)p;\n",
             band ? "_band" : "");
        emit_fixes(c, jneed);
        outf(c, "    for (int k = 0; k < %d; k++)\n        J[k] = 0.0;\n", band ? n * ld : n * n);
        const ectx x = {NULL, 1};
        for (int jj = 0; jj < n; jj++) {
            int any = 0;
            for (int i = 0; i < n; i++)
                any |= cols[jj].entry[i] != NULL;
            if (!any)
                continue;
            outf(c, "    { /* d/d %s */\n", LVEC_AT(m->states, lang_state, jj).name);
            for (int q = 0; q < m->fixes.n; q++) {
                const int k = m->fix_order[q];
                const node *dk = cols[jj].fixd[k];
                if (!dk || dk->kind == N_NUM)
                    continue;
                const lang_formula *f = &LVEC_AT(m->fixes, lang_formula, k);
                line_dir(c, f->pos);
                outf(c, "        const double dv%d_%s = ", jj, f->name);
                expr(c, dk, &x);
                puts_(c, ";\n");
                outf(c, "        (void)dv%d_%s;\n", jj, f->name);
            }
            for (int i = 0; i < n; i++) {
                if (!cols[jj].entry[i])
                    continue;
                line_dir(c, LVEC_AT(m->states, lang_state, i).pos);
                outf(c, "        J[%d] = ", band ? jj * ld + m->band_up + i - jj : i * n + jj);
                expr(c, cols[jj].entry[i], &x);
                puts_(c, ";\n");
            }
            puts_(c, "    }\n");
        }
        puts_(c, "    return 0;\n}\n\n");
    }
    char *jac = c->out;
    const size_t jac_len = c->out_len;
    c->out = saved;
    c->out_saved = NULL;
    c->out_len = saved_len;
    c->out_cap = saved_cap;
    /* keep the Jacobian's text in the arena until it is appended */
    j->text = lang_strndup(c, jac ? jac : "", jac ? jac_len : 0);
    j->text_len = jac ? jac_len : 0;
    free(jac);
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
    if (e->kind == N_NEG) {
        emit_bound(c, e->args[0], x);
        return;
    }
    if (e->kind == N_FIX) { /* its bound, a local written before (emit_fix_bounds) */
        outf(c, "b_%s", LVEC_AT(c->m.fixes, lang_formula, e->index).name);
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
        puts_(c, "((");
        expr(c, e->args[0], x);
        puts_(c, ") != 0.0 ? ");
        emit_bound(c, e->args[1], x);
        puts_(c, " : ");
        emit_bound(c, e->args[2], x);
        puts_(c, ")");
        return;
    }
    if (e->kind == N_BIN &&
        (e->op == OP_ADD || e->op == OP_SUB || e->op == OP_MUL || e->op == OP_DIV)) {
        puts_(c, "(");
        if (e->op == OP_DIV) {
            emit_bound(c, e->args[0], x);
            puts_(c, " / fabs(");
            expr(c, e->args[1], x);
            puts_(c, ")");
        } else {
            emit_bound(c, e->args[0], x);
            puts_(c, e->op == OP_MUL ? " * " : " + ");
            emit_bound(c, e->args[1], x);
        }
        puts_(c, ")");
        return;
    }
    puts_(c, "fabs(");
    expr(c, e, x);
    puts_(c, ")");
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
    puts_(c, "static void dk_alg_residual(double t, const double *y, const double *p, "
             "const double *w, double *r, double *rb)\n{\n    (void)t;\n    (void)y;\n"
             "    (void)p;\n    (void)w;\n");
    emit_fixes(c, needed);
    for (int i = 0; i < na; i++) {
        const lang_formula *f = &LVEC_AT(m->algeqs, lang_formula, i);
        line_dir(c, f->pos);
        outf(c, "    r[%d] = ", i);
        expr(c, f->expr, &x);
        puts_(c, ";\n");
    }
    puts_(c, "    if (!rb)\n        return;\n");
    for (int q = 0; q < m->fixes.n; q++) { /* the fixed quantities' bounds */
        const int k = m->fix_order[q];
        if (!needed[k])
            continue;
        const lang_formula *f = &LVEC_AT(m->fixes, lang_formula, k);
        outf(c, "    const double b_%s = ", f->name);
        emit_bound(c, f->expr, &x);
        outf(c, ";\n    (void)b_%s;\n", f->name);
    }
    for (int i = 0; i < na; i++) {
        const lang_formula *f = &LVEC_AT(m->algeqs, lang_formula, i);
        line_dir(c, f->pos);
        outf(c, "    rb[%d] = ", i);
        emit_bound(c, f->expr, &x);
        puts_(c, ";\n");
    }
    puts_(c, "}\n\n");
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
        puts_(c, "/* r and J = dr/dw, exact */\n"
                 "static void dk_alg_jacobian(double t, const double *y, const double *p, "
                 "double *w, const double *s, double *r, double *rb, double *J)\n{\n"
                 "    (void)s;\n    dk_alg_residual(t, y, p, w, r, rb);\n");
        emit_fixes(c, jneed);
        outf(c, "    for (int k = 0; k < %d; k++)\n        J[k] = 0.0;\n", na * na);
        for (int k = 0; k < na; k++) {
            outf(c, "    { /* d/d %s */\n", LVEC_AT(m->algs, lang_formula, k).name);
            for (int q = 0; q < nf; q++) {
                const int f = m->fix_order[q];
                const node *df = aj.fixd[(size_t)k * ((size_t)nf + 1) + (size_t)f];
                if (!df || df->kind == N_NUM)
                    continue;
                const lang_formula *fx = &LVEC_AT(m->fixes, lang_formula, f);
                line_dir(c, fx->pos);
                outf(c, "        const double dv%d_%s = ", k, fx->name);
                expr(c, df, &x);
                outf(c, ";\n        (void)dv%d_%s;\n", k, fx->name);
            }
            for (int i = 0; i < na; i++) {
                const node *e = aj.entry[(size_t)k * (size_t)na + (size_t)i];
                if (!e)
                    continue;
                line_dir(c, LVEC_AT(m->algeqs, lang_formula, i).pos);
                outf(c, "        J[%d] = ", i * na + k);
                expr(c, e, &x);
                puts_(c, ";\n");
            }
            puts_(c, "    }\n");
        }
        puts_(c, "}\n\n");
    }
    outf(c,
         "#define DK_ALG_EXACT_JACOBIAN %d\n#line 1 \"<dynkit: the solver of the algebraic "
         "equations>\"\n",
         exact);
    puts_(c, lang_alg_solver_text());
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
        outf(c, "static double dk_event%d(double t, const double *y, void *par)\n{\n"
                "    const double *p = (const double *)par;\n    (void)t;\n    (void)y;\n"
                "    (void)p;\n",
             i);
        if (needs_alg(c, &root, 1, needed))
            emit_alg_solve(c, "return NAN;", 0);
        emit_fixes(c, needed);
        line_dir(c, ev->pos);
        puts_(c, "    return ");
        expr(c, ev->cond, &x);
        puts_(c, ";\n}\n\n");
        if (!ev->nassign)
            continue;
        /* XPPAUT applies a global's assignments in sequence: each sees the ones before */
        outf(c, "static int dk_reset%d(double t, double *y, void *par)\n{\n"
                "    const double *p = (const double *)par;\n    (void)t;\n    (void)p;\n",
             i);
        for (int k = 0; k < ev->nassign; k++) {
            const lang_assign *a = &ev->assign[k];
            root = a->value;
            needed = needed_by(c, &root, 1);
            puts_(c, "    {\n");
            if (needs_alg(c, &root, 1, needed))
                emit_alg_solve(c, "return DK_ALG_FAILED;", 0);
            emit_fixes(c, needed);
            line_dir(c, a->pos);
            outf(c, "        y[%d] = ", a->state);
            expr(c, a->value, &x);
            puts_(c, ";\n    }\n");
        }
        puts_(c, "    return 0;\n}\n\n");
    }
}

static void vars(lang_ctx *c, const char *decl, lvec *v, int states)
{
    outf(c, "static const dyn_var %s[] = {\n", decl);
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
        puts_(c, "    {");
        str_lit(c, name);
        puts_(c, ", ");
        str_lit(c, d->unit);
        puts_(c, ", ");
        str_lit(c, d->description);
        puts_(c, "},\n");
    }
    puts_(c, "};\n");
}

/* The Jacobian, computed first (it decides the partials of user functions to write). One
 * too large to write is left out with a note (the stiff methods then use differences); the
 * model stays. Returns 1 when it was written. */
static int try_jacobian(lang_ctx *c, jac_plan *jp)
{
    jmp_buf jac_fail;
    jmp_buf *outer = c->fail;
    c->copies = 0;
    c->fail = &jac_fail;
    if (setjmp(jac_fail) == 0) {
        emit_jacobian(c, jp);
        c->fail = outer;
        return 1;
    }
    c->fail = outer;
    derivative_failed(c, jp,
                      "no analytic Jacobian: ", "; the stiff methods use finite differences");
    if (c->out_saved) { /* failed while writing: back to the main text */
        free(c->out);
        c->out = c->out_saved;
        c->out_len = c->out_saved_len;
        c->out_cap = c->out_saved_cap;
        c->out_saved = NULL;
    }
    jp->text = NULL;
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
    int with_jac = n <= LANG_MAX_JAC_STATES && m->algs.n == 0 && !m->no_jacobian;
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
    emit_table_files(c);
    emit_prepare(c);
    const int has_init = emit_initial(c, y0);
    if (jp.text)
        put(c, jp.text, jp.text_len);
    emit_events(c);

    /* data */
    puts_(c, "#line 1 \"<dynkit: the model's tables>\"\n");
    vars(c, "dk_states", &m->states, 1);
    puts_(c, "static const double dk_y0[] = {");
    for (int i = 0; i < n; i++) {
        if (i)
            puts_(c, ", ");
        num_lit(c, y0[i]);
    }
    puts_(c, "};\n");
    if (np) {
        puts_(c, "static const dyn_param dk_params[] = {\n");
        for (int i = 0; i < np; i++) {
            const lang_param *p = &LVEC_AT(m->params, lang_param, i);
            puts_(c, "    {");
            str_lit(c, p->name);
            puts_(c, ", ");
            str_lit(c, p->doc.unit);
            puts_(c, ", ");
            str_lit(c, p->doc.description);
            outf(c, ", %d * sizeof(double), ", i);
            num_lit(c, p->value);
            puts_(c, "},\n");
        }
        puts_(c, "};\n");
    }
    if (m->auxs.n)
        vars(c, "dk_outputs_vars", &m->auxs, 0);
    emit_input_vars(c);
    if (m->events.n) {
        puts_(c, "static const dyn_event dk_events[] = {\n");
        for (int i = 0; i < m->events.n; i++) {
            const lang_event *ev = &LVEC_AT(m->events, lang_event, i);
            puts_(c, "    {");
            str_lit(c, ev->name);
            puts_(c, ", ");
            const char *desc = ev->description;
            if (!desc && ev->is_global)
                desc = lang_printf(c, "XPPAUT global on line %d: resets the state", ev->pos.line);
            str_lit(c, desc);
            outf(c, ", dk_event%d, %d, %d, ", i, ev->direction, ev->terminal);
            if (ev->nassign)
                outf(c, "dk_reset%d},\n", i);
            else
                puts_(c, "NULL},\n");
        }
        puts_(c, "};\n");
    }
    const double rtol = m->rtol > 0 ? m->rtol : 1e-6;
    const double atol = m->atol > 0 ? m->atol : 1e-9;
    puts_(c, "\nstatic const dyn_model dk_model = {\n    .name = ");
    str_lit(c, m->name);
    puts_(c, ",\n    .title = ");
    str_lit(c, m->title);
    puts_(c, ",\n    .description = ");
    str_lit(c, m->description);
    outf(c, ",\n    .n_states = %d,\n    .states = dk_states,\n    .y0 = dk_y0,\n"
            "    .n_params = %d,\n    .params = %s,\n    .par_size = %d * sizeof(double),\n"
            "    .n_outputs = %d,\n    .outputs = %s,\n    .rhs = dk_rhs,\n"
            "    .compute_outputs = %s,\n    .prepare = dk_prepare,\n    .warn = NULL,\n",
         n, np, np ? "dk_params" : "NULL", par_doubles(m) > 0 ? par_doubles(m) : 1, m->auxs.n,
         m->auxs.n ? "dk_outputs_vars" : "NULL", m->auxs.n ? "dk_outputs" : "NULL");
    puts_(c, "    .t0 = ");
    num_lit(c, m->t0);
    puts_(c, ",\n    .t1 = ");
    num_lit(c, m->t0 + m->total);
    puts_(c, ",\n    .step = ");
    num_lit(c, m->dt);
    puts_(c, ",\n    .method = ");
    str_lit(c, m->method ? m->method : "dp45");
    outf(c, ",\n    .n_inputs = %d,\n    .inputs = %s,\n    .set_input = %s,\n"
            "    .jacobian = %s,\n    .n_events = %d,\n    .events = %s,\n"
            "    .samples = DYN_SAMPLES_GRID,\n    .initial_state = %s,\n",
         m->n_inputs, m->n_inputs ? "dk_inputs_vars" : "NULL",
         m->n_inputs ? "dk_set_input" : "NULL", with_jac ? "dk_jacobian" : "NULL", m->events.n, m->events.n ? "dk_events" : "NULL",
         has_init ? "dk_initial_state" : "NULL");
    puts_(c, "    .rtol = ");
    num_lit(c, rtol);
    puts_(c, ",\n    .atol = ");
    num_lit(c, atol);
    puts_(c, ",\n    .phase_x = ");
    if (m->xp)
        str_lit(c, m->xp);
    else
        puts_(c, "NULL");
    puts_(c, ",\n    .phase_y = ");
    if (m->yp)
        str_lit(c, m->yp);
    else
        puts_(c, "NULL");
    puts_(c, ",\n    .source = ");
    str_lit(c, c->path);
    puts_(c, ",\n    .t_trans = ");
    num_lit(c, m->trans);
    outf(c, ",\n    .every = %ld,\n    .bound = ", m->nout);
    num_lit(c, m->bound);
    if (m->has_band)
        outf(c, ",\n    .jac_banded = 1,\n    .jac_lower = %d,\n    .jac_upper = %d,\n"
                "    .jacobian_band = %s",
             m->band_lo, m->band_up, with_jac ? "dk_jacobian_band" : "NULL");
    puts_(c, ",\n};\n\nconst dyn_model *dynkit_model(void) { return &dk_model; }\n");
    /* the functions the text calls, then what comes before it all */
    size_t main_len, defs_len;
    const char *main_text = take_text(c, &main_len);
    unsigned char *done = lang_alloc(c, ((size_t)m->funcs.n + 1) * (LANG_MAX_ARGS + 1));
    emit_function_defs(c, &jp, done);
    const char *defs = take_text(c, &defs_len);
    puts_(c, "/* ");
    puts_(c, m->name);
    puts_(c, ": C text generated by dynkit from the model file ");
    for (const char *s = c->path; *s; s++)
        if (*s == '*' && s[1] == '/')
            puts_(c, "*\\/"), s++;
        else if ((unsigned char)*s >= 32)
            put(c, s, 1);
    puts_(c, "\n * (see \"The .ode format\" in docs/model-files.md). Edit the model file, not "
             "this text. */\n"
             "#include <math.h>\n#include <stddef.h>\n#include <stdio.h>\n");
    if (table_files(m) || m->n_inputs)
        puts_(c, "#include <string.h>\n");
    puts_(c, "\n#include <dynkit/model.h>\n");
    puts_(c, m->n_inputs ? "#include <dynkit/input.h>\n\n" : "\n");
    if (m->algs.n)
        emit_alg_constants(c);
    helpers(c);
    emit_function_protos(c);
    put(c, defs, defs_len);
    if (defs_len)
        puts_(c, "\n");
    put(c, main_text, main_len);
    char *r = c->out;
    c->out = NULL;
    return r;
}
