/* SPDX-License-Identifier: BSD-3-Clause */
/* The pieces of syntax the statements of a mechanism file share (mbs_syntax.c). */
#ifndef DYNKIT_MBS_SYNTAX_H
#define DYNKIT_MBS_SYNTAX_H

#include "mbs/mbs_internal.h"

/* the next word if it is w (case folded; then consumed) */
int mbs_take_word(lang_lexer *lx, const char *w);
/* an expression kept as an input (an unnamed fixed quantity): its index among the fixes */
int mbs_add_input(lang_ctx *c, node *e);
/* an expression, "expected WHAT" at the end of the line */
node *mbs_parse_value(lang_lexer *lx, const char *what);
/* an expression kept as an input */
int mbs_input_expr(lang_lexer *lx, const char *what);
/* (x, y, z) into three inputs */
void mbs_tuple(lang_lexer *lx, int *out, const char *what);
/* a value, in degrees when it ends in deg (30deg, 30 deg, pi/6 deg) */
node *mbs_angle_value(lang_lexer *lx, const char *what);
/* a body by name (-1: the ground, when ground_ok), else fails with the nearest name */
int mbs_find_body(lang_ctx *c, const char *name, lpos pos, int ground_ok);
/* AXIS:ANGLE ... (elementary rotations) or quat:(w, x, y, z) into b */
void mbs_parse_rot(lang_ctx *c, lang_lexer *lx, mbs_body *b);
/* BODY[(x, y, z)]: a body (or the ground) and its point */
mbs_attach mbs_attachment(lang_ctx *c, lang_lexer *lx);

#endif /* DYNKIT_MBS_SYNTAX_H */
