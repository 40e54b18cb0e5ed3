/* SPDX-License-Identifier: BSD-3-Clause */
/* Expressions of an .ode file: tokens and the parse into a tree, with XPPAUT's operator
 * priorities as its parser has them (parserslow.c's symbol table) and as xppaut computes:
 *   4: + - |      6: * / &  and the prefix - and not      7: ^ ** > < >= <= == !=
 * every binary operator left-associative, so 2^3^2 = 64, 1+1==2 is 1+(1==2) = 1,
 * -2^2 = -4, not 0+1 = 2, 2*3>1 = 2*(3>1) = 2. Functions, `if(c)then(a)else(b)`, numbers
 * like 1e-3 and .5; names are case-insensitive. More lenient than XPPAUT where the meaning
 * is unambiguous: a sign after an operator (2*-3), blanks anywhere between tokens. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lang/lang_internal.h"

int lang_is_ident_start(int ch) { return isalpha(ch) || ch == '_'; }
int lang_is_ident_char(int ch) { return isalnum(ch) || ch == '_'; }

node *lang_node(lang_ctx *c, node_kind kind, lpos pos)
{
    node *n = lang_alloc(c, sizeof *n);
    n->kind = kind;
    n->pos = pos;
    return n;
}

static const struct {
    const char *name;
    int arity;
} funs[F_COUNT] = {
    [F_SIN] = {"sin", 1},     [F_COS] = {"cos", 1},     [F_TAN] = {"tan", 1},
    [F_ASIN] = {"asin", 1},   [F_ACOS] = {"acos", 1},   [F_ATAN] = {"atan", 1},
    [F_ATAN2] = {"atan2", 2}, [F_SINH] = {"sinh", 1},   [F_COSH] = {"cosh", 1},
    [F_TANH] = {"tanh", 1},   [F_EXP] = {"exp", 1},     [F_LN] = {"ln", 1},
    [F_LOG10] = {"log10", 1}, [F_SQRT] = {"sqrt", 1},   [F_ABS] = {"abs", 1},
    [F_HEAV] = {"heav", 1},   [F_SIGN] = {"sign", 1},   [F_MOD] = {"mod", 2},
    [F_FLR] = {"flr", 1},     [F_CEIL] = {"ceil", 1},   [F_MAX] = {"max", 2},
    [F_MIN] = {"min", 2},     [F_ERF] = {"erf", 1},     [F_ERFC] = {"erfc", 1},
};

static int ieq(const char *a, size_t alen, const char *word)
{
    const size_t n = strlen(word);
    if (alen != n)
        return 0;
    for (size_t i = 0; i < n; i++)
        if (tolower((unsigned char)a[i]) != word[i])
            return 0;
    return 1;
}

int lang_fun_lookup(const char *name, int *arity)
{
    const size_t n = strlen(name);
    if (ieq(name, n, "log")) { /* natural, as in XPPAUT */
        *arity = 1;
        return F_LN;
    }
    for (int f = 0; f < F_COUNT; f++)
        if (ieq(name, n, funs[f].name)) {
            *arity = funs[f].arity;
            return f;
        }
    return -1;
}

const char *lang_fun_name(int f) { return f >= 0 && f < F_COUNT ? funs[f].name : "?"; }

/* XPPAUT's reserved words this translator does not implement, with the feature's name. */
static const struct {
    const char *word, *feature;
} unsupported[] = {
    {"del_shft", "delay-differential equations ('del_shft')"},
    {"poisson", "random numbers ('poisson')"},
    {"besselj", "Bessel functions ('besselj')"},
    {"bessely", "Bessel functions ('bessely')"},
    {"besseli", "Bessel functions ('besseli')"},
    {"lgamma", "the log-gamma function ('lgamma')"},
    {"ishift", "indirect addressing ('ishift')"},
    {"hom_bcs", "homoclinic boundary conditions ('hom_bcs', XPPAUT's projections of the "
                "ends onto the unstable and stable subspaces of equilibria held in states, "
                "which its (H)omoclinic dialog sets up)"},
};

/* The feature's name when name is a reserved word of XPPAUT that is not supported. */
static const char *unsupported_feature(const char *name, size_t n)
{
    for (size_t i = 0; i < sizeof unsupported / sizeof unsupported[0]; i++)
        if (ieq(name, n, unsupported[i].word))
            return unsupported[i].feature;
    return NULL;
}

int lang_is_reserved(const char *name)
{
    const size_t n = strlen(name);
    int arity;
    static const char *const words[] = {"t", "pi", "if", "then", "else", "not", "sum", "of",
                                        "shift", "ran", "normal", "delay", "int"};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        if (ieq(name, n, words[i]))
            return 1;
    return lang_fun_lookup(name, &arity) >= 0 || unsupported_feature(name, n) != NULL;
}

static const char *const op_texts[] = {
    [OP_ADD] = "+", [OP_SUB] = "-", [OP_OR] = "|",  [OP_MUL] = "*",  [OP_DIV] = "/",
    [OP_AND] = "&", [OP_POW] = "^", [OP_GT] = ">",  [OP_LT] = "<",   [OP_GE] = ">=",
    [OP_LE] = "<=", [OP_EQ] = "==", [OP_NE] = "!=",
};

const char *lang_op_text(int op) { return op >= 0 && op <= OP_NE ? op_texts[op] : "?"; }

int lang_op_priority(int op)
{
    if (op == OP_ADD || op == OP_SUB || op == OP_OR)
        return 4;
    if (op == OP_MUL || op == OP_DIV || op == OP_AND)
        return 6;
    return 7;
}

static int is_comparison(const node *n) { return n->kind == N_BIN && n->op >= OP_GT; }

/* ---- tokens ---- */

enum tok_kind { T_END, T_NUM, T_NAME, T_OP, T_LP, T_RP, T_COMMA, T_OTHER };

typedef struct tok {
    int kind, op;
    int start, end; /* offsets in the line */
    double num;
} tok;

lpos lang_here(const lang_lexer *lx)
{
    const int i = lx->i < lx->end ? lx->i : lx->end;
    return lx->line->pos[i];
}

int lang_skip_blanks(lang_lexer *lx)
{
    while (lx->i < lx->end && (lx->line->text[lx->i] == ' ' || lx->line->text[lx->i] == '\t'))
        lx->i++;
    return lx->i < lx->end ? (unsigned char)lx->line->text[lx->i] : 0;
}

const char *lang_read_name(lang_lexer *lx, lpos *pos, const char *what)
{
    const int ch = lang_skip_blanks(lx);
    *pos = lang_here(lx);
    if (!lang_is_ident_start(ch)) {
        if (ch)
            lang_fail(lx->c, *pos, "%s, found '%c'", what, ch);
        lang_fail(lx->c, *pos, "%s, found the end of the line", what);
    }
    const int a = lx->i;
    while (lx->i < lx->end && lang_is_ident_char((unsigned char)lx->line->text[lx->i]))
        lx->i++;
    return lang_strndup(lx->c, lx->line->text + a, (size_t)(lx->i - a));
}

void lang_expect_char(lang_lexer *lx, int ch, const char *what)
{
    const int got = lang_skip_blanks(lx);
    if (got != ch) {
        if (got)
            lang_fail(lx->c, lang_here(lx), "%s, found '%c'", what, got);
        lang_fail(lx->c, lang_here(lx), "%s, found the end of the line", what);
    }
    lx->i++;
}

void lang_expect_end(lang_lexer *lx, const char *after)
{
    const int ch = lang_skip_blanks(lx);
    if (!ch)
        return;
    if (lang_is_ident_start(ch) || isdigit(ch) || ch == '(')
        lang_fail(lx->c, lang_here(lx), "missing operator before '%c' (after %s)", ch, after);
    lang_fail(lx->c, lang_here(lx), "unexpected '%c' after %s", ch, after);
}

static lpos pos_at(const lang_lexer *lx, int i) { return lx->line->pos[i < lx->end ? i : lx->end]; }

static tok next_tok(lang_lexer *lx, int consume)
{
    const char *s = lx->line->text;
    tok t = {T_END, 0, 0, 0, 0.0};
    const int ch = lang_skip_blanks(lx);
    int i = lx->i;
    t.start = i;
    if (!ch) {
        t.end = i;
        return t;
    }
    if (isdigit(ch) || (ch == '.' && i + 1 < lx->end && isdigit((unsigned char)s[i + 1]))) {
        int k = i;
        while (k < lx->end && isdigit((unsigned char)s[k]))
            k++;
        if (k < lx->end && s[k] == '.') {
            k++;
            while (k < lx->end && isdigit((unsigned char)s[k]))
                k++;
        }
        if (k < lx->end && (s[k] == 'e' || s[k] == 'E')) {
            int q = k + 1;
            if (q < lx->end && (s[q] == '+' || s[q] == '-'))
                q++;
            if (q < lx->end && isdigit((unsigned char)s[q])) {
                while (q < lx->end && isdigit((unsigned char)s[q]))
                    q++;
                k = q;
            } else {
                lang_fail(lx->c, pos_at(lx, k), "malformed number: an exponent needs digits");
            }
        }
        if (k < lx->end && (lang_is_ident_start((unsigned char)s[k]) || s[k] == '.'))
            lang_fail(lx->c, pos_at(lx, k),
                      "missing operator after the number '%.*s' (write 2*v, not 2v)", k - i,
                      s + i);
        char buf[64];
        if (k - i >= (int)sizeof buf)
            lang_fail(lx->c, pos_at(lx, i), "number too long");
        memcpy(buf, s + i, (size_t)(k - i));
        buf[k - i] = '\0';
        t.kind = T_NUM;
        t.num = strtod(buf, NULL);
        t.end = k;
        /* what is no double is refused, as on the command line: 1e999 is not infinity and
         * 1e-999 not zero */
        if (isinf(t.num))
            lang_fail(lx->c, pos_at(lx, i),
                      "the number '%s' is beyond the range of doubles (at most about 1.8e308)",
                      buf);
        if (t.num == 0.0 && strcspn(buf, "123456789") < strcspn(buf, "eE"))
            lang_fail(lx->c, pos_at(lx, i),
                      "the number '%s' is below the smallest double (about 4.9e-324) and "
                      "would be 0",
                      buf);
    } else if (lang_is_ident_start(ch)) {
        int k = i;
        while (k < lx->end && lang_is_ident_char((unsigned char)s[k]))
            k++;
        t.kind = T_NAME;
        t.end = k;
    } else {
        const char c2 = i + 1 < lx->end ? s[i + 1] : '\0';
        t.kind = T_OP;
        t.end = i + 1;
        switch (ch) {
        case '+': t.op = OP_ADD; break;
        case '-': t.op = OP_SUB; break;
        case '|': t.op = OP_OR; break;
        case '/': t.op = OP_DIV; break;
        case '&': t.op = OP_AND; break;
        case '^': t.op = OP_POW; break;
        case '*':
            if (c2 == '*') {
                t.op = OP_POW;
                t.end = i + 2;
            } else {
                t.op = OP_MUL;
            }
            break;
        case '>':
            t.op = c2 == '=' ? OP_GE : OP_GT;
            t.end = c2 == '=' ? i + 2 : i + 1;
            break;
        case '<':
            t.op = c2 == '=' ? OP_LE : OP_LT;
            t.end = c2 == '=' ? i + 2 : i + 1;
            break;
        case '=':
            if (c2 == '=') {
                t.op = OP_EQ;
                t.end = i + 2;
            } else {
                t.kind = T_OTHER;
            }
            break;
        case '!':
            if (c2 == '=') {
                t.op = OP_NE;
                t.end = i + 2;
            } else {
                t.kind = T_OTHER;
            }
            break;
        case '(': t.kind = T_LP; break;
        case ')': t.kind = T_RP; break;
        case ',': t.kind = T_COMMA; break;
        default: t.kind = T_OTHER; break;
        }
    }
    if (consume)
        lx->i = t.end;
    return t;
}

static tok peek(lang_lexer *lx) { return next_tok(lx, 0); }
static tok take(lang_lexer *lx) { return next_tok(lx, 1); }

static int tok_is_word(const lang_lexer *lx, const tok *t, const char *word)
{
    return t->kind == T_NAME && ieq(lx->line->text + t->start, (size_t)(t->end - t->start), word);
}

static _Noreturn void unexpected(lang_lexer *lx, const tok *t, const char *what)
{
    if (t->kind == T_END)
        lang_fail(lx->c, pos_at(lx, t->start), "%s, found the end of the line", what);
    const int n = t->end - t->start > 0 ? t->end - t->start : 1;
    lang_fail(lx->c, pos_at(lx, t->start), "%s, found '%.*s'", what, n > 40 ? 40 : n,
              lx->line->text + t->start);
}

static void expect(lang_lexer *lx, int kind, const char *what)
{
    tok t = take(lx);
    if (t.kind != kind)
        unexpected(lx, &t, what);
}

static node *parse_binary(lang_lexer *lx, int minprec);

static void enter(lang_lexer *lx, lpos p)
{
    if (++lx->c->depth > LANG_MAX_DEPTH)
        lang_fail(lx->c, p, "expression nested too deeply (more than %d levels)",
                  LANG_MAX_DEPTH);
}

static node *parse_paren(lang_lexer *lx, const char *what)
{
    expect(lx, T_LP, what);
    node *e = parse_binary(lx, 0);
    tok t = take(lx);
    if (t.kind != T_RP)
        unexpected(lx, &t, "expected ')'");
    e->paren = 1;
    return e;
}

static node *parse_primary(lang_lexer *lx)
{
    tok t = take(lx);
    const lpos p = pos_at(lx, t.start);
    const char *s = lx->line->text + t.start;
    const size_t n = (size_t)(t.end - t.start);
    if (t.kind == T_NUM) {
        node *e = lang_node(lx->c, N_NUM, p);
        e->num = t.num;
        return e;
    }
    if (t.kind == T_LP) {
        node *e = parse_binary(lx, 0);
        tok r = take(lx);
        if (r.kind != T_RP)
            unexpected(lx, &r, "expected ')'");
        e->paren = 1;
        return e;
    }
    if (t.kind != T_NAME)
        unexpected(lx, &t, "expected a number, a name or '('");
    const char *feature = unsupported_feature(s, n);
    if (feature && ieq(s, n, "hom_bcs"))
        lang_fail(lx->c, p, "hom_bcs(K) is a whole boundary condition, 'bdry hom_bcs(K)' "
                            "(XPPAUT's K-th projection condition of a homoclinic orbit), not "
                            "a value inside a formula");
    if (feature)
        lang_fail(lx->c, p, "%s %s not supported", feature,
                  strstr(feature, "s (") || strstr(feature, "ions") ? "are" : "is");
    if (ieq(s, n, "int")) /* integrals were read by src/lang/integrals.c */
        lang_fail(lx->c, p, "'int' begins a Volterra integral: int{u}, int{K#u} or "
                            "int[m]{K#u}");
    if (ieq(s, n, "delay")) { /* delay(state, lag): the state's value lag ago */
        node *e = lang_node(lx->c, N_DELAY, p);
        expect(lx, T_LP, "expected '(' after 'delay': delay(x, tau)");
        tok v = take(lx);
        if (v.kind != T_NAME)
            unexpected(lx, &v, "expected the name of a state in delay(x, tau)");
        e->name = lang_strndup(lx->c, lx->line->text + v.start, (size_t)(v.end - v.start));
        expect(lx, T_COMMA, "expected ',' after the state in delay(x, tau)");
        e->nargs = 1;
        e->args = lang_alloc(lx->c, sizeof *e->args);
        e->args[0] = parse_binary(lx, 0);
        expect(lx, T_RP, "expected ')' after the lag in delay(x, tau)");
        lx->c->m.n_delays++;
        return e;
    }
    if (ieq(s, n, "if")) {
        node *e = lang_node(lx->c, N_IF, p);
        e->nargs = 3;
        e->args = lang_alloc(lx->c, 3 * sizeof *e->args);
        e->args[0] = parse_paren(lx, "expected '(' after 'if'");
        tok w = take(lx);
        if (!tok_is_word(lx, &w, "then"))
            unexpected(lx, &w, "expected 'then' in if(...)then(...)else(...)");
        e->args[1] = parse_paren(lx, "expected '(' after 'then'");
        w = take(lx);
        if (!tok_is_word(lx, &w, "else"))
            unexpected(lx, &w, "expected 'else' in if(...)then(...)else(...)");
        e->args[2] = parse_paren(lx, "expected '(' after 'else'");
        return e;
    }
    if (ieq(s, n, "sum") && peek(lx).kind == T_LP) {
        /* sum(j1,j2)of(formula of i') */
        take(lx);
        node *e = lang_node(lx->c, N_SUM, p);
        e->nargs = 3;
        e->args = lang_alloc(lx->c, 3 * sizeof *e->args);
        e->args[0] = parse_binary(lx, 0);
        expect(lx, T_COMMA, "expected ',' between the bounds of sum(j1,j2)");
        e->args[1] = parse_binary(lx, 0);
        expect(lx, T_RP, "expected ')' after the bounds of sum(j1,j2)");
        tok w = take(lx);
        if (!tok_is_word(lx, &w, "of"))
            unexpected(lx, &w, "expected 'of' in sum(j1,j2)of(...)");
        e->args[2] = parse_paren(lx, "expected '(' after 'of'");
        return e;
    }
    if (ieq(s, n, "i") && lx->i < lx->end && lx->line->text[lx->i] == '\'') {
        lx->i++;
        return lang_node(lx->c, N_SUMIDX, p);
    }
    if (ieq(s, n, "then") || ieq(s, n, "else") || ieq(s, n, "not") || ieq(s, n, "of"))
        unexpected(lx, &t, "expected a number, a name or '('");
    if (ieq(s, n, "t")) {
        if (peek(lx).kind == T_LP)
            lang_fail(lx->c, p, "'t' is the time, not a function");
        return lang_node(lx->c, N_TIME, p);
    }
    if (ieq(s, n, "pi")) {
        node *e = lang_node(lx->c, N_NUM, p);
        e->num = 3.14159265358979323846;
        e->name = "pi";
        return e;
    }
    const char *name = lang_strndup(lx->c, s, n);
    if (peek(lx).kind != T_LP) {
        node *e = lang_node(lx->c, N_NAME, p);
        e->name = name;
        if (lx->c->in_bdry && lx->i < lx->end && lx->line->text[lx->i] == '\'') {
            lx->i++; /* NAME' in a bdry line: NAME at the right end (bdry.c) */
            e->op = 1;
        }
        return e;
    }
    /* a call: built-in or user function, resolved later */
    take(lx);
    node *e = lang_node(lx->c, N_FUN, p);
    e->name = name;
    lvec args = {0};
    if (peek(lx).kind == T_RP)
        lang_fail(lx->c, p, "'%s()' needs arguments", name);
    for (;;) {
        node *a = parse_binary(lx, 0);
        *(node **)lvec_push(lx->c, &args, sizeof(node *)) = a;
        if (args.n > LANG_MAX_ARGS)
            lang_fail(lx->c, a->pos, "too many arguments (at most %d)", LANG_MAX_ARGS);
        tok r = take(lx);
        if (r.kind == T_RP)
            break;
        if (r.kind != T_COMMA)
            unexpected(lx, &r, "expected ',' or ')' in the arguments");
    }
    e->nargs = args.n;
    e->args = args.data;
    return e;
}

/* A prefix operator binds what follows up to the next operator of priority 6 or lower. */
static node *parse_prefix(lang_lexer *lx)
{
    tok t = peek(lx);
    const lpos p = pos_at(lx, t.start);
    enter(lx, p);
    node *e;
    if (t.kind == T_OP && (t.op == OP_SUB || t.op == OP_ADD)) {
        take(lx);
        node *a = parse_binary(lx, 7);
        if (t.op == OP_ADD) {
            e = a;
        } else {
            e = lang_node(lx->c, N_NEG, p);
            e->nargs = 1;
            e->args = lang_alloc(lx->c, sizeof *e->args);
            e->args[0] = a;
        }
    } else if (tok_is_word(lx, &t, "not")) {
        take(lx);
        e = lang_node(lx->c, N_NOT, p);
        e->nargs = 1;
        e->args = lang_alloc(lx->c, sizeof *e->args);
        e->args[0] = parse_binary(lx, 7);
    } else {
        e = parse_primary(lx);
    }
    lx->c->depth--;
    return e;
}

static node *parse_binary(lang_lexer *lx, int minprec)
{
    node *lhs = parse_prefix(lx);
    for (;;) {
        tok t = peek(lx);
        if (t.kind != T_OP)
            return lhs;
        const int prec = lang_op_priority(t.op);
        if (prec < minprec)
            return lhs;
        take(lx);
        const lpos p = pos_at(lx, t.start);
        enter(lx, p);
        node *rhs = parse_binary(lx, prec + 1);
        lx->c->depth--;
        node *e = lang_node(lx->c, N_BIN, p);
        e->op = t.op;
        e->nargs = 2;
        e->args = lang_alloc(lx->c, 2 * sizeof *e->args);
        e->args[0] = lhs;
        e->args[1] = rhs;
        if (prec < 7) {
            const node *cmp = is_comparison(lhs) && !lhs->paren   ? lhs
                              : is_comparison(rhs) && !rhs->paren ? rhs
                                                                  : NULL;
            if (cmp) {
                const char *o1 = lang_op_text(cmp == lhs ? cmp->op : t.op);
                const char *o2 = lang_op_text(cmp == lhs ? t.op : cmp->op);
                if (cmp == lhs)
                    lang_note(lx->c, cmp->pos,
                              "col %d: a%sb%sc is read as (a%sb)%sc (XPPAUT's priorities: "
                              "comparisons bind tighter than + - * /); add parentheses to "
                              "say which you mean", cmp->pos.col, o1, o2, o1, o2);
                else
                    lang_note(lx->c, cmp->pos,
                              "col %d: a%sb%sc is read as a%s(b%sc) (XPPAUT's priorities: "
                              "comparisons bind tighter than + - * /); add parentheses to "
                              "say which you mean", cmp->pos.col, o1, o2, o1, o2);
            }
        }
        lhs = e;
    }
}

node *lang_parse_expr(lang_lexer *lx)
{
    const int depth = lx->c->depth;
    node *e = parse_binary(lx, 0);
    lx->c->depth = depth;
    return e;
}
