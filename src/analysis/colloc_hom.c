/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_hom.c — projection boundary conditions of a homoclinic or heteroclinic orbit on a
 * truncated interval (XPPAUT's hom_bcs(k); W.-J. Beyn, "The numerical computation of
 * connecting orbits in dynamical systems", IMA J. Numer. Anal. 10 (1990) 379-405; AUTO-07p's
 * HomCont, Champneys, Kuznetsov & Sandstede, Int. J. Bifurcation and Chaos 6 (1996) 867-887):
 * u(0) - x_L lies in the unstable subspace of the Jacobian A_L of the flow (the first dim
 * states) at the left equilibrium x_L, and u(1) - x_R in the stable subspace of A_R.
 *
 * The subspaces come from the matrix sign function S = sign(A) (Newton's iteration
 * S <- (c S + (c S)^-1) / 2 with determinant scaling c = |det S|^(-1/dim); N. J. Higham,
 * Functions of Matrices, SIAM 2008, ch. 5), defined when A has no eigenvalue on the
 * imaginary axis: P_s = (I - S)/2 projects onto the stable subspace along the unstable one,
 * P_u = (I + S)/2 the other way, and the unstable dimension is (dim + trace S)/2. The vector
 * v = u(0) - x_L is in the unstable subspace when P_s v = 0; its n_s independent rows are
 * B_L^T P_s v = 0 with B_L an orthonormal basis of the range of P_s at the first guess, kept
 * fixed so that the conditions are smooth functions of the states and parameters (the aim
 * of Beyn's normalization). At the right end P_u (u(1) - x_R) = 0 the same way. As in
 * XPPAUT, hom_bcs(0) .. hom_bcs(n_s(L) - 1) are the left end's rows and the next n_u(R) the
 * right end's; the Jacobian is taken at the equilibrium with the other states (constants,
 * a free parameter carried as a state) at their left-end values. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/colloc_hom.h"
#include "ode/linalg.h"

/* A (dim x dim of the flow) at the equilibrium held from state `at` of u into h->work */
static int flow_jacobian(bvp_hom *h, const double *u, int at, double *A)
{
    const dyn_model *m = h->m;
    const int n = h->n, d = h->dim;
    double *y = h->work, *J = y + n, *fp = J + (size_t)n * n, *fm = fp + n;
    memcpy(y, u, (size_t)n * sizeof(double));
    memcpy(y, u + at, (size_t)d * sizeof(double));
    if (m->jacobian) {
        if (m->jacobian(h->t, y, J, h->par))
            return 1;
        for (int i = 0; i < d; i++)
            for (int j = 0; j < d; j++)
                A[i * d + j] = J[(size_t)i * n + j];
        return 0;
    }
    for (int j = 0; j < d; j++) {
        const double keep = y[j], e = 6e-6 * fmax(fabs(keep), 1.0);
        y[j] = keep + e;
        int st = m->rhs(h->t, y, fp, h->par);
        y[j] = keep - e;
        st = st || m->rhs(h->t, y, fm, h->par);
        y[j] = keep;
        if (st)
            return 1;
        for (int i = 0; i < d; i++)
            A[i * d + j] = (fp[i] - fm[i]) / (2 * e);
    }
    return 0;
}

static double norm1(int d, const double *A)
{
    double best = 0.0;
    for (int j = 0; j < d; j++) {
        double s = 0.0;
        for (int i = 0; i < d; i++)
            s += fabs(A[i * d + j]);
        best = fmax(best, s);
    }
    return best;
}

/* sign(A) into S (dim x dim); 0, or 1 when A has an eigenvalue on (or too near) the
 * imaginary axis or is not finite */
static int matrix_sign(bvp_hom *h, const double *A, double *S)
{
    const int d = h->dim;
    const size_t dd = (size_t)d * d;
    double *LU = h->work + 3 * (size_t)h->n + (size_t)h->n * h->n, *X = LU + dd,
           *col = X + dd;
    memcpy(S, A, dd * sizeof(double));
    int scale = 1;
    for (int it = 0; it < 100; it++) {
        memcpy(LU, S, dd * sizeof(double));
        if (dyn_lu_factor(d, LU, h->piv))
            return 1;
        double logdet = 0.0;
        for (int i = 0; i < d; i++)
            logdet += log(fabs(LU[i * d + i]));
        const double c = scale ? exp(-logdet / d) : 1.0;
        for (int j = 0; j < d; j++) { /* X = S^-1, column by column */
            for (int i = 0; i < d; i++)
                col[i] = i == j;
            dyn_lu_solve(d, LU, h->piv, col);
            for (int i = 0; i < d; i++)
                X[i * d + j] = col[i];
        }
        double change = 0.0;
        for (size_t k = 0; k < dd; k++) {
            const double next = 0.5 * (c * S[k] + X[k] / c);
            change = fmax(change, fabs(next - S[k]));
            S[k] = next;
        }
        const double size = norm1(d, S);
        if (!isfinite(size))
            return 1;
        if (change < 1e-2 * size)
            scale = 0; /* near convergence the scaling only slows it down */
        if (change <= 1e-14 * size) {
            /* a sign function squares to I; an eigenvalue on the axis leaves it far off */
            double off = 0.0;
            for (int i = 0; i < d; i++)
                for (int j = 0; j < d; j++) {
                    double s = 0.0;
                    for (int k = 0; k < d; k++)
                        s += S[i * d + k] * S[k * d + j];
                    off = fmax(off, fabs(s - (i == j)));
                }
            return off > 1e-8;
        }
    }
    return 1;
}

/* the projector (I + sgn S)/2 of A into P; its rank (the dimension of the unstable
 * subspace for sgn = 1, the stable one for -1) in *rank; 0 or non-zero */
static int projector(bvp_hom *h, const double *A, int sgn, double *P, int *rank)
{
    const int d = h->dim;
    if (matrix_sign(h, A, P))
        return 1;
    double trace = 0.0;
    for (int i = 0; i < d; i++)
        trace += P[i * d + i];
    for (int i = 0; i < d; i++)
        for (int j = 0; j < d; j++)
            P[i * d + j] = 0.5 * ((i == j) + sgn * P[i * d + j]);
    *rank = (int)lround(0.5 * (d + sgn * trace));
    return 0;
}

/* an orthonormal basis (dim x k, row-major) of the range of P (rank k): Gram-Schmidt on
 * P's columns, the largest remaining one first */
static void range_basis(int d, int k, const double *P, double *B, double *v)
{
    for (int c = 0; c < k; c++) {
        double best = -1.0;
        int pick = 0;
        for (int j = 0; j < d; j++) {
            double s = 0.0;
            for (int i = 0; i < d; i++) {
                double r = P[i * d + j];
                for (int q = 0; q < c; q++) {
                    double dot = 0.0;
                    for (int l = 0; l < d; l++)
                        dot += B[l * k + q] * P[l * d + j];
                    r -= dot * B[i * k + q];
                }
                s += r * r;
            }
            if (s > best) {
                best = s;
                pick = j;
            }
        }
        for (int i = 0; i < d; i++)
            v[i] = P[i * d + pick];
        for (int pass = 0; pass < 2; pass++) /* twice is enough (Kahan) */
            for (int q = 0; q < c; q++) {
                double dot = 0.0;
                for (int l = 0; l < d; l++)
                    dot += B[l * k + q] * v[l];
                for (int l = 0; l < d; l++)
                    v[l] -= dot * B[l * k + q];
            }
        double s = 0.0;
        for (int i = 0; i < d; i++)
            s += v[i] * v[i];
        s = s > 0 ? 1.0 / sqrt(s) : 0.0;
        for (int i = 0; i < d; i++)
            B[i * k + c] = v[i] * s;
    }
}

void bvp_hom_free(bvp_hom *h)
{
    free(h->basis_left);
    free(h->work);
    free(h->piv);
    h->basis_left = h->basis_right = h->work = NULL;
    h->piv = NULL;
}

int bvp_hom_init(bvp_hom *h, const dyn_model *m, void *par, double t, const double *y0,
                 char *msg, size_t len)
{
    memset(h, 0, sizeof *h);
    const dyn_hom_bcs *hb = m->hom;
    const int n = m->n_states;
    h->m = m;
    h->par = par;
    h->t = t;
    h->n = n;
    if (!hb || hb->dim < 1 || hb->left < 0 || hb->right < 0 || hb->left + hb->dim > n ||
        hb->right + hb->dim > n) {
        snprintf(msg, len, "hom_bcs: the equilibria were not found: the flow is the states "
                 "before the first one with x'=0, and the other conditions must use as many "
                 "x'=0 states (the equilibrium of both ends, homoclinic) or twice as many (the "
                 "left end's, then the right end's, heteroclinic), each group in a row");
        return 1;
    }
    const int d = hb->dim;
    h->dim = d;
    h->left = hb->left;
    h->right = hb->right;
    const size_t dd = (size_t)d * d;
    h->work = malloc((3 * (size_t)n + (size_t)n * n + 4 * dd + 2 * (size_t)d) * sizeof(double));
    h->piv = malloc((size_t)d * sizeof(int));
    h->basis_left = malloc(2 * dd * sizeof(double));
    if (!h->work || !h->piv || !h->basis_left) {
        snprintf(msg, len, "out of memory");
        bvp_hom_free(h);
        return 1;
    }
    double *A = h->work + 3 * (size_t)n + (size_t)n * n + 2 * dd + (size_t)d,
           *P = A + dd, *v = h->work; /* v: the Jacobian's scratch is free again */
    int at = h->left;
    int st = flow_jacobian(h, y0, at, A) || projector(h, A, -1, P, &h->n_left);
    if (!st) {
        h->basis_right = h->basis_left + (size_t)d * h->n_left;
        range_basis(d, h->n_left, P, h->basis_left, v);
        at = h->right;
        st = flow_jacobian(h, y0, at, A) || projector(h, A, 1, P, &h->n_right);
    }
    if (!st) {
        range_basis(d, h->n_right, P, h->basis_right, v);
    }
    if (st) {
        snprintf(msg, len, "hom_bcs: the equilibrium held in %s..%s at the first guess has "
                 "an eigenvalue on the imaginary axis (or its Jacobian failed): the "
                 "projections need a hyperbolic equilibrium (give the states that hold it "
                 "values near one with --init)", m->states[at].name,
                 m->states[at + d - 1].name);
        bvp_hom_free(h);
        return 1;
    }
    /* the file's hom_bcs(k) must be 0 .. n_left + n_right - 1, each once */
    const int total = h->n_left + h->n_right;
    int count = 0, bad = -1;
    for (int j = 0; j < m->n_bdry; j++) {
        const int k = hb->index[j];
        if (k < 0)
            continue;
        count++;
        for (int q = 0; q < j; q++)
            if (hb->index[q] == k)
                bad = j;
        if (k >= total)
            bad = j;
    }
    if (bad >= 0 || count != total) {
        snprintf(msg, len, "hom_bcs: the equilibria (%s.., %s..) ask for %d projection "
                 "condition(s) at the left end and %d at the right, hom_bcs(0) to "
                 "hom_bcs(%d) once each; the file has %d%s%s", m->states[h->left].name,
                 m->states[h->right].name, h->n_left, h->n_right, total - 1, count,
                 bad >= 0 ? ", line " : "", bad >= 0 ? m->bdry_text[bad] : "");
        bvp_hom_free(h);
        return 1;
    }
    return 0;
}

/* rows B^T P (u - x) of one end into g at the conditions k0 .. k0 + k - 1 */
static int end_rows(bvp_hom *h, const double *u, int at, int sgn, const double *B, int k,
                    int k0, double *g)
{
    const int d = h->dim;
    const size_t dd = (size_t)d * d;
    double *A = h->work + 3 * (size_t)h->n + (size_t)h->n * h->n + 2 * dd + (size_t)d,
           *P = A + dd;
    int rank;
    if (flow_jacobian(h, u, at, A) || projector(h, A, sgn, P, &rank) || rank != k)
        return 1;
    const dyn_hom_bcs *hb = h->m->hom;
    for (int j = 0; j < h->m->n_bdry; j++) {
        const int r = hb->index[j] - k0;
        if (hb->index[j] < 0 || r < 0 || r >= k)
            continue;
        double s = 0.0;
        for (int i = 0; i < d; i++) {
            double row = 0.0; /* (B^T P)[r][i] */
            for (int l = 0; l < d; l++)
                row += B[l * k + r] * P[l * d + i];
            s += row * (u[i] - u[at + i]);
        }
        g[j] = s;
    }
    return 0;
}

int bvp_hom_rows(bvp_hom *h, const double *u0, const double *u1, double *g)
{
    if (end_rows(h, u0, h->left, -1, h->basis_left, h->n_left, 0, g))
        return 1;
    /* the right end's equilibrium with the other states at their left-end values, as
     * XPPAUT: they are constants of the orbit */
    double *u = malloc((size_t)h->n * sizeof(double));
    if (!u)
        return 1;
    memcpy(u, u0, (size_t)h->n * sizeof(double));
    memcpy(u, u1, (size_t)h->dim * sizeof(double));
    const int st = end_rows(h, u, h->right, 1, h->basis_right, h->n_right, h->n_left, g);
    free(u);
    return st;
}
