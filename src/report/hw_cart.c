/* SPDX-License-Identifier: BSD-3-Clause */
/* Homework problem 4 (three-wheeled cart): the prescribed backward motion sX = -v0 t,
 * theta = pi/8 sin(2 pi f t); 4a the initial lateral velocity from the constraint; 4b the
 * force table of the inverse dynamics at N samples of Ts; 4c the forward run with modified
 * Euler (heun) at Ts reading the table as a zero-order hold (index = round(t/Ts)) and the
 * error in sX at te = (N-1) Ts; 4d the rear-axle constraint force lambda = Fy - 2 Is
 * domega / l at the N samples of the forward run against the friction limit mu (2/3) m g.
 * Because the open-loop backward run is unstable, the forward error is also shown against
 * the sampling time and with linearly interpolated forces. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/cart.h"
#include "report/hw_common.h"

typedef struct lambda_watch {
    dyn_cart_par *p;
    double v0, f;
    double max_abs, t_max, max_residual;
    double t_1cm, t_1m; /* first sample times off the prescribed path by 1 cm, 1 m */
} lambda_watch;

static int watch_lambda(long k, double t, const double *y, void *ctx)
{
    lambda_watch *w = ctx;
    double dydt[6], Fx, Fy;
    (void)k;
    dyn_cart_rhs(t, y, dydt, w->p);
    dyn_cart_forces_at(w->p, t, &Fx, &Fy);
    double lambda = fabs(dyn_cart_lambda(w->p, Fy, dydt[5]));
    if (lambda > w->max_abs) {
        w->max_abs = lambda;
        w->t_max = t;
    }
    w->max_residual = fmax(w->max_residual, fabs(dyn_cart_constraint_residual(w->p, y)));
    double s[6];
    dyn_cart_prescribed(w->p, w->v0, w->f, t, s, NULL);
    double off = hypot(y[0] - s[0], y[1] - s[1]);
    if (off > 0.01 && isnan(w->t_1cm))
        w->t_1cm = t;
    if (off > 1.0 && isnan(w->t_1m))
        w->t_1m = t;
    return 0;
}

/* The cart driven by the forces of the exact prescribed motion at every instant. */
typedef struct exact_drive {
    dyn_cart_par p;
    double v0, f;
} exact_drive;

static int exact_drive_rhs(double t, const double *y, double *dydt, void *par)
{
    exact_drive *d = par;
    double s[6], acc[3];
    if (dyn_cart_prescribed(&d->p, d->v0, d->f, t, s, acc))
        return 1;
    dyn_cart_inverse_forces(&d->p, s[2], acc[0], acc[1], acc[2], &d->p.Fx, &d->p.Fy);
    return dyn_cart_rhs(t, y, dydt, &d->p);
}

/* How violently the backward motion is unstable, without tables or coarse steps. */
static int sensitivity(dyn_hw_cart *r, const dyn_cart_par *p, const double *y0, char *err,
                       size_t errlen)
{
    exact_drive d = {*p, r->v0, r->f};
    double y[6], y_changed[6], y0_changed[6], s[6];
    d.p.forces = NULL;
    d.p.n_forces = 0;
    r->sensitivity_step = r->Ts / 10.0;
    r->sensitivity_dtheta0 = 1e-12;
    memcpy(y0_changed, y0, sizeof y0_changed);
    y0_changed[2] += r->sensitivity_dtheta0;
    int rc = hw_final_state("rk4", exact_drive_rhs, &d, 6, 0.0, r->te, r->sensitivity_step, y0,
                            y, err, errlen);
    rc = rc ? rc
            : hw_final_state("rk4", exact_drive_rhs, &d, 6, 0.0, r->te, r->sensitivity_step,
                             y0_changed, y_changed, err, errlen);
    dyn_cart_prescribed(p, r->v0, r->f, r->te, s, NULL);
    r->sensitivity_error_sX_m = fabs(y[0] - s[0]);
    r->sensitivity_sX_m = fabs(y_changed[0] - y[0]);
    return rc;
}

/* Forward run with heun over the N samples of a force table at Ts; final state in y. */
static int forward(dyn_cart_par *p, const char *method, const double *table, long N, double Ts,
                   dyn_interp interp, const double *y0, double *y, lambda_watch *watch, char *err,
                   size_t errlen)
{
    if (dyn_cart_set_forces(p, table, N, interp, err, errlen))
        return 1;
    return hw_run(method, dyn_cart_rhs, p, 6, 0.0, (double)(N - 1) * Ts, Ts, y0, y,
                  watch ? watch_lambda : NULL, watch, err, errlen);
}

/* sX error of the forward run with method for a table of N samples at Ts read with interp. */
static int forward_error(dyn_cart_par *p, const char *method, double v0, double f, long N,
                         double Ts, dyn_interp interp, const double *y0, double *error,
                         char *err, size_t errlen)
{
    double *table = malloc((size_t)N * 3 * sizeof *table), y[6];
    int rc = !table;
    if (rc)
        snprintf(err, errlen, "out of memory for a force table of %ld rows", N);
    rc = rc ? rc : dyn_cart_force_table(p, v0, f, N, Ts, table, err, errlen);
    rc = rc ? rc : forward(p, method, table, N, Ts, interp, y0, y, NULL, err, errlen);
    *error = fabs(y[0] - (-v0 * (double)(N - 1) * Ts));
    dyn_cart_set_forces(p, NULL, 0, DYN_INTERP_HOLD, NULL, 0);
    free(table);
    return rc;
}

int dyn_hw_cart_compute(dyn_hw_cart *r, char *err, size_t errlen)
{
    dyn_cart_par p;
    memset(r, 0, sizeof *r);
    if (dyn_model_default_params(&dyn_model_cart, &p, err, errlen))
        return 1;
    r->v0 = 20.0;
    r->f = 2.0;
    r->N = 500;
    r->Ts = 0.01;
    r->te = (double)(r->N - 1) * r->Ts;
    r->mu = p.mu;
    r->g = p.g;
    r->m = p.m;

    double y0[6], y[6];
    int rc = dyn_cart_prescribed(&p, r->v0, r->f, 0.0, y0, NULL);
    if (rc) {
        snprintf(err, errlen, "prescribed motion of the cart failed");
        return rc;
    }
    r->initial_dsY_mps = y0[4];

    double *table = malloc((size_t)r->N * 3 * sizeof *table);
    if (!table) {
        snprintf(err, errlen, "out of memory for the force table");
        return 1;
    }
    rc = dyn_cart_force_table(&p, r->v0, r->f, r->N, r->Ts, table, err, errlen);
    if (!rc) {
        r->final_Fx_N = table[(r->N - 1) * 3 + 1];
        r->final_Fy_N = table[(r->N - 1) * 3 + 2];
        /* 4d along the exact prescribed motion, for comparison */
        for (long k = 0; k < r->N && !rc; k++) {
            double s[6], acc[3];
            rc = dyn_cart_prescribed(&p, r->v0, r->f, (double)k * r->Ts, s, acc);
            double lambda = fabs(dyn_cart_lambda(&p, table[k * 3 + 2], acc[2]));
            r->max_constraint_force_prescribed_N = fmax(r->max_constraint_force_prescribed_N,
                                                        lambda);
        }
    }
    lambda_watch watch = {&p, r->v0, r->f, 0.0, 0.0, 0.0, NAN, NAN};
    rc = rc ? rc
            : forward(&p, "heun", table, r->N, r->Ts, DYN_INTERP_HOLD, y0, y, &watch, err,
                      errlen);
    rc = rc ? rc : sensitivity(r, &p, y0, err, errlen);
    dyn_cart_set_forces(&p, NULL, 0, DYN_INTERP_HOLD, NULL, 0);
    free(table);
    if (rc)
        return rc;
    r->forward_sX_m = y[0];
    r->exact_sX_m = -r->v0 * r->te;
    r->forward_error_sX_m = fabs(r->forward_sX_m - r->exact_sX_m);
    r->max_constraint_force_N = watch.max_abs;
    r->t_max_constraint_force = watch.t_max;
    r->max_constraint_residual = watch.max_residual;
    r->t_departure_1cm = watch.t_1cm;
    r->t_departure_1m = watch.t_1m;
    r->friction_limit_N = dyn_cart_friction_limit(&p);
    const double l = p.length_cart;
    r->instability_rate = p.m * r->v0 * l / (p.m * l * l / 2.0 + 2.0 * p.Is);
    r->rear_wheels_slip = r->max_constraint_force_N > r->friction_limit_N;

    r->n_study = DYN_HW_CART_STUDY;
    for (int i = 0; i < r->n_study && !rc; i++) {
        long scale = 1L << i;
        long N = (r->N - 1) * scale + 1;
        r->study_Ts[i] = r->Ts / (double)scale;
        rc = forward_error(&p, "heun", r->v0, r->f, N, r->study_Ts[i], DYN_INTERP_HOLD, y0,
                           &r->study_error_heun_hold[i], err, errlen);
        rc = rc ? rc
                : forward_error(&p, "rk4", r->v0, r->f, N, r->study_Ts[i], DYN_INTERP_HOLD, y0,
                                &r->study_error_rk4_hold[i], err, errlen);
        rc = rc ? rc
                : forward_error(&p, "rk4", r->v0, r->f, N, r->study_Ts[i], DYN_INTERP_LINEAR,
                                y0, &r->study_error_rk4_linear[i], err, errlen);
    }
    return rc;
}
