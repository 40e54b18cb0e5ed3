/* SPDX-License-Identifier: BSD-3-Clause */
/* The default box in which the equilibria of a model are searched (dynkit equilibria, and
 * dynkit continue when no equilibrium is near its start): the range of the model's default
 * run widened by half its width (at least 1) on each side, the file's @ xlo..yhi for the
 * states of its phase plane (eq_box.c). docs/analysis.md, "Equilibria". */
#ifndef DYNKIT_CLI_EQ_BOX_H
#define DYNKIT_CLI_EQ_BOX_H

#include "cli.h"

/* lo, hi: n_states values each; from_file[i] is 1 where the file's window gave state i. */
void cli_eq_default_box(const cli_run *run, double *lo, double *hi, int *from_file);

#endif
