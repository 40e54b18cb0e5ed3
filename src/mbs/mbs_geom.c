/* SPDX-License-Identifier: BSD-3-Clause */
/* The geometry statements of a mechanism file (docs/mechanisms.md, "Geometry to draw"):
 *   box NAME on BODY size (lx, ly, lz) [at (x, y, z)] [color C]
 *   cylinder NAME on BODY radius R length L [axis x|y|z] [at (x, y, z)] [color C]
 *   disk NAME on BODY radius R [axis x|y|z] [at (x, y, z)] [color C]
 *   sphere NAME on BODY [radius R] [at (x, y, z)] [color C]
 *   rod NAME between A[(x, y, z)] and B[(x, y, z)] [color C]
 *   frame BODY|ground [size S]
 *   ground [at (x, y, z)] [normal (nx, ny, nz)] [size S] [color C]
 *   trace NAME on BODY [at (x, y, z)] [color C]
 *   arrow CONSTRAINT on BODY [at (x, y, z)] along (dx, dy, dz) [in N|B]
 * Points and offsets are in the body's frame (in N for the ground and a point mass), as the
 * spring's ends; sizes and directions are formulas (inputs, as every formula of the file). */
#include <string.h>
#include <strings.h>

#include "dynkit/mbs.h"
#include "mbs/mbs_internal.h"
#include "mbs/mbs_syntax.h"

/* the colours a file may name, as the page draws them */
static const struct {
    const char *name, *hex;
} colors[] = {
    {"red", "#d62728"},    {"orange", "#ff7f0e"}, {"yellow", "#e6b800"}, {"green", "#2ca02c"},
    {"teal", "#17becf"},   {"blue", "#1f77b4"},   {"purple", "#9467bd"}, {"pink", "#e377c2"},
    {"brown", "#8c564b"},  {"grey", "#7f7f7f"},   {"gray", "#7f7f7f"},   {"black", "#222222"},
    {"silver", "#c0c0c0"}, {"white", "#f4f4f4"},
};

static const char *color_of(lang_ctx *c, lang_lexer *lx)
{
    lpos pos;
    const char *w = lang_read_name(lx, &pos, "expected a colour's name after 'color' (red, "
                                             "orange, yellow, green, teal, blue, purple, pink, "
                                             "brown, grey, black, silver, white)");
    const int n = (int)(sizeof colors / sizeof *colors);
    const char *names[sizeof colors / sizeof *colors];
    for (int i = 0; i < n; i++) {
        if (strcasecmp(w, colors[i].name) == 0)
            return colors[i].hex;
        names[i] = colors[i].name;
    }
    const char *near = dyn_lang_nearest(w, names, n);
    lang_fail(c, pos, "unknown colour '%s'%s%s%s (red, orange, yellow, green, teal, blue, "
              "purple, pink, brown, grey, black, silver, white)", w,
              near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "");
}

static int axis_of(lang_ctx *c, lang_lexer *lx)
{
    lpos pos;
    const char *a = lang_read_name(lx, &pos, "expected the axis x, y or z after 'axis'");
    if (strlen(a) != 1 || !strchr("xyzXYZ", a[0]))
        lang_fail(c, pos, "unknown axis '%s': x, y or z of the body's frame", a);
    return (a[0] | 0x20) - 'x';
}

static int find_constraint(lang_ctx *c, const char *name, lpos pos)
{
    mbs_model *mb = c->hook_ctx;
    const char **names = lang_alloc(c, ((size_t)mb->cons.n + 1) * sizeof *names);
    for (int i = 0; i < mb->cons.n; i++) {
        names[i] = LVEC_AT(mb->cons, mbs_constraint, i).name;
        if (strcasecmp(names[i], name) == 0)
            return i;
    }
    const char *near = mb->cons.n ? dyn_lang_nearest(name, names, mb->cons.n) : NULL;
    lang_fail(c, pos, "unknown constraint '%s'%s%s%s (an arrow draws the force of a constraint "
              "declared before it)", name, near ? " (did you mean '" : "", near ? near : "",
              near ? "'?)" : "");
}

/* the words after the shape's head, each once: at, size, radius, length, axis, normal,
 * along, in, color; allowed: the words this statement takes */
static void options(lang_ctx *c, lang_lexer *lx, mbs_shape *s, const char *allowed,
                    const char *what)
{
    while (lang_skip_blanks(lx)) {
        lpos wpos;
        const char *w = lang_read_name(lx, &wpos, lang_printf(c, "expected one of: %s", allowed));
        char key[16];
        snprintf(key, sizeof key, "%s", w);
        for (char *p = key; *p; p++)
            *p = (char)(*p | 0x20);
        /* a whole word of the list */
        const char *at = strstr(allowed, key);
        const size_t n = strlen(key);
        while (at && ((at > allowed && at[-1] != ' ' && at[-1] != ',') ||
                      (at[n] && at[n] != ',' && at[n] != ' ')))
            at = strstr(at + 1, key);
        if (!at || strlen(w) >= sizeof key)
            lang_fail(c, wpos, "unknown word '%s' in a %s: expected %s", w, what, allowed);
        if (!strcmp(key, "at"))
            mbs_tuple(lx, s->a.p, "the point");
        else if (!strcmp(key, "size") && s->kind == DYN_MECH_BOX)
            mbs_tuple(lx, s->v, "the size");
        else if (!strcmp(key, "size"))
            s->size = mbs_input_expr(lx, key);
        else if (!strcmp(key, "radius"))
            s->v[0] = mbs_input_expr(lx, key);
        else if (!strcmp(key, "length"))
            s->v[1] = mbs_input_expr(lx, key);
        else if (!strcmp(key, "axis"))
            s->axis = axis_of(c, lx);
        else if (!strcmp(key, "normal") || !strcmp(key, "along"))
            mbs_tuple(lx, s->v, !strcmp(key, "normal") ? "the normal" : "the direction");
        else if (!strcmp(key, "color"))
            s->color = color_of(c, lx);
        else { /* in N|B */
            lpos fpos;
            const char *f = lang_read_name(lx, &fpos, "expected the frame N or B");
            if (strcasecmp(f, "B") == 0)
                s->in_body = 1;
            else if (strcasecmp(f, "N") != 0)
                lang_fail(c, fpos, "unknown frame '%s': N (fixed) or B (the body's)", f);
        }
    }
}

/* on BODY */
static void on_body(lang_ctx *c, lang_lexer *lx, mbs_shape *s)
{
    if (!mbs_take_word(lx, "on"))
        lang_fail(c, lang_here(lx), "expected 'on' BODY after the name");
    lpos bpos;
    const char *b = lang_read_name(lx, &bpos, "expected a body's name or ground");
    s->a.body = mbs_find_body(c, b, bpos, 1);
}

mbs_shape mbs_shape_init(int kind)
{
    mbs_shape s;
    memset(&s, 0, sizeof s);
    s.kind = kind;
    s.a.body = s.b.body = -1;
    for (int j = 0; j < 3; j++)
        s.a.p[j] = s.b.p[j] = s.v[j] = s.avec[j] = -1;
    s.axis = 2;
    s.con = -1;
    s.size = -1;
    s.wheel = -1;
    return s;
}

int mbs_geom_statement(lang_ctx *c, lang_lexer *lx, const char *w, lpos wpos)
{
    static const char *const words[] = {"box", "cylinder", "disk", "sphere", "rod",
                                        "frame", "ground", "trace", "arrow"};
    static const int kinds[] = {DYN_MECH_BOX,   DYN_MECH_CYLINDER, DYN_MECH_CYLINDER,
                                DYN_MECH_SPHERE, DYN_MECH_ROD,     DYN_MECH_FRAME,
                                DYN_MECH_GROUND, DYN_MECH_TRACE,   DYN_MECH_ARROW};
    int k = -1;
    for (int i = 0; i < (int)(sizeof words / sizeof *words); i++)
        if (strcasecmp(w, words[i]) == 0)
            k = i;
    if (k < 0)
        return -1;
    mbs_model *mb = c->hook_ctx;
    mbs_shape s = mbs_shape_init(kinds[k]);
    s.pos = wpos;
    lpos npos = wpos;
    const char *what = words[k];
    switch (s.kind) {
    case DYN_MECH_FRAME: {
        const char *b = lang_read_name(lx, &npos, "expected a body's name or ground");
        s.a.body = mbs_find_body(c, b, npos, 1);
        s.name = b;
        options(c, lx, &s, "size", what);
        break;
    }
    case DYN_MECH_GROUND:
        s.name = "ground";
        options(c, lx, &s, "at, normal, size, color", what);
        break;
    case DYN_MECH_ROD:
        s.name = lang_read_name(lx, &npos, "expected the rod's name");
        if (!mbs_take_word(lx, "between"))
            lang_fail(c, lang_here(lx), "expected 'between' A and B after the rod's name");
        s.a = mbs_attachment(c, lx);
        if (!mbs_take_word(lx, "and"))
            lang_fail(c, lang_here(lx), "expected 'and' between the rod's two ends");
        s.b = mbs_attachment(c, lx);
        options(c, lx, &s, "color", what);
        break;
    case DYN_MECH_ARROW:
        s.name = lang_read_name(lx, &npos, "expected the constraint whose force the arrow draws");
        s.con = find_constraint(c, s.name, npos);
        on_body(c, lx, &s);
        options(c, lx, &s, "at, along, in, color", what);
        if (s.v[0] < 0)
            lang_fail(c, wpos, "arrow '%s' has no direction: write along (dx, dy, dz), the "
                      "direction of the constraint's force", s.name);
        if (s.in_body && (s.a.body < 0 || !LVEC_AT(mb->bodies, mbs_body, s.a.body).frame))
            lang_fail(c, wpos, "'in B' needs a rigid body: %s has no frame B",
                      s.a.body < 0 ? "the ground" : "a point mass");
        break;
    default: /* box, cylinder, disk, sphere, trace */
        s.name = lang_read_name(lx, &npos, lang_printf(c, "expected the %s's name", what));
        on_body(c, lx, &s);
        if (s.kind == DYN_MECH_BOX)
            options(c, lx, &s, "size, at, color", what);
        else if (s.kind == DYN_MECH_CYLINDER && k == 1)
            options(c, lx, &s, "radius, length, axis, at, color", what);
        else if (s.kind == DYN_MECH_CYLINDER)
            options(c, lx, &s, "radius, axis, at, color", what);
        else if (s.kind == DYN_MECH_SPHERE)
            options(c, lx, &s, "radius, at, color", what);
        else
            options(c, lx, &s, "at, color", what);
        if (s.kind == DYN_MECH_BOX && s.v[0] < 0)
            lang_fail(c, wpos, "box '%s' has no size: write size (lx, ly, lz), its edges along "
                      "the body's axes", s.name);
        if (s.kind == DYN_MECH_CYLINDER && (s.v[0] < 0 || (k == 1 && s.v[1] < 0)))
            lang_fail(c, wpos, "%s '%s' needs radius R%s", what, s.name,
                      k == 1 ? " and length L" : "");
        break;
    }
    *(mbs_shape *)lvec_push(c, &mb->shapes, sizeof s) = s;
    return 0;
}
