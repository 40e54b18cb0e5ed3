/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/mbs.h — mechanism files: bodies, joints by formulas, loads and constraints in;
 * the C text of a dyn_model out, its equations of motion derived by TMT (virtual power with
 * generalized coordinates). The syntax and the method are in docs/mechanisms.md.
 *
 * A mechanism becomes an ordinary dyn_model: the states are the coordinates and their
 * speeds, the outputs the constraints' multipliers (named after the constraints, with
 * units) and the energies. Part of the optional layer dynkit_lang; never prints or exits.
 */
#ifndef DYNKIT_MBS_H
#define DYNKIT_MBS_H

#include <stddef.h>

#include "dynkit/lang.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Translate the mechanism text (len bytes; path for messages) into C source, as
 * dyn_ode_to_c_tables does for an .ode file (tables: the files named for `table NAME FILE`
 * lines, may be NULL with n_tables 0): 0 and *c_source (malloc'd), or 2 (error in the
 * file, *diag filled with FILE:LINE:COL) or 1 (out of memory). */
int dyn_mech_to_c(const char *path, const char *text, size_t len,
                  const dyn_lang_table_file *tables, int n_tables, char **c_source,
                  dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx);

/* dyn_mech_to_c with flags: DYN_MECH_UNCHECKED_INIT leaves out the check that the
 * constraints hold at the file's initial state (the caller projects the state onto them
 * before a run; the checks of the mass matrix and the constraints' rows stay). */
#define DYN_MECH_UNCHECKED_INIT 1u
int dyn_mech_to_c_flags(const char *path, const char *text, size_t len,
                        const dyn_lang_table_file *tables, int n_tables, unsigned flags,
                        char **c_source, dyn_lang_diag *diag, dyn_lang_note_fn note,
                        void *note_ctx);

/* What was derived, as readable formulas in the file's names (dynkit derive): the mass
 * matrix M (lower triangle), the forces F, and each constraint's row D and convective term
 * c, with M q'' = F + D' lambda and D q'' + c = 0; then the fixed quantities they use.
 * 0 and *out (malloc'd), or non-zero with *diag filled as dyn_mech_to_c. */
int dyn_mech_derive_text(const char *path, const char *text, size_t len, char **out,
                         dyn_lang_diag *diag);

/* The same mechanism as dyn_mech_to_c, but each constraint's output is its value on the
 * speeds, h = D(q, t) u + h_t(q, t) (for a holonomic constraint f(q, t) = 0, h = df/dt),
 * instead of its multiplier, with the unit "holonomic" or "speeds" saying which kind it
 * is; the other outputs, the states and the parameters (their struct) are those of
 * dyn_mech_to_c's model. After them, one output for each holonomic constraint: its value
 * f(q, t), named NAME:f, with the unit "position" ("prescribed" for a `prescribe`). The
 * constraints need not hold at the file's initial state. The admissible directions of the linearization come from it:
 * dh/du for the positions of holonomic ones, (dh/dq, dh/du) for all (docs/analysis.md). */
int dyn_mech_constraints_to_c(const char *path, const char *text, size_t len,
                              const dyn_lang_table_file *tables, int n_tables, char **c_source,
                              dyn_lang_diag *diag);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_MBS_H */
