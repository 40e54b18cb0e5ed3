/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_branching.c — the direction of the other branch at a simple branch point of
 * G(z) = 0, G: R^(N+1) -> R^N (cont_core.h), by the algebraic branching equation (Keller
 * 1977; Doedel, "Lecture notes on numerical analysis of nonlinear equations", sec. 3;
 * AUTO-07p's manual, ch. 5): at the branch point DG has a two-dimensional null space
 * {phi1, phi2} and a left null vector psi; the tangents a phi1 + b phi2 of the branches
 * through it are the roots of
 *     c11 a^2 + 2 c12 a b + c22 b^2 = 0,   cij = psi . D^2G(z)[phi_i, phi_j].
 * The null vectors come from inverse iteration on the normal matrices DG^T DG (two at once,
 * orthonormalized) and DG DG^T, with a ridge of 1e-13 of their largest diagonal entry; the
 * second derivatives from central differences of the exact Jacobian along phi1 and phi2,
 * extrapolated by Richardson's rule over the steps h and h/2. Of the two roots the one
 * farther from the known branch's tangent is the other branch. Where the equation is
 * degenerate (no two distinct real roots: an isolated point, branches tangent to each
 * other, a quadratic form zero to its accuracy) the direction orthogonal to the known
 * branch in the null space is given instead. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cont_core.h"
#include "ode/cholesky.h"

static double vdot(const double *a, const double *b, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

static int normalize(double *v, int n)
{
    const double nv = sqrt(vdot(v, v, n));
    if (!(nv > 0.0) || !isfinite(nv))
        return -1;
    for (int i = 0; i < n; i++)
        v[i] /= nv;
    return 0;
}

int cont_normal_factor(const double *A, int r, int m, int left, double *G)
{
    const int k = left ? r : m, len = left ? m : r;
    double big = 0.0;
    for (int a = 0; a < k; a++)
        for (int b = 0; b <= a; b++) {
            double g = 0.0;
            for (int i = 0; i < len; i++)
                g += left ? A[(size_t)a * (size_t)m + (size_t)i] * A[(size_t)b * (size_t)m + (size_t)i]
                          : A[(size_t)i * (size_t)m + (size_t)a] * A[(size_t)i * (size_t)m + (size_t)b];
            G[(size_t)a * (size_t)k + (size_t)b] = G[(size_t)b * (size_t)k + (size_t)a] = g;
            if (a == b)
                big = fmax(big, g);
        }
    const double ridge = big > 0.0 ? 1e-13 * big : 1.0;
    for (int a = 0; a < k; a++)
        G[(size_t)a * (size_t)k + (size_t)a] += ridge;
    return isfinite(big) ? dyn_cholesky_factor(k, G) : -1;
}

int cont_inverse_iteration(const double *G, int k, int q, int iterations, double *V)
{
    for (int j = 0; j < q; j++)
        for (int i = 0; i < k; i++)
            V[(size_t)j * (size_t)k + (size_t)i] =
                (j ? (i % 3) - 1.0 : 1.0 / (1.0 + i) * (i % 2 ? -1.0 : 1.0) + 0.1);
    for (int it = 0; it < iterations; it++)
        for (int j = 0; j < q; j++) {
            double *v = V + (size_t)j * (size_t)k;
            dyn_cholesky_solve(k, G, v);
            for (int l = 0; l < j; l++) {
                const double *u = V + (size_t)l * (size_t)k;
                const double c = vdot(u, v, k);
                for (int i = 0; i < k; i++)
                    v[i] -= c * u[i];
            }
            if (normalize(v, k))
                return -1;
        }
    return 0;
}

/* psi . D^2G(z)[u, v] and psi . D^2G(z)[u, u] by central differences of DG along u with the
 * steps h and h/2, extrapolated */
static int second_derivatives(const cont_system *s, const double *z, const double *psi,
                              const double *u, const double *v, double h, double *J, double *zh,
                              double *uv, double *uu)
{
    const int N = s->N, M = N + 1;
    double d_uv[2], d_uu[2];
    for (int k = 0; k < 2; k++) {
        const double hk = k ? 0.5 * h : h;
        d_uv[k] = d_uu[k] = 0.0;
        for (int sign = 1; sign >= -1; sign -= 2) {
            for (int i = 0; i < M; i++)
                zh[i] = z[i] + sign * hk * u[i];
            if (s->jacobian(s->ctx, zh, J))
                return -1;
            for (int r = 0; r < N; r++) {
                const double *row = J + (size_t)r * (size_t)M;
                d_uv[k] += sign * psi[r] * vdot(row, v, M);
                d_uu[k] += sign * psi[r] * vdot(row, u, M);
            }
        }
        d_uv[k] /= 2.0 * hk;
        d_uu[k] /= 2.0 * hk;
    }
    *uv = (4.0 * d_uv[1] - d_uv[0]) / 3.0;
    *uu = (4.0 * d_uu[1] - d_uu[0]) / 3.0;
    return isfinite(*uv) && isfinite(*uu) ? 0 : -1;
}

int cont_branch_direction(const cont_system *s, const double *z, const double *t, double *v)
{
    const int N = s->N, M = N + 1;
    const size_t MM = (size_t)M;
    double *buf = malloc((3 * MM * MM + 6 * MM) * sizeof *buf);
    if (!buf)
        return -1;
    double *J = buf, *G = J + MM * MM, *phi = G + MM * MM, *psi = phi + 2 * MM, *zh = psi + MM;
    double *orth = zh + MM;
    int rc = -1;
    if (s->jacobian(s->ctx, z, J))
        goto done;
    /* the null space of DG: phi1, phi2 orthonormal */
    if (cont_normal_factor(J, N, M, 0, G) || cont_inverse_iteration(G, M, 2, 6, phi))
        goto done;
    const double *phi1 = phi, *phi2 = phi + MM;
    /* the direction orthogonal to t in that plane: the fallback */
    const double a1 = vdot(phi1, t, M), a2 = vdot(phi2, t, M);
    for (int i = 0; i < M; i++)
        orth[i] = a2 * phi1[i] - a1 * phi2[i];
    if (normalize(orth, M))
        goto done;
    memcpy(v, orth, MM * sizeof *v);
    rc = 1;
    /* the left null vector psi of DG */
    if (N > 0 && (cont_normal_factor(J, N, M, 1, G) || cont_inverse_iteration(G, N, 1, 6, psi)))
        goto done;
    double zmax = 1.0;
    for (int i = 0; i < M; i++)
        zmax = fmax(zmax, fabs(z[i]));
    const double h = 1e-3 * zmax;
    double c11, c12, c21, c22;
    if (second_derivatives(s, z, psi, phi1, phi2, h, J, zh, &c12, &c11) ||
        second_derivatives(s, z, psi, phi2, phi1, h, J, zh, &c21, &c22))
        goto done;
    c12 = 0.5 * (c12 + c21);
    /* the roots of the quadratic form: its eigenvalues l1 >= l2 with eigenvectors e1, e2;
     * sqrt(-l2) e1 +- sqrt(l1) e2 where l1 > 0 > l2 */
    const double scale = fmax(fmax(fabs(c11), fabs(c22)), fabs(c12));
    const double disc = c12 * c12 - c11 * c22;
    if (!(scale > 0.0) || !(disc > 1e-12 * scale * scale))
        goto done;
    const double mean = 0.5 * (c11 + c22), rad = hypot(0.5 * (c11 - c22), c12);
    const double l1 = mean + rad, l2 = mean - rad;
    /* e1 for l1: (c12, l1 - c11) or (l1 - c22, c12), whichever is larger */
    double e1[2] = {c12, l1 - c11};
    if (hypot(l1 - c22, c12) > hypot(e1[0], e1[1])) {
        e1[0] = l1 - c22;
        e1[1] = c12;
    }
    const double ne = hypot(e1[0], e1[1]);
    if (!(ne > 0.0))
        goto done;
    e1[0] /= ne;
    e1[1] /= ne;
    const double e2[2] = {-e1[1], e1[0]};
    double best = INFINITY;
    for (int sign = 1; sign >= -1; sign -= 2) {
        const double a = sqrt(-l2) * e1[0] + sign * sqrt(l1) * e2[0];
        const double b = sqrt(-l2) * e1[1] + sign * sqrt(l1) * e2[1];
        for (int i = 0; i < M; i++)
            zh[i] = a * phi1[i] + b * phi2[i];
        if (normalize(zh, M))
            continue;
        const double along = fabs(vdot(zh, t, M));
        if (along < best) {
            best = along;
            memcpy(v, zh, MM * sizeof *v);
        }
    }
    rc = isfinite(best) ? 0 : 1;
    if (rc)
        memcpy(v, orth, MM * sizeof *v);
done:
    free(buf);
    return rc;
}
