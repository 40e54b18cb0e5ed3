/* SPDX-License-Identifier: BSD-3-Clause */
/* Right-hand sides timed by the benchmarks, written once as static inline functions so the
 * same arithmetic is called through a dyn_rhs_fn pointer by the library and inlined into
 * the hand-written loops.
 *
 * - van der Pol (homework problem 2): 2 states, mu = 1, y0 = (2, 0), h = 0.01, 1500 steps.
 *   A cheap right-hand side: the step loop itself is what is measured.
 * - model plane on a spring (homework problem 3): 12 states (sX, sY, sZ, psi, theta, phi,
 *   dsX, dsY, dsZ, omegax, omegay, omegaz); spring from the origin to the body point P,
 *   gravity along +Z, Euler's equations in the body frame, type I Euler-angle rates
 *   (Greenwood 3.16); h = 0.01, 500 steps. The right-hand side (six trigonometric calls, a
 *   square root, divisions) dominates. Self-contained on purpose: it does not use the mech
 *   layer, so the benchmark measures the ODE core only.
 * - Arenstorf orbit (HNW I sec. II.0): 4 states, the same arithmetic as the library's
 *   dyn_arenstorf_rhs (src/models/arenstorf.c), for the adaptive work-precision runs.
 * - Kepler's two-body problem (HNW I sec. II.10, problem "KEPL" with e = 0.9), 4 states,
 *   y0 = (1 - e, 0, 0, sqrt((1 + e)/(1 - e))): an orbit of period 2 pi, so that after one
 *   period the exact solution is y0 again; the step must shrink by ~ 60 at the pericentre.
 *   For the step-size controllers of the adaptive pairs (dynkit's only).
 * - van der Pol's Jacobian, for the stiff runs (mu = 1000).
 * The header is also compiled as C++ (the Boost.Odeint benchmark), hence BENCH_RESTRICT.
 */
#ifndef DYNKIT_BENCH_SYSTEMS_H
#define DYNKIT_BENCH_SYSTEMS_H

#include <math.h>

/* the small right-hand sides: in C always inlined, also into the large step loop of
 * dyn_solve_inline, whose size stops gcc's inliner otherwise (dynkit/solve_inline.h asks
 * this of a right-hand side: DYN_INLINE_RHS); the C++ peer (Boost) compiles them as before,
 * plain inline, as its templates are written to be used */
#if defined(__GNUC__) && !defined(__cplusplus)
#define BENCH_SMALL_EVAL static inline __attribute__((always_inline))
#else
#define BENCH_SMALL_EVAL static inline
#endif

#ifdef __cplusplus
#define BENCH_RESTRICT __restrict
#else
#define BENCH_RESTRICT restrict

#endif

/* ---- van der Pol ---- */
typedef struct bench_vdp_par {
    double mu;
} bench_vdp_par;

BENCH_SMALL_EVAL void bench_vdp_eval(const double *BENCH_RESTRICT y, double *BENCH_RESTRICT dydt,
                                  const bench_vdp_par *BENCH_RESTRICT p)
{
    dydt[0] = y[1];
    dydt[1] = p->mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
}

/* df/dy (2 x 2, row-major) */
static inline void bench_vdp_jac(const double *BENCH_RESTRICT y, double *BENCH_RESTRICT J,
                                 const bench_vdp_par *BENCH_RESTRICT p)
{
    J[0] = 0.0;
    J[1] = 1.0;
    J[2] = -2.0 * p->mu * y[0] * y[1] - 1.0;
    J[3] = p->mu * (1.0 - y[0] * y[0]);
}

/* ---- model plane hanging on a spring ---- */
typedef struct bench_plane_par {
    double m;             /* [kg] */
    double Ixx, Iyy, Izz; /* [kg m^2] principal moments about the body axes */
    double g;             /* [m/s^2] along +Z */
    double l0, k;         /* [m], [N/m] spring rest length and stiffness */
    double rp[3];         /* [m] spring attachment point P in the body frame */
} bench_plane_par;

static inline void bench_plane_eval(const double *BENCH_RESTRICT x, double *BENCH_RESTRICT dx,
                                    const bench_plane_par *BENCH_RESTRICT p)
{
    const double psi = x[3], th = x[4], ph = x[5];
    const double wx = x[9], wy = x[10], wz = x[11];
    const double cps = cos(psi), sps = sin(psi);
    const double cth = cos(th), sth = sin(th);
    const double cph = cos(ph), sph = sin(ph);
    /* R = R_phi R_theta R_psi maps N coordinates to B coordinates (row-major 3 x 3). */
    const double R[9] = {cth * cps,
                         cth * sps,
                         -sth,
                         -cph * sps + sph * sth * cps,
                         cph * cps + sph * sth * sps,
                         sph * cth,
                         sph * sps + cph * sth * cps,
                         -sph * cps + cph * sth * sps,
                         cph * cth};
    /* P in N: s + R^T rp; the spring pulls P towards the origin A. */
    double d[3];
    for (int i = 0; i < 3; i++)
        d[i] = x[i] + R[0 + i] * p->rp[0] + R[3 + i] * p->rp[1] + R[6 + i] * p->rp[2];
    const double L = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double scale = -p->k * (L - p->l0) / L;
    const double Fs[3] = {scale * d[0], scale * d[1], scale * d[2]};
    /* Spring force in B and its moment about the centre of mass. */
    double FB[3];
    for (int i = 0; i < 3; i++)
        FB[i] = R[3 * i] * Fs[0] + R[3 * i + 1] * Fs[1] + R[3 * i + 2] * Fs[2];
    const double Mx = p->rp[1] * FB[2] - p->rp[2] * FB[1];
    const double My = p->rp[2] * FB[0] - p->rp[0] * FB[2];
    const double Mz = p->rp[0] * FB[1] - p->rp[1] * FB[0];
    /* Euler-angle rates (type I, singular at theta = +-90 deg). */
    const double dpsi = (wy * sph + wz * cph) / cth;
    dx[0] = x[6];
    dx[1] = x[7];
    dx[2] = x[8];
    dx[3] = dpsi;
    dx[4] = wy * cph - wz * sph;
    dx[5] = wx + dpsi * sth;
    dx[6] = Fs[0] / p->m;
    dx[7] = Fs[1] / p->m;
    dx[8] = (Fs[2] + p->m * p->g) / p->m;
    dx[9] = (Mx - (p->Izz - p->Iyy) * wy * wz) / p->Ixx;
    dx[10] = (My - (p->Ixx - p->Izz) * wz * wx) / p->Iyy;
    dx[11] = (Mz - (p->Iyy - p->Ixx) * wx * wy) / p->Izz;
}

/* The plane's parameters and initial state used by the benchmarks. */
static inline void bench_plane_defaults(bench_plane_par *p, double *y0)
{
    const bench_plane_par par = {1.0, 0.005, 0.005, 0.01, 9.81, 1.0, 20.0, {0.1, 0.0, -0.1}};
    const double x0[12] = {-0.1, 0.2, 1.0 + 9.81 / 20.0,
                           0.0,  0.0, 0.0,
                           2.0,  0.0, 0.0,
                           0.0,  0.0, 3.14159265358979323846 / 40.0};
    *p = par;
    for (int i = 0; i < 12; i++)
        y0[i] = x0[i];
}

/* ---- Arenstorf orbit (restricted three-body problem, rotating frame) ---- */
typedef struct bench_arenstorf_par {
    double mu; /* Moon / (Earth + Moon) */
} bench_arenstorf_par;

BENCH_SMALL_EVAL void bench_arenstorf_eval(const double *BENCH_RESTRICT y, double *BENCH_RESTRICT dydt,
                                        const bench_arenstorf_par *BENCH_RESTRICT p)
{
    const double mu = p->mu, mup = 1.0 - mu;
    const double x1 = y[0] + mu, x2 = y[0] - mup;
    const double r1s = x1 * x1 + y[1] * y[1], r2s = x2 * x2 + y[1] * y[1];
    const double D1 = r1s * sqrt(r1s), D2 = r2s * sqrt(r2s);
    dydt[0] = y[2];
    dydt[1] = y[3];
    dydt[2] = y[0] + 2.0 * y[3] - mup * x1 / D1 - mu * x2 / D2;
    dydt[3] = y[1] - 2.0 * y[2] - mup * y[1] / D1 - mu * y[1] / D2;
}

/* ---- Kepler's problem, unit mass parameter ---- */
BENCH_SMALL_EVAL void bench_kepler_eval(const double *BENCH_RESTRICT y, double *BENCH_RESTRICT dydt,
                                     const void *p)
{
    (void)p;
    const double r2 = y[0] * y[0] + y[1] * y[1], r3 = r2 * sqrt(r2);
    dydt[0] = y[2];
    dydt[1] = y[3];
    dydt[2] = -y[0] / r3;
    dydt[3] = -y[1] / r3;
}
#define BENCH_KEPLER_E 0.9
#endif
