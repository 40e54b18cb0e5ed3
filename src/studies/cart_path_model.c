/* SPDX-License-Identifier: BSD-3-Clause */
/* The cart following the prescribed motion of homework problem 4a (sX = -v0 t, theta = pi/8
 * sin(2 pi f t)), as a model for sweeps over v0 and f (report_studies.h): the states sX and
 * theta integrated from their prescribed rates (cheap: a sweep runs it a thousand times), and
 * at each sample the rear-axle force lambda of the inverse dynamics' forces
 * (dyn_cart_prescribed_rates: no quadrature of sY), exactly 4d's "along the
 * exact prescribed motion" (dyn_cart_inverse_forces, dyn_cart_lambda), against the friction
 * limit mu (2/3) m g of the two rear wheels. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "dynkit/report_studies.h"

/* d(sX, theta)/dt = (-v0, (pi/8) w cos(w t)), w = 2 pi f */
static int path_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_cart_path_par *p = par;
    const double w = 2.0 * DYN_PI * p->f;
    (void)y;
    dydt[0] = -p->v0;
    dydt[1] = DYN_CART_THETA_AMPLITUDE * w * cos(w * t);
    return 0;
}

/* lambda at time t along the prescribed motion (NaN for bad v0 or f). */
static double path_lambda(const dyn_cart_path_par *p, double t)
{
    double rates[3], acc[3], Fx, Fy;
    if (dyn_cart_prescribed_rates(&p->cart, p->v0, p->f, t, rates, acc))
        return NAN;
    const double theta = DYN_CART_THETA_AMPLITUDE * sin(2.0 * DYN_PI * p->f * t);
    dyn_cart_inverse_forces(&p->cart, theta, acc[0], acc[1], acc[2], &Fx, &Fy);
    return dyn_cart_lambda(&p->cart, Fy, acc[2]);
}

static int path_outputs(double t, const double *y, const void *par, double *out)
{
    const dyn_cart_path_par *p = par;
    (void)y;
    out[0] = path_lambda(p, t);
    out[1] = fabs(out[0]) / dyn_cart_friction_limit(&p->cart);
    out[2] = out[1] >= 1.0 ? 1.0 : 0.0;
    return isfinite(out[0]) ? 0 : 1;
}

static double path_slip(double t, const double *y, void *par)
{
    const dyn_cart_path_par *p = par;
    (void)y;
    return fabs(path_lambda(p, t)) / dyn_cart_friction_limit(&p->cart) - 1.0;
}

static int path_prepare(void *par, char *err, size_t errlen)
{
    dyn_cart_path_par *p = par;
    if (!isfinite(p->v0) || !(isfinite(p->f) && p->f >= 0.0)) {
        if (err && errlen)
            snprintf(err, errlen,
                     "v0 must be a finite number and f a finite number >= 0 "
                     "(got v0 = %g m/s, f = %g Hz)",
                     p->v0, p->f);
        return DYN_ERR_ARG;
    }
    p->cart.Fx = p->cart.Fy = 0.0;
    p->cart.forces = NULL;
    p->cart.n_forces = 0;
    return dyn_cart_prepare(&p->cart, err, errlen);
}

static const dyn_var states[] = {
    {"sX", "m", "X position of the centre of mass S, -v0 t"},
    {"theta", "rad", "heading, pi/8 sin(2 pi f t)"},
};
static const double y0[] = {0.0, 0.0};
static const dyn_param params[] = {
    {"v0", "m/s", "backward speed", offsetof(dyn_cart_path_par, v0), 20.0},
    {"f", "Hz", "frequency of the steering", offsetof(dyn_cart_path_par, f), 2.0},
    {"m", "kg", "mass of the cart", offsetof(dyn_cart_path_par, cart.m), 20.0},
    {"length_cart", "m", "length l", offsetof(dyn_cart_path_par, cart.length_cart), 2.0},
    {"width_cart", "m", "width d", offsetof(dyn_cart_path_par, cart.width_cart), 1.0},
    {"mu", "1", "friction coefficient of the rear wheels", offsetof(dyn_cart_path_par, cart.mu),
     0.7},
    {"g", "m/s^2", "acceleration of gravity", offsetof(dyn_cart_path_par, cart.g), 9.81},
};
static const dyn_var outputs[] = {
    {"lambda", "N", "lateral force on the rear axle, Fy - 2 Is domega / l (inverse dynamics)"},
    {"slip_ratio", "1", "|lambda| / (mu (2/3) m g); above 1 the rear wheels would slip"},
    {"slipping", "1", "1 while slip_ratio >= 1, else 0 (its time average: the time slipping)"},
};
static const dyn_event events[] = {
    {"slip", "|lambda| reaches the friction limit mu (2/3) m g", path_slip, 1, 0, NULL},
};

const dyn_model dyn_model_cart_path = {
    .name = "cart-path",
    .title = "the cart along the prescribed motion of problem 4a, lambda against friction",
    .description = "sX = -v0 t, theta = pi/8 sin(2 pi f t), dsY from the constraint; lambda from\n"
                   "the forces of the inverse dynamics, slip_ratio = |lambda| / (mu (2/3) m g).",
    .n_states = 2,
    .states = states,
    .y0 = y0,
    .n_params = 7,
    .params = params,
    .par_size = sizeof(dyn_cart_path_par),
    .n_outputs = 3,
    .outputs = outputs,
    .rhs = path_rhs,
    .compute_outputs = path_outputs,
    .prepare = path_prepare,
    .t0 = 0.0,
    .t1 = 4.99,
    .step = 0.01,
    .method = "rk4",
    .n_events = 1,
    .events = events,
};
