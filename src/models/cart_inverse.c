/* SPDX-License-Identifier: BSD-3-Clause */
/* Inverse dynamics of the three-wheeled cart (homework problem 4a, 4b): the body-frame
 * forces at the front wheel that produce given accelerations (the seed's hint
 * inversedynamics_cart), and the prescribed backward motion with its force table.
 *
 * Inverse dynamics. With a_x = c ddsX + s ddsY and a_y = -s ddsX + c ddsY the acceleration
 * of S in body coordinates (s = sin(theta), c = cos(theta)) and lambda the lateral force of
 * the ground on the rear axle:
 *     Newton along body x:  m a_x = Fx
 *     Newton along body y:  m a_y = Fy + lambda
 *     Euler about S:        Is domega = (l/2) (Fy - lambda)
 * Eliminating lambda: Fx = m a_x, Fy = (m a_y + 2 Is domega / l) / 2. These are rows 1 and
 * 2 of A ddq = b (cart.h) solved for Fx, Fy; row 3 (the constraint) is not checked.
 *
 * Prescribed motion (problem 4a): sX = -v0 t, theta = A sin(w t), A = pi/8, w = 2 pi f:
 *     omega = A w cos(w t),  domega = -A w^2 sin(w t),  dsX = -v0,  ddsX = 0.
 * The constraint dsY c - dsX s = (l/2) omega gives
 *     dsY = ((l/2) omega + dsX s) / c,
 * and its time derivative, ddsY c - dsY s omega - ddsX s - dsX c omega = (l/2) domega,
 *     ddsY = ((l/2) domega + ddsX s + omega (dsX c + dsY s)) / c
 * (the third row of A ddq = b). At t = 0: dsY(0) = (l/2) A w = pi^2/2 m/s for l = 2 m,
 * f = 2 Hz. The position sY = integral of dsY from 0 splits into
 *     (l/2) integral omega / cos(theta) dt = (l/2) atanh(sin(theta))   (exact)
 *     -v0 integral tan(A sin(w tau)) dtau                               (quadrature)
 * The integrand g(tau) = tan(A sin(w tau)) is odd and has period T = 1/f, with
 * g(T - tau) = -g(tau); so its integral I is even, T-periodic and I(T - t) = I(t), and I(t)
 * only needs the quadrature over [0, r] with r = (|t| mod T) folded into [0, T/2]. There it
 * is analytic in a strip of half-width acosh(4)/w around the real axis (tan has its poles
 * where A sin(w tau) = +-pi/2, i.e. sin(w tau) = +-4), and 10-point Gauss-Legendre on
 * panels of T/16 converges far past double precision (the error of n-point Gauss on a
 * function analytic in the Bernstein ellipse of parameter rho decays like rho^(-2n):
 * Trefethen, "Is Gauss quadrature better than Clenshaw-Curtis?", SIAM Review 50, 2008).
 */
#include <math.h>
#include <stdio.h>

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "dynkit/cart.h"

void dyn_cart_inverse_forces(const dyn_cart_par *p, double theta, double ddsX, double ddsY,
                             double domega, double *Fx, double *Fy)
{
    const double s = sin(theta), c = cos(theta);
    const double ax = c * ddsX + s * ddsY;
    const double ay = -s * ddsX + c * ddsY;
    *Fx = p->m * ax;
    *Fy = 0.5 * (p->m * ay + 2.0 * p->Is * domega / p->length_cart);
}

/* 10-point Gauss-Legendre nodes (positive half) and weights on [-1, 1]. */
static const double gl_x[5] = {0.97390652851717172, 0.86506336668898451, 0.67940956829902441,
                               0.43339539412924719, 0.14887433898163122};
static const double gl_w[5] = {0.066671344308688138, 0.14945134915058059, 0.21908636251598204,
                               0.26926671930999635, 0.29552422471475287};

/* Integral of tan(A sin(w tau)) over [0, t] for f >= 0 (w = 2 pi f). */
static double tan_theta_integral(double f, double t)
{
    if (f == 0.0 || t == 0.0)
        return 0.0;
    const double A = DYN_CART_THETA_AMPLITUDE, w = 2.0 * DYN_PI * f;
    const double T = 1.0 / f;
    double r = fmod(fabs(t), T);
    if (r > 0.5 * T)
        r = T - r;
    if (r == 0.0)
        return 0.0;
    const int panels = (int)ceil(8.0 * r / (0.5 * T));
    const double h = r / panels;
    double sum = 0.0;
    for (int j = 0; j < panels; j++) {
        const double mid = (j + 0.5) * h, half = 0.5 * h;
        double part = 0.0;
        for (int i = 0; i < 5; i++)
            part += gl_w[i] * (tan(A * sin(w * (mid - half * gl_x[i]))) +
                               tan(A * sin(w * (mid + half * gl_x[i]))));
        sum += half * part;
    }
    return sum;
}

int dyn_cart_prescribed_rates(const dyn_cart_par *p, double v0, double f, double t,
                              double rates[3], double accel[3])
{
    if (!isfinite(t) || !isfinite(v0) || !isfinite(f) || f < 0.0)
        return DYN_ERR_ARG;
    const double A = DYN_CART_THETA_AMPLITUDE, w = 2.0 * DYN_PI * f;
    const double half_l = 0.5 * p->length_cart;
    const double phase = w * t;
    const double theta = A * sin(phase);
    const double omega = A * w * cos(phase);
    const double domega = -A * w * w * sin(phase);
    const double s = sin(theta), c = cos(theta);
    const double dsX = -v0, ddsX = 0.0;
    const double dsY = (half_l * omega + dsX * s) / c;
    rates[0] = dsX;
    rates[1] = dsY;
    rates[2] = omega;
    if (accel) {
        accel[0] = ddsX;
        accel[1] = (half_l * domega + ddsX * s + omega * (dsX * c + dsY * s)) / c;
        accel[2] = domega;
    }
    return 0;
}

int dyn_cart_prescribed(const dyn_cart_par *p, double v0, double f, double t, double state[6],
                        double accel[3])
{
    double rates[3];
    if (dyn_cart_prescribed_rates(p, v0, f, t, rates, accel))
        return DYN_ERR_ARG;
    const double theta = DYN_CART_THETA_AMPLITUDE * sin(2.0 * DYN_PI * f * t);
    state[0] = -v0 * t + 0.0; /* + 0.0: +0 rather than -0 at t = 0 */
    state[1] = 0.5 * p->length_cart * atanh(sin(theta)) - v0 * tan_theta_integral(f, t);
    state[2] = theta;
    state[3] = rates[0];
    state[4] = rates[1];
    state[5] = rates[2];
    return 0;
}

int dyn_cart_force_table(const dyn_cart_par *p, double v0, double f, long N, double Ts,
                         double *table, char *err, size_t errlen)
{
    const char *bad = NULL;
    if (N < 1)
        bad = "the number of samples N must be >= 1";
    else if (!(isfinite(Ts) && Ts > 0.0))
        bad = "the sample time Ts must be a finite number > 0";
    else if (!isfinite(v0))
        bad = "the speed v0 must be a finite number";
    else if (!(isfinite(f) && f >= 0.0))
        bad = "the frequency f must be a finite number >= 0";
    else if (!table)
        bad = "no table to write to";
    if (bad) {
        if (err && errlen)
            snprintf(err, errlen, "cart force table: %s", bad);
        return DYN_ERR_ARG;
    }
    for (long k = 0; k < N; k++) {
        double state[6], acc[3];
        const double t = (double)k * Ts;
        dyn_cart_prescribed(p, v0, f, t, state, acc);
        table[3 * k] = t;
        dyn_cart_inverse_forces(p, state[2], acc[0], acc[1], acc[2], &table[3 * k + 1],
                                &table[3 * k + 2]);
        if (!isfinite(table[3 * k + 1]) || !isfinite(table[3 * k + 2]) ||
            !isfinite(state[4])) {
            if (err && errlen)
                snprintf(err, errlen,
                         "cart force table: the forces are not finite at t = %s s (Fx = %g "
                         "N, Fy = %g N): v0 = %g m/s and f = %g Hz are too large for doubles",
                         dyn_shortest(t).s, table[3 * k + 1], table[3 * k + 2], v0, f);
            return DYN_ERR_ARG;
        }
    }
    return 0;
}
