/* SPDX-License-Identifier: BSD-3-Clause */
/* Nonlinear pendulum of homework problem 1: a point mass m on a massless rigid rod of
 * length l, angle phi from the downward vertical, gravity g.
 * Equation of motion (Lagrange or Newton about the pivot): m l^2 ddphi = -m g l sin(phi).
 * Defaults: m = 2 kg, l = 9.81 m, g = 9.81 m/s^2, phi(0) = 0, dphi(0) = pi/2 1/s.
 * Analyses: maximum height from energy (1a) and the small-angle solution (1c).
 */
#include <math.h>
#include <stddef.h>

#include "dynkit/models.h"

int dyn_pendulum_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_pendulum_par *p = par;
    (void)t;
    dydt[0] = y[1];
    dydt[1] = -(p->g / p->l) * sin(y[0]);
    return 0;
}

double dyn_pendulum_energy(const dyn_pendulum_par *p, const double *y)
{
    const double v = p->l * y[1];
    return 0.5 * p->m * v * v + p->m * p->g * p->l * (1.0 - cos(y[0]));
}

double dyn_pendulum_max_height(const dyn_pendulum_par *p, const double *y)
{
    const double h = dyn_pendulum_energy(p, y) / (p->m * p->g);
    return h < 2.0 * p->l ? h : 2.0 * p->l;
}

double dyn_pendulum_small_angle(const dyn_pendulum_par *p, const double *y0, double t)
{
    const double w = sqrt(p->g / p->l);
    return y0[0] * cos(w * t) + y0[1] / w * sin(w * t);
}

static int pendulum_outputs(double t, const double *y, const void *par, double *out)
{
    const dyn_pendulum_par *p = par;
    (void)t;
    out[0] = dyn_pendulum_energy(p, y);
    out[1] = p->l * (1.0 - cos(y[0]));
    return 0;
}

static int pendulum_prepare(void *par, char *err, size_t errlen)
{
    const dyn_pendulum_par *p = par;
    return dyn_check_positive("l", p->l, err, errlen) ||
           dyn_check_positive("m", p->m, err, errlen);
}

static const dyn_var states[] = {
    {"phi", "rad", "rod angle from the downward vertical, positive to the right"},
    {"dphi", "rad/s", "angular velocity of the rod"},
};
static const double y0[] = {0.0, DYN_PI / 2.0};
static const dyn_param params[] = {
    {"m", "kg", "mass of the point mass", offsetof(dyn_pendulum_par, m), 2.0},
    {"l", "m", "length of the rod", offsetof(dyn_pendulum_par, l), 9.81},
    {"g", "m/s^2", "acceleration of gravity", offsetof(dyn_pendulum_par, g), 9.81},
};
static const dyn_var outputs[] = {
    {"energy", "J", "kinetic plus potential energy (zero at rest at the bottom)"},
    {"height", "m", "height of the mass above its bottom position, l (1 - cos phi)"},
};

/* Events: the turning point (dphi = 0) and the passage through the bottom, phi = 0 mod 2 pi
 * (sin(phi/2) changes sign there, also for a pendulum going over the top). */
static double pendulum_turn(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[1];
}

static double pendulum_bottom(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return sin(0.5 * y[0]);
}

static const dyn_event events[] = {
    {"turn", "the rod stops and turns back: dphi = 0", pendulum_turn, 0, 0, NULL},
    {"bottom", "the rod passes the downward vertical: phi = 0 (mod 2 pi)", pendulum_bottom, 0, 0, NULL},
};

const dyn_model dyn_model_pendulum = {
    .name = "pendulum",
    .title = "nonlinear pendulum (homework problem 1)",
    .description = "Point mass m on a massless rigid rod of length l under gravity g.\n"
                   "phi is the angle from the downward vertical.\n"
                   "  dphi/dt  = dphi\n"
                   "  ddphi/dt = -(g/l) sin(phi)",
    .n_states = 2,
    .states = states,
    .y0 = y0,
    .n_params = 3,
    .params = params,
    .par_size = sizeof(dyn_pendulum_par),
    .n_outputs = 2,
    .outputs = outputs,
    .rhs = dyn_pendulum_rhs,
    .compute_outputs = pendulum_outputs,
    .prepare = pendulum_prepare,
    .t0 = 0.0,
    .t1 = 10.0,   /* a little over one swing (period 7.9 s from the default state) */
    .step = 0.01, /* the sample grid, and the step of fixed-step methods */
    /* an adaptive method whatever the span (the homework's one Euler step of 0.2 s, problem
     * 1e, is `--method euler --step 0.2 --tspan 0:0.2`) */
    .method = "dp45",
    .n_events = 2,
    .events = events,
    .rtol = 1e-8,
    .atol = 1e-10,
};
