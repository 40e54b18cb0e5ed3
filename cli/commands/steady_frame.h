/* SPDX-License-Identifier: BSD-3-Clause */
/* steady_frame.h — what dynkit steady and dynkit continue share about a steady motion
 * (steady_frame.c): the states kept by a mechanism's constraints and the admissible
 * directions P, the dependent states solved from the constraints, and the cyclic states
 * found from the linearization along P. docs/analysis.md, "Steady motions". */
#ifndef DYNKIT_CLI_STEADY_FRAME_H
#define DYNKIT_CLI_STEADY_FRAME_H

#include <stddef.h>

#include "models/lin_constrained.h"

/* The model's states kept (all, or a mechanism's minimal ones), the others (dep) and P. */
typedef struct steady_frame {
    const cli_lin_constraints *cc;
    int n, k, nd;
    int *kept, *dep;
    double *P;
} steady_frame;

/* fr for n states over cc; 0, or non-zero when out of memory (fr freed). */
int steady_frame_alloc(steady_frame *fr, const cli_lin_constraints *cc, int n);
void steady_frame_free(steady_frame *fr);
/* kept, dep and P at (t, y); CLI_OK, or CLI_FAILED after a message prefixed by cmd. */
int steady_frame_at(const char *cmd, steady_frame *fr, double t, const double *y, void *par);
/* The dependent states of y solved from the constraints (a dyn_steady_complete_fn; ctx is
 * the steady_frame). */
int steady_complete_dependent(void *ctx, double t, double *y, void *par, char *err,
                              size_t errlen);
/* The list "a,b,c" into names (at most max, the list cut in place): the count, or -1. */
int steady_split_names(char *list, char **names, int max);
/* The cyclic states among fr's kept ones (cyclic: fr->k flags): the names in given (a
 * comma list, cut in place), or when given is empty those dyn_steady_cyclic finds at y and
 * at a nearby state. CLI_OK or a CLI status after a message prefixed by cmd. */
int steady_find_cyclic(const char *cmd, const dyn_model *m, double t, const double *y, void *par,
                       const steady_frame *fr, char *given, int *cyclic);

/* Everything a steady motion's equations need at (t, y), as steady and continue both ask:
 * steady_frame_at, the dependent states of y solved from the constraints (y changed in
 * place), steady_find_cyclic (given, cyclic as there) and the equations: the kept states
 * that are not cyclic (eqs, *n_eq of them). CLI_OK or a CLI status after a message
 * prefixed by cmd. */
int steady_frame_prepare(const char *cmd, steady_frame *fr, const dyn_model *m, double t,
                         double *y, void *par, char *given, int *cyclic, int *eqs, int *n_eq);

#endif
