/* SPDX-License-Identifier: BSD-3-Clause */
/* A run of a delay model (dyn_model.delay, dynkit/delay.h): the history is attached to the
 * run's parameters, fed by dyn_solve's step callback with every accepted step's dense
 * output, and the adaptive steps land on the breaking points of the constant lags. The
 * store grows here, between steps (the drivers never allocate); with the model's maximal
 * delay only the steps within it are kept. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/delay.h"
#include "run_internal.h"

/* breaking points at most (they come from at most DYN_DELAY_MAX_LAGS lags and the order) */
#define DELAY_MAX_BREAKS 4096

int run_history_grow(dyn_history *h, void *ctx)
{
    (void)ctx;
    const long cap = h->capacity ? 2 * h->capacity : 256;
    const size_t block = dyn_dense_record_block(h->n, h->degree);
    double *d = realloc(h->data, (size_t)cap * block * sizeof *d);
    if (!d)
        return 1;
    h->data = d;
    h->capacity = cap;
    return 0;
}

int run_delay_start(const run_ctx *rc, run_delay *cd, dyn_solve_opts *opts, char *err,
                    size_t errlen)
{
    const dyn_model *m = rc->m;
    const dyn_run_opts *o = rc->o;
    const dyn_delay_model *dm = m->delay;
    memset(cd, 0, sizeof *cd);
    if (!dm)
        return 0;
    cd->history = calloc(1, sizeof *cd->history);
    if (!cd->history) {
        snprintf(err, errlen, "out of memory");
        return 1;
    }
    cd->history->grow = run_history_grow;
    dyn_history_init(cd->history, m->n_states, dyn_method_dense_degree(o->method), o->t0,
                     rc->y0, dm->history, rc->par, dm->max_delay, NULL, 0);
    dm->attach(rc->par, cd->history);
    opts->step = dyn_history_push;
    opts->step_ctx = cd->history;
    if (dm->n_lags > 0 && dm->lags) {
        double lags[DYN_DELAY_MAX_LAGS * 4];
        const int nl = dm->n_lags < (int)(sizeof lags / sizeof *lags)
                           ? dm->n_lags
                           : (int)(sizeof lags / sizeof *lags);
        double *all = malloc((size_t)dm->n_lags * sizeof *all);
        cd->breaks = malloc(DELAY_MAX_BREAKS * sizeof *cd->breaks);
        if (!all || !cd->breaks) {
            free(all);
            snprintf(err, errlen, "out of memory");
            return 1;
        }
        dm->lags(rc->par, all);
        memcpy(lags, all, (size_t)nl * sizeof *lags);
        free(all);
        for (int k = 0; k < nl; k++)
            if (!(lags[k] >= 0.0) || !isfinite(lags[k])) {
                snprintf(err, errlen,
                         "a lag of delay(x, tau) is %g with these parameters: a lag must be a "
                         "finite number >= 0",
                         lags[k]);
                return 1;
            }
        for (int k = 0; k < nl; k++)
            if (dm->max_delay > 0.0 && lags[k] > dm->max_delay) {
                snprintf(err, errlen,
                         "a lag of delay(x, tau) is %g with these parameters, longer than the "
                         "maximal delay %g (the model's @ delay=): raise it in the file",
                         lags[k], dm->max_delay);
                return 1;
            }
        /* a lag of 0 breaks nothing: the others only */
        int np = 0;
        for (int k = 0; k < nl; k++)
            if (lags[k] > 0.0)
                lags[np++] = lags[k];
        cd->n_breaks = dyn_delay_breaks(o->t0, o->t1, lags, np, o->method->order + 1,
                                        cd->breaks, DELAY_MAX_BREAKS);
        opts->stops = cd->breaks;
        opts->n_stops = cd->n_breaks;
    }
    return 0;
}

void run_delay_finish(const run_ctx *rc, run_delay *cd, dyn_result *res)
{
    if (!cd->history)
        return;
    const dyn_model *m = rc->m;
    if (cd->history->failed && res->status != DYN_OK) {
        /* the run stopped on the NaN of a refused lag: say why */
        const char **names = malloc((size_t)m->n_states * sizeof *names);
        for (int i = 0; names && i < m->n_states; i++)
            names[i] = m->states[i].name;
        dyn_history_message(cd->history, names, res->message, sizeof res->message);
        free(names);
        res->fail_t = cd->history->fail_t;
        res->fail_index = -1; /* the message says it all */
    }
    m->delay->attach(rc->par, NULL);
    free(cd->history->data);
    free(cd->history);
    free(cd->breaks);
    memset(cd, 0, sizeof *cd);
}
