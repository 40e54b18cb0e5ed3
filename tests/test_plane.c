/* SPDX-License-Identifier: BSD-3-Clause */
/* test_plane.c — tests of the plane models of homework problem 3 (dynkit/plane.h): the
 * right-hand side at hand-computed states (hanging equilibrium, a state with a known
 * moment and gyroscopic terms, the failure cases), the two formulations (Euler angles and
 * quaternion) against each other, the invariants of the exact dynamics (energy, angular
 * momentum about the vertical through A) with the observed 4th order of RK4, the warning
 * near theta = +-90 deg, the parameters through the registry, and the CLI.
 *
 * A fact these tests pin down: the default motion itself (not only Euler's method) passes
 * within about 2.2 deg of theta = +90 deg at t = 0.825 s (the plane pitches about its
 * equilibrium attitude theta = +45 deg with an amplitude of about 45 deg). The Euler-angle
 * rates are amplified by sec(theta) ~ 26 there, so the Euler-angle model is markedly less
 * accurate than the quaternion model at equal step; tolerances below reflect that.
 */
#define _POSIX_C_SOURCE 200809L /* popen for the CLI test */

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/dynkit.h"
#include "dynkit/mech.h"
#include "dynkit/plane.h"
#include "test_cli_run.h"

/* Fail with both values when |a - b| > tol. */
#define assert_close(a, b, tol)                                                              \
    do {                                                                                     \
        double a_ = (a), b_ = (b), t_ = (tol);                                               \
        if (!(fabs(a_ - b_) <= t_)) {                                                        \
            print_error("%s = %.17g, %s = %.17g, |diff| = %.3g > %.3g\n", #a, a_, #b, b_,    \
                        fabs(a_ - b_), t_);                                                  \
            fail();                                                                          \
        }                                                                                    \
    } while (0)

/* Fail unless lo <= x <= hi, printing x. */
#define assert_between(x, lo, hi)                                                            \
    do {                                                                                     \
        double x_ = (x);                                                                     \
        if (!(x_ >= (lo) && x_ <= (hi))) {                                                   \
            print_error("%s = %.6g not in [%g, %g]\n", #x, x_, (double)(lo), (double)(hi));  \
            fail();                                                                          \
        }                                                                                    \
    } while (0)

/* ---- helpers ---- */

static const dyn_model *model(const char *name)
{
    const dyn_model *m = dyn_model_find(name);
    assert_non_null(m);
    return m;
}

static dyn_plane_par default_par(void)
{
    dyn_plane_par p;
    char err[200];
    assert_int_equal(dyn_model_default_params(model("plane"), &p, err, sizeof err), 0);
    return p;
}

static double angle_diff(double a, double b)
{
    return fabs(remainder(a - b, 2.0 * DYN_PI));
}

/* What a run records at every sample: the 12-state (Euler angles; converted for
 * plane-quat), invariants and the closest approach to the Euler-angle singularity. */
typedef struct recorder {
    const dyn_plane_par *par;
    int quat;          /* 1 for plane-quat states */
    double *traj;      /* (samples x 12) or NULL */
    long samples;
    double E0, LZ0;
    double max_dE, max_dLZ, max_qnorm_err;
    double min_margin, t_min_margin;
    int warned;        /* the model's warn fired at some sample */
} recorder;

static int record(long k, double t, const double *y, void *ctx)
{
    recorder *r = ctx;
    double y12[12];
    if (r->quat) {
        dyn_plane_quat_to_state(y, y12);
        double n = sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]);
        if (fabs(n - 1.0) > r->max_qnorm_err)
            r->max_qnorm_err = fabs(n - 1.0);
    } else {
        memcpy(y12, y, sizeof y12);
        if (dyn_model_plane.warn(t, y, r->par))
            r->warned = 1;
    }
    double E = r->quat ? dyn_plane_quat_energy(r->par, y) : dyn_plane_energy(r->par, y);
    double LZ = dyn_plane_vertical_angular_momentum(r->par, y12);
    double margin = dyn_euler_singularity_distance(y12[4]);
    if (k == 0) {
        r->E0 = E;
        r->LZ0 = LZ;
        r->min_margin = margin;
    }
    if (fabs(E - r->E0) > r->max_dE)
        r->max_dE = fabs(E - r->E0);
    if (fabs(LZ - r->LZ0) > r->max_dLZ)
        r->max_dLZ = fabs(LZ - r->LZ0);
    if (margin < r->min_margin) {
        r->min_margin = margin;
        r->t_min_margin = t;
    }
    if (r->traj)
        memcpy(r->traj + 12 * k, y12, sizeof y12);
    r->samples = k + 1;
    return 0;
}

/* Run model name from its default state over [0, 5] s with method and step h;
 * traj (may be NULL) needs round(5/h) + 1 rows of 12. */
static recorder run(const char *name, const char *method, double h, double *traj)
{
    static dyn_plane_par par; /* outlives the recorder's use within one test */
    const dyn_model *m = model(name);
    const dyn_tableau *tab = dyn_method_find(method);
    assert_non_null(tab);
    par = default_par();
    recorder r = {.par = &par, .quat = m->n_states == 13, .traj = traj};
    dyn_system sys = {m->rhs, m->n_states, &par};
    double *work = malloc(dyn_fixed_work_size(tab, m->n_states) * sizeof *work);
    assert_non_null(work);
    double y[13];
    dyn_fixed_opts opts = {0};
    opts.output = record;
    opts.output_ctx = &r;
    dyn_result res;
    int status = dyn_fixed_solve(tab, &sys, 0.0, 5.0, h, m->y0, y, work, &opts, &res);
    free(work);
    if (status != DYN_OK)
        print_error("%s %s h=%g: %s\n", name, method, h, res.message);
    assert_int_equal(status, DYN_OK);
    assert_int_equal(r.samples, lround(5.0 / h) + 1);
    return r;
}

/* The hanging equilibrium: P straight below A at the static spring length l0 + m g/k,
 * S straight below P. Z points down, so "below" is +Z. rp_B = (px, 0, pz) with px = -pz
 * points forward and up at 45 deg in B; it is vertical (R^T rp_B = (0, 0, -|rp_B|)) when
 * the third column of R, (-s_theta, s_phi c_theta, c_phi c_theta), equals -rp_B/|rp_B| =
 * (-1, 0, 1)/sqrt(2): theta = +pi/4 (nose up), phi = 0, psi arbitrary. */
static void hanging_state(const dyn_plane_par *p, double psi, double y[12])
{
    double L = p->l0 + p->m * p->g / p->k;
    double rp = hypot(p->px, p->pz);
    const double s[12] = {0, 0, L + rp, psi, DYN_PI / 4.0, 0, 0, 0, 0, 0, 0, 0};
    memcpy(y, s, sizeof s);
}

/* ---- registry and parameters ---- */

static void test_registry_and_defaults(void **state)
{
    (void)state;
    const dyn_model *m = model("plane");
    const dyn_model *mq = model("plane-quat");
    assert_ptr_equal(m, &dyn_model_plane);
    assert_ptr_equal(mq, &dyn_model_plane_quat);

    const char *names[] = {"sX",  "sY",  "sZ",  "psi",    "theta",  "phi",
                           "dsX", "dsY", "dsZ", "omegax", "omegay", "omegaz"};
    assert_int_equal(m->n_states, 12);
    for (int i = 0; i < 12; i++)
        assert_string_equal(m->states[i].name, names[i]);
    const char *qnames[] = {"sX",  "sY",  "sZ",  "qw",     "qx",     "qy",    "qz",
                            "dsX", "dsY", "dsZ", "omegax", "omegay", "omegaz"};
    assert_int_equal(mq->n_states, 13);
    for (int i = 0; i < 13; i++)
        assert_string_equal(mq->states[i].name, qnames[i]);

    /* simulate_plane.m, value by value */
    dyn_plane_par p = default_par();
    double Ip = 1 * .1 * .1; /* 0.010000000000000002, as MATLAB computes 1*.1^2 */
    assert_true(p.g == 9.81 && p.l0 == 1 && p.k == 20 && p.m == 1);
    assert_true(p.px == .1 && p.py == 0 && p.pz == -.1);
    assert_true(p.Ixx == .5 * Ip && p.Iyy == .5 * Ip && p.Izz == Ip); /* bit for bit */
    assert_true(p.length_plane == 2 && p.wingspan == 4 && p.height_fin == .5);
    assert_true(p.wing_x == .1 && p.wing_y == 0 && p.wing_z == -.01);
    for (int i = 0; i < m->n_params; i++) {
        assert_non_null(m->params[i].unit);
        assert_true(strlen(m->params[i].description) > 0);
    }

    /* initial state of simulate_plane.m from these parameters */
    const double y0[12] = {-p.px, .2, p.l0 + p.m * p.g / p.k, 0, 0, 0, 2, 0, 0, 0, 0,
                           DYN_PI / 4 / 10};
    for (int i = 0; i < 12; i++)
        assert_true(m->y0[i] == y0[i]);
    double y13[13];
    dyn_plane_state_to_quat(m->y0, y13);
    for (int i = 0; i < 13; i++)
        assert_true(mq->y0[i] == y13[i]); /* the same physical state */

    assert_true(m->t0 == 0 && m->t1 == 5 && m->step == 0.01);
    /* adaptive by default (the seed's ode45 run); rk4 and euler are asked for by name */
    assert_string_equal(m->method, "dp45");
    assert_string_equal(mq->method, "dp45");
    assert_true(m->rtol == 1e-8 && m->atol == 1e-10);
    assert_true(mq->t1 == 5 && mq->step == 0.01);

    /* outputs by name */
    assert_int_equal(dyn_model_output_index(m, "energy"), 0);
    assert_int_equal(dyn_model_output_index(m, "spring_length"), 1);
    assert_int_equal(dyn_model_output_index(m, "theta_margin"), 2);
    const char *qout[] = {"energy", "spring_length", "psi", "theta", "phi"};
    for (int i = 0; i < 5; i++)
        assert_true(dyn_model_output_index(mq, qout[i]) >= 0);

    /* a parameter set by name reaches the dynamics: doubling k doubles the spring force */
    int ik = dyn_model_param_index(m, "k");
    assert_true(ik >= 0);
    dyn_model_set_param(m, &p, ik, 40.0);
    assert_true(p.k == 40.0);
    double d20[12], d40[12];
    dyn_plane_par p20 = default_par();
    assert_int_equal(dyn_plane_rhs(0, m->y0, d20, &p20), 0);
    assert_int_equal(dyn_plane_rhs(0, m->y0, d40, &p), 0);
    /* dds = F_spring/m + g e_Z */
    for (int i = 6; i < 9; i++) {
        double g = (i == 8) ? p.g : 0.0;
        assert_close(d40[i] - g, 2.0 * (d20[i] - g), 1e-13);
    }

    /* prepare rejects what the dynamics cannot take */
    char err[200] = "";
    dyn_model_set_param(m, &p, dyn_model_param_index(m, "Iyy"), 0.0);
    assert_int_not_equal(m->prepare(&p, err, sizeof err), 0);
    assert_non_null(strstr(err, "Iyy"));
    p = default_par();
    p.m = -1;
    assert_int_not_equal(m->prepare(&p, err, sizeof err), 0);
}

/* ---- the right-hand side at hand-computed states ---- */

static void test_rhs_hanging_equilibrium(void **state)
{
    (void)state;
    dyn_plane_par p = default_par();
    for (int j = 0; j < 3; j++) {
        double psi = -2.0 + 1.7 * j; /* any heading */
        double y[12], dy[12], y13[13], dy13[13];
        hanging_state(&p, psi, y);
        assert_close(dyn_plane_spring_length(&p, y), p.l0 + p.m * p.g / p.k, 1e-15);
        assert_int_equal(dyn_plane_rhs(0, y, dy, &p), 0);
        for (int i = 0; i < 12; i++)
            assert_close(dy[i], 0.0, 1e-12); /* forces balance; S, P, A aligned: no moment */
        dyn_plane_state_to_quat(y, y13);
        assert_int_equal(dyn_plane_quat_rhs(0, y13, dy13, &p), 0);
        for (int i = 0; i < 13; i++)
            assert_close(dy13[i], 0.0, 1e-12);
    }
    /* and nowhere else nearby: a pitch of 0.01 rad gives a restoring moment
     * m g |SP| sin(0.01) (SP = sqrt(0.02) m) about the body y axis */
    double y[12], dy[12];
    hanging_state(&p, 0.3, y);
    y[4] += 0.01;
    /* keep P where it was so that the spring force is still -m g e_Z */
    double R0[9], R1[9], e0[3] = {0.3, DYN_PI / 4.0, 0}, a[3], b[3];
    const double rp_B[3] = {p.px, p.py, p.pz};
    dyn_euler_to_mat(e0, R0);
    dyn_euler_to_mat(y + 3, R1);
    dyn_mat3_tmul_vec(R0, rp_B, a);
    dyn_mat3_tmul_vec(R1, rp_B, b);
    for (int i = 0; i < 3; i++)
        y[i] += a[i] - b[i];
    assert_int_equal(dyn_plane_rhs(0, y, dy, &p), 0);
    for (int i = 6; i < 9; i++)
        assert_close(dy[i], 0.0, 1e-12);
    double M = p.m * p.g * hypot(p.px, p.pz) * sin(0.01);
    assert_close(dy[10], -M / p.Iyy, 1e-10); /* back towards theta = pi/4 */
    assert_close(dy[9], 0.0, 1e-12);
    assert_close(dy[11], 0.0, 1e-12);
}

/* Level attitude, P straight below A at l0 + m g/k (spring force -m g e_Z, so no net
 * force), body rates (1, 2, 3): by hand
 *   M_B = rp_B x (0, 0, -m g) = (0, -pz... ) = (0, px m g, 0) = (0, 0.981, 0) N m
 *   dwx = (Iyy - Izz) wy wz / Ixx = -0.005*6/0.005 = -6
 *   dwy = (0.981 + (Izz - Ixx) wz wx) / Iyy = (0.981 + 0.015)/0.005 = 199.2
 *   dwz = (Ixx - Iyy) wx wy / Izz = 0
 *   (dpsi, dtheta, dphi) = (wz, wy, wx) at psi = theta = phi = 0. */
static void test_rhs_by_hand(void **state)
{
    (void)state;
    dyn_plane_par p = default_par();
    double L = p.l0 + p.m * p.g / p.k;
    const double y[12] = {-p.px, 0, L - p.pz, 0, 0, 0, 0.5, -0.25, 0.125, 1, 2, 3};
    double dy[12];
    assert_close(dyn_plane_spring_length(&p, y), L, 1e-15);
    assert_int_equal(dyn_plane_rhs(0, y, dy, &p), 0);
    const double expect[12] = {0.5, -0.25, 0.125, 3, 2, 1, 0, 0, 0, -6, 199.2, 0};
    for (int i = 0; i < 12; i++)
        assert_close(dy[i], expect[i], 1e-12);

    /* the quaternion model: the same accelerations, dq = 1/2 (1,0,0,0) (x) (0, w) */
    double y13[13], dy13[13];
    dyn_plane_state_to_quat(y, y13);
    assert_int_equal(dyn_plane_quat_rhs(0, y13, dy13, &p), 0);
    const double dq[4] = {0, 0.5, 1, 1.5};
    for (int i = 0; i < 4; i++)
        assert_close(dy13[3 + i], dq[i], 1e-15);
    for (int i = 0; i < 3; i++) {
        assert_close(dy13[i], dy[i], 0.0);
        assert_close(dy13[7 + i], dy[6 + i], 1e-12);
        assert_close(dy13[10 + i], dy[9 + i], 1e-12);
    }

    /* Greenwood (3.16) at theta = pi/3, phi = 0: dpsi = wz/cos(theta) = 6, dtheta = wy,
     * dphi = wx + dpsi sin(theta) */
    double y2[12];
    memcpy(y2, y, sizeof y2);
    y2[4] = DYN_PI / 3.0;
    assert_int_equal(dyn_plane_rhs(0, y2, dy, &p), 0);
    assert_close(dy[3], 6.0, 1e-13);
    assert_close(dy[4], 2.0, 1e-15);
    assert_close(dy[5], 1.0 + 6.0 * sqrt(3.0) / 2.0, 1e-13);
}

/* The two right-hand sides describe the same motion: at a general state the derivative of
 * the quaternion state equals the chain rule through q(e) (central difference along de). */
static void test_rhs_formulations_consistent(void **state)
{
    (void)state;
    dyn_plane_par p = default_par();
    const double y[12] = {0.3, -0.2, 1.2, 0.7, -0.4, 1.1, 0.5, 1.5, -0.3, 2.0, -3.0, 0.7};
    double dy[12], y13[13], dy13[13];
    assert_int_equal(dyn_plane_rhs(0, y, dy, &p), 0);
    dyn_plane_state_to_quat(y, y13);
    assert_int_equal(dyn_plane_quat_rhs(0, y13, dy13, &p), 0);
    for (int i = 0; i < 3; i++) {
        assert_close(dy13[i], dy[i], 0.0);
        assert_close(dy13[7 + i], dy[6 + i], 1e-13);
        assert_close(dy13[10 + i], dy[9 + i], 1e-12);
    }
    const double eps = 1e-5;
    double ep[3], em[3], qp[4], qm[4];
    for (int i = 0; i < 3; i++) {
        ep[i] = y[3 + i] + eps * dy[3 + i];
        em[i] = y[3 + i] - eps * dy[3 + i];
    }
    dyn_euler_to_quat(ep, qp);
    dyn_euler_to_quat(em, qm);
    for (int i = 0; i < 4; i++)
        assert_close(dy13[3 + i], (qp[i] - qm[i]) / (2 * eps), 1e-8);
    /* and the energies agree */
    assert_close(dyn_plane_quat_energy(&p, y13), dyn_plane_energy(&p, y), 1e-14);
}

static void test_rhs_failures(void **state)
{
    (void)state;
    dyn_plane_par p = default_par();
    double dy[13];
    /* P at A: level attitude with S at -rp_B */
    double y[12] = {-p.px, -p.py, -p.pz, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    assert_int_equal(dyn_plane_rhs(0, y, dy, &p), DYN_PLANE_ERR_SPRING);
    double y13[13];
    dyn_plane_state_to_quat(y, y13);
    assert_int_equal(dyn_plane_quat_rhs(0, y13, dy, &p), DYN_PLANE_ERR_SPRING);
    /* a zero quaternion has no orientation */
    y13[0] = 0.5;
    y13[3] = y13[4] = y13[5] = y13[6] = 0.0;
    assert_int_equal(dyn_plane_quat_rhs(0, y13, dy, &p), DYN_PLANE_ERR_QUAT);
    /* a non-unit quaternion is the same orientation */
    double y12b[12], y13b[13], d1[13], d2[13];
    hanging_state(&p, 0.2, y12b);
    y12b[11] = 1.0;
    dyn_plane_state_to_quat(y12b, y13b);
    assert_int_equal(dyn_plane_quat_rhs(0, y13b, d1, &p), 0);
    for (int i = 3; i < 7; i++)
        y13b[i] *= 1.5;
    assert_int_equal(dyn_plane_quat_rhs(0, y13b, d2, &p), 0);
    for (int i = 7; i < 13; i++)
        assert_close(d2[i], d1[i], 1e-13);
    /* theta = pi/2 rounded to double: cos(theta) = 6.1e-17, not 0, so the rhs does not
     * fail; dpsi = sec(theta) (...) is huge and finite */
    double ys[12] = {0, 0, 1.5, 0, DYN_PI / 2, 0, 0, 0, 0, 0, 0, 1.0};
    assert_true(cos(ys[4]) != 0.0);
    assert_int_equal(dyn_plane_rhs(0, ys, dy, &p), 0);
    assert_true(isfinite(dy[3]) && fabs(dy[3]) > 1e15);
}

/* ---- invariants and accuracy over the homework's run ---- */

/* Energy is conserved by the exact dynamics; RK4's drift is O(h^4). */
static void test_energy_conservation(void **state)
{
    (void)state;
    recorder q1 = run("plane-quat", "rk4", 1e-3, NULL);
    recorder q2 = run("plane-quat", "rk4", 5e-4, NULL);
    recorder e1 = run("plane", "rk4", 1e-3, NULL);
    recorder e2 = run("plane", "rk4", 5e-4, NULL);
    double E0 = fabs(q1.E0);
    assert_close(q1.E0, e1.E0, 1e-15 * E0);
    print_message("energy drift (max |E - E0|/|E0| over 5 s, rk4): plane-quat h=1e-3 %.3g, "
                  "5e-4 %.3g; plane h=1e-3 %.3g, 5e-4 %.3g\n",
                  q1.max_dE / E0, q2.max_dE / E0, e1.max_dE / E0, e2.max_dE / E0);
    /* quaternion model: < 1e-8 at h = 1e-3 (measured 6.9e-11) */
    assert_true(q1.max_dE / E0 < 1e-8);
    /* Euler-angle model: the passage near theta = 90 deg dominates; measured 5.7e-8 at
     * h = 1e-3 and 3.4e-9 at h = 5e-4 */
    assert_true(e1.max_dE / E0 < 1e-7);
    assert_true(e2.max_dE / E0 < 1e-8);
    /* halving h divides the drift by about 2^4 = 16 (plane: measured 16.9) */
    assert_between(e1.max_dE / e2.max_dE, 12.0, 22.0);
    /* at least 4th order for the quaternion model (measured 35: its leading error term
     * is small here) */
    assert_true(q1.max_dE / q2.max_dE > 12.0);
}

/* Angular momentum about the vertical through A: gravity is along Z and the spring force
 * passes through A, so L_Z = m (r_S x v_S)_Z + (R^T I omega_B)_Z is conserved. */
static void test_vertical_angular_momentum(void **state)
{
    (void)state;
    dyn_plane_par p = default_par();
    /* by hand at the initial state: m (sX dsY - sY dsX) + Izz omegaz */
    assert_close(dyn_plane_vertical_angular_momentum(&p, dyn_model_plane.y0),
                 1.0 * (-0.1 * 0 - 0.2 * 2) + 0.01 * DYN_PI / 40, 1e-16);
    recorder q = run("plane-quat", "rk4", 1e-3, NULL);
    recorder e = run("plane", "rk4", 2.5e-4, NULL);
    print_message("max |L_Z - L_Z0| over 5 s, rk4: plane-quat h=1e-3 %.3g, plane h=2.5e-4 "
                  "%.3g (L_Z0 = %.6g)\n", q.max_dLZ, e.max_dLZ, q.LZ0);
    assert_true(q.max_dLZ < 1e-9);
    assert_true(e.max_dLZ < 1e-9);
    /* the quaternion norm drifts little with RK4 at this step */
    assert_true(q.max_qnorm_err < 1e-9);
}

/* Both formulations converge to the same motion: samples agree to 1e-8 at h = 1e-4, and
 * their difference shrinks at 4th order. Also pins down the near-singular passage. */
static void test_models_agree(void **state)
{
    (void)state;
    const double hs[3] = {1e-3, 5e-4, 1e-4};
    double dpos[3], dang[3];
    for (int j = 0; j < 3; j++) {
        long n = lround(5.0 / hs[j]) + 1;
        double *a = malloc((size_t)n * 12 * sizeof *a), *b = malloc((size_t)n * 12 * sizeof *b);
        assert_true(a && b);
        recorder ra = run("plane", "rk4", hs[j], a);
        recorder rb = run("plane-quat", "rk4", hs[j], b);
        dpos[j] = dang[j] = 0.0;
        double dvel = 0.0;
        for (long k = 0; k < n; k++) {
            const double *ya = a + 12 * k, *yb = b + 12 * k;
            for (int i = 0; i < 3; i++) {
                dpos[j] = fmax(dpos[j], fabs(ya[i] - yb[i]));
                dang[j] = fmax(dang[j], angle_diff(ya[3 + i], yb[3 + i]));
                dvel = fmax(dvel, fabs(ya[6 + i] - yb[6 + i]));
                dvel = fmax(dvel, fabs(ya[9 + i] - yb[9 + i]));
            }
            dang[j] = fmax(dang[j], dyn_principal_angle_euler(ya + 3, yb + 3, NULL));
        }
        print_message("plane vs plane-quat, rk4 h=%g: max |d pos| %.3g m, max |d angle| %.3g "
                      "rad, max |d rate| %.3g; closest to theta=+-90 deg: %.4f rad at t=%.3f s\n",
                      hs[j], dpos[j], dang[j], dvel, rb.min_margin, rb.t_min_margin);
        /* the motion passes within 2.2 deg of theta = +90 deg near t = 0.825 s: found by
         * the singularity-free model, the same with both, and the Euler-angle model warns */
        assert_between(rb.min_margin, 0.035, 0.042);
        assert_between(rb.t_min_margin, 0.80, 0.85);
        assert_close(ra.min_margin, rb.min_margin, 2e-3);
        assert_true(ra.warned);
        if (j == 2) {
            assert_true(dpos[j] < 1e-8);
            assert_true(dang[j] < 1e-8);
            assert_true(dvel < 1e-7);
        }
        free(a);
        free(b);
    }
    /* 4th order: halving h divides the difference by about 16 (measured about 20) */
    assert_between(dpos[0] / dpos[1], 12.0, 25.0);
    assert_between(dang[0] / dang[1], 12.0, 25.0);
}

/* ---- warnings and outputs ---- */

static void test_warning_near_singularity(void **state)
{
    (void)state;
    dyn_plane_par p = default_par();
    const double deg = DYN_PI / 180.0;
    double y[12];
    memcpy(y, dyn_model_plane.y0, sizeof y);
    const struct {
        double theta;
        int warns;
    } cases[] = {{0, 0},          {84 * deg, 0},         {86 * deg, 1},  {-86 * deg, 1},
                 {90 * deg, 1},   {-84 * deg, 0},        {95.5 * deg, 0}, {94.5 * deg, 1},
                 {180 * deg, 0},  {266 * deg, 1}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        y[4] = cases[i].theta;
        const char *w = dyn_model_plane.warn(0, y, &p);
        if (cases[i].warns != (w != NULL))
            print_error("theta = %g deg\n", cases[i].theta / deg);
        assert_int_equal(cases[i].warns, w != NULL);
        if (w)
            assert_non_null(strstr(w, "plane-quat"));
        double out[3];
        assert_int_equal(dyn_model_plane.compute_outputs(0, y, &p, out), 0);
        assert_close(out[2], fabs(remainder(cases[i].theta - DYN_PI / 2, DYN_PI)), 1e-12);
    }
    /* Euler's method at the homework's step passes much closer (DESIGN "Plane run length") */
    recorder eu = run("plane", "euler", 0.01, NULL);
    print_message("euler h=0.01: closest theta margin %.4f rad at t=%.2f s\n", eu.min_margin,
                  eu.t_min_margin);
    assert_true(eu.warned);
    assert_true(eu.min_margin < 5 * deg);
}

static void test_outputs(void **state)
{
    (void)state;
    dyn_plane_par p = default_par();
    const double y[12] = {0.3, -0.2, 1.2, 0.7, -0.4, 1.1, 0.5, 1.5, -0.3, 2.0, -3.0, 0.7};
    double out[3], y13[13], outq[6], back[12];
    assert_int_equal(dyn_model_plane.compute_outputs(0, y, &p, out), 0);
    assert_close(out[0], dyn_plane_energy(&p, y), 0.0);
    assert_close(out[1], dyn_plane_spring_length(&p, y), 0.0);
    assert_close(out[2], DYN_PI / 2 - 0.4, 1e-15);
    /* energy by hand from its parts */
    double R[9], rpN[3];
    const double rpB[3] = {p.px, p.py, p.pz};
    dyn_euler_to_mat(y + 3, R);
    dyn_mat3_tmul_vec(R, rpB, rpN);
    dyn_vec3_add(rpN, y, rpN);
    double L = dyn_vec3_norm(rpN);
    double E = 0.5 * p.m * (0.25 + 2.25 + 0.09) +
               0.5 * (p.Ixx * 4.0 + p.Iyy * 9.0 + p.Izz * 0.49) +
               0.5 * p.k * (L - p.l0) * (L - p.l0) - p.m * p.g * 1.2;
    assert_close(out[0], E, 1e-14);

    dyn_plane_state_to_quat(y, y13);
    assert_int_equal(dyn_model_plane_quat.compute_outputs(0, y13, &p, outq), 0);
    assert_close(outq[0], out[0], 1e-14);
    assert_close(outq[1], out[1], 1e-15);
    for (int i = 0; i < 3; i++)
        assert_close(outq[2 + i], y[3 + i], 1e-14); /* psi, theta, phi back */
    assert_close(outq[5], 0.0, 1e-15);
    assert_int_equal(dyn_plane_quat_to_state(y13, back), 0);
    for (int i = 0; i < 12; i++)
        assert_close(back[i], y[i], 1e-14);
    /* R(q) is the Euler-angle R */
    double Rq[9];
    assert_int_equal(dyn_quat_to_mat(y13 + 3, Rq), 0);
    for (int i = 0; i < 9; i++)
        assert_close(Rq[i], R[i], 1e-15);
}

/* ---- the command line ---- */

/* The stdout of cmd, which must exit with status 0. */
static char *capture(const char *cmd)
{
    int status;
    char *out = cli_capture(cmd, &status);
    assert_int_equal(status, 0);
    return out;
}

static void test_cli(void **state)
{
    (void)state;
    char *s = capture(DYNKIT_CLI " run plane --final 2>/dev/null");
    const char *header = "t,sX,sY,sZ,psi,theta,phi,dsX,dsY,dsZ,omegax,omegay,omegaz\n";
    assert_true(strncmp(s, header, strlen(header)) == 0);
    double v[13];
    const char *row = s + strlen(header);
    int nread = sscanf(row, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0],
                       &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7], &v[8], &v[9], &v[10],
                       &v[11], &v[12]);
    assert_int_equal(nread, 13);
    assert_true(v[0] == 5.0);
    free(s);

    s = capture(DYNKIT_CLI " run plane --method euler --final 2>&1 >/dev/null");
    assert_non_null(strstr(s, "warning"));
    assert_non_null(strstr(s, "plane-quat"));
    free(s);

    s = capture(DYNKIT_CLI " info plane");
    assert_non_null(strstr(s, "Greenwood"));
    assert_non_null(strstr(s, "theta_margin"));
    free(s);

    s = capture(DYNKIT_CLI " run plane-quat --outputs --final");
    assert_non_null(strstr(s, "t,sX,sY,sZ,qw,qx,qy,qz,dsX,dsY,dsZ,omegax,omegay,omegaz,"
                              "energy,spring_length,psi,theta,phi"));
    free(s);
}

/* The default initial state follows the parameters: the spring hangs stretched by the
 * weight (sZ = l0 + m g/k) below A with P straight under the centre of mass (sX = -px), for
 * any k, m and px; both formulations start from the same physical state. */
static void test_initial_state_follows_parameters(void **state)
{
    (void)state;
    dyn_plane_par p;
    char err[256];
    double y12[12], y13[13], back[12];
    assert_int_equal(dyn_model_default_params(&dyn_model_plane, &p, err, sizeof err), 0);
    dyn_model_initial_state(&dyn_model_plane, &p, y12);
    for (int i = 0; i < 12; i++)
        assert_true(y12[i] == dyn_model_plane.y0[i]); /* defaults: the seed's state exactly */
    p.k = 40.0;
    p.m = 2.0;
    p.px = 0.25;
    dyn_model_initial_state(&dyn_model_plane, &p, y12);
    assert_true(y12[0] == -0.25);
    assert_true(fabs(y12[2] - (1.0 + 2.0 * 9.81 / 40.0)) < 1e-15);
    dyn_model_initial_state(&dyn_model_plane_quat, &p, y13);
    assert_int_equal(dyn_plane_quat_to_state(y13, back), 0);
    for (int i = 0; i < 12; i++)
        assert_true(fabs(back[i] - y12[i]) < 1e-15);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_registry_and_defaults),
        cmocka_unit_test(test_rhs_hanging_equilibrium),
        cmocka_unit_test(test_rhs_by_hand),
        cmocka_unit_test(test_rhs_formulations_consistent),
        cmocka_unit_test(test_rhs_failures),
        cmocka_unit_test(test_energy_conservation),
        cmocka_unit_test(test_vertical_angular_momentum),
        cmocka_unit_test(test_models_agree),
        cmocka_unit_test(test_warning_near_singularity),
        cmocka_unit_test(test_outputs),
        cmocka_unit_test(test_cli),
        cmocka_unit_test(test_initial_state_follows_parameters),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
