/* SPDX-License-Identifier: BSD-3-Clause */
/* bvp_guess.h — dynkit bvp --guess FILE: a first guess read from a CSV table (the one
 * dynkit bvp and dynkit run write); bvp_guess.c. */
#ifndef DYNKIT_CLI_BVP_GUESS_H
#define DYNKIT_CLI_BVP_GUESS_H

#include <stddef.h>

#include "dynkit/model.h"

/* The table at path: a header line of names, the first t, every state of m among the
 * others (in any order; other columns are left), then rows of numbers. *t (rows) and *u
 * (rows x n_states) are allocated. Returns 0, or -1 with "FILE:LINE: ..." in err. */
int bvp_guess_read(const char *path, const dyn_model *m, double **t, double **u, long *rows,
                   char *err, size_t errlen);

#endif
