/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/cart.h — the three-wheeled cart of homework problem 4: a rigid block in the
 * horizontal plane with a non-holonomic rear axle, forward and inverse dynamics.
 *
 * Geometry (body frame B: x forward, y to the left, origin at the centre of mass S): the
 * rear wheels A, B at (-l/2, -+d/2) roll along x without slip, so the rear axle has no
 * lateral velocity; the front omniwheel C at (l/2, 0) transmits the applied forces Fx, Fy
 * (body frame). Generalised coordinates q = (sX, sY, theta): position of S in the space
 * frame N and the heading angle. The constraint (rear axle point at x = -l/2):
 *     dsY cos(theta) - dsX sin(theta) = (l/2) omega.
 * Lagrange with one multiplier lambda (the lateral force of the ground on the rear axle,
 * along body y) gives the seed's cart_equationsofmotion, A ddq = b:
 *     [ m           0            -(2 Is/l) sin(theta) ] [ddsX  ]   [ Fx cos(theta) - 2 Fy sin(theta)       ]
 *     [ 0           m             (2 Is/l) cos(theta) ] [ddsY  ] = [ Fx sin(theta) + 2 Fy cos(theta)       ]
 *     [ sin(theta) -cos(theta)    l/2                 ] [domega]   [ -omega (dsX cos(theta) + dsY sin(theta)) ]
 * (the third row, printed "1/2" in the seed, is l/2; the seed's initial state satisfies
 * the constraint only with l/2), and lambda = Fy - 2 Is domega / l.
 */
#ifndef DYNKIT_CART_H
#define DYNKIT_CART_H

#include <stddef.h>

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parameters of the cart. The first seven members are parameters (settable by name); Is is
 * derived by dyn_cart_prepare; the force table is optional input. */
typedef struct dyn_cart_par {
    double m;           /* [kg] mass (20) */
    double length_cart; /* [m] l, length: rear axle at x = -l/2, front wheel at x = +l/2 (2) */
    double width_cart;  /* [m] d, width: only enters Is (1) */
    double Fx;          /* [N] constant body-x force at C when there is no table (-50) */
    double Fy;          /* [N] constant body-y force at C when there is no table (0) */
    double mu;          /* [1] friction coefficient of the rear wheels (0.7) */
    double g;           /* [m/s^2] gravity, for the friction limit (9.81) */
    /* derived: the moment of inertia about S of a homogeneous block, m (l^2 + d^2) / 12
     * [kg m^2]; dyn_cart_prepare sets it, so it follows m, l and d */
    double Is;
    /* optional force input, set with dyn_cart_set_forces (NULL: the constants Fx, Fy) */
    const double *forces; /* (n_forces x 3) rows (t, Fx, Fy), body frame, borrowed */
    long n_forces;
    dyn_interp interp;    /* how the table is read between samples */
    double forces_dt;     /* sample time if the table is uniform, else 0 (derived) */
} dyn_cart_par;

extern const dyn_model dyn_model_cart;

/* Check the parameters (m, l, d > 0, mu, g >= 0, finite) and derive Is. 0 or non-zero with
 * a message in err. dyn_model_default_params calls it; call it again after changing m, l, d. */
int dyn_cart_prepare(dyn_cart_par *p, char *err, size_t errlen);

/* Attach a force table (rows x 3: t, Fx, Fy; t finite and strictly increasing, forces
 * finite; rows >= 1) to p, read with interp. The table is borrowed, not copied. A table is
 * uniform when every t_k is within 1e-9 dt of t_0 + k dt, dt = (t_last - t_0)/(rows - 1).
 * Returns 0, or DYN_ERR_ARG with a message naming the bad row in err (p unchanged).
 * table == NULL with rows == 0 detaches the table (constant Fx, Fy again). */
int dyn_cart_set_forces(dyn_cart_par *p, const double *table, long rows, dyn_interp interp,
                        char *err, size_t errlen);

/* The applied body-frame forces at time t: the constants Fx, Fy, or the table read with
 * p->interp. Hold: the nearest sample, index round((t - t_0)/dt) for a uniform table (the
 * homework's index = round(t/Ts)), else the nearest sample time with ties to the later
 * sample. Linear: straight line between the neighbouring samples. Before the first and
 * after the last sample the end values are held. */
void dyn_cart_forces_at(const dyn_cart_par *p, double t, double *Fx, double *Fy);

/* Solve A ddq = b (closed form) for the accelerations acc = (ddsX, ddsY, domega) at a state
 * (only theta, dsX, dsY, omega enter) under body forces Fx, Fy at C. Never fails for
 * prepared parameters (det A = m (m l/2 + 2 Is/l) > 0). */
void dyn_cart_accelerations(const dyn_cart_par *p, double theta, double dsX, double dsY,
                            double omega, double Fx, double Fy, double acc[3]);

/* Right-hand side for y = (sX, sY, theta, dsX, dsY, omega); par is a prepared dyn_cart_par.
 * Always returns 0. */
int dyn_cart_rhs(double t, const double *y, double *dydt, void *par);

/* Lateral constraint force on the rear axle [N] (body y, from the ground), given the
 * applied Fy and the angular acceleration: lambda = Fy - 2 Is domega / l. */
double dyn_cart_lambda(const dyn_cart_par *p, double Fy, double domega);
/* The friction limit of the rear wheels [N]: mu (2/3) m g (two of three wheels carry
 * two thirds of the weight). */
double dyn_cart_friction_limit(const dyn_cart_par *p);
/* Constraint residual [m/s]: dsY cos(theta) - dsX sin(theta) - (l/2) omega of y (6). */
double dyn_cart_constraint_residual(const dyn_cart_par *p, const double *y);
/* The lateral velocity dsY that satisfies the constraint for theta, dsX, omega:
 * ((l/2) omega + dsX sin(theta)) / cos(theta) (NaN-free only for cos(theta) != 0). */
double dyn_cart_constraint_dsY(const dyn_cart_par *p, double theta, double dsX, double omega);
/* Kinetic energy [J] of y: m (dsX^2 + dsY^2)/2 + Is omega^2/2. */
double dyn_cart_kinetic_energy(const dyn_cart_par *p, const double *y);

/* ---- inverse dynamics (problem 4a, 4b), cart_inverse.c ---- */

/* The homework's inversedynamics_cart: body-frame forces (Fx, Fy) at C that produce the
 * accelerations ddsX, ddsY, domega at heading theta (the constraint is not checked):
 * Newton along body x and y and Euler about S with lambda eliminated,
 *     Fx = m a_x,   Fy = (m a_y + 2 Is domega / l) / 2,
 * with (a_x, a_y) the acceleration of S in body coordinates. */
void dyn_cart_inverse_forces(const dyn_cart_par *p, double theta, double ddsX, double ddsY,
                             double domega, double *Fx, double *Fy);

/* Amplitude of the prescribed heading of problem 4a [rad]: theta = (pi/8) sin(2 pi f t). */
#define DYN_CART_THETA_AMPLITUDE (DYN_PI / 8.0)

/* The velocities of the prescribed motion of problem 4a at time t, without the quadrature of
 * sY: rates (3) = (dsX, dsY, omega) and, if accel is not NULL, accel (3) = (ddsX, ddsY,
 * domega); the same numbers as dyn_cart_prescribed's. 0, or DYN_ERR_ARG as there. */
int dyn_cart_prescribed_rates(const dyn_cart_par *p, double v0, double f, double t,
                              double rates[3], double accel[3]);
/* The prescribed motion of problem 4a at time t: sX = -v0 t, theta = (pi/8) sin(2 pi f t),
 * dsY from the constraint and sY = integral of dsY from 0 (sY(0) = 0): the part
 * (l/2) omega / cos(theta) integrates in closed form to (l/2) atanh(sin(theta)), the rest
 * -v0 tan(theta) by composite 10-point Gauss-Legendre over the reduced period (error at
 * rounding level: within 2e-15 m of a 40-digit quadrature for the homework's motion over
 * 0..4.99 s). Writes state (6) = (sX, sY, theta, dsX, dsY,
 * omega) and, if accel is not NULL, accel (3) = (ddsX, ddsY, domega), all analytic.
 * Returns 0, or DYN_ERR_ARG for non-finite t, v0 or f, or f < 0. */
int dyn_cart_prescribed(const dyn_cart_par *p, double v0, double f, double t, double state[6],
                        double accel[3]);

/* The force table of problem 4b: N samples at t_k = k Ts (k = 0 .. N-1), rows (t_k, Fx,
 * Fy) of the inverse dynamics at the exact prescribed motion, into table (N x 3, caller-
 * owned). Returns 0, or DYN_ERR_ARG with a message in err (N >= 1, Ts > 0 finite, ...). */
int dyn_cart_force_table(const dyn_cart_par *p, double v0, double f, long N, double Ts,
                         double *table, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_CART_H */
