/* SPDX-License-Identifier: BSD-3-Clause */
/* Example: a model of your own as a dyn_model: a planar double pendulum (two point masses
 * on massless rods, angles from the downward vertical), with named states and parameters in
 * SI units, extra outputs (the energy and the lower bob's position), the bob positions and
 * velocities as 3-vectors with dynkit/mech.h, run with dyn_solve. The equations of motion
 * are Lagrange's for this system (e.g. Goldstein, "Classical Mechanics", ch. 1; the same
 * form as in the double pendulum of XPPAUT's examples). The energy is a first integral; its
 * drift measures the accuracy of the run. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include <dynkit/dynkit.h>
#include <dynkit/mech.h>

typedef struct dp_par {
    double m1, m2; /* [kg] bob masses */
    double l1, l2; /* [m] rod lengths */
    double g;      /* [m/s^2] gravity */
} dp_par;

/* states y = (th1, th2, w1, w2) */
static int dp_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const dp_par *p = par;
    const double d = y[0] - y[1], w1 = y[2], w2 = y[3];
    const double den = 2.0 * p->m1 + p->m2 - p->m2 * cos(2.0 * d);
    dydt[0] = w1;
    dydt[1] = w2;
    dydt[2] = (-p->g * (2.0 * p->m1 + p->m2) * sin(y[0]) - p->m2 * p->g * sin(y[0] - 2.0 * y[1]) -
               2.0 * sin(d) * p->m2 * (w2 * w2 * p->l2 + w1 * w1 * p->l1 * cos(d))) /
              (p->l1 * den);
    dydt[3] = 2.0 * sin(d) *
              (w1 * w1 * p->l1 * (p->m1 + p->m2) + p->g * (p->m1 + p->m2) * cos(y[0]) +
               w2 * w2 * p->l2 * p->m2 * cos(d)) /
              (p->l2 * den);
    return 0;
}

/* Positions and velocities of the bobs (x right, y up, z out of the plane). */
static void bobs(const dp_par *p, const double *y, double r1[3], double r2[3], double v1[3],
                 double v2[3])
{
    const double e1[3] = {sin(y[0]), -cos(y[0]), 0.0}, e2[3] = {sin(y[1]), -cos(y[1]), 0.0};
    const double t1[3] = {cos(y[0]), sin(y[0]), 0.0}, t2[3] = {cos(y[1]), sin(y[1]), 0.0};
    double a[3];
    dyn_vec3_scale(e1, p->l1, r1);
    dyn_vec3_scale(e2, p->l2, a);
    dyn_vec3_add(r1, a, r2);
    dyn_vec3_scale(t1, p->l1 * y[2], v1);
    dyn_vec3_scale(t2, p->l2 * y[3], a);
    dyn_vec3_add(v1, a, v2);
}

/* outputs: energy [J] (zero with both bobs at rest below the pivot), x2, y2 [m] */
static int dp_outputs(double t, const double *y, const void *par, double *out)
{
    (void)t;
    const dp_par *p = par;
    double r1[3], r2[3], v1[3], v2[3];
    bobs(p, y, r1, r2, v1, v2);
    const double up[3] = {0.0, 1.0, 0.0};
    const double kinetic =
        dyn_rigid_translational_energy(p->m1, v1) + dyn_rigid_translational_energy(p->m2, v2);
    const double potential = p->m1 * p->g * (dyn_vec3_dot(r1, up) + p->l1) +
                             p->m2 * p->g * (dyn_vec3_dot(r2, up) + p->l1 + p->l2);
    out[0] = kinetic + potential;
    out[1] = r2[0];
    out[2] = r2[1];
    return 0;
}

static const dyn_var dp_states[] = {{"th1", "rad", "upper rod's angle from the downward vertical"},
                                    {"th2", "rad", "lower rod's angle from the downward vertical"},
                                    {"w1", "rad/s", "upper rod's angular velocity"},
                                    {"w2", "rad/s", "lower rod's angular velocity"}};
static const double dp_y0[] = {DYN_PI / 2.0, DYN_PI / 2.0, 0.0, 0.0}; /* both rods level */
static const dyn_param dp_params[] = {
    {"m1", "kg", "upper bob's mass", offsetof(dp_par, m1), 1.0},
    {"m2", "kg", "lower bob's mass", offsetof(dp_par, m2), 1.0},
    {"l1", "m", "upper rod's length", offsetof(dp_par, l1), 1.0},
    {"l2", "m", "lower rod's length", offsetof(dp_par, l2), 1.0},
    {"g", "m/s^2", "gravity", offsetof(dp_par, g), 9.81}};
static const dyn_var dp_outs[] = {{"energy", "J", "total energy, zero hanging at rest"},
                                  {"x2", "m", "lower bob, horizontal"},
                                  {"y2", "m", "lower bob, vertical (up)"}};

static const dyn_model double_pendulum = {
    .name = "double-pendulum",
    .title = "planar double pendulum",
    .description = "Two point masses on massless rods; Lagrange's equations in the angles.",
    .n_states = 4,
    .states = dp_states,
    .y0 = dp_y0,
    .n_params = 5,
    .params = dp_params,
    .par_size = sizeof(dp_par),
    .n_outputs = 3,
    .outputs = dp_outs,
    .rhs = dp_rhs,
    .compute_outputs = dp_outputs,
    .t0 = 0.0,
    .t1 = 10.0,
    .step = 0.01,
    .method = "dop853",
    .rtol = 1e-10,
    .atol = 1e-12};

/* Print a sample every second: the state and the outputs, by name. */
typedef struct printer {
    const dyn_model *m;
    const void *par;
    double e0, drift;
} printer;

static int print_sample(long k, double t, const double *y, void *ctx)
{
    (void)k;
    printer *p = ctx;
    double out[3];
    p->m->compute_outputs(t, y, p->par, out);
    if (k == 0)
        p->e0 = out[0];
    p->drift = fmax(p->drift, fabs(out[0] - p->e0));
    printf("%5.1f %10.6f %10.6f %10.6f %10.6f %10.6f %.12f\n", t, y[0], y[1], out[1], out[2],
           out[0], out[0] - p->e0);
    return 0;
}

int main(void)
{
    const dyn_model *m = &double_pendulum;
    dp_par par;
    char err[128];
    if (dyn_model_default_params(m, &par, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    dyn_model_set_param(m, &par, dyn_model_param_index(m, "m2"), 0.5); /* set by name */
    double y0[4], y[4];
    dyn_model_initial_state(m, &par, y0);
    printf("%s: %s\n", m->name, m->title);
    for (int i = 0; i < m->n_params; i++)
        printf("  %-3s = %5.2f %-6s %s\n", m->params[i].name, dyn_model_get_param(m, &par, i),
               m->params[i].unit, m->params[i].description);
    printf("%5s %10s %10s %10s %10s %10s %s\n", "t [s]", "th1", "th2", "x2 [m]", "y2 [m]",
           "E [J]", "E - E(0) [J]");
    const dyn_tableau *method = dyn_method_find(m->method);
    printer pr = {m, &par, 0.0, 0.0};
    dyn_solve_opts opts = {.rtol = m->rtol, .atol = m->atol, .out_step = 1.0};
    opts.output = print_sample;
    opts.output_ctx = &pr;
    dyn_system sys = {m->rhs, m->n_states, &par};
    double *work = malloc(dyn_solve_work_size(method, m->n_states, &opts) * sizeof *work);
    if (!work)
        return 1;
    dyn_result res;
    int rc = dyn_solve(method, &sys, m->t0, m->t1, y0, y, work, &opts, &res);
    free(work);
    if (rc != DYN_OK) {
        fprintf(stderr, "solve failed: %s\n", res.message);
        return 1;
    }
    printf("energy conserved to %.1e J of %.4f J over %g s (%s, rtol %g: %ld steps)\n",
           pr.drift, pr.e0, m->t1, method->name, m->rtol, res.stats.accepted);
    return pr.drift < 1e-7 ? 0 : 1;
}
