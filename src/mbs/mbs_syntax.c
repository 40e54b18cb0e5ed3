/* SPDX-License-Identifier: BSD-3-Clause */
/* The pieces of syntax that the statements of a mechanism file share (docs/mechanisms.md,
 * "Statements"): a word, an expression kept as an input (an unnamed fixed quantity of the
 * model, so that lang_check resolves its names with FILE:LINE:COL messages), a tuple
 * (x, y, z), a value in degrees, a body by name, elementary rotations and a body's point.
 * The statements' parsers (mbs_parse.c, and mbs_joint.c and mbs_geom.c that it calls) call
 * these; these call none of them. */
#include <ctype.h>
#include <string.h>
#include <strings.h>

#include "mbs/mbs_syntax.h"

static mbs_model *model_of(lang_ctx *c) { return c->hook_ctx; }

static int peek(lang_lexer *lx) { return lang_skip_blanks(lx); }

/* The next word if it is w (case folded; then consumed). */
int mbs_take_word(lang_lexer *lx, const char *w)
{
    if (!lang_is_ident_start(peek(lx)))
        return 0;
    const size_t n = strlen(w);
    const char *s = lx->line->text + lx->i;
    if ((int)n > lx->end - lx->i || strncasecmp(s, w, n) != 0)
        return 0;
    if (lx->i + (int)n < lx->end && lang_is_ident_char((unsigned char)s[n]))
        return 0;
    lx->i += (int)n;
    return 1;
}

/* An expression of the file kept as an input (an unnamed fixed quantity). */
int mbs_add_input(lang_ctx *c, node *e)
{
    mbs_model *mb = model_of(c);
    lang_formula *f = lvec_push(c, &c->m.fixes, sizeof *f);
    f->name = lang_printf(c, "mbs_in%d", mb->ninputs++);
    f->pos = e->pos;
    f->expr = e;
    return c->m.fixes.n - 1;
}

node *mbs_parse_value(lang_lexer *lx, const char *what)
{
    if (!peek(lx))
        lang_fail(lx->c, lang_here(lx), "expected %s, found the end of the line", what);
    return lang_parse_expr(lx);
}

int mbs_input_expr(lang_lexer *lx, const char *what)
{
    return mbs_add_input(lx->c, mbs_parse_value(lx, what));
}

void mbs_tuple(lang_lexer *lx, int *out, const char *what)
{
    lang_expect_char(lx, '(', lang_printf(lx->c, "expected '(' before %s (x, y, z)", what));
    for (int k = 0; k < 3; k++) {
        out[k] = mbs_input_expr(lx, what);
        lang_expect_char(lx, k < 2 ? ',' : ')',
                         lang_printf(lx->c, k < 2 ? "expected ',' in %s (x, y, z)"
                                                  : "expected ')' after %s (x, y, z)", what));
    }
}

/* a value, in degrees when it ends in deg (30deg, 30 deg, pi/6 deg) */
node *mbs_angle_value(lang_lexer *lx, const char *what)
{
    const char *t = lx->line->text;
    int end = lx->i, depth = 0;
    while (end < lx->end) {
        const char ch = t[end];
        if (ch == '(')
            depth++;
        else if (ch == ')')
            depth--;
        else if (depth == 0 && (ch == ',' || ch == '[' || ch == '"'))
            break;
        else if (depth == 0 && lang_is_ident_start((unsigned char)ch) &&
                 (end == 0 || !lang_is_ident_char((unsigned char)t[end - 1]) ||
                  isdigit((unsigned char)t[end - 1])) &&
                 strncasecmp(t + end, "deg", 3) == 0 &&
                 (end + 3 >= lx->end || !lang_is_ident_char((unsigned char)t[end + 3])))
            break;
        end++;
    }
    const int deg = end < lx->end && strncasecmp(t + end, "deg", 3) == 0;
    const int save = lx->end;
    if (deg)
        lx->end = end;
    node *e = mbs_parse_value(lx, what);
    if (deg) {
        if (peek(lx))
            lang_fail(lx->c, lang_here(lx), "unexpected '%c' before deg", peek(lx));
        lx->end = save;
        lx->i = end + 3;
        node *k = lang_node(lx->c, N_NUM, e->pos);
        k->num = 3.14159265358979323846 / 180.0;
        node *r = lang_node(lx->c, N_BIN, e->pos);
        r->op = OP_MUL;
        r->nargs = 2;
        r->args = lang_alloc(lx->c, 2 * sizeof *r->args);
        r->args[0] = e;
        r->args[1] = k;
        e->paren = 1;
        e = r;
    }
    return e;
}

int mbs_find_body(lang_ctx *c, const char *name, lpos pos, int ground_ok)
{
    mbs_model *mb = model_of(c);
    if (ground_ok && strcasecmp(name, "ground") == 0)
        return -1;
    const char **names = lang_alloc(c, ((size_t)mb->bodies.n + 1) * sizeof *names);
    for (int i = 0; i < mb->bodies.n; i++) {
        names[i] = LVEC_AT(mb->bodies, mbs_body, i).name;
        if (strcasecmp(names[i], name) == 0)
            return i;
    }
    names[mb->bodies.n] = ground_ok ? "ground" : "";
    const char *near = dyn_lang_nearest(name, names, mb->bodies.n + 1);
    lang_fail(c, pos, "unknown body '%s'%s%s%s (bodies are declared before they are used%s)",
              name, near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "",
              ground_ok ? "; 'ground' is the fixed frame" : "");
}

/* AXIS:ANGLE ... (elementary rotations) or quat:(w, x, y, z) into b */
void mbs_parse_rot(lang_ctx *c, lang_lexer *lx, mbs_body *b)
{
    while (lang_is_ident_start(peek(lx))) {
        const int save = lx->i;
        lpos apos;
        const char *a = lang_read_name(lx, &apos, "expected an axis x, y or z");
        if (peek(lx) == ':' && strcasecmp(a, "quat") == 0) { /* Euler parameters */
            lx->i++;
            if (b->nrot || b->quat[0] >= 0)
                lang_fail(c, apos, "quat:(w, x, y, z) is the whole orientation: no "
                          "other rotation beside it");
            lang_expect_char(lx, '(',
                             "expected '(' before the Euler parameters (w, x, y, z)");
            for (int k = 0; k < 4; k++) {
                b->quat[k] = mbs_input_expr(lx, "an Euler parameter");
                lang_expect_char(lx, k < 3 ? ',' : ')',
                                 k < 3 ? "expected ',' between the Euler parameters "
                                         "(w, x, y, z)"
                                       : "expected ')' after the Euler parameters "
                                         "(w, x, y, z)");
            }
            continue;
        }
        if (peek(lx) != ':' || strlen(a) != 1 || !strchr("xyzXYZ", a[0])) {
            lx->i = save;
            break;
        }
        if (b->quat[0] >= 0)
            lang_fail(c, apos, "quat:(w, x, y, z) is the whole orientation: no other "
                      "rotation beside it");
        lx->i++;
        if (b->nrot >= MBS_MAX_ROT)
            lang_fail(c, apos, "more than %d elementary rotations", MBS_MAX_ROT);
        b->axis[b->nrot] = tolower((unsigned char)a[0]) - 'x';
        b->angle[b->nrot++] = mbs_add_input(c, mbs_angle_value(lx, "the rotation's angle"));
    }
    if (b->nrot == 0 && b->quat[0] < 0)
        lang_fail(c, lang_here(lx), "expected elementary rotations AXIS:ANGLE after "
                  "'rot' (e.g. rot z:psi y:theta x:phi), or quat:(w, x, y, z)");
}

/* BODY[(x, y, z)] */
mbs_attach mbs_attachment(lang_ctx *c, lang_lexer *lx)
{
    mbs_attach a;
    lpos pos;
    const char *name = lang_read_name(lx, &pos, "expected a body's name or ground");
    a.body = mbs_find_body(c, name, pos, 1);
    a.p[0] = a.p[1] = a.p[2] = -1;
    if (peek(lx) == '(')
        mbs_tuple(lx, a.p, "the attachment point");
    return a;
}
