/* SPDX-License-Identifier: BSD-3-Clause */
/* The report's study of problem 1: the pendulum's period against its amplitude, one run per
 * amplitude through dyn_sweep (released at rest from phi = a, dop853 with rtol = atol =
 * 1e-12, stopped at the first bottom, a quarter period), against the exact period
 * 4 K(k) / w, k = sin(a/2), w = sqrt(g/l), with K by the arithmetic-geometric mean
 * (Abramowitz and Stegun, Handbook of Mathematical Functions, 17.6). */
#include <math.h>
#include <string.h>

#include "dynkit/models.h"
#include "dynkit/report_studies.h"
#include "dynkit/sweep.h"

double dyn_elliptic_k(double k)
{
    double a = 1.0, b = sqrt(1.0 - k * k);
    for (int i = 0; i < 64 && fabs(a - b) > 1e-16 * a; i++) {
        const double an = 0.5 * (a + b);
        b = sqrt(a * b);
        a = an;
    }
    return DYN_PI / (a + b);
}

int dyn_study_period_compute(dyn_study_period *s, int threads, char *err, size_t errlen)
{
    const dyn_model *m = &dyn_model_pendulum;
    dyn_pendulum_par p;
    memset(s, 0, sizeof *s);
    if (dyn_model_default_params(m, &p, err, errlen))
        return 1;
    dyn_sweep_var phi;
    dyn_reduce red[1];
    int n_red = 0, stop = -1;
    for (int e = 0; e < m->n_events; e++)
        if (strcmp(m->events[e].name, "bottom") == 0)
            stop = e;
    if (dyn_sweep_var_find(m, "phi", &phi, err, errlen) ||
        dyn_reduce_parse(m, "event:bottom", red, 1, &n_red, err, errlen) || stop < 0)
        return 1;
    s->n = DYN_STUDY_PERIOD_RUNS;
    s->w = sqrt(p.g / p.l);
    s->rtol = 1e-12;
    /* amplitudes up to 3 rad (172 deg), where the period is 2.8 times the small-angle one */
    for (int i = 0; i < s->n; i++)
        s->amplitude_rad[i] = dyn_linspace_at(0.05, 3.0, s->n, i);
    const double y0[2] = {0.0, 0.0};
    double quarter[DYN_STUDY_PERIOD_RUNS];
    int status[DYN_STUDY_PERIOD_RUNS];
    dyn_sweep sw = {0};
    sw.model = m;
    sw.y0 = y0;
    sw.n_vars = 1, sw.vars = &phi, sw.n_runs = s->n, sw.values = s->amplitude_rad;
    sw.method = dyn_method_find("dop853");
    sw.t0 = 0.0, sw.t1 = 4.0 * m->t1; /* the longest quarter period here is 4.1 s */
    sw.step = 0.0;
    sw.rtol = sw.atol = s->rtol;
    sw.n_reduce = n_red, sw.reduce = red;
    sw.n_stop = 1, sw.stop = &stop;
    sw.threads = threads;
    int rc = dyn_sweep_run(&sw, quarter, status, err, errlen);
    if (rc != DYN_OK)
        return rc;
    s->max_difference_s = 0.0;
    for (int i = 0; i < s->n; i++) {
        s->period_s[i] = 4.0 * quarter[i];
        s->exact_s[i] = 4.0 * dyn_elliptic_k(sin(0.5 * s->amplitude_rad[i])) / s->w;
        if (status[i] != DYN_OK || !isfinite(s->period_s[i])) {
            s->n_failed++;
            continue;
        }
        const double d = fabs(s->period_s[i] - s->exact_s[i]);
        if (d >= s->max_difference_s) {
            s->max_difference_s = d;
            s->amplitude_at_max_rad = s->amplitude_rad[i];
        }
    }
    return 0;
}
