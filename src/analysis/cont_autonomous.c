/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_autonomous.c — whether a model's right-hand side depends on the time t, checked
 * before a branch of equilibria (or a map's fixed points) is started: an equilibrium is a
 * zero of f(x, p) for every t, which a forced model (x'' + x = a cos(w t)) has not; the
 * points solved at one frozen time t0 are those of the model without its forcing's
 * motion (a stimulus that starts later: the rest state), no solutions of the forced model,
 * and the note made here says so. f is evaluated at the start's state at t0 and at three
 * later times, at the start's parameter and at a second value of it (a forcing whose
 * amplitude is the parameter, zero at the start, still makes the branch time-dependent).
 * (AUTO-07p's demo frc writes the forcing as an autonomous oscillator's states and
 * continues the responses as periodic orbits from a known one; periodic branches here
 * start at Hopf points only.) */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cont_equilibrium.h"
#include "dynkit/io.h"

/* later times: unrelated to any period a model is likely to have */
static const double cont_time_shifts[] = {0.7317, 2.3179, 9.8731};

/* the first state whose rate differs between cm->f (at t0) and cm->fp (at t0 + shift),
 * beyond rounding, or -1 */
static int rates_differ(const cont_model *cm)
{
    for (int i = 0; i < cm->n; i++) {
        const double a = cm->f[i], b = cm->fp[i];
        if (fabs(a - b) > 1e-13 * (1.0 + fabs(a) + fabs(b)))
            return i;
    }
    return -1;
}

int cont_time_dependent(cont_model *cm, const double *x, char *msg, size_t len)
{
    const double p0 = cm->p_set[0], t0 = cm->t;
    const double moved[2] = {p0, p0 + 0.5 * fmax(1.0, fabs(p0))};
    int found = -1;
    double at_t = t0, at_p = p0;
    for (int k = 0; k < 2 && found < 0; k++) {
        if (cont_model_set(cm, moved[k], NAN)) /* a value the model refuses: not checked */
            continue;
        cm->t = t0;
        if (cont_model_f(cm, x, cm->f))
            continue;
        for (size_t j = 0; j < sizeof cont_time_shifts / sizeof *cont_time_shifts; j++) {
            cm->t = t0 + cont_time_shifts[j];
            const int f_rc = cont_model_f(cm, x, cm->fp);
            if (f_rc == 0 && (found = rates_differ(cm)) >= 0) {
                at_t = cm->t;
                at_p = moved[k];
                break;
            }
        }
    }
    cm->t = t0;
    if (cont_model_set(cm, p0, NAN))
        return -1;
    if (found < 0)
        return 0;
    const char *name = cm->m->params[cm->ip].name;
    snprintf(msg, len,
             "%s depends on the time t (%.24s%s at %.24s = %s differs at t = %s and %s): these "
             "are the %s of the model frozen at t = %s, not of the forced model; see its "
             "stroboscopic map (run --section t=PERIOD)",
             cm->map ? "F" : "f", cm->m->states[found].name, cm->map ? "(t+1)" : "'", name,
             dyn_shortest(at_p).s, dyn_shortest(t0).s, dyn_shortest(at_t).s,
             cm->map ? "fixed points" : "equilibria", dyn_shortest(t0).s);
    return 1;
}
