/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal interface of the .ani reader (dynkit/ani.h): a parsed animation keeps the
 * translator's context (lang_internal.h) alive — its arena holds the formulas, and, when the
 * model is an .ode file, the model as the translator reads it (states, parameters, fixed
 * quantities, functions) — and its primitives with their formulas. ani_parse.c reads the
 * file, ani_eval.c evaluates the formulas for a frame.
 *
 * In an animation's formula (not in a function body) the node N_ARG k is the model's k-th
 * output (an aux of the .ode file): outputs are what a frame brings besides the states, as
 * arguments bring values into a function. */
#ifndef DYNKIT_ANI_INTERNAL_H
#define DYNKIT_ANI_INTERNAL_H

#include "dynkit/ani.h"
#include "lang/lang_internal.h"

#define ANI_MAX_VALUES 5 /* 4 coordinates (or 3 and a value) and a colour */

typedef struct ani_item {
    dyn_ani_prim p;
    node *expr[ANI_MAX_VALUES]; /* p.n_values formulas */
} ani_item;

struct dyn_ani {
    lang_ctx *c;        /* the arena and the model's names (c->m) */
    int from_ode;       /* the names come from an .ode file */
    int n_states, n_outputs, n_params;
    ani_item *items;
    int n_items;
    int n_values;
    double window[4];
    int speed;
};

/* Whether the formula changes from frame to frame (uses t, a state, an output or a fixed
 * quantity, directly or through a function). */
int ani_varies(const dyn_ani *a, const node *e);

/* The animation's text (ani_path names it in messages) read with the names of the model c
 * has read (an .ode file's, a mechanism's), each of its formulas appended to the model's
 * outputs as ani:K, K its place in a frame (an output named in a formula replaced by its
 * formula). An error fails c (lang_fail) at the animation's line. */
void ani_append_outputs(lang_ctx *c, const char *ani_path, const char *ani_text, size_t ani_len);

#endif /* DYNKIT_ANI_INTERNAL_H */
