/* SPDX-License-Identifier: BSD-3-Clause */
/* plane_quat.c — the model plane on a spring of homework problem 3 with a quaternion for the
 * orientation instead of Euler angles, so it has no singularity at theta = +-90 deg.
 * Same Newton–Euler equations and parameters as plane.c (plane_common.c); the orientation
 * matrix is R(q) (N->B, dyn_quat_to_mat, equal to R_phi R_theta R_psi for
 * q = dyn_euler_to_quat(psi, theta, phi)) and q evolves by dq/dt = 1/2 q (x) (0, omega_B)
 * (Markley & Crassidis, "Fundamentals of Spacecraft Attitude Determination and Control",
 * 2014, ch. 3, read with the Hamilton product of dynkit/mech.h).
 * No norm-stabilising term is added: the exact flow keeps |q| = 1, a Runge–Kutta method only
 * approximately. R(q) divides by |q|^2, so the drift of |q| never distorts the orientation;
 * it is exposed as the output quat_norm_error.
 */
#include <math.h>
#include <stddef.h>

#include "dynkit/mech.h"
#include "dynkit/plane.h"
#include "models/plane_common.h"

int dyn_plane_quat_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_plane_par *p = par;
    const double *rs_N = y, *q = y + 3, *v_N = y + 7, *omega_B = y + 10;
    double R[9];
    (void)t;
    if (dyn_quat_to_mat(q, R))
        return DYN_PLANE_ERR_QUAT;
    int status = dyn_plane_accel(p, rs_N, R, omega_B, dydt + 7, dydt + 10);
    if (status)
        return status;
    dyn_quat_derivative(q, omega_B, dydt + 3);
    dydt[0] = v_N[0];
    dydt[1] = v_N[1];
    dydt[2] = v_N[2];
    return 0;
}

double dyn_plane_quat_energy(const dyn_plane_par *p, const double *y)
{
    double R[9];
    dyn_quat_to_mat(y + 3, R);
    return dyn_plane_energy_at(p, y, R, y + 7, y + 10);
}

static int plane_quat_outputs(double t, const double *y, const void *par, double *out)
{
    const dyn_plane_par *p = par;
    const double *q = y + 3;
    double R[9], rp_N[3];
    (void)t;
    if (dyn_quat_to_mat(q, R))
        return 1;
    dyn_plane_spring_point(p, y, R, rp_N);
    out[0] = dyn_plane_energy_at(p, y, R, y + 7, y + 10);
    out[1] = dyn_vec3_norm(rp_N);
    dyn_mat_to_euler(R, out + 2); /* psi, theta, phi */
    out[5] = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]) - 1.0;
    return 0;
}

static const dyn_var states[] = {
    {"sX", "m", "centre of mass S: X in N (A, the spring's ceiling point, is the origin)"},
    {"sY", "m", "centre of mass S: Y in N"},
    {"sZ", "m", "centre of mass S: Z in N (down, along gravity)"},
    {"qw", "1", "orientation quaternion (N axes onto B axes): scalar part"},
    {"qx", "1", "orientation quaternion: x"},
    {"qy", "1", "orientation quaternion: y"},
    {"qz", "1", "orientation quaternion: z"},
    {"dsX", "m/s", "velocity of S: X in N"},
    {"dsY", "m/s", "velocity of S: Y in N"},
    {"dsZ", "m/s", "velocity of S: Z in N"},
    {"omegax", "rad/s", "angular velocity of B in N: x in B"},
    {"omegay", "rad/s", "angular velocity of B in N: y in B"},
    {"omegaz", "rad/s", "angular velocity of B in N: z in B"},
};
/* the state of plane's y0: level attitude, q = dyn_euler_to_quat(0, 0, 0) = (1, 0, 0, 0) */
static const double y0[] = {
    DYN_PLANE_SX0, DYN_PLANE_SY0, DYN_PLANE_SZ0, 1.0, 0.0, 0.0, 0.0,
    DYN_PLANE_DSX0, 0.0, 0.0, 0.0, 0.0, DYN_PLANE_OMEGAZ0,
};
static const dyn_var outputs[] = {
    {"energy", "J",
     "1/2 m |ds|^2 + 1/2 omega.I omega + k/2 (|rp| - l0)^2 - m g sZ (conserved)"},
    {"spring_length", "m", "|rp_N|, the distance from A to the spring point P"},
    {"psi", "rad", "type I Euler angle about Z of q, in (-pi, pi]"},
    {"theta", "rad", "type I Euler angle about Y' of q, in [-pi/2, pi/2]"},
    {"phi", "rad", "type I Euler angle about x of q, in (-pi, pi] (0 at theta = +-pi/2)"},
    {"quat_norm_error", "1", "|q| - 1, the integrator's drift of the quaternion norm"},
};

/* simulate_plane.m's state for the parameters, with the level attitude as a quaternion */
static void plane_quat_seed_state(const void *par, double *y13)
{
    double y12[12];
    dyn_plane_seed_state(par, y12);
    dyn_plane_state_to_quat(y12, y13);
}

const dyn_model dyn_model_plane_quat = {
    .name = "plane-quat",
    .title = "model plane on a spring, quaternion attitude (homework problem 3, no gimbal lock)",
    .description =
        "The plane of the model 'plane' (same parameters, forces and Newton-Euler equations)\n"
        "with its orientation as a quaternion q = (qw, qx, qy, qz) instead of Euler angles:\n"
        "  R = R(q) (maps N to B; = R_phi R_theta R_psi for q = q_Z(psi) q_Y(theta) q_X(phi))\n"
        "  rp_N = rs_N + R^T rp_B,  Fspring_N = -k (|rp_N| - l0) rp_N/|rp_N|\n"
        "  dds_N = (Fspring_N + (0, 0, m g)) / m,  M_B = rp_B x (R Fspring_N)\n"
        "  Ixx domegax = Mx + (Iyy - Izz) omegay omegaz, and cyclic\n"
        "  dq = 1/2 q (x) (0, omega_B)\n"
        "No singularity at theta = +-90 deg. |q| is not forced to 1 (R(q) divides by |q|^2);\n"
        "its drift is the output quat_norm_error. The outputs psi, theta, phi are the Euler\n"
        "angles of q (principal ranges), to compare with the model 'plane' column by column.\n"
        "The default initial state is the plane's default, with q = (1, 0, 0, 0).",
    .n_states = 13,
    .states = states,
    .y0 = y0,
    .initial_state = plane_quat_seed_state,
    .n_params = DYN_PLANE_N_PARAMS,
    .params = dyn_plane_params,
    .par_size = sizeof(dyn_plane_par),
    .n_outputs = 6,
    .outputs = outputs,
    .rhs = dyn_plane_quat_rhs,
    .compute_outputs = plane_quat_outputs,
    .prepare = dyn_plane_prepare,
    .warn = NULL,
    .t0 = 0.0,
    .t1 = 5.0,
    .step = 0.01, /* the seed's Ts: the sample grid, and fixed-step methods' step */
    .method = "dp45", /* the seed's ode45 run; its RK4 and Euler: --method rk4, euler */
    .rtol = 1e-8,
    .atol = 1e-10,
};
