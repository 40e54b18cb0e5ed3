/* SPDX-License-Identifier: BSD-3-Clause */
/* plane_common.c — what the two plane models (homework problem 3) share: the Newton–Euler
 * equations of the plane for a given orientation matrix, its energy, and its parameters.
 *
 * Following the homework's plane_equationsofmotion.m with the conventions of dynkit/mech.h
 * (R maps N coordinates to B coordinates):
 *   rp_N      = rs_N + R^T rp_B                       spring point P in N
 *   Fspring_N = -k (|rp_N| - l0) rp_N / |rp_N|        spring from A (the origin) to P
 *   Fg_N      = (0, 0, m g)                           gravity along +Z (down)
 *   dds_N     = (Fspring_N + Fg_N) / m                Newton, in N
 *   M_B       = rp_B x (R Fspring_N)                  moment about S, in B
 *   I domega  = M_B - omega x I omega                 Euler's equations, in B
 * (the Newton–Euler equations of a rigid body; Greenwood, "Advanced Dynamics", ch. 4).
 */
#include "models/plane_common.h"

#include <math.h>
#include <stdio.h>

#include "dynkit/mech.h"

#define PAR(member) offsetof(dyn_plane_par, member)
#define DYN_PLANE_IP (1.0 * 0.1 * 0.1)
#define DYN_PLANE_IXX (0.5 * DYN_PLANE_IP)

const dyn_param dyn_plane_params[DYN_PLANE_N_PARAMS] = {
    {"g", "m/s^2", "acceleration of gravity, along +Z (down)", PAR(g), 9.81},
    {"l0", "m", "rest length of the spring", PAR(l0), 1.0},
    {"k", "N/m", "stiffness of the spring", PAR(k), 20.0},
    {"px", "m", "spring attachment point P: x in B", PAR(px), 0.1},
    {"py", "m", "spring attachment point P: y in B", PAR(py), 0.0},
    {"pz", "m", "spring attachment point P: z in B", PAR(pz), -0.1},
    {"m", "kg", "mass of the plane", PAR(m), 1.0},
    /* Ip = 1*.1^2 as in simulate_plane.m (0.010000000000000002 in double), Ixx = Iyy = Ip/2 */
    {"Ixx", "kg m^2", "moment of inertia about the body x axis (.5*Ip, Ip = 1*.1^2)", PAR(Ixx),
     DYN_PLANE_IXX},
    {"Iyy", "kg m^2", "moment of inertia about the body y axis (.5*Ip)", PAR(Iyy),
     DYN_PLANE_IXX},
    {"Izz", "kg m^2", "moment of inertia about the body z axis (Ip)", PAR(Izz), DYN_PLANE_IP},
    {"length_plane", "m", "length of the plane's body (animation only)", PAR(length_plane),
     2.0},
    {"wingspan", "m", "wingspan (animation only)", PAR(wingspan), 4.0},
    {"height_fin", "m", "height of the fin (animation only)", PAR(height_fin), 0.5},
    {"wing_x", "m", "r_wingcenter, S to the wing centre: x in B (animation only)",
     PAR(wing_x), 0.1},
    {"wing_y", "m", "r_wingcenter: y in B (animation only)", PAR(wing_y), 0.0},
    {"wing_z", "m", "r_wingcenter: z in B (animation only)", PAR(wing_z), -0.01},
};

static int check_nonnegative(const char *name, double value, char *err, size_t errlen)
{
    if (isfinite(value) && value >= 0.0)
        return 0;
    if (err && errlen)
        snprintf(err, errlen, "parameter %s must be a finite number >= 0 (got %g)", name,
                 value);
    return 1;
}

static int check_finite(const char *name, double value, char *err, size_t errlen)
{
    if (isfinite(value))
        return 0;
    if (err && errlen)
        snprintf(err, errlen, "parameter %s must be a finite number (got %g)", name, value);
    return 1;
}

int dyn_plane_prepare(void *par, char *err, size_t errlen)
{
    const dyn_plane_par *p = par;
    return dyn_check_positive("m", p->m, err, errlen) ||
           dyn_check_positive("Ixx", p->Ixx, err, errlen) ||
           dyn_check_positive("Iyy", p->Iyy, err, errlen) ||
           dyn_check_positive("Izz", p->Izz, err, errlen) ||
           check_nonnegative("k", p->k, err, errlen) ||
           check_nonnegative("l0", p->l0, err, errlen) || check_finite("g", p->g, err, errlen) ||
           check_finite("px", p->px, err, errlen) || check_finite("py", p->py, err, errlen) ||
           check_finite("pz", p->pz, err, errlen) ||
           check_nonnegative("length_plane", p->length_plane, err, errlen) ||
           check_nonnegative("wingspan", p->wingspan, err, errlen) ||
           check_nonnegative("height_fin", p->height_fin, err, errlen) ||
           check_finite("wing_x", p->wing_x, err, errlen) ||
           check_finite("wing_y", p->wing_y, err, errlen) ||
           check_finite("wing_z", p->wing_z, err, errlen);
}

void dyn_plane_spring_point(const dyn_plane_par *p, const double rs_N[3], const double R[9],
                            double rp_N[3])
{
    const double rp_B[3] = {p->px, p->py, p->pz};
    double d[3];
    dyn_mat3_tmul_vec(R, rp_B, d);
    dyn_vec3_add(rs_N, d, rp_N);
}

int dyn_plane_accel(const dyn_plane_par *p, const double rs_N[3], const double R[9],
                    const double omega_B[3], double dds_N[3], double domega_B[3])
{
    const double rp_B[3] = {p->px, p->py, p->pz};
    const double inertia[3] = {p->Ixx, p->Iyy, p->Izz};
    double rp_N[3], u[3], Fspring_N[3], Ftot_N[3], Fspring_B[3], M_B[3];
    dyn_plane_spring_point(p, rs_N, R, rp_N);
    double len = dyn_vec3_normalize(rp_N, u); /* u = rp_N / |rp_N| */
    if (len == 0.0)
        return DYN_PLANE_ERR_SPRING;
    dyn_vec3_scale(u, -p->k * (len - p->l0), Fspring_N);
    const double Fg_N[3] = {0.0, 0.0, p->m * p->g};
    dyn_vec3_add(Fspring_N, Fg_N, Ftot_N);
    if (dyn_rigid_linear_accel(p->m, Ftot_N, dds_N))
        return DYN_PLANE_ERR_PARAM;
    dyn_mat3_mul_vec(R, Fspring_N, Fspring_B);
    dyn_vec3_cross(rp_B, Fspring_B, M_B);
    if (dyn_rigid_euler_accel(inertia, omega_B, M_B, domega_B))
        return DYN_PLANE_ERR_PARAM;
    return 0;
}

double dyn_plane_energy_at(const dyn_plane_par *p, const double rs_N[3], const double R[9],
                           const double v_N[3], const double omega_B[3])
{
    const double inertia[3] = {p->Ixx, p->Iyy, p->Izz};
    double rp_N[3];
    dyn_plane_spring_point(p, rs_N, R, rp_N);
    double stretch = dyn_vec3_norm(rp_N) - p->l0;
    return dyn_rigid_translational_energy(p->m, v_N) +
           dyn_rigid_rotational_energy(inertia, omega_B) + 0.5 * p->k * stretch * stretch -
           p->m * p->g * rs_N[2];
}

void dyn_plane_seed_state(const void *par, double *y12)
{
    const dyn_plane_par *p = par;
    for (int i = 0; i < 12; i++)
        y12[i] = 0.0;
    y12[0] = -p->px;
    y12[1] = DYN_PLANE_SY0;
    y12[2] = p->l0 + p->m * p->g / p->k;
    y12[6] = DYN_PLANE_DSX0;
    y12[11] = DYN_PLANE_OMEGAZ0;
}
