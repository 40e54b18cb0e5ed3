/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/ani.h — XPPAUT's animation files (.ani): the reader and the evaluation of their
 * primitives for the frames of a recorded run.
 *
 * An .ani file describes a picture (lines, circles, rectangles, ellipses, text, comets) whose
 * coordinates and colours are formulas of the model's quantities; XPPAUT plays it beside a
 * solution (its manual, "Animation", /usr/share/doc/xppaut/html/xppanim.html; where the
 * manual is silent the behaviour of XPPAUT's own reader, aniparse.c, is followed).
 * docs/model-files.md, "Animation files (.ani)", lists what is read, what is accepted and
 * ignored, and what is refused.
 *
 * Part of the optional layer `dynkit_lang` (C11 + libm); never prints or exits. Errors are
 * reported like the .ode translator's: FILE:LINE:COL, a message and the line
 * (dyn_lang_diag, dynkit/lang.h).
 */
#ifndef DYNKIT_ANI_H
#define DYNKIT_ANI_H

#include <stddef.h>

#include "dynkit/lang.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DYN_ANI_MAX_PRIMS 10000  /* drawing commands of one file (after arrays expand) */
#define DYN_ANI_MAX_TEXT 255     /* characters of one text */
#define DYN_ANI_MAX_COMET 100000 /* points of a comet's tail */

typedef enum dyn_ani_kind {
    DYN_ANI_LINE,     /* x1;y1;x2;y2[;colour[;thickness]] */
    DYN_ANI_RLINE,    /* dx;dy[;colour[;thickness]]: from the end of the last line */
    DYN_ANI_RECT,     /* x1;y1;x2;y2[;colour[;thickness]]: two opposite corners */
    DYN_ANI_FRECT,    /* the same, filled */
    DYN_ANI_CIRCLE,   /* x;y;r[;colour[;thickness]] */
    DYN_ANI_FCIRCLE,  /* the same, filled */
    DYN_ANI_ELLIPSE,  /* x;y;rx;ry[;colour[;thickness]] */
    DYN_ANI_FELLIPSE, /* the same, filled */
    DYN_ANI_TEXT,     /* x;y;string */
    DYN_ANI_VTEXT,    /* x;y;string;value: the string followed by the value (%g) */
    DYN_ANI_COMET,    /* x;y;type;n[;colour]: the last n points, a line of width type
                         (pixels) when type >= 0, else dots of radius -type */
    DYN_ANI_SETTEXT,  /* size;font;colour of the texts that follow */
    DYN_ANI_KIND_COUNT
} dyn_ani_kind;

/* XPPAUT's named colours ($RED, ...). DYN_ANI_FOREGROUND is the drawing colour (black on
 * the white page): XPPAUT draws $BLACK, $WHITE and a missing colour with it. */
typedef enum dyn_ani_color {
    DYN_ANI_FOREGROUND, DYN_ANI_RED, DYN_ANI_REDORANGE, DYN_ANI_ORANGE, DYN_ANI_YELLOWORANGE,
    DYN_ANI_YELLOW, DYN_ANI_YELLOWGREEN, DYN_ANI_GREEN, DYN_ANI_BLUEGREEN, DYN_ANI_BLUE,
    DYN_ANI_PURPLE, DYN_ANI_COLOR_COUNT
} dyn_ani_color;

/* One command that draws (or, for settext, sets how texts are drawn). */
typedef struct dyn_ani_prim {
    dyn_ani_kind kind;
    int line, col;    /* where it is written in the file */
    int permanent;    /* drawn with the values of the first frame (XPPAUT's `permanent`) */
    int offset;       /* its numbers in a frame: values[offset .. offset + n_values) */
    int n_values;     /* the coordinates in the order written (vtext: x, y, value), then,
                         when color < 0, the colour in [0, 1] (clamped, as XPPAUT) */
    int color;        /* a dyn_ani_color, or -1: a formula (the last value) */
    int thickness;    /* line width in pixels (0: the thinnest) */
    int comet_type;   /* comet: >= 0 line width, < 0 dots of radius -comet_type pixels */
    int comet_length; /* comet: points of the tail, >= 1 */
    int text_size;    /* settext: 0 (smallest) .. 4 */
    int text_font;    /* settext: 0 roman, 1 symbol (XPPAUT's Greek letters) */
    const char *text; /* text, vtext: the string ("" otherwise) */
} dyn_ani_prim;

/* The model an animation belongs to. With ode_text (the model's .ode file, as translated by
 * dyn_ode_to_c) every name of the file is known: states, aux outputs, parameters, derived
 * parameters, numbers, fixed quantities and functions. Without it (a C model) the names
 * given are: the states, the outputs and the parameters. */
typedef struct dyn_ani_model {
    const char *ode_path;
    const char *ode_text; /* NULL: names only */
    size_t ode_len;
    int n_states, n_outputs, n_params;
    const char *const *states, *const *outputs, *const *params;
} dyn_ani_model;

typedef struct dyn_ani dyn_ani;

/* Read the animation text (len bytes; path is used in messages) for model. On success
 * returns 0 with *ani (release with dyn_ani_free). On failure returns non-zero with *diag
 * filled and *ani NULL: 2 for an error in a file (the .ani, or the .ode when it cannot be
 * read), 1 when out of memory. Notes (commands accepted and ignored) go to note. */
int dyn_ani_parse(const char *path, const char *text, size_t len, const dyn_ani_model *model,
                  dyn_ani **ani, dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx);
void dyn_ani_free(dyn_ani *ani);

int dyn_ani_count(const dyn_ani *ani);                     /* primitives, in drawing order */
const dyn_ani_prim *dyn_ani_at(const dyn_ani *ani, int i); /* NULL outside 0..count-1 */
int dyn_ani_n_values(const dyn_ani *ani);                  /* numbers of one frame */
/* The window in the file's coordinates: xlo, ylo, xhi, yhi ([0,1]x[0,1] unless
 * `dimension` says otherwise), y up. */
void dyn_ani_window(const dyn_ani *ani, double window[4]);
int dyn_ani_speed(const dyn_ani *ani); /* `speed`: ms between XPPAUT's frames (10) */
/* What a frame must hold: states, outputs and parameter values (for an .ode model the
 * parameters in file order, then the derived parameters: the model's parameter array). */
void dyn_ani_sizes(const dyn_ani *ani, int *n_states, int *n_outputs, int *n_params);
/* Whether value k of primitive i is the same in every frame of a run (it depends on
 * numbers and parameters only). */
int dyn_ani_value_is_constant(const dyn_ani *ani, int i, int k);

/* One frame: the time, the states, the outputs and the parameters. */
typedef struct dyn_ani_frame {
    double t;
    const double *y;
    const double *outputs;
    const double *params;
} dyn_ani_frame;

/* Every primitive's numbers for the frame into values (dyn_ani_n_values doubles), with
 * XPPAUT's meaning of each operator and function (the same as the C text of dyn_ode_to_c;
 * colours clamped to [0, 1]). Returns 0, or 1 when out of memory. Re-entrant: a dyn_ani
 * may be evaluated on several threads at once. */
int dyn_ani_eval(const dyn_ani *ani, const dyn_ani_frame *frame, double *values);

/* The C text of the .ode model (as dyn_ode_to_c_tables translates it) whose outputs end
 * with the numbers of the animation's frames: one output ani:K per number K of a frame of
 * dyn_ani_eval (the primitives' numbers in their order; a colour not clamped), so that a
 * program running the model's C gets every frame with its sample (dynkit's live pages,
 * docs/web.md). Returns 0, or non-zero as dyn_ode_to_c with *diag: an error of either file,
 * and a formula of the animation calling a function of the model that reads its fixed
 * quantities (the animation's evaluator computes it; the model's C does not take it). */
int dyn_ani_ode_to_c(const char *ode_path, const char *ode_text, size_t ode_len,
                     const dyn_lang_table_file *tables, int n_tables, const char *ani_path,
                     const char *ani_text, size_t ani_len, char **c_source,
                     dyn_lang_diag *diag);

/* The text XPPAUT shows for a vtext: the string followed by the value as printf's "%g". */
char *dyn_ani_vtext(const char *text, double value, char *buf, size_t size);

/* XPPAUT's name of a named colour ("RED", ...; "BLACK" for the foreground). */
const char *dyn_ani_color_name(int color);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_ANI_H */
