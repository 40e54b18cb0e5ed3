/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady_switch.h — branch switching on branches of steady motions (private;
 * cont_steady_switch.c). */
#ifndef DYN_ANALYSIS_CONT_STEADY_SWITCH_H
#define DYN_ANALYSIS_CONT_STEADY_SWITCH_H

#include <stddef.h>

#include "cont_steady_system.h"

/* For every BP of the branches of c->d from index first on (those appended meanwhile
 * included, not their first points), the other branch followed both ways (sc_follow, parent
 * and parent_point set) while c->d has fewer than o->max_branches; a BP where the equations
 * are regular gets a sentence appended to note instead. 0, or -1 (c->message). */
int sc_switch_all(sc_ctx *c, const cont_system *s, cont_work *w, const dyn_cont_opts *o,
                  int first, char *note, size_t notelen);

#endif /* DYN_ANALYSIS_CONT_STEADY_SWITCH_H */
