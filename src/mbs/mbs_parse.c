/* SPDX-License-Identifier: BSD-3-Clause */
/* Statements of a mechanism file (docs/mechanisms.md): coord, gravity, point, body, spring,
 * force, torque, constraint, prescribe, stabilize, wheel, and units and descriptions in par lines;
 * every other line is an .ode statement (par, number, !derived, name=formula, f(x)=...,
 * aux, table, global, @ options), read by src/lang as in an .ode file. Expressions are
 * src/lang's; each is kept as an unnamed fixed quantity of the model (an input) so that
 * lang_check resolves its names with FILE:LINE:COL messages. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "mbs/mbs_internal.h"
#include "mbs/mbs_syntax.h"

static mbs_model *model_of(lang_ctx *c) { return c->hook_ctx; }

static int peek(lang_lexer *lx) { return lang_skip_blanks(lx); }






/* a unit written at the line's offset a: refused at its place unless it reads */
static void check_unit(lang_ctx *c, const lang_line *line, int a, const char *unit)
{
    int off = 0;
    const char *why;
    if (!mbs_unit_error(c, unit, &off, &why))
        return;
    const int len = (int)strlen(unit);
    if (off >= len && len > 0)
        off = len - 1;
    lang_fail(c, line->pos[a + off], "%s in a unit: %s", why, MBS_UNIT_SYMBOLS);
}

/* [unit] and "description", each optional, in either order */
static void doc_of(lang_lexer *lx, lang_doc *doc)
{
    for (;;) {
        const int ch = peek(lx);
        const int close = ch == '[' ? ']' : ch == '"' ? '"' : 0;
        if (!close)
            return;
        const lpos at = lang_here(lx);
        const int a = ++lx->i;
        while (lx->i < lx->end && lx->line->text[lx->i] != close)
            lx->i++;
        if (lx->i >= lx->end)
            lang_fail(lx->c, at, "'%c' without its closing '%c'", ch, close);
        const char *s = lang_strndup(lx->c, lx->line->text + a, (size_t)(lx->i - a));
        lx->i++;
        if (close == ']') {
            check_unit(lx->c, lx->line, a, s);
            doc->unit = s;
        }
        else
            doc->description = s;
    }
}

static void add_doc(lang_ctx *c, const char *name, lpos pos, lang_doc doc)
{
    if (!doc.unit && !doc.description)
        return;
    lang_docline *d = lvec_push(c, &c->m.docs, sizeof *d);
    d->name = name;
    d->pos = pos;
    d->doc = doc;
}

static int add_state(lang_ctx *c, const char *name, lpos pos, node *init)
{
    if (lang_is_reserved(name))
        lang_fail(c, pos, "'%s' is a reserved word and cannot be a coordinate", name);
    const int idx = c->m.states.n;
    lang_declare(c, name, pos, SYM_STATE, idx);
    lang_state *s = lvec_push(c, &c->m.states, sizeof *s);
    s->name = name;
    s->pos = pos;
    s->rhs = lang_num(c, 0.0); /* written by mbs_derive */
    if (!init)
        return idx; /* 0 unless an init line says */
    lang_init *in = lvec_push(c, &c->m.inits, sizeof *in);
    in->name = name;
    in->pos = pos;
    in->value = init;
    return idx;
}


static const char *speed_unit(lang_ctx *c, const char *unit)
{
    if (!unit)
        return NULL;
    if (strcmp(unit, "1") == 0)
        return "1/s";
    return lang_printf(c, "%s/s", unit);
}

static void unit_without_brackets(lang_ctx *c, const lang_line *line, int from, int i, int end);

/* coord NAME=VALUE[deg] [UNIT] "DESCRIPTION" [speed NAME[=VALUE]], ... */
static void parse_coord(lang_ctx *c, lang_lexer *lx)
{
    mbs_model *mb = model_of(c);
    do {
        mbs_coord *q = lvec_push(c, &mb->coords, sizeof *q);
        q->name = lang_read_name(lx, &q->pos, "expected a coordinate's name");
        q->kin = -1;
        node *init = NULL;
        if (peek(lx) == '=') {
            lx->i++;
            init = mbs_angle_value(lx, "the coordinate's initial value");
        } else {
            init = lang_num(c, 0.0);
        }
        if (lang_is_ident_start(peek(lx)))
            unit_without_brackets(c, lx->line, 0, lx->i, lx->end);
        lang_doc doc = {0};
        doc_of(lx, &doc);
        q->unit = doc.unit;
        q->q = add_state(c, q->name, q->pos, init);
        add_doc(c, q->name, q->pos, doc);
        lpos spos = q->pos;
        node *sinit = NULL;
        q->speed = lang_printf(c, "d%s", q->name);
        if (mbs_take_word(lx, "speed")) {
            q->speed = lang_read_name(lx, &spos, "expected the speed's name after 'speed'");
            if (peek(lx) == '=') {
                lx->i++;
                sinit = mbs_angle_value(lx, "the speed's initial value");
            }
        }
        q->u = -1;
        q->speed_pos = spos;
        q->speed_init = sinit;
        q->speed_doc = (lang_doc){speed_unit(c, doc.unit), lang_printf(c, "d%s/dt", q->name)};
        doc_of(lx, &q->speed_doc);
    } while (peek(lx) == ',' && (lx->i++, 1));
    lang_expect_end(lx, "the coordinates");
}

/* speeds NAME[=VALUE] [UNIT] "DESCRIPTION", ...: generalized speeds in place of the rates */
static void parse_speeds(lang_ctx *c, lang_lexer *lx)
{
    mbs_model *mb = model_of(c);
    do {
        mbs_speed *u = lvec_push(c, &mb->speeds, sizeof *u);
        u->name = lang_read_name(lx, &u->pos, "expected a speed's name");
        if (peek(lx) == '=') {
            lx->i++;
            u->init = mbs_angle_value(lx, "the speed's initial value");
        }
        u->doc.description = "generalized speed";
        doc_of(lx, &u->doc);
    } while (peek(lx) == ',' && (lx->i++, 1));
    lang_expect_end(lx, "the speeds");
}

/* rate q' = FORMULA, ...: the kinematic equations, linear in the speeds */
static void parse_rates(lang_ctx *c, lang_lexer *lx)
{
    mbs_model *mb = model_of(c);
    do {
        lpos pos;
        const char *name = lang_read_name(lx, &pos, "expected a coordinate's name: rate q' = "
                                          "formula of the coordinates and speeds");
        mbs_coord *q = NULL;
        for (int i = 0; i < mb->coords.n && !q; i++)
            if (strcasecmp(LVEC_AT(mb->coords, mbs_coord, i).name, name) == 0)
                q = &LVEC_AT(mb->coords, mbs_coord, i);
        if (!q)
            lang_fail(c, pos, "'%s' is not a coordinate (declared by coord before its rate)",
                      name);
        if (q->kin >= 0)
            lang_fail(c, pos, "the rate of '%s' is given twice", name);
        lang_expect_char(lx, '\'', "expected q' = formula: the rate of the coordinate");
        lang_expect_char(lx, '=', "expected '=' after q'");
        q->kin = mbs_input_expr(lx, "the coordinate's rate");
        q->kin_pos = pos;
    } while (peek(lx) == ',' && (lx->i++, 1));
    lang_expect_end(lx, "the rates");
}

/* The declared speeds take the places of the rates (as many, in order); each coordinate
 * then needs its rate. */
static void finish_speeds(lang_ctx *c, mbs_model *mb)
{
    const int ns = mb->speeds.n, n = mb->coords.n;
    for (int i = 0; i < n && !ns; i++) {
        const mbs_coord *q = &LVEC_AT(mb->coords, mbs_coord, i);
        if (q->kin >= 0)
            lang_fail(c, q->kin_pos, "a rate line needs the generalized speeds it uses, "
                      "declared by speeds NAME, ...");
    }
    if (!ns)
        return;
    if (ns != n)
        lang_fail(c, LVEC_AT(mb->speeds, mbs_speed, 0).pos, "%d speeds for %d coordinates: "
                  "declare as many speeds as coordinates", ns, n);
    for (int i = 0; i < n; i++) {
        mbs_coord *q = &LVEC_AT(mb->coords, mbs_coord, i);
        const mbs_speed *u = &LVEC_AT(mb->speeds, mbs_speed, i);
        if (strcmp(q->speed, lang_printf(c, "d%s", q->name)) != 0 || q->speed_init)
            lang_fail(c, q->speed_pos, "coordinate '%s' names its speed, but the speeds are "
                      "declared by speeds: leave out 'speed' here", q->name);
        if (q->kin < 0)
            lang_fail(c, q->pos, "coordinate '%s' has no rate: with declared speeds, write "
                      "rate %s' = formula of the coordinates and speeds", q->name, q->name);
        q->speed = u->name;
        q->speed_pos = u->pos;
        q->speed_init = u->init;
        q->speed_doc = u->doc;
    }
}

/* a word at offset i of the line after a number (from offset from on), up to the next ','
 * or the end, that reads as a unit: refused, saying that units go in brackets */
static void unit_without_brackets(lang_ctx *c, const lang_line *line, int from, int i, int end)
{
    const char *t = line->text;
    int b = i - 1;
    while (b >= from && (t[b] == ' ' || t[b] == '\t'))
        b--;
    if (b < from || b == i - 1 || !(isdigit((unsigned char)t[b]) || t[b] == '.'))
        return;
    int e = i;
    while (e < end && t[e] != ',' && t[e] != '[' && t[e] != '"')
        e++;
    while (e > i && (t[e - 1] == ' ' || t[e - 1] == '\t'))
        e--;
    const char *word = lang_strndup(c, t + i, (size_t)(e - i));
    int off;
    const char *why;
    if (mbs_unit_error(c, word, &off, &why))
        return;
    lang_fail(c, line->pos[i], "a unit goes in brackets after the value: [%s]", word);
}

/* par lines: [unit] and "description" after a value go to the name before them; they are
 * blanked so that src/lang reads the rest as an .ode par line */
static void par_docs(lang_ctx *c, lang_lexer *lx)
{
    char *t = (char *)lx->line->text;
    const char *name = NULL;
    lpos npos = {0, 0};
    for (int i = lx->i; i < lx->end; i++) {
        if (lang_is_ident_start((unsigned char)t[i]) && (i == 0 || !lang_is_ident_char(
                                                                       (unsigned char)t[i - 1]))) {
            int k = i;
            while (k < lx->end && lang_is_ident_char((unsigned char)t[k]))
                k++;
            int e = k;
            while (e < lx->end && (t[e] == ' ' || t[e] == '\t'))
                e++;
            if (e < lx->end && t[e] == '=') {
                name = lang_strndup(c, t + i, (size_t)(k - i));
                npos = lx->line->pos[i];
            } else {
                unit_without_brackets(c, lx->line, lx->i, i, lx->end);
            }
            i = k - 1;
        } else if (t[i] == '[' || t[i] == '"') {
            const char close = t[i] == '[' ? ']' : '"';
            int k = i + 1;
            while (k < lx->end && t[k] != close)
                k++;
            if (k >= lx->end)
                lang_fail(c, lx->line->pos[i], "'%c' without its closing '%c'", t[i], close);
            if (!name)
                lang_fail(c, lx->line->pos[i], "a unit or description follows a parameter's "
                          "value: NAME=VALUE [UNIT] \"DESCRIPTION\"");
            lang_doc doc = {0};
            const char *s = lang_strndup(c, t + i + 1, (size_t)(k - i - 1));
            if (close == ']') {
                check_unit(c, lx->line, i + 1, s);
                doc.unit = s;
            } else
                doc.description = s;
            add_doc(c, name, npos, doc);
            for (int j = i; j <= k; j++)
                t[j] = ' ';
            i = k;
        }
    }
}


static void new_body_name(lang_ctx *c, const char *name, lpos pos)
{
    mbs_model *mb = model_of(c);
    if (strcasecmp(name, "ground") == 0)
        lang_fail(c, pos, "'ground' is the fixed frame; a body needs another name");
    for (int i = 0; i < mb->bodies.n; i++)
        if (strcasecmp(LVEC_AT(mb->bodies, mbs_body, i).name, name) == 0)
            lang_fail(c, pos, "body '%s' is declared twice", name);
}


/* point NAME mass=M at (x, y, z)
 * body NAME mass=M inertia=(Ixx, Iyy, Izz[, Ixy, Ixz, Iyz]) at (x, y, z) [rot AXIS:ANGLE ...] */
static void parse_body(lang_ctx *c, lang_lexer *lx, int point, lpos kpos)
{
    mbs_model *mb = model_of(c);
    mbs_body b = {0};
    b.point = point;
    b.name = lang_read_name(lx, &b.pos,
                            point ? "expected the point's name" : "expected the body's name");
    new_body_name(c, b.name, b.pos);
    b.mass = -1;
    for (int k = 0; k < 6; k++)
        b.inertia[k] = -1;
    for (int k = 0; k < 4; k++)
        b.quat[k] = -1;
    b.about[0] = b.about[1] = b.about[2] = -1;
    int has_at = 0, has_inertia = 0, about_pivot = 0;
    while (peek(lx)) {
        lpos wpos;
        const char *w = lang_read_name(lx, &wpos, "expected mass=, inertia=, at or rot");
        if (strcasecmp(w, "mass") == 0) {
            lang_expect_char(lx, '=', "expected '=' after mass");
            b.mass = mbs_input_expr(lx, "the mass");
        } else if (strcasecmp(w, "inertia") == 0 && !point) {
            lang_expect_char(lx, '=', "expected '=' after inertia");
            const int paren = peek(lx) == '(';
            if (paren)
                lx->i++;
            for (int k = 0; k < 6; k++) {
                b.inertia[k] = mbs_input_expr(lx, "a moment of inertia");
                if (k == 2 || k == 5) {
                    if (peek(lx) != ',' || k == 5)
                        break;
                    if (!paren) { /* Ixx,Iyy,Izz then a keyword or products */
                        int save = lx->i;
                        lx->i++;
                        if (lang_is_ident_start(peek(lx))) {
                            lpos p2;
                            const char *nx = lang_read_name(lx, &p2, "");
                            lx->i = save;
                            if (!strcasecmp(nx, "at") || !strcasecmp(nx, "rot") ||
                                !strcasecmp(nx, "mass") || !strcasecmp(nx, "about") ||
                                mbs_joint_kind(nx))
                                break;
                        }
                        lx->i = save;
                    }
                }
                lang_expect_char(lx, ',', "expected ',' between the moments of inertia");
            }
            if (paren)
                lang_expect_char(lx, ')',
                                 "expected ')' after the moments of inertia (Ixx, Iyy, Izz[, "
                                 "Ixy, Ixz, Iyz])");
            has_inertia = 1;
            if (mbs_take_word(lx, "about")) {
                b.about_pos = lang_here(lx);
                if (peek(lx) == '(')
                    mbs_tuple(lx, b.about, "the point the inertia is about");
                else if (!mbs_take_word(lx, "pivot"))
                    lang_fail(c, b.about_pos, "expected the point the inertia is about after "
                              "'about': (x, y, z) in the body's frame from its mass centre, or "
                              "pivot (its joint's pivot)");
                else
                    about_pivot = 1;
            }
        } else if (strcasecmp(w, "at") == 0) {
            if (b.joint)
                lang_fail(c, wpos, "the joint places '%s': no at (x, y, z) beside it", b.name);
            mbs_tuple(lx, b.at, "the mass centre");
            has_at = 1;
        } else if (strcasecmp(w, "rot") == 0 && !point) {
            if (b.joint)
                lang_fail(c, wpos, "the joint gives the orientation of '%s': no rot beside it",
                          b.name);
            mbs_parse_rot(c, lx, &b);
        } else if (mbs_joint_kind(w) != MBS_NO_JOINT) {
            if (has_at || b.nrot || b.quat[0] >= 0)
                lang_fail(c, wpos, "a %s is placed either by a joint or by at (x, y, z) rot "
                          "...: not both", point ? "point" : "body");
            mbs_parse_joint(c, lx, &b, mbs_joint_kind(w));
            has_at = 1;
        } else {
            lang_fail(c, wpos, "unknown word '%s' in a %s: expected mass=, %sat (x, y, z)%s",
                      w, point ? "point" : "body", point ? "" : "inertia=(Ixx, Iyy, Izz), ",
                      point ? "" : " or rot AXIS:ANGLE ...");
        }
    }
    if (b.mass < 0)
        lang_fail(c, kpos, "%s '%s' has no mass: write mass=M", point ? "point" : "body",
                  b.name);
    if (!point && !has_inertia)
        lang_fail(c, kpos, "body '%s' has no inertia: write inertia=(Ixx, Iyy, Izz) about its "
                  "mass centre in its frame, or declare a point mass with 'point'", b.name);
    if (!has_at)
        lang_fail(c, kpos, "%s '%s' has no position: write at (x, y, z), its mass centre in N "
                  "as formulas of the coordinates", point ? "point" : "body", b.name);
    if (about_pivot) {
        if (!b.joint)
            lang_fail(c, b.about_pos, "'about pivot' needs a joint with a pivot (x, y, z): "
                      "'%s' is placed by at (x, y, z); give the point, about (x, y, z)", b.name);
        memcpy(b.about, b.pivot, sizeof b.about); /* -1: the pivot is the mass centre */
    }
    b.frame = !point || (b.joint && (b.nrot || b.quat[0] >= 0 ||
                                     (b.parent >= 0 &&
                                      LVEC_AT(mb->bodies, mbs_body, b.parent).frame)));
    *(mbs_body *)lvec_push(c, &mb->bodies, sizeof b) = b;
}



/* spring NAME between A[(x,y,z)] and B[(x,y,z)] k=K [l0=L0] [c=C]
 *                                              | law=F [energy=G] [l0=L0] */
static void parse_spring(lang_ctx *c, lang_lexer *lx, lpos kpos)
{
    mbs_model *mb = model_of(c);
    mbs_spring s = {0};
    s.name = lang_read_name(lx, &s.pos, "expected the spring's name");
    if (!mbs_take_word(lx, "between"))
        lang_fail(c, lang_here(lx), "expected 'between' A and B after the spring's name");
    s.a = mbs_attachment(c, lx);
    if (!mbs_take_word(lx, "and"))
        lang_fail(c, lang_here(lx), "expected 'and' between the spring's two ends");
    s.b = mbs_attachment(c, lx);
    s.k = s.l0 = s.c = s.law = s.energy = -1;
    lpos kcpos = {0, 0};
    while (peek(lx)) {
        lpos wpos;
        const char *w = lang_read_name(lx, &wpos, "expected k=, l0=, c=, law= or energy=");
        const int law = !strcasecmp(w, "law"), energy = !strcasecmp(w, "energy");
        int *to = !strcasecmp(w, "k") ? &s.k : !strcasecmp(w, "l0") ? &s.l0
                                             : !strcasecmp(w, "c") ? &s.c : NULL;
        if (!to && !law && !energy)
            lang_fail(c, wpos, "unknown word '%s' in a spring: expected k=, l0=, c=, law= or "
                      "energy=", w);
        lang_expect_char(lx, '=', "expected '='");
        if (law)
            s.law_name = lang_read_name(lx, &s.law_pos, "expected the name of a function "
                                        "F(x, v) of the file (the tension in N)");
        else if (energy)
            s.energy_name = lang_read_name(lx, &s.energy_pos, "expected the name of a function "
                                           "G(x) of the file (the law's integral in J)");
        else
            *to = mbs_input_expr(lx, w);
        if (to && to != &s.l0 && !kcpos.line)
            kcpos = wpos;
    }
    if (s.law_name && kcpos.line)
        lang_fail(c, kcpos, "spring '%s' has a law=: its tension is the law's alone, no k= or c= "
                  "beside it (add k x + c v to the law)", s.name);
    if (s.energy_name && !s.law_name)
        lang_fail(c, s.energy_pos, "energy= of spring '%s' goes with a law= (a spring with k= "
                  "has its energy k x^2/2 already)", s.name);
    if (s.k < 0 && s.c < 0 && !s.law_name)
        lang_fail(c, kpos, "spring '%s' has neither a stiffness k=, a damping c= nor a law=",
                  s.name);
    *(mbs_spring *)lvec_push(c, &mb->springs, sizeof s) = s;
}

/* force NAME on BODY [at (x,y,z)] = (fx, fy, fz) [in N|B]; torque NAME on BODY = (...) */
static void parse_load(lang_ctx *c, lang_lexer *lx, int torque)
{
    mbs_model *mb = model_of(c);
    mbs_load l = {0};
    l.torque = torque;
    l.name = lang_read_name(lx, &l.pos, torque ? "expected the torque's name"
                                               : "expected the force's name");
    if (!mbs_take_word(lx, "on"))
        lang_fail(c, lang_here(lx), "expected 'on' BODY after the name");
    lpos bpos;
    const char *b = lang_read_name(lx, &bpos, "expected a body's name");
    l.body = mbs_find_body(c, b, bpos, 0);
    l.at[0] = l.at[1] = l.at[2] = -1;
    if (!torque && mbs_take_word(lx, "at"))
        mbs_tuple(lx, l.at, "the point of application");
    lang_expect_char(lx, '=', torque ? "expected '= (mx, my, mz)'" : "expected '= (fx, fy, fz)'");
    mbs_tuple(lx, l.f, torque ? "the torque" : "the force");
    if (mbs_take_word(lx, "in")) {
        lpos fpos;
        const char *f = lang_read_name(lx, &fpos, "expected the frame N or B");
        if (strcasecmp(f, "B") == 0)
            l.in_body = 1;
        else if (strcasecmp(f, "N") != 0)
            lang_fail(c, fpos, "unknown frame '%s': N (fixed) or B (the body's)", f);
    }
    if (l.in_body && LVEC_AT(mb->bodies, mbs_body, l.body).point)
        lang_fail(c, l.pos, "'%s' is a point mass: it has no frame B", b);
    if (torque && LVEC_AT(mb->bodies, mbs_body, l.body).point)
        lang_fail(c, l.pos, "'%s' is a point mass: a torque on it does nothing", b);
    lang_expect_end(lx, torque ? "the torque" : "the force");
    *(mbs_load *)lvec_push(c, &mb->loads, sizeof l) = l;
}

static void declare_output(lang_ctx *c, const char *name, lpos pos, int *index)
{
    *index = c->m.auxs.n;
    lang_declare(c, name, pos, SYM_AUX, c->m.auxs.n);
    lang_formula *f = lvec_push(c, &c->m.auxs, sizeof *f);
    f->name = name;
    f->pos = pos;
    f->expr = lang_num(c, 0.0); /* written by mbs_derive */
}

/* constraint NAME [UNIT]: EXPR [= EXPR];  prescribe NAME: COORD = EXPR */
static void parse_constraint(lang_ctx *c, lang_lexer *lx, int prescribe)
{
    mbs_model *mb = model_of(c);
    mbs_constraint k = {0};
    k.prescribed = -1;
    k.wheel = -1;
    k.name = lang_read_name(lx, &k.pos, "expected the constraint's name (its force is named so)");
    lang_doc doc = {0};
    doc_of(lx, &doc);
    k.unit = doc.unit;
    lang_expect_char(lx, ':', "expected ':' after the constraint's name");
    node *lhs = mbs_parse_value(lx, "the constraint's expression");
    if (prescribe) {
        if (lhs->kind != N_NAME)
            lang_fail(c, lhs->pos, "prescribe NAME: COORDINATE = formula of t");
        for (int i = 0; i < mb->coords.n; i++)
            if (strcasecmp(LVEC_AT(mb->coords, mbs_coord, i).name, lhs->name) == 0)
                k.prescribed = i;
        if (k.prescribed < 0)
            lang_fail(c, lhs->pos, "'%s' is not a coordinate (prescribe NAME: COORDINATE = "
                      "formula of t)", lhs->name);
    }
    if (peek(lx) == '=') {
        lx->i++;
        node *rhs = mbs_parse_value(lx, "the right-hand side");
        node *d = lang_node(c, N_BIN, lhs->pos);
        d->op = OP_SUB;
        d->nargs = 2;
        d->args = lang_alloc(c, 2 * sizeof *d->args);
        d->args[0] = lhs;
        d->args[1] = rhs;
        rhs->paren = 1;
        lhs = d;
    } else if (prescribe) {
        lang_fail(c, lang_here(lx), "expected '= formula of t' after the coordinate");
    }
    lang_expect_end(lx, "the constraint");
    k.expr = mbs_add_input(c, lhs);
    declare_output(c, k.name, k.pos, &k.aux);
    add_doc(c, k.name, k.pos, (lang_doc){NULL, doc.description});
    *(mbs_constraint *)lvec_push(c, &mb->cons, sizeof k) = k;
}

static void wheel_constraint(lang_ctx *c, mbs_model *mb, int wheel, int part, node *sym)
{
    const mbs_wheel *wh = &LVEC_AT(mb->wheels, mbs_wheel, wheel);
    static const char *const what[3] = {"force on the wheel %s along x",
                                        "force on the wheel %s along y",
                                        "normal force on the wheel %s"};
    mbs_constraint k = {0};
    k.name = lang_printf(c, "%s_%c", wh->name, "xyz"[part]);
    k.pos = wh->pos;
    k.unit = part < 2 ? "m/s" : "m";
    k.expr = -1;
    k.prescribed = -1;
    k.wheel = wheel;
    k.part = part;
    k.sym = sym;
    declare_output(c, k.name, k.pos, &k.aux);
    LVEC_AT(c->m.auxs, lang_formula, k.aux).doc.description =
        lang_printf(c, "the ground's %s", lang_printf(c, what[part], wh->name));
    *(mbs_constraint *)lvec_push(c, &mb->cons, sizeof k) = k;
}

void mbs_wheel_normal(lang_ctx *c, mbs_model *mb, int wheel, node *height)
{
    wheel_constraint(c, mb, wheel, 2, height);
}

/* wheel NAME on BODY radius=R axis=(x, y, z) [at (x, y, z)] */
static void parse_wheel(lang_ctx *c, lang_lexer *lx, lpos kpos)
{
    mbs_model *mb = model_of(c);
    mbs_wheel wh = {0};
    wh.name = lang_read_name(lx, &wh.pos, "expected the wheel's name");
    if (!mbs_take_word(lx, "on"))
        lang_fail(c, lang_here(lx), "expected 'on' BODY after the wheel's name");
    lpos bpos;
    const char *b = lang_read_name(lx, &bpos, "expected a body's name");
    wh.body = mbs_find_body(c, b, bpos, 0);
    if (LVEC_AT(mb->bodies, mbs_body, wh.body).point)
        lang_fail(c, bpos, "'%s' is a point mass: a wheel needs a body with a frame", b);
    wh.radius = wh.axis[0] = -1;
    wh.at[0] = wh.at[1] = wh.at[2] = -1;
    while (peek(lx)) {
        lpos wpos;
        const char *w = lang_read_name(lx, &wpos, "expected radius=, axis= or at");
        if (strcasecmp(w, "radius") == 0) {
            lang_expect_char(lx, '=', "expected '=' after radius");
            wh.radius = mbs_input_expr(lx, "the wheel's radius");
        } else if (strcasecmp(w, "axis") == 0) {
            lang_expect_char(lx, '=', "expected '=' after axis");
            mbs_tuple(lx, wh.axis, "the wheel's axis in the body's frame");
        } else if (strcasecmp(w, "at") == 0) {
            mbs_tuple(lx, wh.at, "the wheel's centre in the body's frame");
        } else {
            lang_fail(c, wpos, "unknown word '%s' in a wheel: expected radius=R, axis=(x, y, "
                      "z) or at (x, y, z)", w);
        }
    }
    if (wh.radius < 0 || wh.axis[0] < 0)
        lang_fail(c, kpos, "wheel '%s' needs radius=R and axis=(x, y, z), its axle's "
                  "direction in the frame of %s", wh.name, b);
    *(mbs_wheel *)lvec_push(c, &mb->wheels, sizeof wh) = wh;
    for (int part = 0; part < 2; part++)
        wheel_constraint(c, mb, mb->wheels.n - 1, part, NULL);
}

int mbs_statement(lang_ctx *c, lang_lexer *lx, const char *w, lpos wpos)
{
    mbs_model *mb = model_of(c);
    if (!strcasecmp(w, "par") || !strcasecmp(w, "p") || !strcasecmp(w, "param") ||
        !strcasecmp(w, "params") || !strcasecmp(w, "parameter") ||
        !strcasecmp(w, "parameters") || !strcasecmp(w, "pars")) {
        par_docs(c, lx);
        return -1;
    }
    if (!strcasecmp(w, "coord") || !strcasecmp(w, "coords"))
        parse_coord(c, lx);
    else if (!strcasecmp(w, "gravity")) {
        for (int k = 0; k < 3; k++) {
            mb->gravity[k] = mbs_input_expr(lx, "a component of gravity (gx, gy, gz)");
            if (k < 2)
                lang_expect_char(lx, ',', "expected ',' between the components gx, gy, gz");
        }
        lang_expect_end(lx, "gravity");
    } else if (!strcasecmp(w, "point") || !strcasecmp(w, "body"))
        parse_body(c, lx, !strcasecmp(w, "point"), wpos);
    else if (!strcasecmp(w, "spring"))
        parse_spring(c, lx, wpos);
    else if (!strcasecmp(w, "force") || !strcasecmp(w, "torque"))
        parse_load(c, lx, !strcasecmp(w, "torque"));
    else if (!strcasecmp(w, "speeds"))
        parse_speeds(c, lx);
    else if (!strcasecmp(w, "rate") || !strcasecmp(w, "rates"))
        parse_rates(c, lx);
    else if (!strcasecmp(w, "constraint") || !strcasecmp(w, "prescribe"))
        parse_constraint(c, lx, !strcasecmp(w, "prescribe"));
    else if (!strcasecmp(w, "wheel"))
        parse_wheel(c, lx, wpos);
    else if (!strcasecmp(w, "input") || !strcasecmp(w, "inputs")) {
        do {
            mbs_named *in = lvec_push(c, &mb->input_names, sizeof *in);
            in->name = lang_read_name(lx, &in->pos, "expected a parameter's name");
        } while (peek(lx) == ',' && (lx->i++, 1));
        lang_expect_end(lx, "the inputs");
    } else if (!strcasecmp(w, "stabilize")) {
        node *e = mbs_parse_value(lx, "Baumgarte's rate [1/s]");
        if (e->kind != N_NUM || !(e->num >= 0.0))
            lang_fail(c, e->pos, "stabilize takes a number >= 0 (Baumgarte's rate, 1/s)");
        mb->alpha = e->num;
        lang_expect_end(lx, "stabilize");
    } else if (mbs_geom_statement(c, lx, w, wpos) == 0) {
        return 0;
    } else {
        static const char *const words[] = {"coord", "gravity", "point", "body", "spring",
                                            "force", "torque", "constraint", "prescribe",
                                            "stabilize", "input", "speeds", "rate", "wheel"};
        const char *near = lang_is_statement_keyword(w)
                               ? NULL
                               : dyn_lang_nearest(w, words, (int)(sizeof words / sizeof *words));
        if (near)
            lang_fail(c, wpos, "unknown statement '%s' (did you mean '%s'?)", w, near);
        return -1;
    }
    return 0;
}

/* a constraint's multiplier is an output column named after it: a coordinate, speed or
 * other name that it shares would give two columns of one name (or lose one) */
static void constraint_names(lang_ctx *c, const mbs_model *mb)
{
    for (int i = 0; i < mb->cons.n; i++) {
        const mbs_constraint *k = &LVEC_AT(mb->cons, mbs_constraint, i);
        const lang_sym *s = lang_lookup(c, k->name);
        if (s && (s->kind != SYM_AUX || s->index != k->aux))
            lang_fail(c, k->pos, "constraint '%s' shares its name with %s on line %d: its "
                      "force is an output column named so; give it another name", k->name,
                      s->kind == SYM_STATE ? "a coordinate or speed" : lang_sym_kind_name(s->kind),
                      s->pos.line);
    }
}

void mbs_finish_parse(lang_ctx *c, mbs_model *mb)
{
    if (mb->coords.n == 0)
        lang_fail(c, (lpos){0, 0}, "no coordinates: declare them with coord NAME=VALUE");
    if (mb->bodies.n == 0)
        lang_fail(c, (lpos){0, 0}, "no bodies: declare them with point or body");
    for (int i = 0; i < c->m.symcap; i++) {
        const lang_sym *s = &c->m.syms[i];
        if (s->key && strncmp(s->key, "mbs_", 4) == 0)
            lang_fail(c, s->pos, "names beginning with mbs_ are dynkit's own");
    }
    finish_speeds(c, mb);
    for (int i = 0; i < mb->coords.n; i++) { /* the speeds after the coordinates */
        mbs_coord *q = &LVEC_AT(mb->coords, mbs_coord, i);
        q->u = add_state(c, q->speed, q->speed_pos, q->speed_init);
        add_doc(c, q->speed, q->speed_pos, q->speed_doc);
    }
    constraint_names(c, mb);
    static const char *const names[3] = {"kinetic", "potential", "energy"};
    int *idx[3] = {&mb->aux_kinetic, &mb->aux_potential, &mb->aux_energy};
    static const char *const desc[3] = {
        "kinetic energy, 1/2 sum m v.v + omega.I omega",
        ("potential energy of gravity and the springs (0 at the origin and rest lengths; a "
         "spring with a law= only with its energy=)"),
        "kinetic + potential energy"};
    for (int k = 0; k < 3; k++) {
        *idx[k] = -1;
        const lang_sym *own = lang_lookup(c, names[k]);
        static const char *const what[3] = {"kinetic energy", "potential energy",
                                            "kinetic + potential energy"};
        if (own)
            lang_fail(c, own->pos, "'%s' is an output of every mechanism (its %s): give %s "
                      "another name", names[k], what[k],
                      own->kind == SYM_STATE ? "the coordinate or speed"
                      : own->kind == SYM_AUX ? "the constraint or aux"
                                             : lang_sym_kind_name(own->kind));
        declare_output(c, names[k], (lpos){0, 0}, idx[k]);
        add_doc(c, names[k], (lpos){0, 0}, (lang_doc){"J", desc[k]});
    }
}

/* a spring's law= or energy= names a function of the file with nargs arguments */
static int law_function(lang_ctx *c, const char *name, lpos pos, int nargs, const char *role)
{
    const lang_sym *s = lang_lookup(c, name);
    if (!s || s->kind != SYM_FUNC)
        lang_fail(c, pos, "%s '%s' is %s: write %s(%s)=formula in the file", role, name,
                  s ? lang_sym_kind_name(s->kind) : "not a function of the file", name,
                  nargs == 2 ? "x, v" : "x");
    const lang_func *fn = &LVEC_AT(c->m.funcs, lang_func, s->index);
    if (fn->nargs != nargs)
        lang_fail(c, pos, "%s '%s' has %d argument%s; it takes %d: %s", role, name, fn->nargs,
                  fn->nargs == 1 ? "" : "s", nargs,
                  nargs == 2 ? "the stretch x = l - l0 [m] and its rate v = dl/dt [m/s]"
                             : "the stretch x = l - l0 [m]");
    return s->index;
}

void mbs_resolve_laws(lang_ctx *c, mbs_model *mb)
{
    for (int i = 0; i < mb->springs.n; i++) {
        mbs_spring *s = &LVEC_AT(mb->springs, mbs_spring, i);
        if (s->law_name)
            s->law = law_function(c, s->law_name, s->law_pos, 2, "the law");
        if (s->energy_name)
            s->energy = law_function(c, s->energy_name, s->energy_pos, 1, "the energy");
    }
}

void mbs_resolve_inputs(lang_ctx *c, mbs_model *mb)
{
    lang_model *m = &c->m;
    const int n = mb->input_names.n;
    if (!n)
        return;
    m->n_inputs = n;
    m->input_param = lang_alloc(c, (size_t)n * sizeof *m->input_param);
    m->param_input = lang_alloc(c, ((size_t)m->params.n + 1) * sizeof *m->param_input);
    for (int i = 0; i < m->params.n; i++)
        m->param_input[i] = -1;
    for (int k = 0; k < n; k++) {
        const mbs_named *in = &LVEC_AT(mb->input_names, mbs_named, k);
        const lang_sym *s = lang_lookup(c, in->name);
        if (!s || s->kind != SYM_PARAM)
            lang_fail(c, in->pos, "input '%s': an input is a parameter (par %s=VALUE, its value "
                      "when no table is given)%s%s", in->name, in->name, s ? "; it is " : "",
                      s ? lang_sym_kind_name(s->kind) : "");
        if (m->param_input[s->index] >= 0)
            lang_fail(c, in->pos, "input '%s' is named twice", in->name);
        m->param_input[s->index] = k;
        m->input_param[k] = s->index;
    }
}


