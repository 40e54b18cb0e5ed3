/* SPDX-License-Identifier: BSD-3-Clause */
/* The checks of a mechanism at its initial state (mbs_check.c). */
#ifndef DYNKIT_MBS_CHECK_H
#define DYNKIT_MBS_CHECK_H

#include "mbs/mbs_internal.h"

typedef struct mbs_initial {
    double *pv;   /* parameters, then derived parameters, at their defaults */
    double *args; /* the default initial states, then t0 */
    int nstates;
} mbs_initial;

/* the default parameters and initial state (after lang_check) */
void mbs_initial_values(lang_ctx *c, mbs_initial *ini);
/* a symbolic formula of the states and t at the initial state (NaN where a table or an
 * input would be read) */
double mbs_value(lang_ctx *c, const mbs_initial *ini, const node *e);
/* a body's mass (not negative) and its inertia I (3 x 3 about its mass centre in B; NULL
 * for a point mass) at the initial state: else fails at the formula, naming the rule */
void mbs_check_body(lang_ctx *c, const mbs_body *b, double mass, const double *I);
/* 1 when the n x n matrix M is positive definite (or not known: not finite), else 0 */
int mbs_positive_definite(lang_ctx *c, const double *M, int n);
/* M (n x n, the mass matrix; overwritten) positive definite and the rows D (m x n)
 * independent, else fails naming the coordinates or constraints */
void mbs_check_initial(lang_ctx *c, const mbs_model *mb, double *M, const double *D);

#endif /* DYNKIT_MBS_CHECK_H */
