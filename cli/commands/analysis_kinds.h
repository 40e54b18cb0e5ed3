/* SPDX-License-Identifier: BSD-3-Clause */
/* What the analysis commands (equilibria, steady, continue, linearize, plot --phase-plane)
 * do with the model kinds whose right-hand side alone is not the whole model: noise (the
 * deterministic part is analysed, with a note), Markov states (they jump at random: refused
 * where their values would be solved for), delays and Volterra integrals (refused where the
 * right-hand side would be read away from a run) (analysis_kinds.c). */
#ifndef DYNKIT_CLI_ANALYSIS_KINDS_H
#define DYNKIT_CLI_ANALYSIS_KINDS_H

#include "cli.h"

/* A note on standard error when m has noise (wiener, normal(), ran()): what the command
 * assumed (what; NULL: its answer is that of the deterministic part, every noise term 0). */
void cli_kinds_noise_note(const char *command, const dyn_model *m, const char *what);

/* CLI_OK, or a usage error (printed) when m has Markov states: `what` (e.g. "its
 * equilibria") would treat them as continuous states. */
int cli_kinds_refuse_markov(const char *command, const dyn_model *m, const char *what);

/* A note when m has Markov states: they are held at their values (the linearization's rows
 * of them are 0) and other noise terms are 0. */
void cli_kinds_markov_note(const char *command, const dyn_model *m);

/* CLI_OK, or a usage error when m has delays or Volterra integrals: `what` reads the
 * right-hand side at states away from a run, where the past it needs is not defined;
 * `instead` says what the user can do. */
int cli_kinds_refuse_history(const char *command, const dyn_model *m, const char *what,
                             const char *instead);

#endif
