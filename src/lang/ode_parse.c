/* SPDX-License-Identifier: BSD-3-Clause */
/* Statements of an .ode file (XPPAUT's manual, "Structure of ODE files" and "Options"):
 * x'=, dx/dt=, x(0)=, par/param/p, number, init/i, aux, name=expr (fixed), !name=expr
 * (derived), f(a,b)=expr, x(t+1)=expr, table, global sign cond {x=..;y=..}, @ options, done;
 * and dynkit's
 * extensions in `#:` comment lines (title, description, units and descriptions of names,
 * named events). XPPAUT's features this translator does not implement are refused with the
 * place and the feature's name. Keywords are case-insensitive, blanks around `=` allowed. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "dynkit/ode.h" /* DYN_EVENT_JUMPS */
#include "dynkit/model.h" /* DYN_POINCARE_* */
#include "dynkit/sde.h"
#include "lang/lang_internal.h"

typedef struct pstate {
    int seen_statement;
    lvec desc;                  /* leading comment lines (char *) */
    const char *global_name;    /* from `#: event NAME` right before a global */
    const char *global_desc;
    int global_name_line;       /* the line of that `#:` (0: none) */
} pstate;

static int ieqn(const char *a, size_t n, const char *word)
{
    if (strlen(word) != n)
        return 0;
    for (size_t i = 0; i < n; i++)
        if (tolower((unsigned char)a[i]) != tolower((unsigned char)word[i]))
            return 0;
    return 1;
}

static node *expr_to_end(lang_lexer *lx, const char *after)
{
    node *e = lang_parse_expr(lx);
    lang_expect_end(lx, after);
    return e;
}

static void check_new_name(lang_ctx *c, const char *name, lpos pos)
{
    if (lang_is_reserved(name))
        lang_fail(c, pos, "'%s' is a reserved word of XPPAUT and cannot be declared", name);
}

/* Resolve the built-in calls of a constant expression in place; names are refused. */
static void resolve_const(lang_ctx *c, node *e, const char *what)
{
    if (e->kind == N_SUM || e->kind == N_SUMIDX)
        lang_fail(c, e->pos, "%s must be a number, not a sum", what);
    for (int i = 0; i < e->nargs; i++)
        resolve_const(c, e->args[i], what);
    if (e->kind == N_NAME)
        lang_fail(c, e->pos, "%s must be a number, not a formula of '%s' (a derived parameter "
                  "'!name=formula' computes a value from parameters)", what, e->name);
    if (e->kind == N_TIME)
        lang_fail(c, e->pos, "%s must be a number, not a formula of t", what);
    if (e->kind == N_FUN) {
        int arity;
        const int f = lang_fun_lookup(e->name, &arity);
        if (f < 0)
            lang_fail(c, e->pos, "%s must be a number; '%s' is not a built-in function", what,
                      e->name);
        if (arity != e->nargs)
            lang_fail(c, e->pos, "'%s' takes %d argument%s, not %d", e->name, arity,
                      arity == 1 ? "" : "s", e->nargs);
        e->op = f;
    }
}

/* The value of a formula of numbers and built-in functions; one that is not finite
 * (1/0, exp(1000)) is refused at its place. */
static double const_value(lang_ctx *c, node *e, const char *what)
{
    resolve_const(c, e, what);
    const double v = lang_eval(c, e, NULL, NULL);
    if (!isfinite(v))
        lang_fail(c, e->pos, "%s is not finite (%g): give a finite number", what, v);
    return v;
}

/* 1 when e is a formula of numbers and built-in functions only (its value is known when the
 * file is read). */
static int is_constant(const node *e)
{
    if (e->kind == N_NAME || e->kind == N_TIME || e->kind == N_SUM || e->kind == N_SUMIDX)
        return 0;
    if (e->kind == N_FUN) {
        int arity;
        if (lang_fun_lookup(e->name, &arity) < 0 || arity != e->nargs)
            return 0;
    }
    for (int i = 0; i < e->nargs; i++)
        if (!is_constant(e->args[i]))
            return 0;
    return 1;
}

/* An initial value or guess that is a constant formula must be finite (one of parameters
 * is checked when the parameters are known, at each run). */
static void check_constant_value(lang_ctx *c, node *e, const char *what, const char *name)
{
    if (is_constant(e))
        (void)const_value(c, e, lang_printf(c, "%s of '%s'", what, name));
}

/* XPPAUT 6.11 reads a value of par, number, init and x(0)= with atof: of '2*pi' only the 2,
 * of 'a' 0 (measured). Its manual gives x(0)= an expression, and a formula means what it
 * says: dynkit computes it, and notes the difference. */
static void note_formula_value(lang_ctx *c, lang_lexer *lx, int from, const node *e,
                               const char *name)
{
    const node *v = e->kind == N_NEG ? e->args[0] : e;
    if (v->kind == N_NUM && !v->name && !v->paren)
        return;
    char text[64];
    int n = lx->i - from;
    while (n > 0 && (lx->line->text[from + n - 1] == ' ' || lx->line->text[from + n - 1] == '\t'))
        n--;
    if (n >= (int)sizeof text)
        n = (int)sizeof text - 1;
    int k = 0;
    for (int i = 0; i < n; i++)
        if (lx->line->text[from + i] != ' ' && lx->line->text[from + i] != '\t')
            text[k++] = lx->line->text[from + i];
    text[k] = '\0';
    lang_note(c, e->pos, "the value of '%s' is a formula, '%s': dynkit computes it; XPPAUT 6.11 "
              "reads only the number it starts with (%g)", name, text, strtod(text, NULL));
}

/* ---- declarations ---- */

static int add_state(lang_ctx *c, const char *name, lpos pos, node *rhs)
{
    check_new_name(c, name, pos);
    const int idx = c->m.states.n;
    lang_declare(c, name, pos, SYM_STATE, idx);
    lang_state *s = lvec_push(c, &c->m.states, sizeof *s);
    s->name = name;
    s->pos = pos;
    s->rhs = rhs;
    return idx;
}

/* volt NAME=formula (or NAME(t)= a formula with an integral): an integral equation
 * NAME(t) = formula (src/lang/integrals.c) */
static void parse_volt(lang_ctx *c, lang_lexer *lx)
{
    lpos pos;
    const char *name = lang_read_name(lx, &pos, "expected the name after 'volt'");
    lang_expect_char(lx, '=', "expected '=' after the name of an integral equation");
    const int i = add_state(c, name, pos, expr_to_end(lx, "the integral equation"));
    LVEC_AT(c->m.states, lang_state, i).is_int = 1;
}

/* x(t+1)=expr, the lexer after "x(t": a difference equation (XPPAUT's manual,
 * "Difference equations"), which makes the whole file a discrete map. */
static void parse_map_equation(lang_ctx *c, lang_lexer *lx, const char *w, lpos wpos)
{
    lx->i++; /* '+' */
    if (lang_skip_blanks(lx) != '1')
        lang_fail(c, lang_here(lx), "expected x(t+1)=: a difference equation steps by 1");
    lx->i++;
    lang_expect_char(lx, ')', "expected ')' in x(t+1)");
    lang_expect_char(lx, '=', "expected '=' after x(t+1)");
    add_state(c, w, wpos, expr_to_end(lx, "the right-hand side"));
    if (!c->m.map_eq && !c->m.map_meth)
        c->m.map_pos = wpos;
    c->m.map_eq = 1;
}

static void add_formula(lang_ctx *c, lvec *v, sym_kind kind, const char *name, lpos pos,
                        node *e)
{
    check_new_name(c, name, pos);
    lang_declare(c, name, pos, kind, v->n);
    lang_formula *f = lvec_push(c, v, sizeof *f);
    f->name = name;
    f->pos = pos;
    f->expr = e;
}

static void add_init(lang_ctx *c, const char *name, lpos pos, node *value, int x0)
{
    check_constant_value(c, value, "the initial value", name);
    lang_init *in = lvec_push(c, &c->m.inits, sizeof *in);
    in->name = name;
    in->pos = pos;
    in->value = value;
    in->x0 = x0;
}

/* par / number / init / solv: name=value lists, separated by commas or blanks. */
static void name_value_list(lang_ctx *c, lang_lexer *lx, int kind, const char *keyword)
{
    int count = 0;
    for (;;) {
        lpos pos;
        const char *name = lang_read_name(lx, &pos, count ? "expected a name"
                                                          : "expected a name after the keyword");
        node *e;
        if (lang_skip_blanks(lx) == '=') {
            lx->i++;
            const int from = (lang_skip_blanks(lx), lx->i);
            e = lang_parse_expr(lx);
            if (kind != SYM_ALG)
                note_formula_value(c, lx, from, e, name);
        } else {
            /* XPPAUT reads a name without a value as 0 */
            const int nx = lang_skip_blanks(lx);
            if (nx && nx != ',' && !lang_is_ident_start(nx))
                lang_fail(c, lang_here(lx), "expected '=' after the name, found '%c'", nx);
            if (kind != SYM_ALG) /* solv y: the usual way to start Newton's method at 0 */
                lang_note(c, pos, "'%s' has no value in the %s list: 0", name, keyword);
            e = lang_num(c, 0.0);
        }
        if (kind == SYM_PARAM || kind == SYM_NUMBER) {
            const double v = const_value(c, e, lang_printf(c, "the value of %s '%s'",
                                                           kind == SYM_PARAM ? "parameter"
                                                                             : "number",
                                                           name));
            check_new_name(c, name, pos);
            lvec *vec = kind == SYM_PARAM ? &c->m.params : &c->m.numbers;
            lang_declare(c, name, pos, kind, vec->n);
            lang_param *p = lvec_push(c, vec, sizeof *p);
            p->name = name;
            p->pos = pos;
            p->value = v;
        } else if (kind == SYM_ALG) {
            if (c->m.algs.n >= LANG_MAX_ALG)
                lang_fail(c, pos, "more than %d algebraic variables ('solv')", LANG_MAX_ALG);
            check_constant_value(c, e, "the initial guess", name);
            add_formula(c, &c->m.algs, SYM_ALG, name, pos, e);
        } else {
            add_init(c, name, pos, e, 0);
        }
        count++;
        int ch = lang_skip_blanks(lx);
        if (ch == ';') {
            /* XPPAUT 6.11 reads an item's value with atof: `K4=200;` is 200, and what is
             * joined to the ';' (`a=1;b=2`: b) is not read (measured) */
            const lpos spos = lang_here(lx);
            const int from = ++lx->i;
            while (lx->i < lx->end && lx->line->text[lx->i] != ',' &&
                   lx->line->text[lx->i] != ' ' && lx->line->text[lx->i] != '\t')
                lx->i++;
            if (lx->i > from)
                lang_note(c, spos, "'%.*s' after ';' in the %s list is not read, as XPPAUT "
                          "does not read it", lx->i - from, lx->line->text + from, keyword);
            ch = lang_skip_blanks(lx);
        }
        if (ch == ',') {
            const lpos comma = lang_here(lx);
            lx->i++;
            if (!lang_skip_blanks(lx)) { /* `par ka1=0.1,`: XPPAUT 6.11 reads the line */
                lang_note(c, comma, "a ',' ends the %s list: nothing follows it", keyword);
                return;
            }
            continue;
        }
        if (!ch)
            return;
        if (lang_is_ident_start(ch))
            continue;
        lang_fail(c, lang_here(lx), "unexpected '%c' in the %s list (name=value, ...)", ch,
                  keyword);
    }
}

/* wiener NAME, NAME ...: Wiener noises (dynkit/sde.h: dW/dt over a step, XPPAUT's meaning) */
static void parse_wiener(lang_ctx *c, lang_lexer *lx)
{
    int count = 0;
    for (;;) {
        lpos pos;
        const char *name = lang_read_name(lx, &pos, count ? "expected a name"
                                                          : "expected a name after 'wiener'");
        check_new_name(c, name, pos);
        lang_declare(c, name, pos, SYM_NOISE, c->m.noises.n);
        lang_noise *nz = lvec_push(c, &c->m.noises, sizeof *nz);
        nz->name = name;
        nz->pos = pos;
        nz->kind = DYN_NOISE_WIENER;
        count++;
        int ch = lang_skip_blanks(lx);
        if (ch == ',' || ch == ';') {
            lx->i++;
            ch = lang_skip_blanks(lx);
        }
        if (!ch)
            return;
        if (!lang_is_ident_start(ch))
            lang_fail(c, lang_here(lx), "unexpected '%c' in the wiener list (names separated "
                      "by commas or blanks)", ch);
    }
}

static void parse_global(lang_ctx *c, lang_lexer *lx, pstate *ps, lpos kpos)
{
    int ch = lang_skip_blanks(lx);
    const lpos spos = lang_here(lx);
    int sign = 1;
    if (ch == '-' || ch == '+') {
        sign = ch == '-' ? -1 : 1;
        lx->i++;
        ch = lang_skip_blanks(lx);
    }
    if (!isdigit(ch))
        lang_fail(c, spos, "expected the direction of the global after 'global': 1 (rising), "
                  "-1 (falling) or 0 (when a reset takes it to zero)");
    int d = 0;
    while (lx->i < lx->end && isdigit((unsigned char)lx->line->text[lx->i])) {
        d = d * 10 + (lx->line->text[lx->i] - '0');
        if (d > 1000)
            break;
        lx->i++;
    }
    if (d > 1)
        lang_fail(c, spos, "the direction of a global is 1 (rising), -1 (falling) or 0 (when a reset takes it to zero)");
    node *cond;
    if (lang_skip_blanks(lx) == '{') {
        /* global 1 {x-1} {x=0}: the condition in braces */
        lx->i++;
        cond = lang_parse_expr(lx);
        lang_expect_char(lx, '}', "expected '}' after the global's condition");
    } else {
        cond = lang_parse_expr(lx);
    }
    lang_expect_char(lx, '{', "expected '{' with the assignments after the global's condition");
    lvec assign = {0};
    for (;;) {
        ch = lang_skip_blanks(lx);
        if (ch == '}') {
            lx->i++;
            break;
        }
        lpos pos;
        const char *name = lang_read_name(lx, &pos, "expected 'name=value' or '}' in the global");
        lang_expect_char(lx, '=', "expected '=' after the name in the global");
        lang_assign *a = lvec_push(c, &assign, sizeof *a);
        a->name = name;
        a->pos = pos;
        a->value = lang_parse_expr(lx);
        ch = lang_skip_blanks(lx);
        if (ch == ';' || ch == ',') {
            lx->i++;
            continue;
        }
        if (ch == '}')
            continue;
        if (!ch)
            lang_fail(c, lang_here(lx), "missing '}' at the end of the global");
        lang_fail(c, lang_here(lx), "expected ';' or '}' in the global, found '%c'", ch);
    }
    lang_expect_end(lx, "the global's '}'");
    if (assign.n == 0)
        lang_fail(c, kpos, "a global needs at least one assignment in { }");
    lang_event *ev = lvec_push(c, &c->m.events, sizeof *ev);
    int nglobal = 0;
    for (int i = 0; i < c->m.events.n; i++)
        nglobal += LVEC_AT(c->m.events, lang_event, i).is_global;
    if (ps->global_name && ps->global_name_line) {
        ev->name = ps->global_name;
        ev->description = ps->global_desc;
    } else {
        ev->name = lang_printf(c, "global%d", nglobal + 1);
        ev->description = NULL;
    }
    ps->global_name = NULL;
    ps->global_name_line = 0;
    ev->pos = kpos;
    /* sign 0: "the condition vanishes identically" (XPPAUT's manual); XPPAUT 6.11 fires it
     * when another global's reset takes the condition onto or across zero, never when the
     * flow crosses it (measured; docs/model-files.md) */
    ev->direction = d == 0 ? DYN_EVENT_JUMPS : sign * d;
    ev->cond = cond;
    ev->nassign = assign.n;
    ev->assign = assign.data;
    ev->is_global = 1;
}

/* ---- @ options ---- */

static double option_number(lang_ctx *c, const char *name, const char *v, lpos pos)
{
    char *end;
    const double x = strtod(v, &end);
    if (end == v || *end)
        lang_fail(c, pos, "option '%s' needs a number, not '%s'", name, v);
    return x;
}

/* XPPAUT's methods and dynkit's, to dynkit's: a table anyone can read. every_dt: XPPAUT
 * writes a sample every dt with this method and ignores nout (measured with XPPAUT 6.11:
 * `@ dt=.1,total=10,nout=10` gives 101 rows with gear, qualrk, stiff, cvode, 5dp, 83dp and
 * 2rb, 11 with the others); dynkit's own names of adaptive methods do the same. */
static const struct {
    const char *name, *method, *why;
    int every_dt;
} methods[] = {
    /* XPPAUT's names (manual, "Options": METH=) */
    {"euler", "euler", NULL, 0},
    {"modeuler", "heun", NULL, 0},
    {"rungekutta", "rk4", NULL, 0},
    {"adams", "rk4", "XPPAUT's 4th-order Adams-Bashforth runs as rk4, the same order and step",
     0},
    {"gear", "rodas4", NULL, 1},
    {"volterra", "rodas4", "XPPAUT's implicit volterra method runs as the stiff rodas4", 0},
    {"backeul", "rodas4", "backward Euler runs as the stiff rodas4", 0},
    {"qualrk", "dp45", NULL, 1},
    {"stiff", "rodas4", NULL, 1},
    {"cvode", "rodas4", NULL, 1},
    {"5dp", "dp45", NULL, 1},
    {"83dp", "dop853", NULL, 1},
    {"2rb", "rodas4", NULL, 1},
    {"ymp", "rk4", "XPPAUT's symplectic ymp runs as rk4 with the same step", 0},
    /* other spellings */
    {"rk4", "rk4", NULL, 0},
    {"runge", "rk4", NULL, 0},
    {"rk", "rk4", NULL, 0},
    {"heun", "heun", NULL, 0},
    {"midpoint", "midpoint", NULL, 0},
    {"bs23", "bs23", NULL, 1},
    {"ode23", "bs23", NULL, 1},
    {"dp45", "dp45", NULL, 1},
    {"dopri5", "dp45", NULL, 1},
    {"ode45", "dp45", NULL, 1},
    {"dop853", "dop853", NULL, 1},
    {"rodas4", "rodas4", NULL, 1},
    {"rosen", "rodas4", NULL, 1},
    {"rosenbrock", "rodas4", NULL, 1},
};

static void set_method(lang_ctx *c, const char *v, lpos pos)
{
    const size_t n = strlen(v);
    int is_discrete = n > 0;
    for (size_t k = 0; k < n && is_discrete; k++)
        if (k >= 8 || tolower((unsigned char)v[k]) != "discrete"[k])
            is_discrete = 0;
    c->m.map_meth = is_discrete; /* the last meth counts, as in XPPAUT */
    if (is_discrete) { /* XPPAUT takes any prefix: disc, d */
        if (!c->m.map_eq)
            c->m.map_pos = pos;
        c->m.has_meth = 1;
        c->m.meth_name = v;
        return;
    }
    if (n == 0)
        lang_fail(c, pos, "option 'meth' needs a method name");
    int found = -1;
    for (size_t i = 0; i < sizeof methods / sizeof methods[0] && found < 0; i++)
        if (ieqn(v, n, methods[i].name))
            found = (int)i;
    /* XPPAUT takes the first method its value begins: r = rungekutta, 8 = 83dp */
    for (size_t i = 0; i < 14 && found < 0; i++)
        if (n < strlen(methods[i].name)) {
            int ok = 1;
            for (size_t k = 0; k < n; k++)
                if (tolower((unsigned char)v[k]) != methods[i].name[k])
                    ok = 0;
            if (ok)
                found = (int)i;
        }
    /* and otherwise by its first letter alone (measured with XPPAUT 6.11: runge-kutta and rxyz
     * run RK4, euler-foo Euler, modx the modified Euler method, 5dpx Dormand-Prince, dx a
     * discrete map); the first letters of its 15 methods differ */
    const int first = tolower((unsigned char)v[0]);
    for (size_t i = 0; i < 14 && found < 0; i++)
        if (first == methods[i].name[0]) {
            found = (int)i;
            lang_note(c, pos, "meth=%s is read by its first letter as '%s', as XPPAUT does", v,
                      methods[i].name);
        }
    if (found < 0 && first == 'd') {
        lang_note(c, pos, "meth=%s is read by its first letter as 'discrete', as XPPAUT does", v);
        c->m.map_meth = 1;
        if (!c->m.map_eq)
            c->m.map_pos = pos;
        c->m.has_meth = 1;
        c->m.meth_name = v;
        return;
    }
    if (found < 0) {
        const char *names[sizeof methods / sizeof methods[0]];
        for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
            names[i] = methods[i].name;
        const char *near = dyn_lang_nearest(v, names, (int)(sizeof names / sizeof names[0]));
        lang_fail(c, pos, "unknown method '%s'%s%s%s", v, near ? " (did you mean '" : "",
                  near ? near : "", near ? "'?)" : "");
    }
    c->m.method = methods[found].method;
    c->m.has_meth = 1;
    c->m.meth_every_dt = methods[found].every_dt;
    c->m.meth_name = v;
    if (methods[found].why)
        lang_note(c, pos, "meth=%s: %s", v, methods[found].why);
    else
        lang_note(c, pos, "meth=%s runs as dynkit's %s", v, methods[found].method);
}

/* AUTO's settings an @ line may give, as dyn_ode_auto_options names them (dynkit/lang.h) */
static const char *const auto_names[] = {
    "ntst",   "nmax",    "npr",      "ncol",     "ds",       "dsmin",    "dsmax", "parmin",
    "parmax", "par2min", "par2max",  "autoxmin", "autoxmax", "autoymin", "autoymax",
    "autovar", NULL};

/* An @ option of AUTO (XPPAUT's manual, "AUTO"): kept with its place for dynkit continue
 * (dyn_ode_auto_options); a run does not use it. 1 when name is one, else 0. */
static int auto_option(lang_ctx *c, lpos pos, const char *name, const char *value)
{
    const size_t n = strlen(name);
    for (int i = 0; auto_names[i]; i++)
        if (ieqn(name, n, auto_names[i])) {
            lang_auto_option *o = lvec_push(c, &c->m.auto_opts, sizeof *o);
            o->name = auto_names[i];
            o->value = value;
            o->pos = pos;
            lang_note(c, pos, "option '%s' is AUTO's: dynkit continue reads it; a run does not "
                      "use it", name);
            return 1;
        }
    return 0;
}

/* An @ option a run does not use (XPPAUT's manual, "Options"), named with its value (two
 * `fold=` options are two warnings that differ): a warning, as nothing a file
 * asks for is left out without a word: XPPAUT's window and its colours and fonts, which
 * dynkit does not draw, and what dynkit does not do at all (range integrations, stochastic
 * averages, a torus's folding, ...). */
static void option_not_used(lang_ctx *c, lpos pos, const char *name, const char *value)
{
    static const char *const window_options[] = {
        "zp",       "zplot",  "xmin",      "xmax",   "ymin",     "ymax",    "zmin",
        "zmax",     "axes",   "nplot",     "phi",    "theta",    "bell",    "back",
        "smallfont", "bigfont", "smc",     "umc",    "lt",       "but",     "colormap",
        "grads",    "xnc",    "ync",       "nmesh",  "ps_color", "ps_font", "ps_fsize",
        "ps_lw",    "height", "width",     "plotfmt", "autoeval"};
    const size_t n = strlen(name);
    int window = 0;
    for (size_t i = 0; i < sizeof window_options / sizeof window_options[0]; i++)
        window |= ieqn(name, n, window_options[i]);
    /* xp2..xp8, yp2.., zp2..: the curves of XPPAUT's other plots */
    if (n >= 3 && strchr("xyzXYZ", name[0]) && tolower((unsigned char)name[1]) == 'p' &&
        isdigit((unsigned char)name[2]))
        window = 1;
    if (window)
        lang_warn(c, pos, "option '%s=%.40s' sets XPPAUT's window, which dynkit does not draw "
                  "(dynkit plot draws xp, yp in xlo..xhi, ylo..yhi): ignored", name, value);
    else
        lang_warn(c, pos, "option '%s=%.40s' is read and ignored: dynkit does not do what it "
                  "asks (docs/model-files.md, \"Options\")", name, value);
}

static void parse_options(lang_ctx *c, lang_lexer *lx)
{
    for (;;) {
        int ch = lang_skip_blanks(lx);
        if (!ch)
            return;
        if (ch == ',') {
            lx->i++;
            continue;
        }
        lpos pos;
        const char *name = lang_read_name(lx, &pos, "expected an option name=value");
        if (lang_skip_blanks(lx) != '=') {
            /* "@ done": XPPAUT 8 skips a word without '=' on an @ line */
            const int nx = lang_skip_blanks(lx);
            if (nx && nx != ',' && !lang_is_ident_start(nx))
                lang_expect_char(lx, '=', "expected '=' after the option's name");
            lang_warn(c, pos, "option '%s' has no '=value': the word is ignored, as XPPAUT "
                      "does", name);
            continue;
        }
        lang_expect_char(lx, '=', "expected '=' after the option's name");
        lang_skip_blanks(lx);
        const lpos vpos = lang_here(lx);
        const int a = lx->i;
        while (lx->i < lx->end && lx->line->text[lx->i] != ',' &&
               lx->line->text[lx->i] != ' ' && lx->line->text[lx->i] != '\t')
            lx->i++;
        const char *v = lang_strndup(c, lx->line->text + a, (size_t)(lx->i - a));
        const size_t n = strlen(name);
        lang_model *m = &c->m;
        if (ieqn(name, n, "total")) {
            m->total = option_number(c, name, v, vpos);
            m->total_pos = vpos;
            if (!(m->total > 0) || !isfinite(m->total))
                lang_fail(c, vpos, "total must be a finite number > 0");
        } else if (ieqn(name, n, "t0")) {
            m->t0 = option_number(c, name, v, vpos);
            if (!isfinite(m->t0))
                lang_fail(c, vpos, "t0 must be finite");
        } else if (ieqn(name, n, "dt")) {
            m->dt = option_number(c, name, v, vpos);
            m->dt_pos = vpos;
            if (m->dt < 0)
                lang_fail(c, vpos, "dt < 0 (integration backwards in time) is not supported");
            if (!(m->dt > 0) || !isfinite(m->dt))
                lang_fail(c, vpos, "dt must be a finite number > 0");
        } else if (ieqn(name, n, "meth") || ieqn(name, n, "method")) {
            set_method(c, v, vpos);
        } else if (ieqn(name, n, "tol") || ieqn(name, n, "toler")) {
            m->rtol = option_number(c, name, v, vpos);
            if (!(m->rtol > 0) || !isfinite(m->rtol))
                lang_fail(c, vpos, "tol must be a finite number > 0");
        } else if (ieqn(name, n, "atol") || ieqn(name, n, "atoler")) {
            m->atol = option_number(c, name, v, vpos);
            if (!(m->atol > 0) || !isfinite(m->atol))
                lang_fail(c, vpos, "atol must be a finite number > 0");
        } else if (ieqn(name, n, "bound") || ieqn(name, n, "bounds")) {
            m->bound = option_number(c, name, v, vpos);
            if (!(m->bound > 0))
                lang_fail(c, vpos, "bound must be a number > 0");
        } else if (ieqn(name, n, "trans") || ieqn(name, n, "transient")) {
            m->trans = option_number(c, name, v, vpos);
            if (!isfinite(m->trans))
                lang_fail(c, vpos, "trans must be finite");
        } else if (ieqn(name, n, "nout") || ieqn(name, n, "njmp")) {
            const double k = option_number(c, name, v, vpos);
            if (!(k >= 1 && k <= 1e9) || k != floor(k))
                lang_fail(c, vpos, "%s must be a whole number >= 1", name);
            m->nout = (long)k;
            m->nout_pos = pos;
        } else if (ieqn(name, n, "xp") || ieqn(name, n, "xplot")) {
            m->xp = v;
            m->xp_pos = vpos;
        } else if (ieqn(name, n, "xlo") || ieqn(name, n, "xhi") || ieqn(name, n, "ylo") ||
                   ieqn(name, n, "yhi")) {
            const double w = option_number(c, name, v, vpos);
            if (!isfinite(w))
                lang_fail(c, vpos, "%s must be a finite number", name);
            m->window[(tolower((unsigned char)name[0]) == 'y' ? 2 : 0) +
                      (tolower((unsigned char)name[1]) == 'h' ? 1 : 0)] = w;
        } else if (ieqn(name, n, "yp") || ieqn(name, n, "yplot")) {
            m->yp = v;
            m->yp_pos = vpos;
        } else if (ieqn(name, n, "bandlo") || ieqn(name, n, "bandup")) {
            const double k = option_number(c, name, v, vpos);
            if (!(k >= 0 && k <= 1e6) || k != floor(k))
                lang_fail(c, vpos, "%s must be a whole number >= 0 (a bandwidth of the "
                          "Jacobian)", name);
            if (ieqn(name, n, "bandlo"))
                m->band_lo = (int)k;
            else
                m->band_up = (int)k;
            if (!m->has_band)
                m->band_pos = pos;
            m->has_band = 1;
        } else if (ieqn(name, n, "newt_iter") || ieqn(name, n, "newt_tol") ||
                   ieqn(name, n, "jac_eps")) {
            lang_note(c, pos,
                      "option '%s' is accepted and ignored: dynkit solves the algebraic "
                      "equations by Newton's method until it converges, with its own "
                      "difference step",
                      name);
        } else if (ieqn(name, n, "delay")) {
            m->max_delay = option_number(c, name, v, vpos);
            m->max_delay_given = 1;
            if (!(m->max_delay >= 0) || !isfinite(m->max_delay))
                lang_fail(c, vpos, "delay (the maximal delay) must be a finite number >= 0");
        } else if (ieqn(name, n, "vmaxpts")) {
            const double k = option_number(c, name, v, vpos);
            if (!(k >= 1.0 && k <= 1e7) || k != floor(k))
                lang_fail(c, vpos, "vmaxpts (the grid points the Volterra integrals keep) must "
                                   "be a whole number from 1 to 10000000");
            m->vmaxpts = (long)k;
        } else if (ieqn(name, n, "poimap")) {
            /* XPPAUT reads the first letter: section, maxmin (max), period */
            const int k = tolower((unsigned char)v[0]);
            m->poimap = k == 's' ? DYN_POINCARE_SECTION
                        : k == 'm' ? DYN_POINCARE_EXTREMUM
                        : k == 'p' ? DYN_POINCARE_PERIOD : -1;
            if (m->poimap < 0)
                lang_fail(c, vpos, "poimap=%s: give section, max (maxmin) or period", v);
            m->poimap_pos = pos;
        } else if (ieqn(name, n, "poivar")) {
            m->poivar = v;
            m->poivar_pos = vpos;
        } else if (ieqn(name, n, "poipln")) {
            m->poipln = option_number(c, name, v, vpos);
            if (!isfinite(m->poipln))
                lang_fail(c, vpos, "poipln must be a finite number");
        } else if (ieqn(name, n, "poisgn") || ieqn(name, n, "poistop")) {
            const double k = option_number(c, name, v, vpos);
            if (ieqn(name, n, "poistop") ? !(k == 0 || k == 1) : !(k == -1 || k == 0 || k == 1))
                lang_fail(c, vpos, "%s must be %s", name,
                          ieqn(name, n, "poistop") ? "0 or 1" : "1, -1 or 0");
            *(ieqn(name, n, "poistop") ? &m->poistop : &m->poisgn) = (int)k;
        } else if (ieqn(name, n, "maxstor")) {
            lang_note(c, pos, "option 'maxstor' is accepted and ignored (dynkit streams its "
                      "samples; nothing to store)");
        } else if (!auto_option(c, vpos, name, v)) {
            option_not_used(c, pos, name, v);
        }
    }
}

/* ---- lookup tables ---- */

static char *rest_text(lang_lexer *lx);
static char *trimmed(lang_ctx *c, const char *s, size_t n);

/* A number written in a table statement, at the cursor. */
static double table_number(lang_ctx *c, lang_lexer *lx, const char *what)
{
    lang_skip_blanks(lx);
    const lpos pos = lang_here(lx);
    const char *from = lx->line->text + lx->i;
    char *end;
    const double v = strtod(from, &end);
    if (end == from || !isfinite(v))
        lang_fail(c, pos, "expected %s of the table (a number)", what);
    lx->i += (int)(end - from);
    return v;
}

/* The number of points n of table name, written where (NULL: in the statement, else the
 * file that begins with it): a whole number from 1 to LANG_MAX_TABLE, or fail. */
static long table_points(lang_ctx *c, const char *name, double n, const char *where, lpos pos)
{
    if (!(n == floor(n) && n >= 1 && n <= LANG_MAX_TABLE))
        lang_fail(c, pos, "table '%s'%s%s%s: %.15g points: give a whole number from 1 to %d", name,
                  where ? " ('" : "", where ? where : "", where ? "' begins with it)" : "", n,
                  LANG_MAX_TABLE);
    return (long)n;
}

/* The abscissas of a table whose points are counted already. */
static void table_size(lang_ctx *c, lang_table *tb, lpos pos)
{
    if (tb->npts > 1 && !(tb->hi > tb->lo))
        lang_fail(c, pos, "table '%s': the last abscissa %g must be above the first, %g",
                  tb->name, tb->hi, tb->lo);
    if (!isfinite(tb->lo) || !isfinite(tb->hi) || !isfinite(tb->hi - tb->lo))
        lang_fail(c, pos, "table '%s': the abscissas %g to %g are not finite numbers with a "
                  "finite span", tb->name, tb->lo, tb->hi);
}

/* Up to max values from fp into v, stopping at a word that is not a number or at a value
 * that is not finite; returns how many finite ones were read. */
static long scan_values(FILE *fp, double *v, long max)
{
    long k = 0;
    while (k < max && fscanf(fp, "%lf", &v[k]) == 1 && isfinite(v[k]))
        k++;
    return k;
}

/* The values of a table file (XPPAUT's format: npts, xlo, xhi, then npts values, separated
 * by blanks or line ends): a file beside the model file or named by the caller
 * (table_file.c). */
static void read_table_file(lang_ctx *c, lang_table *tb, const char *file, lpos pos)
{
    const char *path;
    FILE *fp = lang_open_table_file(c, tb->name, file, pos, &path);
    double head[3]; /* read as numbers, finite or not (table_size judges the abscissas) */
    int got = 0;
    while (got < 3 && fscanf(fp, "%lf", &head[got]) == 1)
        got++;
    /* the values when the count can be one (table_points judges it below) */
    const long want = got == 3 && head[0] >= 1 && head[0] <= LANG_MAX_TABLE ? (long)head[0] : 0;
    double *v = want ? lang_alloc(c, (size_t)want * sizeof *v) : NULL;
    const long k = want ? scan_values(fp, v, want) : 0;
    fclose(fp);
    if (got < 3)
        lang_fail(c, pos, "table '%s': '%s' must begin with the number of points, xlo and xhi",
                  tb->name, path);
    tb->npts = table_points(c, tb->name, head[0], path, pos);
    tb->lo = head[1];
    tb->hi = head[2];
    if (k < tb->npts)
        lang_fail(c, pos, "table '%s': '%s' has %ld finite values after its first three "
                  "numbers; it announces %ld", tb->name, path, k, tb->npts);
    tb->values = v;
    table_size(c, tb, pos);
}

/* table NAME % NPTS XLO XHI FORMULA (also `table % NAME ...`), or table NAME FILE (XPPAUT's
 * manual, "table"); t in the formula runs over the abscissas. */
static void parse_table(lang_ctx *c, lang_lexer *lx)
{
    lpos npos;
    int formula = lang_skip_blanks(lx) == '%';
    if (formula)
        lx->i++;
    const char *name = lang_read_name(lx, &npos, "expected the table's name after 'table'");
    if (!formula && lang_skip_blanks(lx) == '%') {
        lx->i++;
        formula = 1;
    }
    check_new_name(c, name, npos);
    lang_table tb = {0};
    tb.name = name;
    tb.pos = npos;
    if (formula) {
        tb.npts = table_points(c, name, table_number(c, lx, "the number of points"), NULL, npos);
        tb.lo = table_number(c, lx, "the first abscissa");
        tb.hi = table_number(c, lx, "the last abscissa");
        tb.expr = expr_to_end(lx, "the table's formula of t");
        table_size(c, &tb, npos);
    } else {
        const lpos fpos = (lang_skip_blanks(lx), lang_here(lx));
        const char *file = rest_text(lx);
        if (!*file)
            lang_fail(c, fpos, "table '%s': expected a file name, or %% and a formula", name);
        tb.file = file;
        read_table_file(c, &tb, file, fpos);
    }
    lang_declare(c, name, npos, SYM_TABLE, c->m.tables.n);
    *(lang_table *)lvec_push(c, &c->m.tables, sizeof tb) = tb;
}

/* ---- network sums ---- */

/* The next argument of a special's call: the text up to ',' or ')', trimmed; *last set when
 * it ends the list. */
static const char *special_arg(lang_ctx *c, lang_lexer *lx, lpos *pos, int *last)
{
    lang_skip_blanks(lx);
    *pos = lang_here(lx);
    const int from = lx->i;
    while (lx->i < lx->end && lx->line->text[lx->i] != ',' && lx->line->text[lx->i] != ')')
        lx->i++;
    if (lx->i >= lx->end)
        lang_fail(c, *pos, "expected ',' or ')' in the special's arguments");
    *last = lx->line->text[lx->i] == ')';
    lx->i++;
    return trimmed(c, lx->line->text + from, (size_t)(lx->i - 1 - from));
}

static int special_count(lang_ctx *c, const char *v, lpos pos, const char *what, int min)
{
    char *end;
    const double x = strtod(v, &end);
    if (end == v || *end || x != floor(x) || x < min || x > LANG_MAX_RANGE)
        lang_fail(c, pos, "expected %s (a whole number from %d to %d), not '%s'", what, min,
                  LANG_MAX_RANGE, v);
    return (int)x;
}

/* special NAME=conv(TYPE, N, M, W, ROOT), fconv(TYPE, N, M, W, ROOT, VROOT, F),
 * mmult(M, N, W, ROOT) or sparse(N, M, W, L, ROOT) (XPPAUT's manual, "special"); the other
 * sums are refused by name. */
static void parse_special(lang_ctx *c, lang_lexer *lx, lpos kpos)
{
    lpos npos, fpos;
    const char *name = lang_read_name(lx, &npos, "expected the network sum's name after 'special'");
    lang_expect_char(lx, '=', "expected '=' after the network sum's name");
    const char *fun = lang_read_name(lx, &fpos, "expected conv(...) after 'special NAME='");
    if (strcasecmp(fun, "gill") == 0) {
        lang_gill_parse(c, lx, name, npos, kpos);
        return;
    }
    static const struct {
        const char *name, *args;
        int nargs;
    } sums[] = {{"conv", "type, n, m, the table, the first variable", 5},
                {"fconv", "type, n, m, the table, the first of u, the first of v, the function", 7},
                {"mmult", "m, n, the table, the first variable", 4},
                {"sparse", "n, m, the weights, the indices, the first variable", 5}};
    int kind = -1;
    for (int k = 0; k < 4; k++)
        if (strcasecmp(fun, sums[k].name) == 0)
            kind = k;
    if (kind < 0)
        lang_fail(c, kpos, "network sums ('special' with %s) are not supported: conv, fconv, "
                  "mmult, sparse and gill are", fun);
    const int fconv = kind == LANG_SUM_FCONV, want = sums[kind].nargs;
    lang_expect_char(lx, '(', "expected '(' after conv");
    lpos apos[7];
    const char *arg[7];
    int last = 0, n = 0;
    while (!last) {
        if (n == want)
            lang_fail(c, apos[n - 1], "%s takes %d arguments", fun, want);
        arg[n] = special_arg(c, lx, &apos[n], &last);
        n++;
    }
    if (n != want)
        lang_fail(c, fpos, "%s takes %d arguments (%s), not %d", fun, want, sums[kind].args, n);
    lang_expect_end(lx, "the network sum");
    check_new_name(c, name, npos);
    lang_special sp = {0};
    sp.name = name;
    sp.pos = npos;
    sp.kind = kind;
    if (kind == LANG_SUM_MMULT || kind == LANG_SUM_SPARSE) {
        const int mm = kind == LANG_SUM_MMULT;
        sp.n = special_count(c, arg[mm ? 1 : 0], apos[mm ? 1 : 0], "the number of sums", 1);
        sp.m = special_count(c, arg[mm ? 0 : 1], apos[mm ? 0 : 1], "the terms of each sum", 1);
        sp.table_name = arg[2];
        sp.table_pos = apos[2];
        if (!mm) {
            sp.index_name = arg[3];
            sp.index_pos = apos[3];
        }
        sp.root_name = arg[mm ? 3 : 4];
        sp.root_pos = apos[mm ? 3 : 4];
    } else {
        /* XPPAUT reads the type by its first letter (junk.ode writes 'period') */
        const int t0 = tolower((unsigned char)arg[0][0]);
        if (t0 == 'e')
            sp.type = LANG_CONV_EVEN;
        else if (t0 == 'p')
            sp.type = LANG_CONV_PERIODIC;
        else if (strcmp(arg[0], "0") == 0)
            sp.type = LANG_CONV_ZERO;
        else
            lang_fail(c, apos[0],
                      "conv's type is even, periodic or 0 (zero beyond the ends), "
                      "not '%s'",
                      arg[0]);
        sp.n = special_count(c, arg[1], apos[1], "the number of sums", 1);
        sp.m = special_count(c, arg[2], apos[2], "the half-width", 0);
        sp.table_name = arg[3];
        sp.table_pos = apos[3];
        sp.root_name = arg[4];
        sp.root_pos = apos[4];
        if (fconv) {
            sp.vroot_name = arg[5];
            sp.vroot_pos = apos[5];
            sp.func_name = arg[6];
            sp.func_pos = apos[6];
        }
    }
    lang_declare(c, name, npos, SYM_SPECIAL, c->m.specials.n);
    *(lang_special *)lvec_push(c, &c->m.specials, sizeof sp) = sp;
}

/* ---- #: extension lines ---- */

static char *trimmed(lang_ctx *c, const char *s, size_t n)
{
    while (n && (*s == ' ' || *s == '\t'))
        s++, n--;
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t'))
        n--;
    return lang_strndup(c, s, n);
}

/* The rest of the line from the cursor, without a leading "--". */
static char *rest_text(lang_lexer *lx)
{
    lang_skip_blanks(lx);
    if (lx->i + 1 < lx->end && lx->line->text[lx->i] == '-' && lx->line->text[lx->i + 1] == '-')
        lx->i += 2;
    char *s = trimmed(lx->c, lx->line->text + lx->i, (size_t)(lx->end - lx->i));
    lx->i = lx->end;
    return s;
}

static void append_desc(lang_ctx *c, const char *s)
{
    if (!c->m.description || !*c->m.description)
        c->m.description = s;
    else
        c->m.description = lang_printf(c, "%s\n%s", c->m.description, s);
}

static void extension(lang_ctx *c, lang_lexer *lx, pstate *ps)
{
    lpos pos;
    const int ch = lang_skip_blanks(lx);
    if (!ch)
        return; /* an empty "#:" line */
    const char *word = lang_read_name(lx, &pos, "expected 'title', 'description', 'event' or a "
                                                "declared name after '#:'");
    const size_t n = strlen(word);
    if (ieqn(word, n, "title")) {
        c->m.title = rest_text(lx);
        return;
    }
    if (ieqn(word, n, "description")) {
        append_desc(c, rest_text(lx));
        return;
    }
    if (ieqn(word, n, "event") && lang_skip_blanks(lx) != '[') {
        const char *name = lang_read_name(lx, &pos, "expected the event's name after '#: event'");
        const lpos npos = pos;
        if (lang_skip_blanks(lx) != '=') {
            /* names the global on the next line */
            const char *desc = rest_text(lx);
            ps->global_name = name;
            ps->global_desc = *desc ? desc : NULL;
            ps->global_name_line = npos.line;
            return;
        }
        lx->i++;
        node *cond = lang_parse_expr(lx);
        lang_expect_char(lx, ',', "expected ', rising', ', falling' or ', both' after the event's "
                                  "expression");
        lpos dpos;
        const char *dir = lang_read_name(lx, &dpos, "expected rising, falling or both");
        int direction;
        if (ieqn(dir, strlen(dir), "rising"))
            direction = 1;
        else if (ieqn(dir, strlen(dir), "falling"))
            direction = -1;
        else if (ieqn(dir, strlen(dir), "both"))
            direction = 0;
        else
            lang_fail(c, dpos, "expected rising, falling or both, found '%s'", dir);
        int terminal = 0;
        if (lang_skip_blanks(lx) == ',') {
            lx->i++;
            lpos tpos;
            const char *w = lang_read_name(lx, &tpos, "expected 'stop' after ','");
            if (!ieqn(w, strlen(w), "stop"))
                lang_fail(c, tpos, "expected 'stop' after ',', found '%s'", w);
            terminal = 1;
        }
        const int rc = lang_skip_blanks(lx);
        if (rc && !(rc == '-' && lx->i + 1 < lx->end && lx->line->text[lx->i + 1] == '-'))
            lang_fail(c, lang_here(lx), "expected '-- description' or the end of the line");
        const char *desc = rest_text(lx);
        for (int i = 0; i < c->m.events.n; i++)
            if (ieqn(LVEC_AT(c->m.events, lang_event, i).name, strlen(name), name))
                lang_fail(c, npos, "event '%s' is declared twice", name);
        lang_event *ev = lvec_push(c, &c->m.events, sizeof *ev);
        ev->name = name;
        ev->description = *desc ? desc : NULL;
        ev->pos = npos;
        ev->direction = direction;
        ev->terminal = terminal;
        ev->cond = cond;
        return;
    }
    /* t [UNIT]: the unit of the time (ms for a neuron model); a description is allowed */
    if (n == 1 && word[0] == 't') {
        if (lang_skip_blanks(lx) != '[')
            lang_fail(c, lang_here(lx), "expected the unit of the time in brackets after "
                      "'#: t' (e.g. '#: t [ms]')");
        const int a = ++lx->i;
        while (lx->i < lx->end && lx->line->text[lx->i] != ']')
            lx->i++;
        if (lx->i >= lx->end)
            lang_fail(c, lang_here(lx), "missing ']' after the unit");
        c->m.time_unit = trimmed(c, lx->line->text + a, (size_t)(lx->i - a));
        lx->i++;
        rest_text(lx);
        return;
    }
    /* NAME [UNIT] description */
    lang_docline *d = lvec_push(c, &c->m.docs, sizeof *d);
    d->name = word;
    d->pos = pos;
    if (lang_skip_blanks(lx) == '[') {
        const int a = ++lx->i;
        while (lx->i < lx->end && lx->line->text[lx->i] != ']')
            lx->i++;
        if (lx->i >= lx->end)
            lang_fail(c, lang_here(lx), "missing ']' after the unit");
        d->doc.unit = trimmed(c, lx->line->text + a, (size_t)(lx->i - a));
        lx->i++;
    }
    const char *desc = rest_text(lx);
    d->doc.description = *desc ? desc : NULL;
}

/* ---- statements ---- */

static const char *const keywords[] = {
    "par", "param", "params", "pars", "parameter", "parameters", "p", "number", "num", "n", "init", "initial",
    "i", "aux", "a", "global", "g", "done", "d", "markov", "m", "wiener", "w", "table", "tab",
    "bdry", "bndry", "b", "boundary", "volt", "volterra", "v", "set", "special", "sp", "solv",
    "solve", "only", "export", "options", "opt"};

int lang_is_statement_keyword(const char *w)
{
    for (size_t i = 0; i < sizeof keywords / sizeof keywords[0]; i++)
        if (strcasecmp(w, keywords[i]) == 0)
            return 1;
    return 0;
}

static int keyword_is(const char *w, size_t n, const char *const *list, int count)
{
    for (int i = 0; i < count; i++)
        if (ieqn(w, n, list[i]))
            return 1;
    return 0;
}
#define KW(w, n, ...)                                                                        \
    keyword_is(w, n, (const char *const[]){__VA_ARGS__},                                     \
               (int)(sizeof((const char *const[]){__VA_ARGS__}) / sizeof(const char *)))

static int keyword_statement(lang_ctx *c, lang_lexer *lx, pstate *ps, const char *w, lpos wpos)
{
    const size_t n = strlen(w);
    if (c->stmt_hook) {
        const int r = c->stmt_hook(c, lx, w, wpos);
        if (r >= 0)
            return r;
    }
    if (KW(w, n, "done", "d"))
        return 1;
    if (KW(w, n, "par", "param", "params", "pars", "parameter", "parameters", "p"))
        name_value_list(c, lx, SYM_PARAM, "par");
    else if (KW(w, n, "number", "num", "n"))
        name_value_list(c, lx, SYM_NUMBER, "number");
    else if (KW(w, n, "init", "initial", "i"))
        name_value_list(c, lx, 0, "init");
    else if (KW(w, n, "aux", "a")) {
        lpos pos;
        const char *name = lang_read_name(lx, &pos, "expected the output's name after 'aux'");
        /* XPPAUT's aux names are labels: P.E. is one */
        if (lx->i < lx->end && lx->line->text[lx->i] == '.') {
            int k = lx->i;
            while (k < lx->end && (lang_is_ident_char((unsigned char)lx->line->text[k]) ||
                                   lx->line->text[k] == '.'))
                k++;
            name = lang_strndup(c, lx->line->text + (lx->i - (int)strlen(name)),
                                strlen(name) + (size_t)(k - lx->i));
            lx->i = k;
        }
        lang_expect_char(lx, '=', "expected '=' after the output's name");
        add_formula(c, &c->m.auxs, SYM_AUX, name, pos, expr_to_end(lx, "the aux formula"));
    } else if (KW(w, n, "global", "g"))
        parse_global(c, lx, ps, wpos);
    else if (KW(w, n, "markov", "m"))
        lang_markov_parse(c, lx, wpos);
    else if (KW(w, n, "wiener", "w"))
        parse_wiener(c, lx);
    else if (KW(w, n, "table", "tab"))
        parse_table(c, lx);
    else if (KW(w, n, "bdry", "bndry", "b", "boundary"))
        lang_bdry_parse(c, lx, wpos);
    else if (KW(w, n, "volt", "volterra", "v"))
        parse_volt(c, lx);
    else if (KW(w, n, "special", "sp"))
        parse_special(c, lx, wpos);
    else if (KW(w, n, "solv", "solve"))
        name_value_list(c, lx, SYM_ALG, "solv");
    else if (KW(w, n, "export"))
        lang_fail(c, wpos, "dynamically loaded right-hand sides ('export') are not supported");
    else if (KW(w, n, "options", "opt"))
        lang_fail(c, wpos, "option files ('options FILE') are not supported; put the options "
                  "in '@' lines");
    else if (KW(w, n, "set")) {
        lang_note(c, wpos, "'set' (a named set of values chosen from XPPAUT's menus) is "
                  "accepted and ignored: the default run does not use it");
        lx->i = lx->end;
    } else if (KW(w, n, "only")) {
        lang_note(c, wpos, "'only' (XPPAUT's batch output columns) is accepted and ignored");
        lx->i = lx->end;
    } else
        return -1;
    return 0;
}

/* XPPAUT 6.11 takes a first word followed by a blank (and not by '=') as a statement and
 * reads it by its first letter (form_ode.c, compile_em): `par1-3 vc=2` is `par vc=2`, so
 * is any word that begins with p; likewise n (number), i (init), au (aux) and g (global,
 * not gr). The word starts at offset from; 0 when read, -1 when it is not such a
 * statement. */
static int by_first_letters(lang_ctx *c, lang_lexer *lx, pstate *ps, lpos wpos, int from)
{
    const char *text = lx->line->text;
    int k = from;
    while (k < lx->end && text[k] != ' ' && text[k] != '\t') {
        if (strchr("=/'(", text[k]))
            return -1;
        k++;
    }
    int next = k;
    while (next < lx->end && (text[next] == ' ' || text[next] == '\t'))
        next++;
    if (k == lx->end || next == lx->end || text[next] == '=')
        return -1;
    const int a = tolower((unsigned char)text[from]), b = tolower((unsigned char)text[from + 1]);
    const char *as = a == 'p'                 ? "par"
                     : a == 'n'               ? "number"
                     : a == 'i'               ? "init"
                     : a == 'a' && b == 'u'   ? "aux"
                     : a == 'g' && b != 'r'   ? "global"
                                              : NULL;
    if (!as)
        return -1;
    lang_note(c, wpos, "'%.*s' is read as '%s', as XPPAUT reads a statement by its first "
              "letters", k - from, text + from, as);
    lx->i = k;
    return keyword_statement(c, lx, ps, as, wpos);
}

static void statement(lang_ctx *c, lang_lexer *lx, pstate *ps, int *done)
{
    lang_model *m = &c->m;
    const int ch = lang_skip_blanks(lx);
    const lpos start = lang_here(lx);
    if (ch == '@') {
        lx->i++;
        parse_options(c, lx);
        return;
    }
    if (ch == '!') {
        lx->i++;
        lpos pos;
        const char *name =
            lang_read_name(lx, &pos, "expected a derived parameter's name after '!'");
        lang_expect_char(lx, '=', "expected '=' after the derived parameter's name");
        add_formula(c, &m->derived, SYM_DERIVED, name, pos,
                    expr_to_end(lx, "the derived parameter's formula"));
        return;
    }
    if (isdigit(ch)) {
        int k = lx->i;
        while (k < lx->end && isdigit((unsigned char)lx->line->text[k]))
            k++;
        while (k < lx->end && (lx->line->text[k] == ' ' || lx->line->text[k] == '\t'))
            k++;
        if (k < lx->end && lx->line->text[k] == '=') {
            const char *digits = lx->line->text + lx->i;
            if (digits[0] != '0' || isdigit((unsigned char)digits[1]))
                lang_fail(c, start, "an algebraic equation is written 0=expression");
            lx->i = k + 1;
            lang_formula *f = lvec_push(c, &m->algeqs, sizeof *f);
            f->name = NULL;
            f->pos = start;
            f->expr = expr_to_end(lx, "the algebraic equation");
            return;
        }
        lang_fail(c, start, "a statement starts with a name, '@', '!' or '#'");
    }
    if (!lang_is_ident_start(ch))
        lang_fail(c, start, "unexpected '%c' at the start of a statement", ch);
    lpos wpos;
    const int wstart = lx->i;
    const char *w = lang_read_name(lx, &wpos, "expected a name");
    const int nc = lang_skip_blanks(lx);
    if (nc != '=' && nc != '\'' && nc != '(' && nc != '/') {
        const int r = keyword_statement(c, lx, ps, w, wpos);
        if (r == 1) {
            *done = 1;
            return;
        }
        if (r == 0) {
            lang_expect_end(lx, "the statement");
            return;
        }
        /* XPPAUT 6.11 reads a word that begins with "tab" as 'table' (nnet2.ode's
         * 'tabular') */
        if (strlen(w) > 3 && strncasecmp(w, "tab", 3) == 0) {
            lang_note(c, wpos, "'%s' is read as 'table', as XPPAUT does", w);
            parse_table(c, lx);
            return;
        }
        if (by_first_letters(c, lx, ps, wpos, wstart) == 0) {
            lang_expect_end(lx, "the statement");
            return;
        }
        const char *near = dyn_lang_nearest(w, keywords, (int)(sizeof keywords /
                                                                sizeof keywords[0]));
        if (near)
            lang_fail(c, wpos, "unknown statement '%s' (did you mean '%s'?)", w, near);
        if (!nc)
            lang_fail(c, lang_here(lx), "expected ' or = after '%s'", w);
        lang_fail(c, lang_here(lx), "unknown statement '%s': expected ' or = after a name", w);
    }
    if (nc == '\'') {
        lx->i++;
        lang_expect_char(lx, '=', "expected '=' after the prime of a differential equation");
        add_state(c, w, wpos, expr_to_end(lx, "the right-hand side"));
        return;
    }
    if (nc == '/') {
        /* dx/dt=... */
        lx->i++;
        lpos tpos;
        const char *dt = lang_read_name(lx, &tpos, "expected 'dt' in dx/dt");
        if ((w[0] != 'd' && w[0] != 'D') || !w[1] || !ieqn(dt, strlen(dt), "dt"))
            lang_fail(c, wpos, "expected a differential equation dx/dt=... or x'=...");
        lang_expect_char(lx, '=', "expected '=' after dx/dt");
        lpos npos = wpos;
        npos.col++;
        add_state(c, w + 1, npos, expr_to_end(lx, "the right-hand side"));
        return;
    }
    if (nc == '(') {
        lx->i++;
        /* x(0)=, x(t)=, x(t+1)=, or f(a,b)= */
        const int a1 = lang_skip_blanks(lx);
        if (a1 == '0') {
            lx->i++;
            lang_expect_char(lx, ')', "expected ')' in x(0)");
            lang_expect_char(lx, '=', "expected '=' after x(0)");
            const int from = (lang_skip_blanks(lx), lx->i);
            node *e = expr_to_end(lx, "the initial value");
            note_formula_value(c, lx, from, e, w);
            add_init(c, w, wpos, e, 1);
            return;
        }
        lpos apos;
        lvec args = {0};
        for (;;) {
            const char *arg = lang_read_name(lx, &apos, "expected the function's argument names");
            const int is_t = ieqn(arg, strlen(arg), "t");
            if (is_t && args.n == 0 && lang_skip_blanks(lx) == '+') {
                parse_map_equation(c, lx, w, wpos);
                return;
            }
            /* x(t)= a formula with an integral: XPPAUT's integral equation; without
             * one, a function of t */
            if (is_t && args.n == 0 && lang_skip_blanks(lx) == ')') {
                const int at = lx->i;
                lx->i++;
                if (lang_skip_blanks(lx) == '=' &&
                    lang_volt_is_int_formula(c, lx->line, lx->i + 1)) {
                    lx->i++; /* '=' */
                    const int i = add_state(c, w, wpos, expr_to_end(lx, "the integral equation"));
                    LVEC_AT(c->m.states, lang_state, i).is_int = 1;
                    return;
                }
                lx->i = at;
            }
            if (is_t && lang_skip_blanks(lx) != ')' && lang_skip_blanks(lx) != ',')
                lang_fail(c, wpos, "expected x(t+1)= (a difference equation) or a function "
                                   "definition f(t,...)= after '%s('", w);
            if (lang_is_reserved(arg) && !is_t)
                lang_fail(c, apos, "'%s' is a reserved word and cannot be an argument", arg);
            for (int k = 0; k < args.n; k++)
                if (ieqn(arg, strlen(arg), LVEC_AT(args, const char *, k)))
                    lang_fail(c, apos, "argument '%s' appears twice", arg);
            *(const char **)lvec_push(c, &args, sizeof(char *)) = arg;
            if (args.n > LANG_MAX_ARGS)
                lang_fail(c, apos, "too many arguments (at most %d)", LANG_MAX_ARGS);
            const int sep = lang_skip_blanks(lx);
            lx->i++;
            if (sep == ')')
                break;
            if (sep != ',')
                lang_fail(c, lang_here(lx), "expected ',' or ')' in the argument list");
        }
        lang_expect_char(lx, '=', "expected '=' after the function's arguments");
        node *body = expr_to_end(lx, "the function's formula");
        check_new_name(c, w, wpos);
        lang_declare(c, w, wpos, SYM_FUNC, m->funcs.n);
        lang_func *f = lvec_push(c, &m->funcs, sizeof *f);
        f->name = w;
        f->pos = wpos;
        f->nargs = args.n;
        f->argnames = args.data;
        f->body = body;
        return;
    }
    /* name=formula: a fixed temporary */
    lx->i++;
    if (lx->i < lx->end && lx->line->text[lx->i] == '=')
        lang_fail(c, lang_here(lx), "'==' is a comparison; a definition is name=formula");
    add_formula(c, &m->fixes, SYM_FIX, w, wpos, expr_to_end(lx, "the formula"));
}

static int on_line(lang_ctx *c, const lang_line *l, void *ctx)
{
    pstate *ps = ctx;
    lang_lexer lx = {c, l, 0, l->len};
    const int ch = lang_skip_blanks(&lx);
    if (!ch)
        return 0;
    if (ch == '#') {
        if (lx.i + 1 < lx.end && l->text[lx.i + 1] == ':') {
            lx.i += 2;
            extension(c, &lx, ps);
            return 0;
        }
        if (!ps->seen_statement) {
            const char *s = trimmed(c, l->text + lx.i + 1, (size_t)(lx.end - lx.i - 1));
            *(const char **)lvec_push(c, &ps->desc, sizeof(char *)) = s;
        }
        return 0;
    }
    if (ch == '"')
        return 0; /* XPPAUT's comments shown in its own window */
    /* a comment after a statement (XPPAUT refuses it; nothing else can be meant) */
    for (int k = lx.i; k < lx.end; k++)
        if (l->text[k] == '#') {
            lx.end = k;
            break;
        }
    ps->seen_statement = 1;
    if (lang_markov_row(c, &lx))
        return 0;
    int done = 0;
    const int named = ps->global_name_line;
    statement(c, &lx, ps, &done);
    if (named && ps->global_name_line)
        lang_fail(c, (lpos){ps->global_name_line, 1},
                  "'#: event %s' without '=' names the global on the next line, but the next "
                  "line is not a global", ps->global_name);
    return done;
}

/* A discrete map iterates its equations (x'= lines too, as XPPAUT does) with the method
 * "discrete", one step per unit of time whatever dt says (XPPAUT 6.11: t goes 0, 1, 2, ...
 * with dt = 0.5), and has no events to locate between its steps. */
static void finish_map(lang_ctx *c)
{
    lang_model *m = &c->m;
    if (m->map_eq && m->has_meth && !m->map_meth)
        lang_note(c, m->map_pos,
                  "x(t+1)= makes the file a discrete map: meth=%s is ignored, as XPPAUT does",
                  m->meth_name);
    if (m->events.n > 0)
        lang_fail(c, LVEC_AT(m->events, lang_event, 0).pos,
                  "events and globals are not supported in a discrete map: its states jump "
                  "from step to step, with nothing to locate between them");
    m->method = "discrete";
    m->meth_every_dt = 0;
    if (m->dt_pos.line && m->dt != 1.0)
        lang_note(c, m->dt_pos, "dt=%g is ignored by a discrete map: t advances by 1 per step, "
                                "as in XPPAUT", m->dt);
    m->dt = 1.0;
    if (m->total != floor(m->total)) { /* XPPAUT takes the whole steps */
        lang_note(c, m->total_pos, "total=%g: a discrete map takes whole steps, %.0f of them "
                  "(as XPPAUT does)", m->total, floor(m->total));
        m->total = floor(m->total);
        if (!(m->total >= 1.0))
            lang_fail(c, m->total_pos, "total must be at least one step of a discrete map");
    }
    lang_note(c, m->map_pos, "a discrete map: y(t+1) = f(t, y), one step per unit of time");
}

void lang_parse_model(lang_ctx *c)
{
    lang_model *m = &c->m;
    m->t0 = 0.0;
    m->total = 20.0;
    m->dt = 0.05;
    m->nout = 1;
    m->poisgn = 1; /* XPPAUT's default: crossings upwards, maxima */
    pstate ps = {0};
    if (c->stmt_hook || !lang_old_format(c, on_line, &ps))
        lang_lines(c, on_line, &ps);
    lang_markov_finish(c);
    if (ps.global_name_line)
        lang_fail(c, (lpos){ps.global_name_line, 1},
                  "'#: event %s' without '=' names the global on the next line, but there is "
                  "none", ps.global_name);
    /* the leading comment lines describe the model */
    const char *lead = NULL;
    for (int i = 0; i < ps.desc.n; i++) {
        const char *s = LVEC_AT(ps.desc, const char *, i);
        lead = lead ? lang_printf(c, "%s\n%s", lead, s) : s;
    }
    if (lead) {
        /* drop empty lines at the start and the end */
        while (*lead == '\n')
            lead++;
        size_t n = strlen(lead);
        while (n && lead[n - 1] == '\n')
            n--;
        lead = lang_strndup(c, lead, n);
        m->description = m->description && *m->description
                             ? lang_printf(c, "%s\n%s", lead, m->description)
                             : lead;
    }
    if (m->states.n == 0 && !c->stmt_hook) /* a front end's own statements may add them */
        lang_fail(c, (lpos){0, 0},
                  "no differential or difference equation (x'=..., dx/dt=... or x(t+1)=...) "
                  "in the file");
    if (m->map_eq || m->map_meth)
        finish_map(c);
    lang_volt_finish(c);
    if (m->meth_every_dt && m->nout > 1) {
        lang_note(c, m->nout_pos,
                  "nout=%ld is ignored with meth=%s: as in XPPAUT, an adaptive method writes a "
                  "sample every dt (--every thins them)",
                  m->nout, m->meth_name);
        m->nout = 1;
    }
}
