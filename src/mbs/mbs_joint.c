/* SPDX-License-Identifier: BSD-3-Clause */
/* Joints of a mechanism file (docs/mechanisms.md, "Joints"): a body or point placed by a
 * revolute, prismatic, spherical or free joint to a parent body or the ground, read into
 * the body's own rotations (those of the joint, from the parent's frame to the body's) and
 * its joint point, translation and pivot. mbs_derive.c composes them with the parent's
 * pose, x = x_P + R_P'(jp + shift) - R'(pivot) and R = R_joint R_P, as the joint
 * coordinates of Vallery & Schwab, "Advanced Dynamics" (TU Delft), ch. "Kinematics". Each
 * joint moves with coordinates of its own: a coordinate is the variable of one joint. */
#include <string.h>
#include <strings.h>

#include "mbs/mbs_internal.h"
#include "mbs/mbs_syntax.h"

static const char *const kinds[] = {"", "revolute", "prismatic", "spherical", "free"};

int mbs_joint_kind(const char *word)
{
    for (int k = MBS_REVOLUTE; k <= MBS_FREE; k++)
        if (strcasecmp(word, kinds[k]) == 0)
            return k;
    return MBS_NO_JOINT;
}

/* the coordinate that the input k names, marked as the joint's variable */
static void joint_coordinate(lang_ctx *c, const mbs_body *b, int k, const char *what)
{
    mbs_model *mb = c->hook_ctx;
    const node *e = LVEC_AT(c->m.fixes, lang_formula, k).expr;
    if (e->kind == N_NAME)
        for (int i = 0; i < mb->coords.n; i++) {
            mbs_coord *q = &LVEC_AT(mb->coords, mbs_coord, i);
            if (strcasecmp(q->name, e->name) != 0)
                continue;
            if (q->jointed)
                lang_fail(c, e->pos,
                          "coordinate '%s' already moves the joint of '%s': each "
                          "joint has coordinates of its own",
                          q->name, LVEC_AT(mb->bodies, mbs_body, q->jointed - 1).name);
            q->jointed = mb->bodies.n + 1;
            return;
        }
    while (e->kind == N_BIN) /* the formula's start */
        e = e->args[0];
    lang_fail(c, e->pos,
              "%s of the %s joint of '%s' is a coordinate's name (declared by coord "
              "before the joint); for a formula, place the body by at (x, y, z) rot ...",
              what, kinds[b->joint], b->name);
}

/* revolute PARENT[(x, y, z)] AXIS:q     prismatic PARENT[(x, y, z)] AXIS:q, AXIS x, y, z or
 * (ax, ay, az) in the parent's frame
 * spherical PARENT[(x, y, z)] AXIS:q AXIS:q ... | quat:(qw, qx, qy, qz)
 * free PARENT (x, y, z) AXIS:q ... | quat:(...),   each then [pivot (x, y, z)] */
void mbs_parse_joint(lang_ctx *c, lang_lexer *lx, mbs_body *b, int kind)
{
    b->joint = kind;
    for (int k = 0; k < 3; k++)
        b->jp[k] = b->shift[k] = b->pivot[k] = -1;
    lpos ppos;
    const char *parent = lang_read_name(
        lx, &ppos,
        lang_printf(c, "expected the parent body's name or ground after '%s'", kinds[kind]));
    if (strcasecmp(parent, b->name) == 0)
        lang_fail(c, ppos,
                  "'%s' cannot be its own parent: a joint joins a body to one "
                  "declared before it, or to the ground",
                  b->name);
    b->parent = mbs_find_body(c, parent, ppos, 1);
    const int axis_first = kind == MBS_REVOLUTE || kind == MBS_PRISMATIC;
    int axis_read = 0;
    if (lang_skip_blanks(lx) == '(') {
        mbs_tuple(lx, kind == MBS_FREE ? b->shift : b->jp,
                  kind == MBS_FREE ? "the free joint's translations" : "the joint's point");
        if (axis_first && lang_skip_blanks(lx) == ':') { /* PARENT (ax, ay, az):q */
            memcpy(b->axisv, b->jp, sizeof b->axisv);
            b->jp[0] = b->jp[1] = b->jp[2] = -1;
            axis_read = 1;
        }
    } else if (kind == MBS_FREE)
        lang_fail(c, lang_here(lx),
                  "expected the free joint's translations (x, y, z), three "
                  "coordinates along the parent's axes, after its parent");
    if (kind == MBS_FREE)
        for (int k = 0; k < 3; k++)
            joint_coordinate(c, b, b->shift[k], "each translation");
    const lpos rpos = lang_here(lx);
    if (axis_first && (axis_read || lang_skip_blanks(lx) == '(')) {
        if (!axis_read)
            mbs_tuple(lx, b->axisv, "the joint's axis");
        lang_expect_char(lx, ':', "expected ':' and the joint's coordinate after its axis");
        b->axis[0] = 3;
        b->angle[b->nrot++] = mbs_input_expr(lx, "the joint's coordinate");
    } else {
        if (axis_first) { /* name the joint's own syntax, not that of 'rot' */
            const int save = lx->i;
            lpos apos;
            const char *a = lang_is_ident_start(lang_skip_blanks(lx))
                                ? lang_read_name(lx, &apos, "expected an axis")
                                : "";
            const int ok = strlen(a) == 1 && strchr("xyzXYZ", a[0]) &&
                           lang_skip_blanks(lx) == ':';
            lx->i = save;
            if (!ok)
                lang_fail(c, rpos,
                          "expected the %s joint's AXIS:q after its parent, AXIS x, y, z "
                          "or (ax, ay, az) of the parent's frame (e.g. %s ground z:q)",
                          kinds[kind], kinds[kind]);
        }
        mbs_parse_rot(c, lx, b);
    }
    if ((kind == MBS_REVOLUTE || kind == MBS_PRISMATIC) && (b->nrot != 1 || b->quat[0] >= 0))
        lang_fail(c, rpos,
                  "a %s joint has one axis and one coordinate: AXIS:q with AXIS x, y, "
                  "z or (ax, ay, az) of the parent's frame",
                  kinds[kind]);
    for (int i = 0; i < b->nrot; i++)
        joint_coordinate(c, b, b->angle[i],
                         kind == MBS_PRISMATIC ? "the displacement" : "each angle");
    for (int k = 0; k < 4 && b->quat[0] >= 0; k++)
        joint_coordinate(c, b, b->quat[k], "each Euler parameter");
    b->slide = -1;
    if (kind == MBS_PRISMATIC) { /* a translation along the axis, no rotation */
        b->slide = b->angle[0];
        b->slide_axis = b->axis[0];
        b->nrot = 0;
    }
    if (lang_is_ident_start(lang_skip_blanks(lx))) {
        const int save = lx->i;
        lpos wpos;
        if (strcasecmp(lang_read_name(lx, &wpos, "expected pivot"), "pivot") == 0)
            mbs_tuple(lx, b->pivot, "the pivot (the joint's point in the body's frame)");
        else
            lx->i = save;
    }
}
