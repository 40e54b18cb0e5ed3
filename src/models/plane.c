/* SPDX-License-Identifier: BSD-3-Clause */
/* plane.c — the model plane on a spring of homework problem 3 with type I Euler angles:
 * the homework's plane_equationsofmotion.m completed. The Newton–Euler accelerations are in
 * plane_common.c; the orientation is R = R_phi R_theta R_psi (N->B, dyn_euler_to_mat) and
 * the Euler angles evolve by Greenwood, "Advanced Dynamics", eq. (3.16):
 *   dpsi = sec(theta) (wy sin(phi) + wz cos(phi)), dtheta = wy cos(phi) - wz sin(phi),
 *   dphi = wx + dpsi sin(theta),
 * singular at theta = +-pi/2 (the model warns within 5 degrees; plane_quat.c has none).
 * Defaults are simulate_plane.m's: rk4 with Ts = 0.01 s over 0..5 s.
 */
#include <math.h>
#include <stddef.h>

#include "dynkit/mech.h"
#include "dynkit/plane.h"
#include "models/plane_common.h"

/* Warn when theta is within this distance [rad] of +-pi/2 (5 degrees). */
#define PLANE_WARN_MARGIN (5.0 * DYN_PI / 180.0)

int dyn_plane_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_plane_par *p = par;
    const double *rs_N = y, *e = y + 3, *v_N = y + 6, *omega_B = y + 9;
    double R[9];
    (void)t;
    if (cos(e[1]) == 0.0)
        return DYN_PLANE_ERR_GIMBAL;
    dyn_euler_to_mat(e, R);
    int status = dyn_plane_accel(p, rs_N, R, omega_B, dydt + 6, dydt + 9);
    if (status)
        return status;
    /* the status of dyn_euler_rates (|cos(theta)| <= 1e-12) is not a failure here: the
     * rates are finite unless cos(theta) == 0, which is checked above */
    (void)dyn_euler_rates(e, omega_B, dydt + 3);
    dydt[0] = v_N[0];
    dydt[1] = v_N[1];
    dydt[2] = v_N[2];
    return 0;
}

double dyn_plane_energy(const dyn_plane_par *p, const double *y)
{
    double R[9];
    dyn_euler_to_mat(y + 3, R);
    return dyn_plane_energy_at(p, y, R, y + 6, y + 9);
}

double dyn_plane_spring_length(const dyn_plane_par *p, const double *y)
{
    double R[9], rp_N[3];
    dyn_euler_to_mat(y + 3, R);
    dyn_plane_spring_point(p, y, R, rp_N);
    return dyn_vec3_norm(rp_N);
}

double dyn_plane_vertical_angular_momentum(const dyn_plane_par *p, const double *y)
{
    const double inertia[3] = {p->Ixx, p->Iyy, p->Izz};
    double R[9], L_B[3], L_N[3];
    dyn_euler_to_mat(y + 3, R);
    dyn_rigid_angular_momentum(inertia, y + 9, L_B);
    dyn_mat3_tmul_vec(R, L_B, L_N);
    return p->m * (y[0] * y[7] - y[1] * y[6]) + L_N[2];
}

void dyn_plane_state_to_quat(const double *y12, double *y13)
{
    for (int i = 0; i < 3; i++) {
        y13[i] = y12[i];
        y13[7 + i] = y12[6 + i];
        y13[10 + i] = y12[9 + i];
    }
    dyn_euler_to_quat(y12 + 3, y13 + 3);
}

int dyn_plane_quat_to_state(const double *y13, double *y12)
{
    for (int i = 0; i < 3; i++) {
        y12[i] = y13[i];
        y12[6 + i] = y13[7 + i];
        y12[9 + i] = y13[10 + i];
    }
    return dyn_quat_to_euler(y13 + 3, y12 + 3);
}

static int plane_outputs(double t, const double *y, const void *par, double *out)
{
    const dyn_plane_par *p = par;
    (void)t;
    out[0] = dyn_plane_energy(p, y);
    out[1] = dyn_plane_spring_length(p, y);
    out[2] = dyn_euler_singularity_distance(y[4]);
    return 0;
}

static const char *plane_warn(double t, const double *y, const void *par)
{
    (void)t;
    (void)par;
    if (dyn_euler_singularity_distance(y[4]) < PLANE_WARN_MARGIN)
        return "theta is within 5 degrees of +-90 degrees, the singularity of the Euler "
               "angles: the Euler-angle rates (sec(theta)) become large and the results lose "
               "accuracy; the model plane-quat has no such singularity";
    return NULL;
}

static const dyn_var states[] = {
    {"sX", "m", "centre of mass S: X in N (A, the spring's ceiling point, is the origin)"},
    {"sY", "m", "centre of mass S: Y in N"},
    {"sZ", "m", "centre of mass S: Z in N (down, along gravity)"},
    {"psi", "rad", "type I Euler angle about Z"},
    {"theta", "rad", "type I Euler angle about the new Y' (singular at +-pi/2)"},
    {"phi", "rad", "type I Euler angle about the new x"},
    {"dsX", "m/s", "velocity of S: X in N"},
    {"dsY", "m/s", "velocity of S: Y in N"},
    {"dsZ", "m/s", "velocity of S: Z in N"},
    {"omegax", "rad/s", "angular velocity of B in N: x in B"},
    {"omegay", "rad/s", "angular velocity of B in N: y in B"},
    {"omegaz", "rad/s", "angular velocity of B in N: z in B"},
};
static const double y0[] = {
    DYN_PLANE_SX0, DYN_PLANE_SY0, DYN_PLANE_SZ0, 0.0, 0.0, 0.0,
    DYN_PLANE_DSX0, 0.0, 0.0, 0.0, 0.0, DYN_PLANE_OMEGAZ0,
};
static const dyn_var outputs[] = {
    {"energy", "J",
     "1/2 m |ds|^2 + 1/2 omega.I omega + k/2 (|rp| - l0)^2 - m g sZ (conserved)"},
    {"spring_length", "m", "|rp_N|, the distance from A to the spring point P"},
    {"theta_margin", "rad", "distance of theta to the nearest singular value +-pi/2 (+k pi)"},
};

const dyn_model dyn_model_plane = {
    .name = "plane",
    .title = "model plane on a spring, type I Euler angles (homework problem 3)",
    .description =
        "A rigid plane (mass m, principal inertia Ixx, Iyy, Izz about its centre of mass S)\n"
        "hangs from the ceiling point A = origin of N (Z down) by a spring (k, l0) attached\n"
        "at P, rp_B = (px, py, pz) in the body frame B.\n"
        "  R = R_phi R_theta R_psi (maps N to B),  rp_N = rs_N + R^T rp_B\n"
        "  Fspring_N = -k (|rp_N| - l0) rp_N/|rp_N|,  Fg_N = (0, 0, m g)\n"
        "  dds_N = (Fspring_N + Fg_N) / m                       (Newton, in N)\n"
        "  M_B = rp_B x (R Fspring_N)                           (moment about S, in B)\n"
        "  Ixx domegax = Mx + (Iyy - Izz) omegay omegaz, and cyclic  (Euler, in B)\n"
        "  dpsi = sec(theta) (omegay sin(phi) + omegaz cos(phi))\n"
        "  dtheta = omegay cos(phi) - omegaz sin(phi)\n"
        "  dphi = omegax + dpsi sin(theta)                      (Greenwood (3.16))\n"
        "The Euler-angle rates are singular at theta = +-90 deg: the model warns within\n"
        "5 deg (output theta_margin); plane-quat is the same plane without the singularity.\n"
        "The default initial state is simulate_plane.m's: sX = -px, sY = 0.2,\n"
        "sZ = l0 + m g/k (it follows --set), level attitude, dsX = 2, omegaz = pi/40.",
    .n_states = 12,
    .states = states,
    .y0 = y0,
    .initial_state = dyn_plane_seed_state,
    .n_params = DYN_PLANE_N_PARAMS,
    .params = dyn_plane_params,
    .par_size = sizeof(dyn_plane_par),
    .n_outputs = 3,
    .outputs = outputs,
    .rhs = dyn_plane_rhs,
    .compute_outputs = plane_outputs,
    .prepare = dyn_plane_prepare,
    .warn = plane_warn,
    .t0 = 0.0,
    .t1 = 5.0,
    .step = 0.01, /* the seed's Ts: the sample grid, and fixed-step methods' step */
    .method = "dp45", /* the seed's ode45 run; its RK4 and Euler: --method rk4, euler */
    .rtol = 1e-8,
    .atol = 1e-10,
};
