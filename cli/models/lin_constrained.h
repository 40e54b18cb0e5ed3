/* SPDX-License-Identifier: BSD-3-Clause */
/* The admissible directions of a mechanism's linearization (lin_constrained.c). */
#ifndef DYNKIT_CLI_LIN_CONSTRAINED_H
#define DYNKIT_CLI_LIN_CONSTRAINED_H

#include <stddef.h>

#include "cli.h"
#include "dynkit/jit.h"

typedef struct cli_lin_constraints {
    dyn_jit_model jm; /* the mechanism with its constraints' values as outputs */
    int loaded;
    int m; /* constraints; 0: none, or the model is not a mechanism file */
} cli_lin_constraints;

/* For a mechanism file spec (FILE.mech) of the model m: compile its constraints' values.
 * Other models: cc->m = 0. Returns 0 or a CLI status after printing why. */
int cli_lin_constraints_open(const char *spec, const dyn_model *m, cli_lin_constraints *cc);
void cli_lin_constraints_close(cli_lin_constraints *cc);
/* A basis P (N x k, row-major, N the states) of the admissible directions at (t, y), and
 * the states kept (k of them: P's rows there are the identity). P holds N * N doubles. */
int cli_lin_basis(const cli_lin_constraints *cc, double t, const double *y, const void *par,
                  double *P, int *kept, int *k, char *err, size_t errlen);

#endif
