/* SPDX-License-Identifier: BSD-3-Clause */
/* Three-wheeled cart of homework problem 4 (the seed's cart_equationsofmotion.m, with the
 * OCR reading l/2 in the third row of A): forward dynamics of a rigid block in the plane
 * whose rear axle cannot move sideways, driven by body-frame forces at the front wheel C,
 * constant or read from a table of samples. Constrained Lagrange equations with one
 * multiplier for the non-holonomic constraint (Greenwood, "Advanced Dynamics", Cambridge
 * 2003, on Lagrange's equations with non-holonomic constraints; the course's week 7).
 *
 * Closed-form solution of A ddq = b (see cart.h), with s = sin(theta), c = cos(theta),
 * k = 2 Is / l and u = dsX c + dsY s (forward speed of S):
 *     rows 1, 2:  ddsX = (b1 + k s domega) / m,  ddsY = (b2 - k c domega) / m;
 *     row 3:      s ddsX - c ddsY + (l/2) domega = b3 = -omega u, and s b1 - c b2 = -2 Fy,
 *     so          domega = (2 Fy - m u omega) / (k + m l / 2).
 * det A = m (m l/2 + k) > 0, so the solve never fails for prepared parameters.
 *
 * The constraint force. Let lambda be the lateral force of the ground on the rear axle
 * (along body y, at x = -l/2) and a_y = -s ddsX + c ddsY the body-y acceleration of S.
 *     Newton along body y:  m a_y = Fy + lambda
 *     Euler about S:        Is domega = (l/2) Fy - (l/2) lambda
 * The second gives lambda = Fy - 2 Is domega / l; with the first, m a_y = 2 Fy - k domega,
 * which is what rows 1 and 2 of A ddq = b say along body y.
 *
 * Work: the ground does no work on the rear axle (the force is lateral, the axle's lateral
 * velocity is zero), so dKE/dt = Fx u + Fy (v + (l/2) omega) = F_C . v_C, with v the
 * lateral velocity of S.
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "dynkit/cart.h"

int dyn_cart_prepare(dyn_cart_par *p, char *err, size_t errlen)
{
    if (dyn_check_positive("m", p->m, err, errlen) ||
        dyn_check_positive("length_cart", p->length_cart, err, errlen) ||
        dyn_check_positive("width_cart", p->width_cart, err, errlen))
        return DYN_ERR_ARG;
    const struct {
        const char *name;
        double value;
        int nonnegative;
    } checks[] = {{"Fx", p->Fx, 0}, {"Fy", p->Fy, 0}, {"mu", p->mu, 1}, {"g", p->g, 1}};
    for (size_t i = 0; i < sizeof checks / sizeof checks[0]; i++) {
        double v = checks[i].value;
        if (!isfinite(v) || (checks[i].nonnegative && v < 0.0)) {
            if (err && errlen)
                snprintf(err, errlen, "parameter %s must be a finite number%s (got %g)",
                         checks[i].name, checks[i].nonnegative ? " >= 0" : "", v);
            return DYN_ERR_ARG;
        }
    }
    const double l = p->length_cart, d = p->width_cart;
    p->Is = p->m / 12.0 * (l * l + d * d);
    return 0;
}

int dyn_cart_set_forces(dyn_cart_par *p, const double *table, long rows, dyn_interp interp,
                        char *err, size_t errlen)
{
#define FAIL(...)                                                                            \
    do {                                                                                     \
        if (err && errlen)                                                                   \
            snprintf(err, errlen, __VA_ARGS__);                                              \
        return DYN_ERR_ARG;                                                                  \
    } while (0)
    if (!table && rows == 0) {
        p->forces = NULL;
        p->n_forces = 0;
        p->forces_dt = 0.0;
        p->interp = interp;
        return 0;
    }
    if (!table || rows < 1)
        FAIL("force table: need at least 1 row of (t, Fx, Fy) (got %ld)", rows);
    if (interp != DYN_INTERP_HOLD && interp != DYN_INTERP_LINEAR)
        FAIL("force table: unknown interpolation %d (accepted: hold, linear)", (int)interp);
    for (long k = 0; k < rows; k++) {
        const double *r = table + 3 * k;
        if (!isfinite(r[0]) || !isfinite(r[1]) || !isfinite(r[2]))
            FAIL("force table: row %ld (t = %g) has a value that is not finite", k + 1, r[0]);
        if (k > 0 && !(r[0] > r[-3]))
            FAIL("force table: time must increase strictly, but row %ld has t = %s after "
                 "t = %s",
                 k + 1, dyn_shortest(r[0]).s, dyn_shortest(r[-3]).s);
    }
    double dt = 0.0;
    if (rows > 1) {
        dt = (table[3 * (rows - 1)] - table[0]) / (double)(rows - 1);
        for (long k = 1; k < rows - 1 && dt > 0.0; k++)
            if (!(fabs(table[3 * k] - (table[0] + (double)k * dt)) <= 1e-9 * dt))
                dt = 0.0;
    }
    p->forces = table;
    p->n_forces = rows;
    p->interp = interp;
    p->forces_dt = dt;
    return 0;
#undef FAIL
}

/* Index of the last sample with t_k <= t, for t_0 <= t < t_last (binary search). */
static long sample_below(const double *table, long rows, double t)
{
    long lo = 0, hi = rows - 1; /* t_lo <= t < t_hi */
    while (hi - lo > 1) {
        long mid = lo + (hi - lo) / 2;
        if (table[3 * mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

void dyn_cart_forces_at(const dyn_cart_par *p, double t, double *Fx, double *Fy)
{
    const double *tab = p->forces;
    const long n = p->n_forces;
    if (!tab || n < 1) {
        *Fx = p->Fx;
        *Fy = p->Fy;
        return;
    }
    const double *row;
    if (n == 1 || !(t > tab[0])) {
        row = tab; /* before the table (or NaN t): the first values */
    } else if (t >= tab[3 * (n - 1)]) {
        row = tab + 3 * (n - 1); /* after the table: the last values */
    } else if (p->interp == DYN_INTERP_LINEAR) {
        long k = sample_below(tab, n, t);
        const double *a = tab + 3 * k, *b = a + 3;
        double w = (t - a[0]) / (b[0] - a[0]);
        *Fx = a[1] + w * (b[1] - a[1]);
        *Fy = a[2] + w * (b[2] - a[2]);
        return;
    } else if (p->forces_dt > 0.0) {
        /* uniform table: the homework's index = round(t/Ts) (0-based), clamped */
        double x = round((t - tab[0]) / p->forces_dt);
        long k = x <= 0.0 ? 0 : x >= (double)(n - 1) ? n - 1 : (long)x;
        row = tab + 3 * k;
    } else {
        long k = sample_below(tab, n, t);
        if (tab[3 * (k + 1)] - t <= t - tab[3 * k])
            k++; /* nearer to the next sample, or a tie: the later one (like round) */
        row = tab + 3 * k;
    }
    *Fx = row[1];
    *Fy = row[2];
}

void dyn_cart_accelerations(const dyn_cart_par *p, double theta, double dsX, double dsY,
                            double omega, double Fx, double Fy, double acc[3])
{
    const double m = p->m, l = p->length_cart;
    const double k = 2.0 * p->Is / l;
    const double s = sin(theta), c = cos(theta);
    const double b1 = Fx * c - 2.0 * Fy * s;
    const double b2 = Fx * s + 2.0 * Fy * c;
    const double u = dsX * c + dsY * s;
    const double domega = (2.0 * Fy - m * u * omega) / (k + 0.5 * m * l);
    acc[0] = (b1 + k * s * domega) / m;
    acc[1] = (b2 - k * c * domega) / m;
    acc[2] = domega;
}

int dyn_cart_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_cart_par *p = par;
    double Fx, Fy;
    dyn_cart_forces_at(p, t, &Fx, &Fy);
    dydt[0] = y[3];
    dydt[1] = y[4];
    dydt[2] = y[5];
    dyn_cart_accelerations(p, y[2], y[3], y[4], y[5], Fx, Fy, dydt + 3);
    return 0;
}

double dyn_cart_lambda(const dyn_cart_par *p, double Fy, double domega)
{
    return Fy - 2.0 * p->Is * domega / p->length_cart;
}

double dyn_cart_friction_limit(const dyn_cart_par *p)
{
    return p->mu * (2.0 / 3.0) * p->m * p->g;
}

double dyn_cart_constraint_residual(const dyn_cart_par *p, const double *y)
{
    return y[4] * cos(y[2]) - y[3] * sin(y[2]) - 0.5 * p->length_cart * y[5];
}

double dyn_cart_constraint_dsY(const dyn_cart_par *p, double theta, double dsX, double omega)
{
    return (0.5 * p->length_cart * omega + dsX * sin(theta)) / cos(theta);
}

double dyn_cart_kinetic_energy(const dyn_cart_par *p, const double *y)
{
    return 0.5 * p->m * (y[3] * y[3] + y[4] * y[4]) + 0.5 * p->Is * y[5] * y[5];
}

/* lambda at (t, y) with the forces of the input. */
static double lambda_at(const dyn_cart_par *p, double t, const double *y, double *Fx,
                        double *Fy)
{
    double acc[3];
    dyn_cart_forces_at(p, t, Fx, Fy);
    dyn_cart_accelerations(p, y[2], y[3], y[4], y[5], *Fx, *Fy, acc);
    return dyn_cart_lambda(p, *Fy, acc[2]);
}

static int cart_outputs(double t, const double *y, const void *par, double *out)
{
    const dyn_cart_par *p = par;
    double Fx, Fy;
    const double lambda = lambda_at(p, t, y, &Fx, &Fy);
    out[0] = Fx;
    out[1] = Fy;
    out[2] = lambda;
    out[3] = dyn_cart_constraint_residual(p, y);
    out[4] = dyn_cart_friction_limit(p) - fabs(lambda);
    out[5] = dyn_cart_kinetic_energy(p, y);
    return 0;
}

static const char *cart_warn(double t, const double *y, const void *par)
{
    const dyn_cart_par *p = par;
    double Fx, Fy;
    if (fabs(lambda_at(p, t, y, &Fx, &Fy)) > dyn_cart_friction_limit(p))
        return "rear wheels would slip: |lambda| > mu (2/3) m g, the no-slip constraint is "
               "not valid here (see output slip_margin)";
    return NULL;
}

static int cart_prepare(void *par, char *err, size_t errlen)
{
    return dyn_cart_prepare(par, err, errlen);
}

static int cart_set_input(void *par, const double *table, long rows, dyn_interp interp,
                          char *err, size_t errlen)
{
    return dyn_cart_set_forces(par, table, rows, interp, err, errlen);
}

static const dyn_var states[] = {
    {"sX", "m", "X position of the centre of mass S (space frame N)"},
    {"sY", "m", "Y position of the centre of mass S (space frame N)"},
    {"theta", "rad", "heading: angle of the body x axis from the X axis, about Z"},
    {"dsX", "m/s", "X velocity of S"},
    {"dsY", "m/s", "Y velocity of S"},
    {"omega", "rad/s", "angular velocity about Z"},
};
/* simulate_cart.m; they satisfy the constraint: 2 cos 0 - 2 sin 0 = (2/2) 2 */
static const double y0[] = {0.0, 0.2, 0.0, 2.0, 2.0, 2.0};
static const dyn_param params[] = {
    {"m", "kg", "mass of the cart", offsetof(dyn_cart_par, m), 20.0},
    {"length_cart", "m", "length l: rear axle at x = -l/2, front wheel C at x = +l/2",
     offsetof(dyn_cart_par, length_cart), 2.0},
    {"width_cart", "m", "width d (only enters Is = m (l^2 + d^2)/12, derived)",
     offsetof(dyn_cart_par, width_cart), 1.0},
    {"Fx", "N", "body-x force at C (constant; a --forces table replaces it)",
     offsetof(dyn_cart_par, Fx), -50.0},
    {"Fy", "N", "body-y force at C (constant; a --forces table replaces it)",
     offsetof(dyn_cart_par, Fy), 0.0},
    {"mu", "1", "friction coefficient of the rear wheels (slip check)",
     offsetof(dyn_cart_par, mu), 0.7},
    {"g", "m/s^2", "acceleration of gravity (slip check)", offsetof(dyn_cart_par, g), 9.81},
};
static const dyn_var outputs[] = {
    {"Fx", "N", "applied body-x force at C"},
    {"Fy", "N", "applied body-y force at C"},
    {"lambda", "N", "lateral constraint force on the rear axle, Fy - 2 Is domega / l"},
    {"constraint_residual", "m/s", "dsY cos(theta) - dsX sin(theta) - (l/2) omega (0 exactly)"},
    {"slip_margin", "N", "mu (2/3) m g - |lambda|; negative: the rear wheels would slip"},
    {"kinetic_energy", "J", "m (dsX^2 + dsY^2)/2 + Is omega^2/2"},
};
static const dyn_var inputs[] = {
    {"Fx", "N", "body-x force at the front wheel C"},
    {"Fy", "N", "body-y force at the front wheel C"},
};

/* Event: the lateral force on the rear axle reaches the friction limit, |lambda| = mu (2/3) m g
 * (rising: from below the limit to above it). */
static double cart_slip(double t, const double *y, void *par)
{
    const dyn_cart_par *p = par;
    double Fx, Fy;
    return fabs(lambda_at(p, t, y, &Fx, &Fy)) - dyn_cart_friction_limit(p);
}

static const dyn_event events[] = {
    {"slip", "the rear wheels start to slip: |lambda| reaches mu (2/3) m g", cart_slip, 1, 0, NULL},
};

const dyn_model dyn_model_cart = {
    .name = "cart",
    .title = "three-wheeled cart with a non-slipping rear axle (homework problem 4)",
    .description =
        "A homogeneous block (mass m, length l, width d, Is = m (l^2 + d^2)/12 derived)\n"
        "moves in the XY plane. Its rear wheels at x = -l/2 (body frame, x forward) roll\n"
        "without slip, so the rear axle has no lateral velocity:\n"
        "  dsY cos(theta) - dsX sin(theta) = (l/2) omega\n"
        "The front omniwheel C at x = +l/2 applies body-frame forces Fx, Fy: constant\n"
        "parameters, or a table t,Fx,Fy (run --forces FILE, nearest sample by default,\n"
        "--interp linear to interpolate; end values held outside the table).\n"
        "Lagrange with the multiplier lambda (lateral force on the rear axle):\n"
        "  m ddsX - (2 Is/l) sin(theta) domega = Fx cos(theta) - 2 Fy sin(theta)\n"
        "  m ddsY + (2 Is/l) cos(theta) domega = Fx sin(theta) + 2 Fy cos(theta)\n"
        "  sin(theta) ddsX - cos(theta) ddsY + (l/2) domega = -omega (dsX cos(theta) + dsY "
        "sin(theta))\n"
        "  lambda = Fy - 2 Is domega / l; the rear wheels slip when |lambda| > mu (2/3) m g.\n"
        "Inverse dynamics of the homework's prescribed motion: 'dynkit inverse cart'.",
    .n_states = 6,
    .states = states,
    .y0 = y0,
    .n_params = 7,
    .params = params,
    .par_size = sizeof(dyn_cart_par),
    .n_outputs = 6,
    .outputs = outputs,
    .rhs = dyn_cart_rhs,
    .compute_outputs = cart_outputs,
    .prepare = cart_prepare,
    .warn = cart_warn,
    .t0 = 0.0,
    .t1 = 10.0,
    .step = 0.04, /* the homework's Ts: the sample grid, and fixed-step methods' step */
    .method = "dp45", /* the homework's modified Euler (problem 4c): --method heun */
    .rtol = 1e-8,
    .atol = 1e-10,
    .n_inputs = 2,
    .inputs = inputs,
    .set_input = cart_set_input,
    .n_events = 1,
    .events = events,
};
