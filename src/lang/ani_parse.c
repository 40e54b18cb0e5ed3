/* SPDX-License-Identifier: BSD-3-Clause */
/* The reader of XPPAUT's animation files (dynkit/ani.h), after XPPAUT's manual
 * ("Animation": the commands, their fields separated by ';', colours) and, where the manual
 * is silent, XPPAUT's own reader (aniparse.c): commands are known by their first letters
 * (`fcirc`, `circle`), `permanent`/`transient` switch how the following primitives are
 * evaluated, a colour is `$NAME` or a formula whose value in [0, 1] picks a colour of the
 * map, thickness and the comet's type and length are whole numbers (atoi), `dimension`
 * with xlo >= xhi or ylo >= yhi is ignored, `end`/`done` stop the file, vtext shows its
 * string followed by the value with %g. Lines go through the translator's source pass
 * (source.c: `\` continuation, arrays `[j1..j2]` and `%[j1..j2]` blocks, each character's
 * place kept), formulas through its expression parser (expr_parse.c, XPPAUT's priorities).
 *
 * Stricter than XPPAUT where it would misread silently: unknown commands (XPPAUT takes them
 * for comments), an empty field followed by others (XPPAUT's strtok skips it, shifting the
 * rest), fields beyond the last one, a formula where a number is read, a settext colour
 * that is not a name. Accepted and ignored with a note: `speed` (the page plays in real
 * time), `grab` with its two lines (dragging a point with the mouse). Refused by name:
 * `xnull`/`ynull` (nullclines). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "lang/ani_internal.h"

enum cmd {
    CMD_LINE, CMD_RLINE, CMD_RECT, CMD_FRECT, CMD_CIRCLE, CMD_FCIRCLE, CMD_ELLIPSE,
    CMD_FELLIPSE, CMD_TEXT, CMD_VTEXT, CMD_COMET, CMD_SETTEXT, /* = dyn_ani_kind */
    CMD_TRANSIENT, CMD_PERMANENT, CMD_DIMENSION, CMD_SPEED, CMD_END, CMD_DONE, CMD_GRAB,
    CMD_XNULL, CMD_YNULL, CMD_COUNT
};

/* Full names; a command is any beginning of one of at least two letters (XPPAUT compares
 * the first two, its manual speaks of three). */
static const char *const cmd_names[CMD_COUNT] = {
    [CMD_LINE] = "line",           [CMD_RLINE] = "rline",       [CMD_RECT] = "rect",
    [CMD_FRECT] = "frect",         [CMD_CIRCLE] = "circle",     [CMD_FCIRCLE] = "fcircle",
    [CMD_ELLIPSE] = "ellipse",     [CMD_FELLIPSE] = "fellipse", [CMD_TEXT] = "text",
    [CMD_VTEXT] = "vtext",         [CMD_COMET] = "comet",       [CMD_SETTEXT] = "settext",
    [CMD_TRANSIENT] = "transient", [CMD_PERMANENT] = "permanent",
    [CMD_DIMENSION] = "dimension", [CMD_SPEED] = "speed",       [CMD_END] = "end",
    [CMD_DONE] = "done",           [CMD_GRAB] = "grab",         [CMD_XNULL] = "xnullcline",
    [CMD_YNULL] = "ynullcline",
};

/* What each drawing command takes, for messages. */
static const char *const usage[DYN_ANI_KIND_COUNT] = {
    [DYN_ANI_LINE] = "x1;y1;x2;y2[;colour[;thickness]]",
    [DYN_ANI_RLINE] = "dx;dy[;colour[;thickness]]",
    [DYN_ANI_RECT] = "x1;y1;x2;y2[;colour[;thickness]]",
    [DYN_ANI_FRECT] = "x1;y1;x2;y2[;colour]",
    [DYN_ANI_CIRCLE] = "x;y;radius[;colour[;thickness]]",
    [DYN_ANI_FCIRCLE] = "x;y;radius[;colour]",
    [DYN_ANI_ELLIPSE] = "x;y;rx;ry[;colour[;thickness]]",
    [DYN_ANI_FELLIPSE] = "x;y;rx;ry[;colour]",
    [DYN_ANI_TEXT] = "x;y;string",
    [DYN_ANI_VTEXT] = "x;y;string;value",
    [DYN_ANI_COMET] = "x;y;type;n[;colour]",
    [DYN_ANI_SETTEXT] = "size;font;colour",
};

/* XPPAUT's colour names (graf_par.c: color_names, colorline): WHITE and BLACK are both its
 * foreground colour. */
static const struct {
    const char *name;
    int color;
} colors[] = {
    {"WHITE", DYN_ANI_FOREGROUND},   {"RED", DYN_ANI_RED},
    {"REDORANGE", DYN_ANI_REDORANGE}, {"ORANGE", DYN_ANI_ORANGE},
    {"YELLOWORANGE", DYN_ANI_YELLOWORANGE}, {"YELLOW", DYN_ANI_YELLOW},
    {"YELLOWGREEN", DYN_ANI_YELLOWGREEN}, {"GREEN", DYN_ANI_GREEN},
    {"BLUEGREEN", DYN_ANI_BLUEGREEN}, {"BLUE", DYN_ANI_BLUE},
    {"PURPLE", DYN_ANI_PURPLE},       {"BLACK", DYN_ANI_FOREGROUND},
};
#define N_COLORS ((int)(sizeof colors / sizeof colors[0]))

const char *dyn_ani_color_name(int color)
{
    if (color == DYN_ANI_FOREGROUND)
        return "BLACK";
    for (int i = 0; i < N_COLORS; i++)
        if (colors[i].color == color)
            return colors[i].name;
    return "?";
}

/* ---- the text of a file as the translator's context holds it ---- */

static void set_text(lang_ctx *c, const char *path, const char *text, size_t len)
{
    c->path = path;
    c->text = text ? text : "";
    c->len = text ? len : 0;
    c->nlines = 0;
    if (c->diag) {
        strncpy(c->diag->path, path, sizeof c->diag->path - 1);
        c->diag->path[sizeof c->diag->path - 1] = '\0';
    }
    if (c->len > LANG_MAX_TEXT)
        lang_fail(c, (lpos){0, 0}, "file too large (%zu bytes; at most %u)", c->len,
                  LANG_MAX_TEXT);
    int lines = 1;
    for (size_t i = 0; i < c->len; i++)
        lines += c->text[i] == '\n';
    c->line_start = lang_alloc(c, (size_t)lines * sizeof *c->line_start);
    c->line_start[c->nlines++] = 0;
    for (size_t i = 0; i < c->len; i++)
        if (c->text[i] == '\n' && c->nlines < lines)
            c->line_start[c->nlines++] = i + 1;
    if (c->len > 0 && c->text[c->len - 1] == '\n')
        c->nlines--;
}

/* ---- names ---- */

static const char *nearest(lang_ctx *c, const char *word, int funcs)
{
    const lang_model *m = &c->m;
    const int cap = m->nsyms + F_COUNT + 2;
    const char **names = lang_alloc(c, (size_t)cap * sizeof *names);
    int n = 0;
    for (int k = 0; k < m->symcap; k++) {
        const lang_sym *s = &m->syms[k];
        if (s->key && s->kind != SYM_RESERVED && funcs == (s->kind == SYM_FUNC))
            names[n++] = s->key;
    }
    if (funcs) {
        for (int f = 0; f < F_COUNT; f++)
            names[n++] = lang_fun_name(f);
    } else {
        names[n++] = "t";
        names[n++] = "pi";
    }
    return dyn_lang_nearest(word, names, n);
}

static _Noreturn void unknown(lang_ctx *c, const node *e, int funcs)
{
    const char *near = nearest(c, e->name, funcs);
    if (near)
        lang_fail(c, e->pos, "unknown %s '%s' (did you mean '%s'?)", funcs ? "function" : "name",
                  e->name, near);
    lang_fail(c, e->pos, "unknown %s '%s'%s", funcs ? "function" : "name", e->name,
              funcs ? "" : ": an animation's formulas use the model's states, outputs, "
                           "parameters, t and numbers");
}

/* Whether fixed quantity k of the model reads an algebraic variable, which the animation's
 * evaluator cannot solve for. */
static int fix_reads_alg(lang_ctx *c, int k)
{
    const lang_model *m = &c->m;
    if (m->algs.n == 0)
        return 0;
    unsigned char *used = lang_alloc(c, (size_t)m->algs.n);
    unsigned char *fix_seen = lang_alloc(c, (size_t)m->fixes.n);
    unsigned char *fun_seen = lang_alloc(c, (size_t)m->funcs.n + 1);
    lang_alg_uses(c, LVEC_AT(m->fixes, lang_formula, k).expr, used, fix_seen, fun_seen);
    for (int i = 0; i < m->algs.n; i++)
        if (used[i])
            return 1;
    return 0;
}

/* Names of a formula bound to the model's quantities (check.c's resolve, for a formula
 * that may also read the outputs). */
static void resolve(dyn_ani *a, node *e, int depth)
{
    lang_ctx *c = a->c;
    if (depth > 4 * LANG_MAX_DEPTH)
        lang_fail(c, e->pos, "formula nested too deeply");
    for (int i = 0; i < e->nargs; i++)
        resolve(a, e->args[i], depth + 1);
    const lang_model *m = &c->m;
    if (e->kind == N_NAME) {
        const lang_sym *s = lang_lookup(c, e->name);
        if (!s)
            unknown(c, e, 0);
        switch (s->kind) {
        case SYM_STATE: e->kind = N_STATE; e->index = s->index; return;
        case SYM_PARAM: e->kind = N_PARAM; e->index = s->index; return;
        case SYM_DERIVED: e->kind = N_PARAM; e->index = m->params.n + s->index; return;
        case SYM_NUMBER:
            e->kind = N_NUM;
            e->num = LVEC_AT(m->numbers, lang_param, s->index).value;
            return;
        case SYM_FIX:
            if (fix_reads_alg(c, s->index))
                lang_fail(c, e->pos,
                          "'%s' reads an algebraic variable (0=...), which an "
                          "animation cannot solve for: show an aux output of it instead",
                          e->name);
            e->kind = N_FIX;
            e->index = s->index;
            return;
        case SYM_ALG:
            lang_fail(c, e->pos,
                      "'%s' is an algebraic variable (0=...), which an animation "
                      "cannot solve for: show an aux output of it instead (aux %s_=%s)",
                      e->name, e->name, e->name);
        case SYM_AUX:
            /* XPPAUT's animator knows states and fixed quantities, not aux outputs (its
             * manual: "both regular and fixed, but not auxiliary") */
            if (a->from_ode)
                lang_note(c, e->pos, "col %d: '%s' is an aux output: dynkit shows it, "
                          "XPPAUT's animator does not know it (name a fixed quantity for "
                          "both)", e->pos.col, e->name);
            e->kind = N_ARG;
            e->index = s->index;
            return;
        case SYM_FUNC:
            lang_fail(c, e->pos, "'%s' is a function: call it as %s(...)", e->name, e->name);
        default: unknown(c, e, 0);
        }
    }
    switch (e->kind) {
    case N_NUM: case N_TIME: case N_NEG: case N_NOT: case N_BIN: case N_IF: case N_FUN:
    case N_NAME: break;
    case N_DELAY:
        lang_fail(c, e->pos, "delay-differential equations ('delay') are not supported in an "
                  "animation's formula: name a fixed quantity of the model that reads it");
    default:
        /* what the evaluator does not know (the translator's own forms, which it expands
         * in a model's formulas): refused rather than computed wrongly */
        lang_fail(c, e->pos, "not supported in an animation's formula: it takes numbers, "
                  "names, t, operators and functions");
    }
    if (e->kind == N_FUN && e->name &&
        (strcasecmp(e->name, "ran") == 0 || strcasecmp(e->name, "normal") == 0))
        lang_fail(c, e->pos, "random numbers ('%s') are not supported in an animation",
                  e->name);
    if (e->kind == N_FUN && !lang_resolve_call(c, e))
        unknown(c, e, 1);
}

/* A C model's names (those that can be written in a formula; the others cannot be
 * named). */
static void declare_names(lang_ctx *c, const char *const *names, int n, sym_kind kind)
{
    for (int i = 0; i < n; i++) {
        const char *s = names ? names[i] : NULL;
        if (!s || !lang_is_ident_start((unsigned char)s[0]) || lang_is_reserved(s))
            continue;
        int ok = 1;
        for (const char *q = s; *q && ok; q++)
            ok = lang_is_ident_char((unsigned char)*q);
        if (ok && strlen(s) < 256 && !lang_lookup(c, s))
            lang_declare(c, lang_strdup(c, s), (lpos){0, 0}, kind, i);
    }
}

/* ---- fields ---- */

enum { MAX_FIELDS = 8 };

typedef struct field {
    int a, b; /* offsets in the line, trimmed of blanks; a == b: empty */
    int raw_a, raw_b; /* untrimmed */
} field;

typedef struct pstate {
    dyn_ani *a;
    lvec items; /* ani_item */
    int permanent;
    int grab_lines; /* {...} lines of a grab still to come */
    lpos grab_pos;
    int n_values;
} pstate;

static int is_blank(int ch) { return ch == ' ' || ch == '\t'; }

static lpos at(const lang_line *l, int i) { return l->pos[i < l->len ? i : l->len]; }

static void trim(const lang_line *l, field *f)
{
    f->a = f->raw_a;
    f->b = f->raw_b;
    while (f->a < f->b && is_blank(l->text[f->a]))
        f->a++;
    while (f->b > f->a && is_blank(l->text[f->b - 1]))
        f->b--;
}

static node *formula(dyn_ani *a, const lang_line *l, const field *f, const char *what)
{
    lang_ctx *c = a->c;
    if (f->a == f->b)
        lang_fail(c, at(l, f->raw_a), "missing %s", what);
    /* a ';' inside parentheses ends the field: say so rather than "the end of the line" */
    int depth = 0;
    for (int i = f->a; i < f->b; i++)
        depth += l->text[i] == '(' ? 1 : l->text[i] == ')' ? -1 : 0;
    if (depth > 0 && f->raw_b < l->len)
        lang_fail(c, at(l, f->raw_b), "missing ')' before the ';' that ends the field of the "
                  "%s (';' separates the fields of a command)", what);
    lang_lexer lx = {c, l, f->a, f->b};
    node *e = lang_parse_expr(&lx);
    const int ch = lang_skip_blanks(&lx);
    if (ch)
        lang_fail(c, lang_here(&lx), "unexpected '%c' in the formula of the %s", ch, what);
    resolve(a, e, 0);
    return e;
}

/* A whole number where XPPAUT reads one with atoi (thickness, comet type and length,
 * settext size, speed); a decimal part is dropped as atoi does. */
static long whole(lang_ctx *c, const lang_line *l, const field *f, const char *what)
{
    char buf[64];
    const int n = f->b - f->a;
    if (n == 0)
        lang_fail(c, at(l, f->raw_a), "missing %s", what);
    if (n >= (int)sizeof buf)
        lang_fail(c, at(l, f->a), "the %s must be a number", what);
    memcpy(buf, l->text + f->a, (size_t)n);
    buf[n] = '\0';
    char *end;
    errno = 0;
    const double v = strtod(buf, &end);
    if (end == buf || *end || !isfinite(v) || errno == ERANGE)
        lang_fail(c, at(l, f->a), "the %s must be a number (XPPAUT reads it as one, not as a "
                  "formula)", what);
    if (v > 1e6 || v < -1e6)
        lang_fail(c, at(l, f->a), "the %s %s is too large", what, buf);
    return (long)v;
}

static double number(lang_ctx *c, const lang_line *l, const field *f, const char *what)
{
    char buf[64];
    const int n = f->b - f->a;
    if (n == 0)
        lang_fail(c, at(l, f->raw_a), "missing %s", what);
    if (n >= (int)sizeof buf)
        lang_fail(c, at(l, f->a), "the %s must be a number", what);
    memcpy(buf, l->text + f->a, (size_t)n);
    buf[n] = '\0';
    char *end;
    errno = 0;
    const double v = strtod(buf, &end);
    if (end == buf || *end || !isfinite(v) || errno == ERANGE)
        lang_fail(c, at(l, f->a), "the %s must be a number (XPPAUT reads it as one, not as a "
                  "formula)", what);
    return v;
}

/* $NAME: its colour; else -1 (a formula, or empty: then *empty). */
static int named_color(lang_ctx *c, const lang_line *l, const field *f)
{
    if (f->a == f->b || l->text[f->a] != '$')
        return -1;
    char name[32];
    int n = 0;
    for (int i = f->a + 1; i < f->b; i++) {
        if (is_blank(l->text[i]))
            continue; /* XPPAUT removes blanks (de_space) */
        if (n + 1 >= (int)sizeof name)
            break;
        name[n++] = (char)toupper((unsigned char)l->text[i]);
    }
    name[n] = '\0';
    for (int k = 0; k < N_COLORS; k++)
        if (strcmp(name, colors[k].name) == 0)
            return colors[k].color;
    const char *names[N_COLORS];
    for (int k = 0; k < N_COLORS; k++)
        names[k] = colors[k].name;
    const char *near = n ? dyn_lang_nearest(name, names, N_COLORS) : NULL;
    lang_fail(c, at(l, f->a), "unknown colour '$%.*s'%s%s%s (the colours: $WHITE, $RED, "
              "$REDORANGE, $ORANGE, $YELLOWORANGE, $YELLOW, $YELLOWGREEN, $GREEN, $BLUEGREEN, "
              "$BLUE, $PURPLE, $BLACK, or a formula with a value in [0,1])",
              n, name, near ? " (did you mean '$" : "", near ? near : "", near ? "'?)" : "");
}

/* ---- commands ---- */

static int find_cmd(const char *w, int n)
{
    if (n < 2)
        return -1;
    for (int k = 0; k < CMD_COUNT; k++) {
        const char *full = cmd_names[k];
        if ((size_t)n > strlen(full))
            continue;
        int ok = 1;
        for (int i = 0; i < n && ok; i++)
            ok = tolower((unsigned char)w[i]) == full[i];
        if (ok)
            return k;
    }
    /* XPPAUT's own short forms that are not beginnings of the names above */
    static const struct {
        const char *word;
        int cmd;
    } alias[] = {{"circ", CMD_CIRCLE}, {"fcirc", CMD_FCIRCLE}, {"xnull", CMD_XNULL},
                 {"ynull", CMD_YNULL}};
    for (size_t k = 0; k < sizeof alias / sizeof alias[0]; k++)
        if ((size_t)n == strlen(alias[k].word)) {
            int ok = 1;
            for (int i = 0; i < n && ok; i++)
                ok = tolower((unsigned char)w[i]) == alias[k].word[i];
            if (ok)
                return alias[k].cmd;
        }
    return -1;
}

static _Noreturn void unknown_cmd(lang_ctx *c, const lang_line *l, int i, int n)
{
    char word[64];
    const int m = n < (int)sizeof word - 1 ? n : (int)sizeof word - 1;
    for (int k = 0; k < m; k++)
        word[k] = (char)tolower((unsigned char)l->text[i + k]);
    word[m] = '\0';
    const char *near = dyn_lang_nearest(word, cmd_names, CMD_COUNT);
    lang_fail(c, at(l, i), "unknown command '%s'%s%s%s: a line of an animation is a command "
              "(line, rline, rect, frect, circle, fcircle, ellip, fellip, text, vtext, comet, "
              "settext, permanent, transient, dimension, speed, end) or a # comment",
              word, near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "");
}

static void too_many(lang_ctx *c, const lang_line *l, const field *f, int nf, int max,
                     const char *cmd, const char *takes)
{
    if (nf > max)
        lang_fail(c, at(l, f[max].raw_a > 0 ? f[max].raw_a - 1 : 0),
                  "too many fields: '%s' takes %s", cmd, takes);
}

static void too_few(lang_ctx *c, const lang_line *l, int nf, int min, const char *cmd,
                    const char *takes)
{
    if (nf < min)
        lang_fail(c, at(l, l->len), "'%s' takes %s (%d field%s given, separated by ';')", cmd,
                  takes, nf, nf == 1 ? "" : "s");
}

static void add_item(lang_ctx *c, pstate *ps, const lang_line *l, int i, ani_item *it)
{
    if (ps->items.n >= DYN_ANI_MAX_PRIMS)
        lang_fail(c, at(l, i), "too many commands (more than %d)", DYN_ANI_MAX_PRIMS);
    it->p.line = at(l, i).line;
    it->p.col = at(l, i).col;
    it->p.permanent = ps->permanent;
    it->p.offset = ps->n_values;
    ps->n_values += it->p.n_values;
    *(ani_item *)lvec_push(c, &ps->items, sizeof(ani_item)) = *it;
}

static int on_line(lang_ctx *c, const lang_line *l, void *ctx)
{
    pstate *ps = ctx;
    dyn_ani *a = ps->a;
    int i = 0;
    while (i < l->len && is_blank(l->text[i]))
        i++;
    if (i == l->len)
        return 0;
    if (ps->grab_lines > 0) {
        if (l->text[i] != '{')
            lang_fail(c, at(l, i), "'grab' is followed by two lines {name=formula;...}: what "
                      "is set when the point is grabbed, and when it is let go");
        ps->grab_lines--;
        return 0;
    }
    if (l->text[i] == '#')
        return 0;
    int w = i;
    while (w < l->len && !is_blank(l->text[w]) && l->text[w] != ';')
        w++;
    const int cmd = find_cmd(l->text + i, w - i);
    if (cmd < 0)
        unknown_cmd(c, l, i, w - i);
    const char *name = cmd_names[cmd];
    /* the fields: what follows the command, separated by ';' */
    int p = w;
    while (p < l->len && is_blank(l->text[p]))
        p++;
    if (p < l->len && l->text[p] == ';')
        p++;
    field f[MAX_FIELDS + 1];
    int nf = 0;
    if (p < l->len) {
        int s = p;
        for (int k = p; k <= l->len; k++) {
            if (k < l->len && l->text[k] != ';')
                continue;
            if (nf > MAX_FIELDS)
                lang_fail(c, at(l, k), "too many fields (';')");
            f[nf].raw_a = s;
            f[nf].raw_b = k;
            trim(l, &f[nf]);
            nf++;
            s = k + 1;
        }
    }
    while (nf > 0 && f[nf - 1].a == f[nf - 1].b)
        nf--; /* a ';' at the end */
    for (int k = 0; k + 1 < nf; k++)
        if (f[k].a == f[k].b)
            lang_fail(c, at(l, f[k].raw_a), "empty field %d: write every field up to the last "
                      "one (XPPAUT skips empty fields, which would shift the ones after it)",
                      k + 1);

    ani_item it;
    memset(&it, 0, sizeof it);
    it.p.text = "";
    it.p.comet_length = 1;
    switch (cmd) {
    case CMD_END:
    case CMD_DONE:
    case CMD_TRANSIENT:
    case CMD_PERMANENT:
        if (nf > 0)
            lang_fail(c, at(l, f[0].a), "'%s' takes nothing after it", name);
        if (cmd == CMD_TRANSIENT || cmd == CMD_PERMANENT) {
            ps->permanent = cmd == CMD_PERMANENT;
            return 0;
        }
        return 1; /* the end: what follows is not read */
    case CMD_DIMENSION: {
        too_few(c, l, nf, 4, name, "xlo;ylo;xhi;yhi");
        too_many(c, l, f, nf, 4, name, "xlo;ylo;xhi;yhi");
        double d[4];
        static const char *const what[4] = {"xlo", "ylo", "xhi", "yhi"};
        for (int k = 0; k < 4; k++)
            d[k] = number(c, l, &f[k], what[k]);
        if (d[0] < d[2] && d[1] < d[3]) {
            for (int k = 0; k < 4; k++)
                a->window[k] = d[k];
        } else {
            lang_note(c, at(l, i), "dimension ignored (as XPPAUT does): it needs xlo < xhi "
                      "and ylo < yhi");
        }
        return 0;
    }
    case CMD_SPEED:
        too_few(c, l, nf, 1, name, "the delay between frames in ms");
        too_many(c, l, f, nf, 1, name, "the delay between frames in ms");
        {
            long v = whole(c, l, &f[0], "delay");
            a->speed = (int)(v < 0 ? 0 : v > 1000 ? 1000 : v);
        }
        lang_note(c, at(l, i), "speed %d accepted and ignored: the page plays in real time "
                  "(its speed control sets the pace)", a->speed);
        return 0;
    case CMD_GRAB:
        too_few(c, l, nf, 3, name, "x;y;tolerance");
        too_many(c, l, f, nf, 3, name, "x;y;tolerance");
        lang_note(c, at(l, i), "grab (dragging a point with the mouse to set the initial "
                  "state) accepted and ignored: the page plays the recorded run");
        ps->grab_lines = 2;
        ps->grab_pos = at(l, i);
        return 0;
    case CMD_XNULL:
    case CMD_YNULL:
        lang_fail(c, at(l, i), "nullclines in animations ('xnull', 'ynull') are not supported");
    default: break;
    }

    /* the drawing commands and settext */
    const dyn_ani_kind kind = (dyn_ani_kind)cmd;
    it.p.kind = kind;
    const char *takes = usage[kind];
    int ncoord = 0;
    static const char *const names4[] = {"x1", "y1", "x2", "y2"};
    static const char *const names_c[] = {"x", "y", "radius"};
    static const char *const names_e[] = {"x", "y", "rx", "ry"};
    static const char *const names_r[] = {"dx", "dy"};
    static const char *const names_t[] = {"x", "y"};
    const char *const *what = names4;
    switch (kind) {
    case DYN_ANI_LINE:
    case DYN_ANI_RECT:
    case DYN_ANI_FRECT: ncoord = 4; break;
    case DYN_ANI_ELLIPSE:
    case DYN_ANI_FELLIPSE: ncoord = 4; what = names_e; break;
    case DYN_ANI_CIRCLE:
    case DYN_ANI_FCIRCLE: ncoord = 3; what = names_c; break;
    case DYN_ANI_RLINE: ncoord = 2; what = names_r; break;
    case DYN_ANI_TEXT:
    case DYN_ANI_VTEXT:
    case DYN_ANI_COMET: ncoord = 2; what = names_t; break;
    default: break;
    }

    if (kind == DYN_ANI_SETTEXT) {
        too_few(c, l, nf, 3, name, takes);
        too_many(c, l, f, nf, 3, name, takes);
        long size = whole(c, l, &f[0], "text size");
        it.p.text_size = (int)(size < 0 ? 0 : size > 4 ? 4 : size);
        it.p.text_font = l->text[f[1].a] == 's' || l->text[f[1].a] == 'S';
        const int col = named_color(c, l, &f[2]);
        if (col < 0)
            lang_fail(c, at(l, f[2].a), "settext takes a named colour ($RED, $BLACK, ...), not "
                      "a formula");
        it.p.color = col;
        add_item(c, ps, l, i, &it);
        return 0;
    }

    int min = ncoord, max;
    if (kind == DYN_ANI_TEXT)
        min = max = 3;
    else if (kind == DYN_ANI_VTEXT)
        min = max = 4;
    else if (kind == DYN_ANI_COMET)
        min = 4, max = 5;
    else
        max = ncoord + 2; /* colour and thickness */
    too_few(c, l, nf, min, name, takes);
    too_many(c, l, f, nf, max, name, takes);
    for (int k = 0; k < ncoord; k++)
        it.expr[it.p.n_values++] = formula(a, l, &f[k], what[k]);
    int colour_field = -1, thick_field = -1;
    if (kind == DYN_ANI_TEXT || kind == DYN_ANI_VTEXT) {
        const field *s = &f[2];
        /* the string as written between the ';' (XPPAUT's strtok keeps its blanks: a vtext
         * "t = " shows "t = 1.5"); the blanks that end a line are dropped */
        int sa = s->raw_a, sb = s->raw_b;
        if (kind == DYN_ANI_TEXT)
            while (sb > sa && is_blank(l->text[sb - 1]))
                sb--;
        if (sb - sa > DYN_ANI_MAX_TEXT)
            lang_fail(c, at(l, sa), "text too long (more than %d characters)",
                      DYN_ANI_MAX_TEXT);
        it.p.text = lang_strndup(c, l->text + sa, (size_t)(sb - sa));
        if (kind == DYN_ANI_VTEXT)
            it.expr[it.p.n_values++] = formula(a, l, &f[3], "value");
    } else if (kind == DYN_ANI_COMET) {
        it.p.comet_type = (int)whole(c, l, &f[2], "comet's type (line width, or dot radius "
                                                   "when negative)");
        const long n = whole(c, l, &f[3], "comet's length");
        if (n < 1 || n > DYN_ANI_MAX_COMET)
            lang_fail(c, at(l, f[3].a), "the comet's length (its 4th field) is the number of "
                      "points of its tail, a whole number from 1 to %d", DYN_ANI_MAX_COMET);
        it.p.comet_length = (int)n;
        colour_field = nf > 4 ? 4 : -1;
    } else {
        colour_field = nf > ncoord ? ncoord : -1;
        thick_field = nf > ncoord + 1 ? ncoord + 1 : -1;
    }
    it.p.color = DYN_ANI_FOREGROUND;
    if (colour_field >= 0) {
        const int col = named_color(c, l, &f[colour_field]);
        if (col >= 0) {
            it.p.color = col;
        } else {
            it.p.color = -1;
            it.expr[it.p.n_values++] = formula(a, l, &f[colour_field], "colour");
        }
    }
    if (thick_field >= 0) {
        const long th = whole(c, l, &f[thick_field], "thickness");
        it.p.thickness = (int)(th < 0 ? 0 : th);
    }
    add_item(c, ps, l, i, &it);
    return 0;
}

/* ---- the public interface ---- */

static void parse_lines(dyn_ani *a, const char *path, const char *text, size_t len);

static void parse(dyn_ani *a, const char *path, const char *text, size_t len,
                  const dyn_ani_model *model)
{
    lang_ctx *c = a->c;
    if (model && model->ode_text) {
        /* the model as the translator reads it: every name of the file */
        const char *ode_path = model->ode_path ? model->ode_path : "<model>";
        set_text(c, ode_path, model->ode_text, model->ode_len);
        dyn_lang_note_fn note = c->note;
        c->note = NULL; /* the translation has said these already */
        lang_parse_model(c);
        lang_check(c);
        c->note = note;
        a->from_ode = 1;
        a->n_states = c->m.states.n;
        a->n_outputs = c->m.auxs.n;
        a->n_params = c->m.params.n + c->m.derived.n;
    } else if (model) {
        declare_names(c, model->states, model->n_states, SYM_STATE);
        declare_names(c, model->outputs, model->n_outputs, SYM_AUX);
        declare_names(c, model->params, model->n_params, SYM_PARAM);
        a->n_states = model->n_states;
        a->n_outputs = model->n_outputs;
        a->n_params = model->n_params;
    }
    parse_lines(a, path, text, len);
}

/* The animation's own lines, with the names of the model read before */
static void parse_lines(dyn_ani *a, const char *path, const char *text, size_t len)
{
    lang_ctx *c = a->c;
    set_text(c, path, text, len);
    pstate ps;
    memset(&ps, 0, sizeof ps);
    ps.a = a;
    lang_lines(c, on_line, &ps);
    if (ps.grab_lines > 0)
        lang_fail(c, ps.grab_pos, "'grab' is followed by two lines {name=formula;...}: what is "
                  "set when the point is grabbed, and when it is let go");
    a->items = ps.items.data;
    a->n_items = ps.items.n;
    a->n_values = ps.n_values;
}

/* The parse with its error exit; every argument is final before the setjmp. */
static int parse_guarded(dyn_ani *a, const char *path, const char *text, size_t len,
                         const dyn_ani_model *model, dyn_lang_diag *diag)
{
    lang_ctx *c = a->c;
    jmp_buf fail;
    c->fail = &fail;
    if (setjmp(fail)) {
        const int status = c->status ? c->status : 2;
        if (status == 1)
            snprintf(diag->message, sizeof diag->message,
                     "out of memory while reading the animation");
        return status;
    }
    parse(a, path, text, len, model);
    c->fail = NULL;
    return 0;
}

int dyn_ani_parse(const char *path, const char *text, size_t len, const dyn_ani_model *model,
                  dyn_ani **ani, dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx)
{
    dyn_lang_diag scratch;
    dyn_lang_diag *d = diag ? diag : &scratch;
    memset(d, 0, sizeof *d);
    const char *p = path ? path : "<animation>";
    strncpy(d->path, p, sizeof d->path - 1);
    if (ani)
        *ani = NULL;
    if (!ani || (!text && len)) {
        strcpy(d->message, "no text or no place for the animation (a NULL argument)");
        return 2;
    }
    dyn_ani *a = calloc(1, sizeof *a);
    lang_ctx *c = a ? calloc(1, sizeof *c) : NULL;
    if (!c) {
        free(a);
        strcpy(d->message, "out of memory while reading the animation");
        return 1;
    }
    a->c = c;
    a->window[0] = a->window[1] = 0.0;
    a->window[2] = a->window[3] = 1.0;
    a->speed = 10;
    c->diag = d;
    c->note = note;
    c->note_ctx = note_ctx;
    const int status = parse_guarded(a, p, text, len, model, d);
    if (status) {
        lang_ctx_free(c, a);
        return status;
    }
    c->diag = NULL;
    c->note = NULL;
    c->text = NULL;
    c->len = 0;
    c->nlines = 0;
    *ani = a;
    return 0;
}

void dyn_ani_free(dyn_ani *ani)
{
    if (ani)
        lang_ctx_free(ani->c, ani);
}

int dyn_ani_count(const dyn_ani *ani) { return ani ? ani->n_items : 0; }

const dyn_ani_prim *dyn_ani_at(const dyn_ani *ani, int i)
{
    return ani && i >= 0 && i < ani->n_items ? &ani->items[i].p : NULL;
}

int dyn_ani_n_values(const dyn_ani *ani) { return ani ? ani->n_values : 0; }

void dyn_ani_window(const dyn_ani *ani, double window[4])
{
    for (int k = 0; k < 4; k++)
        window[k] = ani ? ani->window[k] : (k < 2 ? 0.0 : 1.0);
}

int dyn_ani_speed(const dyn_ani *ani) { return ani ? ani->speed : 10; }

void dyn_ani_sizes(const dyn_ani *ani, int *n_states, int *n_outputs, int *n_params)
{
    if (n_states)
        *n_states = ani ? ani->n_states : 0;
    if (n_outputs)
        *n_outputs = ani ? ani->n_outputs : 0;
    if (n_params)
        *n_params = ani ? ani->n_params : 0;
}

int dyn_ani_value_is_constant(const dyn_ani *ani, int i, int k)
{
    if (!ani || i < 0 || i >= ani->n_items || k < 0 || k >= ani->items[i].p.n_values)
        return 1;
    return !ani_varies(ani, ani->items[i].expr[k]);
}

/* ---- an animation's numbers as outputs of the model's C (dyn_ani_ode_to_c) ---- */

typedef struct ani_source {
    const char *path, *text;
    size_t len;
} ani_source;

/* A formula of the animation as one of the model's: an aux output (N_ARG k here) replaced
 * by its formula. A call of a function of the file that reads fixed quantities is refused:
 * the translator has rewritten such functions (lang_check), not this call. */
static void as_model_formula(lang_ctx *c, node **e)
{
    node *n = *e;
    if (n->kind == N_ARG) {
        *e = LVEC_AT(c->m.auxs, lang_formula, n->index).expr;
        return;
    }
    if (n->kind == N_UFUN && LVEC_AT(c->m.funcs, lang_func, n->index).uses_fix)
        lang_fail(c, n->pos, "'%s' reads fixed quantities of the model: its value is "
                  "computed by the animation's evaluator only, not as an output of the "
                  "model's C", n->name ? n->name : "the function");
    for (int i = 0; i < n->nargs; i++)
        as_model_formula(c, &n->args[i]);
}

void ani_append_outputs(lang_ctx *c, const char *ani_path, const char *ani_text, size_t ani_len)
{
    const char *ode_path = c->path, *ode_text = c->text;
    const size_t ode_len = c->len;
    dyn_ani a;
    memset(&a, 0, sizeof a);
    a.c = c;
    a.from_ode = 1;
    a.n_states = c->m.states.n;
    a.n_outputs = c->m.auxs.n;
    a.n_params = c->m.params.n + c->m.derived.n;
    a.window[2] = a.window[3] = 1.0;
    a.speed = 10;
    dyn_lang_note_fn note = c->note;
    c->note = NULL; /* the reader of the animation has said these already */
    parse_lines(&a, ani_path, ani_text, ani_len);
    c->note = note;
    for (int i = 0; i < a.n_items; i++) {
        ani_item *it = &a.items[i];
        for (int k = 0; k < it->p.n_values; k++) {
            as_model_formula(c, &it->expr[k]);
            lang_formula *f = lvec_push(c, &c->m.auxs, sizeof *f);
            memset(f, 0, sizeof *f);
            f->name = lang_printf(c, "ani:%d", it->p.offset + k);
            f->expr = it->expr[k];
        }
    }
    set_text(c, ode_path, ode_text, ode_len); /* the model's text again */
}

/* The .ode front end, then the animation's formulas as outputs */
static void ani_ode_front(lang_ctx *c)
{
    const ani_source *src = c->hook_ctx;
    lang_ode_front(c);
    ani_append_outputs(c, src->path, src->text, src->len);
}

int dyn_ani_ode_to_c(const char *ode_path, const char *ode_text, size_t ode_len,
                     const dyn_lang_table_file *tables, int n_tables, const char *ani_path,
                     const char *ani_text, size_t ani_len, char **c_source,
                     dyn_lang_diag *diag)
{
    if (!ani_text && ani_len) {
        if (c_source)
            *c_source = NULL;
        if (diag) {
            memset(diag, 0, sizeof *diag);
            strcpy(diag->message, "no text for the animation (a NULL argument)");
        }
        return 2;
    }
    const ani_source src = {ani_path ? ani_path : "<animation>", ani_text ? ani_text : "",
                            ani_len};
    return lang_translate_with(ode_path, ode_text, ode_len, tables, n_tables, c_source, diag,
                               NULL, NULL, ani_ode_front, NULL, (void *)&src);
}
