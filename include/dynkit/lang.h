/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/lang.h — the model-file front end: XPPAUT's .ode format (and dynkit's extensions in
 * comments) translated into C source that defines a dyn_model.
 *
 * The translation is the whole contract between a model file and the rest of dynkit: the C
 * text it produces defines `const dyn_model *dynkit_model(void)` (the entry point of
 * model.h), exactly like a C model a user writes by hand, and is compiled and loaded by the
 * jit layer (dynkit/jit.h). Nothing downstream knows where a model came from.
 *
 * XPPAUT (Ermentrout, "Simulating, Analyzing, and Animating Dynamical Systems", SIAM 2002,
 * and the manual shipped with it) is the reference for what a file means. Part of the
 * optional layer `dynkit_lang` (C11 + libm, no other dependency); never prints or exits.
 */
#ifndef DYNKIT_LANG_H
#define DYNKIT_LANG_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Where and why a translation failed: FILE:LINE:COL and a message, plus the source line
 * for a caret display. line/col are 1-based; 0 when not tied to a place. */
typedef struct dyn_lang_diag {
    char path[512];
    int line, col;
    char message[512];   /* e.g. "unknown name 'omgea' (did you mean 'omega'?)" */
    char excerpt[256];   /* the offending source line, without its newline ("" if none) */
} dyn_lang_diag;

/* The diagnostic as "FILE:LINE:COL: error: message\n  excerpt\n  ^\n" into buf;
 * returns buf. */
char *dyn_lang_diag_format(const dyn_lang_diag *d, char *buf, size_t size);

/* Notes of a successful translation (options accepted and ignored, ...), one line each,
 * for --verbose; may be NULL. A message that begins with DYN_LANG_WARNING ("warning: ") is
 * a warning: something in the file was left out (a plot option naming no variable), to be
 * shown always. */
#define DYN_LANG_WARNING "warning: "
typedef void (*dyn_lang_note_fn)(const char *path, int line, const char *message, void *ctx);

/* Translate the .ode text (len bytes, need not be NUL-terminated; path is used in messages
 * and in #line directives of the C text) into C source. On success returns 0 and
 * *c_source (NUL-terminated, malloc'd: the caller frees it). On failure returns non-zero
 * with *diag filled and *c_source NULL: 2 for an error in the file, 1 when out of memory.
 *
 * `table NAME FILE` reads FILE only when it is a regular file in the folder of path (the
 * current folder when path has none), named without a folder (no '/': no absolute path, no
 * ".."), and not a symbolic link; it is opened without blocking (O_NONBLOCK) and checked
 * on the descriptor opened, so a FIFO, a device or a directory is refused at once. Anything
 * else is an error naming the file and what is accepted. */
int dyn_ode_to_c(const char *path, const char *text, size_t len, char **c_source,
                 dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx);

/* A file the caller names for a model file's `table NAME FILE` (dynkit's --table
 * NAME=FILE): the table NAME (case folded, as every name of a model file) is read from
 * path, anywhere, instead of the FILE written in the model file; path must be a regular
 * file (symbolic links followed: the caller chose it). */
typedef struct dyn_lang_table_file {
    const char *name;
    const char *path;
} dyn_lang_table_file;

/* dyn_ode_to_c with n_tables files named by the caller; a name that no `table NAME FILE` of
 * the model reads is an error. */
int dyn_ode_to_c_tables(const char *path, const char *text, size_t len,
                        const dyn_lang_table_file *tables, int n_tables, char **c_source,
                        dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx);

/* AUTO's settings of a model file's @ lines (XPPAUT's ntst, ncol, nmax, npr, ds, dsmin,
 * dsmax, parmin, parmax, par2min, par2max, autoxmin, autoxmax, autoymin, autoymax), as the
 * parser of dyn_ode_to_c reads them: fn is called for each, in the file's order, with its
 * name (lower case, as listed here), its value as written and the value's line and column.
 * A run does not use them; `dynkit continue` does. Returns 0, or non-zero as dyn_ode_to_c
 * does (2 an error in the file, 1 out of memory) with diag filled. */
typedef void (*dyn_lang_setting_fn)(const char *name, const char *value, int line, int col,
                                    void *ctx);
int dyn_ode_auto_options(const char *path, const char *text, size_t len, dyn_lang_setting_fn fn,
                         void *ctx, dyn_lang_diag *diag);

/* The status the outputs and a global's reset of a translated model return when its
 * algebraic equations (0=...) have no solution near the branch followed, as at an impasse
 * point where the branch ends. Its right-hand side writes derivatives that are not finite
 * there instead, so that an adaptive method tries a shorter step. */
#define DYN_LANG_ALG_FAILED 3

/* The value of text, one formula of numbers and of the names names[0..n) (their values in
 * values), in the syntax and with the functions of a model file's `par` and `init` lines
 * (XPPAUT's: + - * / ^ **, comparisons, sin, cos, exp, ln, sqrt, abs, heav, max, if ...,
 * pi; names case-insensitive). Returns 0 with *value, 2 when the text is no such formula,
 * a name is unknown or the value is not finite (1 out of memory), with the message and the
 * column in diag (its path empty; NULL: not kept). */
int dyn_lang_formula_value(const char *text, const char *const *names, const double *values,
                           int n, double *value, dyn_lang_diag *diag);

/* The name among names[0..n) nearest to word (Damerau–Levenshtein distance, case folded),
 * or NULL when none is close enough to be a likely typo (distance > max(1, len/3)). */
const char *dyn_lang_nearest(const char *word, const char *const *names, int n);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_LANG_H */
