/* SPDX-License-Identifier: BSD-3-Clause */
/* sde_path.h — the kept Brownian path of the adaptive methods for noise (private; sde.c):
 * every value of W drawn at a time ahead of the run stays until the run passes it, a value
 * between two kept ones comes from the bridge, so a rejected step changes nothing of the path
 * (Rackauckas and Nie 2017, rejection sampling with memory); with area, each segment also
 * carries the time integral of W over it (SRIW1's I_(1,0)). */
#ifndef DYNKIT_SRC_ODE_SDE_PATH_H
#define DYNKIT_SRC_ODE_SDE_PATH_H

#include "dynkit/sde.h"

typedef struct dyn_bpath {
    int m, area;  /* noises; whether segments carry their time integrals */
    dyn_rng *rng; /* the run's numbers */
    /* W at tc is wc; np points ahead at tq (increasing), values wq (m each); with area, aq
     * holds each segment's J, the time integral of W - W(left) from the point before; anew
     * (m) is scratch */
    double tc, *wc, *tq, *wq, *aq, *anew;
    int np;
} dyn_bpath;

/* W at s > tc into out (m values), the point kept: a point already drawn, a bridge between
 * the kept neighbours, or a new increment beyond the last one. Non-zero when
 * DYN_SDE_MAX_POINTS points are kept already. */
int dyn_bpath_at(dyn_bpath *p, double s, double *out);

/* After dyn_bpath_at(p, s, ...): dW from tc to s into dw and, with area, the time integrals
 * of W - W(tc) over [tc, s] into i10 (m each). */
void dyn_bpath_increments(const dyn_bpath *p, double s, double *dw, double *i10);

/* The run reached t (a kept point): W there becomes the current value, the points up to t
 * are dropped. */
void dyn_bpath_advance(dyn_bpath *p, double t);

#endif /* DYNKIT_SRC_ODE_SDE_PATH_H */
