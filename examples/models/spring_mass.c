/* SPDX-License-Identifier: BSD-3-Clause */
/* A mass on a linear spring with viscous damping, as a C model for dynkit:
 *
 *     m x'' = -k x - c x'        states x [m], v = x' [m/s]
 *
 * Run it like a built-in model (dynkit compiles the file and caches the result):
 *     dynkit run examples/models/spring_mass.c --set k=4 --final
 *     dynkit info examples/models/spring_mass.c
 * Undamped (c = 0, the default) it swings as x(t) = x0 cos(w t), v(t) = -x0 w sin(w t) with
 * w = sqrt(k/m): with k = 4 and m = 1 the period is pi seconds.
 *
 * A C model includes <dynkit/model.h> (and may call any function of the library, e.g.
 * <dynkit/mech.h>) and defines dynkit_model(), which returns the model's description.
 */
#include <math.h>
#include <stddef.h>

#include <dynkit/model.h>

typedef struct spring_mass_par {
    double m, k, c; /* mass [kg], stiffness [N/m], damping [N s/m] */
    double w;       /* derived: undamped angular frequency sqrt(k/m) [rad/s] */
} spring_mass_par;

static int rhs(double t, const double *y, double *dydt, void *par)
{
    const spring_mass_par *p = par;
    (void)t;
    dydt[0] = y[1];
    dydt[1] = -(p->k * y[0] + p->c * y[1]) / p->m;
    return 0;
}

static int outputs(double t, const double *y, const void *par, double *out)
{
    const spring_mass_par *p = par;
    (void)t;
    out[0] = 0.5 * p->m * y[1] * y[1] + 0.5 * p->k * y[0] * y[0];
    out[1] = -p->k * y[0] - p->c * y[1];
    return 0;
}

/* derived values, and the parameters checked (dyn_check_positive is the library's) */
static int prepare(void *par, char *err, size_t errlen)
{
    spring_mass_par *p = par;
    if (dyn_check_positive("m", p->m, err, errlen) || dyn_check_positive("k", p->k, err, errlen))
        return 1;
    if (!(p->c >= 0.0)) /* also refuses NaN */
        return dyn_check_positive("c", p->c, err, errlen);
    p->w = sqrt(p->k / p->m);
    return 0;
}

/* the mass passes the spring's rest position (x = 0), moving either way */
static double through_rest(double t, const double *y, void *par)
{
    (void)t, (void)par;
    return y[0];
}

static const dyn_var states[] = {
    {"x", "m", "displacement of the mass from the spring's rest length"},
    {"v", "m/s", "velocity of the mass"},
};
static const double initial[] = {0.1, 0.0}; /* (not y0: math.h declares y0, a Bessel function) */
static const dyn_param params[] = {
    {"m", "kg", "mass", offsetof(spring_mass_par, m), 1.0},
    {"k", "N/m", "spring stiffness", offsetof(spring_mass_par, k), 1.0},
    {"c", "N*s/m", "viscous damping coefficient", offsetof(spring_mass_par, c), 0.0},
};
static const dyn_var outs[] = {
    {"energy", "J", "kinetic plus elastic energy, m v^2/2 + k x^2/2"},
    {"force", "N", "force of the spring and the damper on the mass"},
};
static const dyn_event events[] = {
    {"rest", "the mass passes the rest position (x = 0)", through_rest, 0, 0, NULL},
};

static const dyn_model model = {
    .name = "spring_mass",
    .title = "mass on a linear spring with viscous damping",
    .description = "m x'' = -k x - c x'; undamped (c = 0) x(t) = x0 cos(w t), w = sqrt(k/m).",
    .n_states = 2,
    .states = states,
    .y0 = initial,
    .n_params = 3,
    .params = params,
    .par_size = sizeof(spring_mass_par),
    .n_outputs = 2,
    .outputs = outs,
    .rhs = rhs,
    .compute_outputs = outputs,
    .prepare = prepare,
    .t0 = 0.0,
    .t1 = 10.0,
    .step = 0.01,
    .method = "rk4",
    .n_events = 1,
    .events = events,
    .phase_x = "x",
    .phase_y = "v",
};

const dyn_model *dynkit_model(void) { return &model; }
