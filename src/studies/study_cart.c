/* SPDX-License-Identifier: BSD-3-Clause */
/* The report's study of problem 4: where the rear wheels start to slip. The largest
 * |lambda| / (mu (2/3) m g) along the prescribed motion (dyn_model_cart_path: 4d's "along
 * the exact prescribed motion", N = 500 samples at Ts = 0.01 s, RK4 of the path) over the
 * full grid of the backward speed v0 (0..30 m/s) and the steering frequency f (0..3 Hz),
 * one dyn_sweep with the reductions max:slip_ratio and mean:slipping (the fraction of the
 * time the wheels would slip). The slip boundary of
 * each v0 is the smallest f where the ratio reaches 1, linear between the grid's points. */
#include <math.h>
#include <string.h>

#include "dynkit/report_studies.h"
#include "dynkit/sweep.h"

int dyn_study_cart_compute(dyn_study_cart *s, int threads, char *err, size_t errlen)
{
    enum { NV = DYN_STUDY_CART_V0, NF = DYN_STUDY_CART_F, RUNS = NV * NF };
    const dyn_model *m = &dyn_model_cart_path;
    memset(s, 0, sizeof *s);
    s->n_v0 = NV;
    s->n_f = NF;
    for (int i = 0; i < NV; i++)
        s->v0[i] = dyn_linspace_at(0.0, 30.0, NV, i);
    for (int j = 0; j < NF; j++)
        s->f[j] = dyn_linspace_at(0.0, 3.0, NF, j);
    dyn_sweep_var vars[2];
    dyn_reduce red[2];
    int n_red = 0;
    if (dyn_sweep_var_find(m, "v0", &vars[0], err, errlen) ||
        dyn_sweep_var_find(m, "f", &vars[1], err, errlen) ||
        dyn_reduce_parse(m, "max:slip_ratio,mean:slipping", red, 2, &n_red, err, errlen))
        return 1;
    double values[RUNS * 2], results[RUNS * 2];
    int status[RUNS];
    const double *axes[2] = {s->v0, s->f};
    const long counts[2] = {NV, NF};
    dyn_sweep_grid(2, axes, counts, values, RUNS);
    dyn_sweep sw = {0};
    sw.model = m;
    sw.n_vars = 2, sw.vars = vars, sw.n_runs = RUNS, sw.values = values;
    sw.method = dyn_method_find(m->method);
    sw.t0 = m->t0, sw.t1 = m->t1, sw.step = m->step;
    sw.n_reduce = n_red, sw.reduce = red;
    sw.threads = threads;
    int rc = dyn_sweep_run(&sw, results, status, err, errlen);
    if (rc != DYN_OK)
        return rc;
    for (int r = 0; r < RUNS; r++) {
        s->ratio[r] = results[2 * r];
        s->n_failed += status[r] != DYN_OK;
    }
    for (int i = 0; i < NV; i++) {
        const double *row = s->ratio + i * NF;
        s->boundary_f[i] = NAN;
        for (int j = 0; j < NF; j++)
            if (row[j] >= 1.0) {
                s->boundary_f[i] = j == 0
                                       ? s->f[0]
                                       : s->f[j - 1] + (1.0 - row[j - 1]) / (row[j] - row[j - 1]) *
                                                           (s->f[j] - s->f[j - 1]);
                break;
            }
    }
    /* the homework's point, v0 = 20 m/s and f = 2 Hz, is a point of the grid */
    s->homework_ratio = s->homework_slip_fraction = NAN;
    for (int r = 0; r < RUNS; r++)
        if (values[2 * r] == 20.0 && values[2 * r + 1] == 2.0) {
            s->homework_ratio = s->ratio[r];
            s->homework_slip_fraction = results[2 * r + 1];
        }
    return 0;
}
