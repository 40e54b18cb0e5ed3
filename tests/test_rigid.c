/* SPDX-License-Identifier: BSD-3-Clause */
/* test_rigid.c — tests of the rigid-body layer (src/rigid, dynkit/mech.h): vector and
 * matrix algebra, the Greenwood N->B rotation convention checked against hand-derived
 * matrices, Euler-angle, matrix and quaternion round trips (including gimbal lock),
 * kinematics cross-checked by finite differences, the principal angle near 0 and pi against
 * analytic values, and the torque-free rigid body integrated with RK4 (analytic precession,
 * conserved energy and angular momentum).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <string.h>

#include "dynkit/mech.h"

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

/* Fail when |a - b| > rel * |b|. */
#define assert_rel(a, b, rel) assert_close((a), (b), (rel) * fabs(b))

/* ---- helpers ---- */

typedef struct rng {
    uint64_t s;
} rng;

static double uniform(rng *r, double lo, double hi)
{
    /* xorshift64*, top 53 bits */
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    uint64_t x = r->s * 2685821657736338717ULL;
    return lo + (hi - lo) * ((double)(x >> 11) * (1.0 / 9007199254740992.0));
}

static void random_euler(rng *r, double theta_max, double e[3])
{
    e[0] = uniform(r, -DYN_PI, DYN_PI);
    e[1] = uniform(r, -theta_max, theta_max);
    e[2] = uniform(r, -DYN_PI, DYN_PI);
}

static void random_unit(rng *r, double n[3])
{
    double v[3];
    do {
        v[0] = uniform(r, -1, 1);
        v[1] = uniform(r, -1, 1);
        v[2] = uniform(r, -1, 1);
    } while (dyn_vec3_norm(v) < 0.1);
    dyn_vec3_normalize(v, n);
}

static void random_quat(rng *r, double q[4])
{
    double v[4];
    do {
        for (int i = 0; i < 4; i++) {
            v[i] = uniform(r, -1, 1);
        }
    } while (sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]) < 0.1);
    dyn_quat_normalize(v, q);
}

static double max_abs_diff(const double *a, const double *b, int n)
{
    double m = 0.0;
    for (int i = 0; i < n; i++) {
        double d = fabs(a[i] - b[i]);
        if (!(d <= m)) {
            m = d;
        }
    }
    return m;
}

/* Difference of two angles modulo 2 pi, in [0, pi]. */
static double angle_diff(double a, double b)
{
    return fabs(remainder(a - b, 2.0 * DYN_PI));
}

static void mat_from_axis_angle(const double n[3], double angle, double R[9])
{
    double q[4];
    dyn_quat_from_axis_angle(n, angle, q);
    assert_int_equal(dyn_quat_to_mat(q, R), 0);
}

/* ---- vectors and matrices ---- */

static void test_vec3_algebra(void **state)
{
    (void)state;
    double x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, out[3];
    dyn_vec3_cross(x, y, out); /* right-handed: x cross y = z */
    assert_true(out[0] == 0.0 && out[1] == 0.0 && out[2] == 1.0);

    double a[3] = {1.5, -2.0, 0.25}, b[3] = {-0.5, 3.0, 4.0}, c[3], d[3];
    dyn_vec3_cross(a, b, c);
    dyn_vec3_cross(b, a, d);
    for (int i = 0; i < 3; i++) {
        assert_close(c[i], -d[i], 0.0); /* anticommutative */
    }
    assert_close(dyn_vec3_dot(c, a), 0.0, 1e-14); /* orthogonal to both factors */
    assert_close(dyn_vec3_dot(c, b), 0.0, 1e-14);
    /* |a x b|^2 + (a.b)^2 = |a|^2 |b|^2 (Lagrange's identity) */
    double na = dyn_vec3_norm(a), nb = dyn_vec3_norm(b), ab = dyn_vec3_dot(a, b);
    assert_rel(dyn_vec3_dot(c, c) + ab * ab, na * na * nb * nb, 1e-15);

    dyn_vec3_cross(a, b, a); /* output aliasing an input */
    assert_true(memcmp(a, c, sizeof c) == 0);

    double p[3] = {3, 4, 12};
    assert_true(dyn_vec3_norm(p) == 13.0);
    double u[3];
    assert_true(dyn_vec3_normalize(p, u) == 13.0);
    assert_close(dyn_vec3_norm(u), 1.0, 1e-16);
    assert_close(u[2], 12.0 / 13.0, 1e-16);
    double z[3] = {0, 0, 0};
    assert_true(dyn_vec3_normalize(z, u) == 0.0);
    assert_true(u[0] == 0.0 && u[1] == 0.0 && u[2] == 0.0);

    double s[3] = {1, 2, 3}, t[3] = {4, 6, 3};
    assert_true(dyn_vec3_distance(s, t) == 5.0);
    dyn_vec3_add(s, t, out);
    assert_true(out[0] == 5.0 && out[1] == 8.0 && out[2] == 6.0);
    dyn_vec3_sub(s, t, out);
    assert_true(out[0] == -3.0 && out[1] == -4.0 && out[2] == 0.0);
    dyn_vec3_scale(s, -2.0, out);
    assert_true(out[0] == -2.0 && out[1] == -4.0 && out[2] == -6.0);
}

static void test_mat3_algebra(void **state)
{
    (void)state;
    const double A[9] = {1, 2, 3, 4, 5, 6, 7, 8, 10};
    const double B[9] = {2, 0, 1, -1, 3, 0, 0, 1, 1};
    /* A B by hand: row1 (1,2,3): (2-2+0, 0+6+3, 1+0+3) = (0, 9, 4), etc. */
    const double AB[9] = {0, 9, 4, 3, 21, 10, 6, 34, 17};
    double C[9], D[9], v[3], w[3];
    dyn_mat3_mul(A, B, C);
    assert_true(max_abs_diff(C, AB, 9) == 0.0);
    assert_close(dyn_mat3_det(A), -3.0, 1e-14); /* 1(50-48) - 2(40-42) + 3(32-35) */
    assert_close(dyn_mat3_det(AB), dyn_mat3_det(A) * dyn_mat3_det(B), 1e-12);

    double Bt[9];
    dyn_mat3_transpose(B, Bt);
    dyn_mat3_mul_bt(A, Bt, D); /* A (B^T)^T = A B */
    assert_true(max_abs_diff(D, AB, 9) == 0.0);
    dyn_mat3_transpose(Bt, Bt); /* in place */
    assert_true(max_abs_diff(Bt, B, 9) == 0.0);

    const double x[3] = {1, -1, 2};
    dyn_mat3_mul_vec(A, x, v);
    assert_true(v[0] == 5.0 && v[1] == 11.0 && v[2] == 19.0);
    double At[9];
    dyn_mat3_transpose(A, At);
    dyn_mat3_tmul_vec(At, x, w); /* (A^T)^T x = A x */
    assert_true(max_abs_diff(v, w, 3) == 0.0);

    double I[9];
    dyn_mat3_identity(I);
    assert_true(dyn_mat3_det(I) == 1.0);
    assert_true(dyn_mat3_orthonormality_error(I) == 0.0);
    /* a shear is not orthonormal: S S^T - I = [0.25 0.5 0; 0.5 0 0; 0 0 0] */
    const double S[9] = {1, 0.5, 0, 0, 1, 0, 0, 0, 1};
    assert_close(dyn_mat3_orthonormality_error(S), 0.5, 0.0);

    dyn_mat3_mul(A, B, C);
    double tmp[9];
    memcpy(tmp, A, sizeof tmp);
    dyn_mat3_mul(tmp, B, tmp); /* aliasing the first factor */
    assert_true(max_abs_diff(tmp, C, 9) == 0.0);
}

/* ---- rotation convention ---- */

static void test_elementary_rotations_by_hand(void **state)
{
    (void)state;
    const double X[3] = {1, 0, 0}, Y[3] = {0, 1, 0};
    double R[9], v[3];

    /* psi = pi/2 about Z turns the x axis onto N's +Y, and the y axis onto N's -X.
     * So N's X axis is the body's -y: v_B = R_psi X_N = (c, -s, 0) = (0, -1, 0). */
    dyn_rot_z(DYN_PI / 2, R);
    dyn_mat3_mul_vec(R, X, v);
    assert_close(v[0], 0.0, 1e-16);
    assert_close(v[1], -1.0, 0.0);
    assert_close(v[2], 0.0, 0.0);
    /* N's Y axis is the body's +x. */
    dyn_mat3_mul_vec(R, Y, v);
    assert_close(v[0], 1.0, 0.0);

    /* theta = pi/2 about Y: x -> -Z, z -> +X, so X_N is the body's +z: (c, 0, s). */
    dyn_rot_y(DYN_PI / 2, R);
    dyn_mat3_mul_vec(R, X, v);
    assert_close(v[0], 0.0, 1e-16);
    assert_close(v[2], 1.0, 0.0);

    /* phi = pi/2 about X: y -> +Z, z -> -Y, so Y_N is the body's -z: (0, c, -s). */
    dyn_rot_x(DYN_PI / 2, R);
    dyn_mat3_mul_vec(R, Y, v);
    assert_close(v[1], 0.0, 1e-16);
    assert_close(v[2], -1.0, 0.0);

    /* Euler (psi, theta, phi) = (pi/2, pi/2, 0): yaw left then nose up (Z points down):
     * x_B = -Z_N, y_B = -X_N, z_B = +Y_N; the rows of R are the B axes in N. */
    const double e[3] = {DYN_PI / 2, DYN_PI / 2, 0};
    const double Rhand[9] = {0, 0, -1, -1, 0, 0, 0, 1, 0};
    dyn_euler_to_mat(e, R);
    assert_close(max_abs_diff(R, Rhand, 9), 0.0, 1e-16);

    /* The same convention through the quaternion: q* v q maps N to B coordinates. */
    const double ez[3] = {DYN_PI / 2, 0, 0};
    double q[4];
    dyn_euler_to_quat(ez, q);
    dyn_quat_rotate_inv(q, X, v);
    assert_close(v[0], 0.0, 1e-15);
    assert_close(v[1], -1.0, 1e-15);
    /* and q v q* turns the body's x (in B) into N's +Y. */
    dyn_quat_rotate(q, X, v);
    assert_close(v[1], 1.0, 1e-15);
}

static void test_euler_matrix_closed_form(void **state)
{
    (void)state;
    rng r = {0x9e3779b97f4a7c15ULL};
    for (int k = 0; k < 200; k++) {
        double e[3], R[9];
        random_euler(&r, 4.0, e);
        double cps = cos(e[0]), sps = sin(e[0]), cth = cos(e[1]), sth = sin(e[1]);
        double cph = cos(e[2]), sph = sin(e[2]);
        const double H[9] = {cth * cps, cth * sps, -sth,
                             sph * sth * cps - cph * sps, sph * sth * sps + cph * cps, sph * cth,
                             cph * sth * cps + sph * sps, cph * sth * sps - sph * cps, cph * cth};
        dyn_euler_to_mat(e, R);
        assert_close(max_abs_diff(R, H, 9), 0.0, 4e-16);
    }
}

static void test_euler_matrix_is_rotation(void **state)
{
    (void)state;
    rng r = {12345};
    for (int k = 0; k < 2000; k++) {
        double e[3], R[9];
        e[0] = uniform(&r, -10, 10);
        e[1] = uniform(&r, -10, 10);
        e[2] = uniform(&r, -10, 10);
        dyn_euler_to_mat(e, R);
        assert_close(dyn_mat3_orthonormality_error(R), 0.0, 1e-15);
        assert_close(dyn_mat3_det(R), 1.0, 1e-15);
    }
}

/* ---- Euler angles, matrices, quaternions: round trips ---- */

static void test_euler_mat_euler_roundtrip(void **state)
{
    (void)state;
    rng r = {777};
    for (int k = 0; k < 2000; k++) {
        double e[3], R[9], f[3];
        random_euler(&r, 1.5, e);
        dyn_euler_to_mat(e, R);
        assert_int_equal(dyn_mat_to_euler(R, f), 0);
        assert_true(f[1] >= -DYN_PI / 2 && f[1] <= DYN_PI / 2);
        assert_true(f[0] > -DYN_PI && f[0] <= DYN_PI && f[2] > -DYN_PI && f[2] <= DYN_PI);
        assert_close(angle_diff(f[0], e[0]), 0.0, 1e-13);
        assert_close(f[1], e[1], 1e-14);
        assert_close(angle_diff(f[2], e[2]), 0.0, 1e-13);
    }
}

static void test_euler_near_gimbal_lock(void **state)
{
    (void)state;
    rng r = {4242};
    const double delta[] = {1e-3, 1e-6, 1e-9, 1e-12, 1e-15, 0.0};
    for (int sgn = -1; sgn <= 1; sgn += 2) {
        for (size_t i = 0; i < sizeof delta / sizeof delta[0]; i++) {
            for (int k = 0; k < 50; k++) {
                double e[3], R[9], f[3], R2[9];
                random_euler(&r, 1.0, e);
                e[1] = sgn * (DYN_PI / 2 - delta[i]);
                dyn_euler_to_mat(e, R);
                int singular = dyn_mat_to_euler(R, f);
                /* the angles rebuild the same orientation to rounding, at every theta */
                dyn_euler_to_mat(f, R2);
                assert_close(max_abs_diff(R, R2, 9), 0.0, 2e-15);
                assert_close(f[1], e[1], 1e-15);
                if (delta[i] >= 1e-3) {
                    assert_int_equal(singular, 0);
                    assert_close(angle_diff(f[0], e[0]), 0.0, 1e-12);
                    assert_close(angle_diff(f[2], e[2]), 0.0, 1e-12);
                }
                if (delta[i] == 0.0) {
                    /* at the singularity: phi = 0, the rotation about the vertical in psi */
                    assert_int_equal(singular, 1);
                    assert_true(f[2] == 0.0);
                    double expect = sgn > 0 ? e[0] - e[2] : e[0] + e[2];
                    assert_close(angle_diff(f[0], expect), 0.0, 1e-15);
                }
            }
        }
    }
}

static void test_euler_quat_matches_matrix(void **state)
{
    (void)state;
    rng r = {99};
    for (int k = 0; k < 2000; k++) {
        double e[3], q[4], Rq[9], Re[9], f[3];
        e[0] = uniform(&r, -7, 7);
        e[1] = uniform(&r, -7, 7);
        e[2] = uniform(&r, -7, 7);
        dyn_euler_to_quat(e, q);
        assert_close(sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]), 1.0, 1e-15);
        assert_int_equal(dyn_quat_to_mat(q, Rq), 0);
        dyn_euler_to_mat(e, Re);
        assert_close(max_abs_diff(Rq, Re, 9), 0.0, 1e-15);
        /* and back to Euler angles, for theta inside (-pi/2, pi/2) */
        random_euler(&r, 1.5, e);
        dyn_euler_to_quat(e, q);
        assert_int_equal(dyn_quat_to_euler(q, f), 0);
        assert_close(angle_diff(f[0], e[0]), 0.0, 1e-13);
        assert_close(f[1], e[1], 1e-14);
        assert_close(angle_diff(f[2], e[2]), 0.0, 1e-13);
    }
}

static void check_quat_roundtrip(const double q[4])
{
    double R[9], p[4];
    assert_int_equal(dyn_quat_to_mat(q, R), 0);
    assert_close(dyn_mat3_orthonormality_error(R), 0.0, 2e-15);
    assert_close(dyn_mat3_det(R), 1.0, 2e-15);
    dyn_mat_to_quat(R, p);
    assert_true(p[0] >= 0.0);
    double s = q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3] * p[3] < 0.0 ? -1.0 : 1.0;
    for (int i = 0; i < 4; i++) {
        assert_close(p[i], s * q[i], 1e-15);
    }
}

static void test_quat_mat_quat_roundtrip(void **state)
{
    (void)state;
    rng r = {2024};
    for (int k = 0; k < 5000; k++) {
        double q[4];
        random_quat(&r, q);
        check_quat_roundtrip(q);
    }
    /* every branch of Shepperd's method, including half turns (w = 0) */
    const double special[][4] = {
        {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}, {0, 0.6, 0.8, 0},
        {0, 0, -0.6, 0.8}, {1e-9, 1, 0, 0}, {0.5, 0.5, 0.5, 0.5}, {-0.5, 0.5, -0.5, 0.5}};
    for (size_t i = 0; i < sizeof special / sizeof special[0]; i++) {
        double q[4];
        dyn_quat_normalize(special[i], q);
        check_quat_roundtrip(q);
    }
    /* R(q) does not depend on |q| or on the sign of q */
    double q[4], q2[4], R1[9], R2[9];
    random_quat(&r, q);
    for (int i = 0; i < 4; i++) {
        q2[i] = -3.0 * q[i];
    }
    dyn_quat_to_mat(q, R1);
    dyn_quat_to_mat(q2, R2);
    assert_close(max_abs_diff(R1, R2, 9), 0.0, 1e-15);
    /* the zero quaternion is reported */
    const double zero[4] = {0, 0, 0, 0};
    assert_int_equal(dyn_quat_to_mat(zero, R1), 1);
    assert_true(isnan(R1[0]));
    double e[3];
    assert_int_equal(dyn_quat_to_euler(zero, e), -1);
}

static void test_quat_algebra(void **state)
{
    (void)state;
    rng r = {31337};
    for (int k = 0; k < 500; k++) {
        double p[4], q[4], pq[4], Rp[9], Rq[9], Rpq[9], RqRp[9], v[3], a[3], b[3];
        random_quat(&r, p);
        random_quat(&r, q);
        /* R(p (x) q) = R(q) R(p): first p, then q about the turned axes */
        dyn_quat_mul(p, q, pq);
        dyn_quat_to_mat(p, Rp);
        dyn_quat_to_mat(q, Rq);
        dyn_quat_to_mat(pq, Rpq);
        dyn_mat3_mul(Rq, Rp, RqRp);
        assert_close(max_abs_diff(Rpq, RqRp, 9), 0.0, 1e-15);
        /* q (x) q* = 1 */
        double qc[4], one[4];
        dyn_quat_conj(q, qc);
        dyn_quat_mul(q, qc, one);
        assert_close(one[0], 1.0, 1e-15);
        assert_close(fabs(one[1]) + fabs(one[2]) + fabs(one[3]), 0.0, 1e-15);
        /* rotate_inv is R(q) v (N -> B), rotate is R(q)^T v (B -> N); lengths kept */
        v[0] = uniform(&r, -2, 2);
        v[1] = uniform(&r, -2, 2);
        v[2] = uniform(&r, -2, 2);
        dyn_quat_rotate_inv(q, v, a);
        dyn_mat3_mul_vec(Rq, v, b);
        assert_close(max_abs_diff(a, b, 3), 0.0, 4e-15);
        dyn_quat_rotate(q, v, a);
        dyn_mat3_tmul_vec(Rq, v, b);
        assert_close(max_abs_diff(a, b, 3), 0.0, 4e-15);
        assert_close(dyn_vec3_norm(a), dyn_vec3_norm(v), 1e-14);
        /* axis-angle round trip */
        double n[3], m[3], qa[4];
        random_unit(&r, n);
        double ang = uniform(&r, 0.0, DYN_PI);
        dyn_quat_from_axis_angle(n, ang, qa);
        assert_close(dyn_quat_to_axis_angle(qa, m), ang, 1e-15);
        assert_close(max_abs_diff(m, n, 3), 0.0, 1e-14);
        /* the axis is fixed by the rotation */
        dyn_quat_rotate(qa, n, a);
        assert_close(max_abs_diff(a, n, 3), 0.0, 1e-15);
    }
    /* a quarter turn about Z turns X into Y (active rotation of a vector) */
    const double Z[3] = {0, 0, 1}, X[3] = {1, 0, 0};
    double q[4], v[3];
    dyn_quat_from_axis_angle(Z, DYN_PI / 2, q);
    dyn_quat_rotate(q, X, v);
    assert_close(v[0], 0.0, 1e-15);
    assert_close(v[1], 1.0, 1e-15);
    /* normalisation and its degenerate case */
    const double q3[4] = {0, 3, 0, 4}, q0[4] = {0, 0, 0, 0};
    assert_true(dyn_quat_normalize(q3, q) == 5.0);
    assert_close(q[3], 0.8, 1e-16);
    assert_true(dyn_quat_normalize(q0, q) == 0.0);
    assert_true(q[0] == 1.0 && q[1] == 0.0 && q[2] == 0.0 && q[3] == 0.0);
}

/* ---- kinematics ---- */

static void test_euler_rates_inverse(void **state)
{
    (void)state;
    rng r = {5};
    for (int k = 0; k < 2000; k++) {
        double e[3], w[3], de[3], w2[3], de2[3];
        random_euler(&r, 1.5, e);
        w[0] = uniform(&r, -3, 3);
        w[1] = uniform(&r, -3, 3);
        w[2] = uniform(&r, -3, 3);
        assert_int_equal(dyn_euler_rates(e, w, de), 0);
        dyn_euler_body_rates(e, de, w2);
        assert_close(max_abs_diff(w, w2, 3), 0.0, 1e-13);
        dyn_euler_body_rates(e, w, de2); /* now read w as Euler-angle rates */
        dyn_euler_rates(e, de2, w2);
        assert_close(max_abs_diff(w, w2, 3), 0.0, 1e-12);
    }
    /* Greenwood (3.16) by hand at theta = 0, phi = 0: dpsi = wz, dtheta = wy, dphi = wx */
    const double e0[3] = {0.7, 0.0, 0.0}, w0[3] = {0.1, 0.2, 0.3};
    double de[3];
    dyn_euler_rates(e0, w0, de);
    assert_true(de[0] == 0.3 && de[1] == 0.2 && de[2] == 0.1);
    /* at phi = pi/2, theta = pi/4: dpsi = sqrt(2) wy, dtheta = -wz, dphi = wx + wy */
    const double e1[3] = {0.0, DYN_PI / 4, DYN_PI / 2};
    dyn_euler_rates(e1, w0, de);
    assert_close(de[0], sqrt(2.0) * 0.2, 1e-15);
    assert_close(de[1], -0.3, 1e-16);
    assert_close(de[2], 0.1 + 0.2, 1e-15);
}

static void test_euler_rates_singular(void **state)
{
    (void)state;
    const double w[3] = {0.1, 0.4, -0.3};
    double de[3];
    const double e_far[3] = {0.2, DYN_PI / 2 - 1e-6, 0.3};
    assert_int_equal(dyn_euler_rates(e_far, w, de), 0);
    const double e_lock[3] = {0.2, DYN_PI / 2, 0.3};
    assert_int_equal(dyn_euler_rates(e_lock, w, de), 1);
    /* dtheta does not involve sec(theta) and is still right */
    assert_close(de[1], 0.4 * cos(0.3) + 0.3 * sin(0.3), 1e-16);
    const double e_down[3] = {0.2, -DYN_PI / 2, 0.3};
    assert_int_equal(dyn_euler_rates(e_down, w, de), 1);
    const double e_wrap[3] = {0.2, 3 * DYN_PI / 2, 0.3};
    assert_int_equal(dyn_euler_rates(e_wrap, w, de), 1);

    assert_close(dyn_euler_singularity_distance(0.0), DYN_PI / 2, 1e-16);
    assert_close(dyn_euler_singularity_distance(DYN_PI / 2 - 0.1), 0.1, 1e-15);
    assert_rel(dyn_euler_singularity_distance(-DYN_PI / 2 + 1e-3), 1e-3, 1e-12);
    assert_close(dyn_euler_singularity_distance(DYN_PI + 0.2), DYN_PI / 2 - 0.2, 1e-15);
    assert_close(dyn_euler_singularity_distance(DYN_PI / 2), 0.0, 1e-16);
}

static void test_rotation_kinematics_by_finite_differences(void **state)
{
    (void)state;
    /* With R = R(e(t)) and de from (3.16): dR/dt = -[omega_B x] R (a vector fixed in N turns
     * backwards in B), and the quaternion of e(t) obeys dq/dt = 1/2 q (x) (0, omega_B). */
    rng r = {8};
    const double h = 1e-5;
    for (int k = 0; k < 200; k++) {
        double e[3], w[3], de[3], ep[3], em[3];
        random_euler(&r, 1.2, e);
        w[0] = uniform(&r, -2, 2);
        w[1] = uniform(&r, -2, 2);
        w[2] = uniform(&r, -2, 2);
        dyn_euler_rates(e, w, de);
        for (int i = 0; i < 3; i++) {
            ep[i] = e[i] + h * de[i];
            em[i] = e[i] - h * de[i];
        }
        double R[9], Rp[9], Rm[9], dR[9], W[9], WR[9];
        dyn_euler_to_mat(e, R);
        dyn_euler_to_mat(ep, Rp);
        dyn_euler_to_mat(em, Rm);
        for (int i = 0; i < 9; i++) {
            dR[i] = (Rp[i] - Rm[i]) / (2 * h);
        }
        const double S[9] = {0, w[2], -w[1], -w[2], 0, w[0], w[1], -w[0], 0}; /* -[w x] */
        memcpy(W, S, sizeof W);
        dyn_mat3_mul(W, R, WR);
        assert_close(max_abs_diff(dR, WR, 9), 0.0, 1e-8);

        double q[4], qp[4], qm[4], dq_fd[4], dq[4];
        dyn_euler_to_quat(e, q);
        dyn_euler_to_quat(ep, qp);
        dyn_euler_to_quat(em, qm);
        for (int i = 0; i < 4; i++) {
            dq_fd[i] = (qp[i] - qm[i]) / (2 * h);
        }
        dyn_quat_derivative(q, w, dq);
        assert_close(max_abs_diff(dq, dq_fd, 4), 0.0, 1e-8);
        /* the norm is constant: q . dq = 0 */
        assert_close(q[0] * dq[0] + q[1] * dq[1] + q[2] * dq[2] + q[3] * dq[3], 0.0, 1e-15);
    }
}

/* ---- principal angle ---- */

static void test_principal_angle_equal_orientations(void **state)
{
    (void)state;
    rng r = {11};
    for (int k = 0; k < 500; k++) {
        double e[3], R[9], axis[3], q[4];
        e[0] = uniform(&r, -7, 7);
        e[1] = uniform(&r, -7, 7);
        e[2] = uniform(&r, -7, 7);
        dyn_euler_to_mat(e, R);
        assert_true(dyn_principal_angle(R, R, axis) == 0.0);
        assert_true(axis[0] == 1.0 && axis[1] == 0.0 && axis[2] == 0.0);
        assert_true(dyn_principal_angle_euler(e, e, axis) == 0.0);
        dyn_euler_to_quat(e, q);
        assert_true(dyn_principal_angle_quat(q, q, NULL) == 0.0);
    }
}

static void test_principal_angle_small_and_near_pi(void **state)
{
    (void)state;
    rng r = {13};
    double I[9];
    dyn_mat3_identity(I);
    /* From the identity: R1 R2^T has exactly representable entries, so the analytic angle
     * must be recovered to relative accuracy (acos of the trace would give 0 here). */
    const double tiny[] = {1e-9, 1e-12};
    for (size_t i = 0; i < 2; i++) {
        for (int k = 0; k < 100; k++) {
            double n[3], R2[9], axis[3];
            random_unit(&r, n);
            mat_from_axis_angle(n, tiny[i], R2);
            assert_rel(dyn_principal_angle(I, R2, axis), tiny[i], 1e-6);
            /* R1 R2^T = R2^T turns B2 back onto N: axis -n */
            for (int j = 0; j < 3; j++) {
                assert_close(axis[j], -n[j], 1e-9);
            }
            assert_rel(dyn_principal_angle(R2, I, axis), tiny[i], 1e-6);
            for (int j = 0; j < 3; j++) {
                assert_close(axis[j], n[j], 1e-9);
            }
        }
        /* the same through Euler angles: phi differing by tiny about x */
        const double e1[3] = {0, 0, 0}, e2[3] = {0, 0, tiny[i]};
        double axis[3];
        assert_rel(dyn_principal_angle_euler(e1, e2, axis), tiny[i], 1e-6);
        assert_close(axis[0], -1.0, 1e-12);
        assert_rel(dyn_principal_angle_euler(e2, e1, axis), tiny[i], 1e-6);
        assert_close(axis[0], 1.0, 1e-12);
    }
    /* near a half turn */
    for (int k = 0; k < 100; k++) {
        double n[3], R2[9], axis[3];
        random_unit(&r, n);
        const double a = DYN_PI - 1e-9;
        mat_from_axis_angle(n, a, R2);
        assert_close(dyn_principal_angle(R2, I, axis), a, 1e-15);
        assert_close(max_abs_diff(axis, n, 3), 0.0, 1e-12);
    }
    const double e0[3] = {0, 0, 0}, epi[3] = {DYN_PI - 1e-9, 0, 0};
    assert_close(dyn_principal_angle_euler(epi, e0, NULL), DYN_PI - 1e-9, 1e-15);
}

static void test_principal_angle_exactly_pi(void **state)
{
    (void)state;
    double I[9], axis[3];
    dyn_mat3_identity(I);
    /* 180 degrees about Z, written exactly */
    const double Rz180[9] = {-1, 0, 0, 0, -1, 0, 0, 0, 1};
    assert_true(dyn_principal_angle(I, Rz180, axis) == DYN_PI);
    assert_true(fabs(axis[2]) == 1.0 && axis[0] == 0.0 && axis[1] == 0.0);
    /* 180 degrees about X */
    const double Rx180[9] = {1, 0, 0, 0, -1, 0, 0, 0, -1};
    assert_true(dyn_principal_angle(Rx180, I, axis) == DYN_PI);
    assert_true(fabs(axis[0]) == 1.0);
    /* psi = pi through the Euler angles (sin(pi) is 1.2e-16 in double) */
    const double e0[3] = {0, 0, 0}, e1[3] = {DYN_PI, 0, 0};
    double R1[9];
    dyn_euler_to_mat(e1, R1);
    assert_close(dyn_principal_angle(R1, I, axis), DYN_PI, 1e-15);
    assert_close(fabs(axis[2]), 1.0, 1e-15);
    assert_close(dyn_principal_angle_euler(e1, e0, axis), DYN_PI, 1e-15);
    /* theta and phi together: pi about Y then 0 about x equals the half turn about Y */
    const double e2[3] = {0, 0, DYN_PI};
    assert_close(dyn_principal_angle_euler(e2, e0, NULL), DYN_PI, 1e-15);
}

static void test_principal_angle_general(void **state)
{
    (void)state;
    rng r = {17};
    /* R1 = D R2 with D the N->B matrix of the turn (n, a): R1 R2^T = D, angle a, axis n,
     * for arbitrary R2 (here entries carry rounding, so absolute accuracy ~1e-15). */
    const double angles[] = {1e-9, 1e-6, 0.3, 2.0, DYN_PI - 1e-6, DYN_PI - 1e-9};
    for (size_t i = 0; i < sizeof angles / sizeof angles[0]; i++) {
        for (int k = 0; k < 200; k++) {
            double e2[3], R2[9], D[9], R1[9], n[3], axis[3];
            e2[0] = uniform(&r, -7, 7);
            e2[1] = uniform(&r, -7, 7);
            e2[2] = uniform(&r, -7, 7);
            dyn_euler_to_mat(e2, R2);
            random_unit(&r, n);
            mat_from_axis_angle(n, angles[i], D);
            dyn_mat3_mul(D, R2, R1);
            double a = dyn_principal_angle(R1, R2, axis);
            assert_close(a, angles[i], 2e-15);
            if (angles[i] >= 1e-6) {
                assert_close(max_abs_diff(axis, n, 3), 0.0, 1e-8);
            }
            double b = dyn_principal_angle(R2, R1, NULL); /* symmetric in the angle */
            assert_close(a, b, 2e-15);
        }
    }
    /* Euler-angle and matrix variants agree, and agree with acos of the trace where that
     * is well conditioned (angles away from 0 and pi). */
    int checked = 0;
    for (int k = 0; k < 2000; k++) {
        double e1[3], e2[3], R1[9], R2[9], C[9];
        random_euler(&r, 3.0, e1);
        random_euler(&r, 3.0, e2);
        dyn_euler_to_mat(e1, R1);
        dyn_euler_to_mat(e2, R2);
        double a = dyn_principal_angle(R1, R2, NULL);
        assert_true(a >= 0.0 && a <= DYN_PI);
        assert_close(dyn_principal_angle_euler(e1, e2, NULL), a, 1e-14);
        dyn_mat3_mul_bt(R1, R2, C);
        if (a > 0.1 && a < DYN_PI - 0.1) {
            assert_close(acos(0.5 * (C[0] + C[4] + C[8] - 1.0)), a, 1e-13);
            checked++;
        }
    }
    assert_true(checked > 1000);
    /* two yaw angles: the angle is their difference */
    const double ea[3] = {0.25, 0, 0}, eb[3] = {1.5, 0, 0};
    double axis[3];
    assert_close(dyn_principal_angle_euler(ea, eb, axis), 1.25, 1e-15);
    assert_close(axis[2], -1.0, 1e-15); /* R_psi(0.25) R_psi(1.5)^T = R_psi(-1.25) */
}

/* ---- Newton–Euler ---- */

static void test_newton_euler_by_hand(void **state)
{
    (void)state;
    const double I[3] = {1, 2, 3}, w[3] = {1, 2, 3}, M[3] = {0.5, -1, 2};
    double dw[3];
    assert_int_equal(dyn_rigid_euler_accel(I, w, M, dw), 0);
    assert_close(dw[0], 0.5 + (2 - 3) * 2 * 3, 0.0);        /* -5.5 */
    assert_close(dw[1], (-1 + (3 - 1) * 3 * 1) / 2.0, 0.0); /* 2.5 */
    assert_close(dw[2], (2 + (1 - 2) * 1 * 2) / 3.0, 0.0);  /* 0 */
    assert_close(dyn_rigid_rotational_energy(I, w), 18.0, 0.0);
    double L[3];
    dyn_rigid_angular_momentum(I, w, L);
    assert_true(L[0] == 1.0 && L[1] == 4.0 && L[2] == 9.0);
    /* the gyroscopic term does no work: omega . (omega x L) = 0, so with M = 0
     * dT/dt = sum I_i w_i dw_i = 0 */
    const double M0[3] = {0, 0, 0};
    dyn_rigid_euler_accel(I, w, M0, dw);
    assert_close(I[0] * w[0] * dw[0] + I[1] * w[1] * dw[1] + I[2] * w[2] * dw[2], 0.0, 1e-14);

    const double F[3] = {2, -4, 9.81}, v[3] = {2, 0, 1};
    double a[3];
    assert_int_equal(dyn_rigid_linear_accel(2.0, F, a), 0);
    assert_true(a[0] == 1.0 && a[1] == -2.0 && a[2] == 4.905);
    assert_close(dyn_rigid_translational_energy(3.0, v), 7.5, 0.0);
    /* invalid data is reported, not divided by */
    assert_int_equal(dyn_rigid_linear_accel(0.0, F, a), 1);
    assert_true(isnan(a[0]));
    const double Ibad[3] = {1, -2, 3};
    assert_int_equal(dyn_rigid_euler_accel(Ibad, w, M, dw), 1);
    assert_true(isnan(dw[1]));
}

/* Torque-free body: state (omega_B, q), 7 values. */
typedef struct free_body {
    double inertia[3];
} free_body;

static void free_body_rhs(const free_body *b, const double y[7], double dy[7])
{
    const double M0[3] = {0, 0, 0};
    assert_int_equal(dyn_rigid_euler_accel(b->inertia, y, M0, dy), 0);
    dyn_quat_derivative(y + 3, y, dy + 3);
}

static void rk4_step(const free_body *b, double h, double y[7])
{
    double k1[7], k2[7], k3[7], k4[7], t[7];
    free_body_rhs(b, y, k1);
    for (int i = 0; i < 7; i++) t[i] = y[i] + 0.5 * h * k1[i];
    free_body_rhs(b, t, k2);
    for (int i = 0; i < 7; i++) t[i] = y[i] + 0.5 * h * k2[i];
    free_body_rhs(b, t, k3);
    for (int i = 0; i < 7; i++) t[i] = y[i] + h * k3[i];
    free_body_rhs(b, t, k4);
    for (int i = 0; i < 7; i++) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

static void test_torque_free_symmetric_body(void **state)
{
    (void)state;
    /* The plane's inertia: Ixx = Iyy = Ip/2, Izz = Ip. Euler's equations give wz constant
     * and the transverse rate turning at lambda = (Izz - Ixx)/Ixx wz (body-cone precession). */
    const double Ip = 0.01;
    free_body b = {{0.5 * Ip, 0.5 * Ip, Ip}};
    double y[7] = {0.5, -0.2, 2.0, 1, 0, 0, 0};
    const double h = 1e-3, T = 10.0;
    const long n = (long)(T / h + 0.5);
    double L0[3], L0n, E0 = dyn_rigid_rotational_energy(b.inertia, y);
    dyn_rigid_angular_momentum(b.inertia, y, L0);
    L0n = dyn_vec3_norm(L0);
    for (long k = 0; k < n; k++) {
        rk4_step(&b, h, y);
    }
    const double lambda = (Ip - 0.5 * Ip) / (0.5 * Ip) * 2.0;
    const double a = 0.5, c = -0.2, t = n * h;
    assert_close(y[0], a * cos(lambda * t) - c * sin(lambda * t), 1e-10);
    assert_close(y[1], a * sin(lambda * t) + c * cos(lambda * t), 1e-10);
    assert_true(y[2] == 2.0); /* (Ixx - Iyy) wx wy = 0 exactly */
    double L[3];
    dyn_rigid_angular_momentum(b.inertia, y, L);
    assert_rel(dyn_vec3_norm(L), L0n, 1e-12);
    assert_rel(dyn_rigid_rotational_energy(b.inertia, y), E0, 1e-12);
}

static void test_torque_free_asymmetric_body(void **state)
{
    (void)state;
    /* Spin mostly about the intermediate axis: the motion is unstable (the body flips), yet
     * energy, |L| and the angular momentum vector in N must stay constant. */
    free_body b = {{1.0, 2.0, 3.0}};
    double y[7] = {0.05, 1.0, 0.02, 1, 0, 0, 0};
    const double h = 1e-3;
    double LB[3], LN0[3], LN[3], R[9];
    dyn_rigid_angular_momentum(b.inertia, y, LB);
    dyn_quat_to_mat(y + 3, R);
    dyn_mat3_tmul_vec(R, LB, LN0); /* L_N = R^T L_B */
    const double E0 = dyn_rigid_rotational_energy(b.inertia, y);
    double wy_min = y[1];
    for (long k = 0; k < 30000; k++) {
        rk4_step(&b, h, y);
        if (y[1] < wy_min) {
            wy_min = y[1];
        }
    }
    assert_true(wy_min < -0.9); /* it turned over */
    dyn_rigid_angular_momentum(b.inertia, y, LB);
    assert_int_equal(dyn_quat_to_mat(y + 3, R), 0);
    dyn_mat3_tmul_vec(R, LB, LN);
    assert_close(max_abs_diff(LN, LN0, 3), 0.0, 1e-8);
    assert_rel(dyn_rigid_rotational_energy(b.inertia, y), E0, 1e-9);
    assert_close(sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]), 1.0, 1e-9);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vec3_algebra),
        cmocka_unit_test(test_mat3_algebra),
        cmocka_unit_test(test_elementary_rotations_by_hand),
        cmocka_unit_test(test_euler_matrix_closed_form),
        cmocka_unit_test(test_euler_matrix_is_rotation),
        cmocka_unit_test(test_euler_mat_euler_roundtrip),
        cmocka_unit_test(test_euler_near_gimbal_lock),
        cmocka_unit_test(test_euler_quat_matches_matrix),
        cmocka_unit_test(test_quat_mat_quat_roundtrip),
        cmocka_unit_test(test_quat_algebra),
        cmocka_unit_test(test_euler_rates_inverse),
        cmocka_unit_test(test_euler_rates_singular),
        cmocka_unit_test(test_rotation_kinematics_by_finite_differences),
        cmocka_unit_test(test_principal_angle_equal_orientations),
        cmocka_unit_test(test_principal_angle_small_and_near_pi),
        cmocka_unit_test(test_principal_angle_exactly_pi),
        cmocka_unit_test(test_principal_angle_general),
        cmocka_unit_test(test_newton_euler_by_hand),
        cmocka_unit_test(test_torque_free_symmetric_body),
        cmocka_unit_test(test_torque_free_asymmetric_body),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
