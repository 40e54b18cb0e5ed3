/* SPDX-License-Identifier: BSD-3-Clause */
/* colloc_newton.c — Newton's method on the collocation equations (dynkit/colloc.h) and its
 * linear systems, AUTO-07p's structure (Doedel, Keller & Kernevez 1991, part II, sec. 3):
 * each interval's ncol n collocation rows are reduced by Gaussian elimination with partial
 * pivoting over its (ncol - 1) n interior unknowns ("condensation of parameters"), which
 * leaves n rows in the two mesh points and the free scalars; the border rows (phase and
 * arclength integrals) are reduced over the same pivots. The reduced system in the mesh
 * points w_1..w_ntst is block lower bidiagonal (a band of 2n - 1 below and n - 1 above the
 * diagonal), bordered by w_0, the free scalars, and the boundary and integral rows: the
 * band is factored once (LU with partial pivoting) and the border eliminated by its Schur
 * complement. The interior unknowns follow by back substitution. Work: O(ntst (ncol n)^3). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/colloc_internal.h"
#include "ode/linalg.h"

typedef struct colloc_sys {
    const dyn_colloc_problem *p;
    colloc_basis b;
    int n, ntst, ncol, npar;
    int m, rows, W; /* interior unknowns, rows and columns (with one right-hand side) */
    long nnodes, Nu, Nx;
    int nb;         /* border rows: nbc + phase + arc = n + npar */
    double *blk;    /* ntst x rows x W */
    double *brow;   /* nb x (Nx + 1) */
    double *work;   /* n f, n f2, n x, n*n fu, 3 n scratch */
    double *pwork;  /* npar */
    int det_sign;   /* the sign of the whole matrix's determinant and */
    double det_log; /* log |det|, from the pivots (up to a sign fixed by the sizes) */
} colloc_sys;

/* the global column of interval j's local column c */
static long gcol(const colloc_sys *s, int j, int c)
{
    const int n = s->n, m = s->m;
    if (c < m)
        return ((long)j * s->ncol + 1) * n + c;
    if (c < m + n)
        return (long)j * s->ncol * n + (c - m);
    if (c < m + 2 * n)
        return (long)(j + 1) * s->ncol * n + (c - m - n);
    if (c < m + 2 * n + s->npar)
        return s->Nu + (c - m - 2 * n);
    return s->Nx; /* the right-hand side */
}

static void sys_free(colloc_sys *s)
{
    free(s->blk);
    free(s->brow);
    free(s->work);
    free(s->pwork);
}

static int sys_init(colloc_sys *s, const dyn_colloc_problem *p, const dyn_colloc_sol *x, int arc)
{
    memset(s, 0, sizeof *s);
    if (x->n != p->n || x->npar != p->npar || p->nbc < 0 ||
        p->nbc + (p->phase ? 1 : 0) + arc != p->n + p->npar || (p->nbc && !p->bc) || !p->f)
        return DYN_COLLOC_ERR_ARG;
    if (colloc_basis_init(&s->b, x->ncol))
        return DYN_COLLOC_ERR_ARG;
    s->p = p;
    s->n = x->n;
    s->ntst = x->ntst;
    s->ncol = x->ncol;
    s->npar = x->npar;
    s->m = (x->ncol - 1) * x->n;
    s->rows = x->ncol * x->n;
    s->W = (x->ncol + 1) * x->n + x->npar + 1;
    s->nnodes = dyn_colloc_nodes(x);
    s->Nu = s->nnodes * x->n;
    s->Nx = s->Nu + x->npar;
    s->nb = x->n + x->npar;
    s->det_sign = 1;
    s->blk = malloc((size_t)s->ntst * s->rows * s->W * sizeof(double));
    s->brow = malloc((size_t)s->nb * (s->Nx + 1) * sizeof(double));
    const size_t n = (size_t)x->n;
    s->work = malloc((6 * n + n * n + 8) * sizeof(double));
    s->pwork = malloc(((size_t)x->npar + 1) * sizeof(double));
    if (!s->blk || !s->brow || !s->work || !s->pwork) {
        sys_free(s);
        return DYN_COLLOC_ERR_NOMEM;
    }
    return 0;
}

static int finite_all(int n, const double *v)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

/* interval j's collocation rows and residual (column W - 1: minus the residual) */
static int assemble_interval(colloc_sys *s, const dyn_colloc_sol *x, int j)
{
    const int n = s->n, ncol = s->ncol, W = s->W, m = s->m;
    const dyn_colloc_problem *p = s->p;
    double *A = s->blk + (size_t)j * s->rows * W;
    memset(A, 0, (size_t)s->rows * W * sizeof(double));
    double *f = s->work, *f2 = f + n, *xv = f2 + n, *fu = xv + n, *f3 = fu + (size_t)n * n;
    const double h = x->mesh[j + 1] - x->mesh[j];
    const double *U = x->u + (size_t)j * ncol * n;
    for (int k = 0; k < ncol; k++) {
        const double t = x->mesh[j] + h * s->b.z[k];
        for (int i = 0; i < n; i++) {
            double v = 0.0;
            for (int l = 0; l <= ncol; l++)
                v += s->b.L[k][l] * U[(size_t)l * n + i];
            xv[i] = v;
        }
        if (p->f(t, xv, x->par, f, fu, p->ctx) || !finite_all(n, f) ||
            !finite_all(n * n, fu))
            return DYN_COLLOC_ERR_FN;
        for (int i = 0; i < n; i++) {
            double *row = A + ((size_t)k * n + i) * W;
            double du = 0.0;
            for (int l = 0; l <= ncol; l++) {
                const double d = s->b.D[k][l] / h;
                du += d * U[(size_t)l * n + i];
                const int base = l == 0 ? m : l == ncol ? m + n : (l - 1) * n;
                for (int q = 0; q < n; q++)
                    row[base + q] -= fu[(size_t)i * n + q] * s->b.L[k][l];
                row[base + i] += d;
            }
            row[W - 1] = -(du - f[i]);
        }
        for (int kp = 0; kp < s->npar; kp++) { /* dF/dpar by central differences */
            memcpy(s->pwork, x->par, (size_t)s->npar * sizeof(double));
            const double d = 1e-6 * (1.0 + fabs(x->par[kp]));
            s->pwork[kp] = x->par[kp] + d;
            if (p->f(t, xv, s->pwork, f2, NULL, p->ctx))
                return DYN_COLLOC_ERR_FN;
            s->pwork[kp] = x->par[kp] - d;
            if (p->f(t, xv, s->pwork, f3, NULL, p->ctx))
                return DYN_COLLOC_ERR_FN;
            for (int i = 0; i < n; i++)
                A[((size_t)k * n + i) * W + m + 2 * n + kp] = -(f2[i] - f3[i]) / (2 * d);
        }
    }
    return 0;
}

/* a pivot of the factorization into the determinant (swapped: after a row interchange) */
static void det_factor(colloc_sys *s, double pivot, int swapped)
{
    if ((pivot < 0) != (swapped != 0))
        s->det_sign = -s->det_sign;
    s->det_log += log(fabs(pivot));
}

/* Gaussian elimination with row pivoting over interval j's interior columns */
static int condense_interval(colloc_sys *s, int j)
{
    const int W = s->W, rows = s->rows;
    double *A = s->blk + (size_t)j * rows * W;
    for (int c = 0; c < s->m; c++) {
        int piv = c;
        for (int r = c + 1; r < rows; r++)
            if (fabs(A[(size_t)r * W + c]) > fabs(A[(size_t)piv * W + c]))
                piv = r;
        if (A[(size_t)piv * W + c] == 0.0)
            return DYN_COLLOC_ERR_SINGULAR;
        det_factor(s, A[(size_t)piv * W + c], piv != c);
        if (piv != c)
            for (int q = c; q < W; q++) {
                const double tmp = A[(size_t)c * W + q];
                A[(size_t)c * W + q] = A[(size_t)piv * W + q];
                A[(size_t)piv * W + q] = tmp;
            }
        const double *pr = A + (size_t)c * W;
        for (int r = c + 1; r < rows; r++) {
            double *rr = A + (size_t)r * W;
            const double fct = rr[c] / pr[c];
            if (fct == 0.0)
                continue;
            for (int q = c; q < W; q++)
                rr[q] -= fct * pr[q];
        }
    }
    /* the border rows over the same pivots */
    for (int bi = 0; bi < s->nb; bi++) {
        double *br = s->brow + (size_t)bi * (s->Nx + 1);
        for (int c = 0; c < s->m; c++) {
            const double a = br[gcol(s, j, c)];
            if (a == 0.0)
                continue;
            const double *pr = A + (size_t)c * W;
            const double fct = a / pr[c];
            for (int q = c; q < W; q++)
                br[gcol(s, j, q)] -= fct * pr[q];
        }
    }
    return 0;
}

/* the border rows: boundary conditions, phase, arclength (minus the residual last) */
static int assemble_border(colloc_sys *s, const dyn_colloc_sol *x, const dyn_colloc_sol *ref,
                           const dyn_colloc_arc *arc)
{
    const int n = s->n, ncol = s->ncol, npar = s->npar;
    const dyn_colloc_problem *p = s->p;
    const long stride = s->Nx + 1;
    memset(s->brow, 0, (size_t)s->nb * stride * sizeof(double));
    int bi = 0;
    if (p->nbc) {
        const size_t nn = (size_t)n;
        double *u0 = malloc((4 * nn + 2 * (size_t)p->nbc + (size_t)npar + 1) * sizeof(double));
        if (!u0)
            return DYN_COLLOC_ERR_NOMEM;
        double *u1 = u0 + nn, *g = u1 + nn, *gp = g + p->nbc, *gm = gp + p->nbc,
               *pp = gm + 2 * nn;
        const double *ulast = x->u + (size_t)(s->nnodes - 1) * n;
        memcpy(u0, x->u, nn * sizeof(double));
        memcpy(u1, ulast, nn * sizeof(double));
        memcpy(pp, x->par, (size_t)npar * sizeof(double));
        int st = p->bc(u0, u1, pp, g, p->ctx) || !finite_all(p->nbc, g);
        for (int r = 0; r < p->nbc; r++)
            s->brow[(size_t)r * stride + s->Nx] = -g[r];
        /* columns: u(0), u(1), par by central differences */
        for (int c = 0; c < 2 * n + npar && !st; c++) {
            double *v = c < n ? &u0[c] : c < 2 * n ? &u1[c - n] : &pp[c - 2 * n];
            const double keep = *v, d = 1e-6 * (1.0 + fabs(keep));
            *v = keep + d;
            st = p->bc(u0, u1, pp, gp, p->ctx);
            *v = keep - d;
            st = st || p->bc(u0, u1, pp, gm, p->ctx);
            *v = keep;
            const long col = c < n ? c : c < 2 * n ? (s->nnodes - 1) * n + (c - n)
                                                   : s->Nu + (c - 2 * n);
            for (int r = 0; r < p->nbc; r++)
                s->brow[(size_t)r * stride + col] += (gp[r] - gm[r]) / (2 * d);
        }
        free(u0);
        if (st)
            return DYN_COLLOC_ERR_FN;
        bi = p->nbc;
    }
    if (p->phase) { /* int_0^1 u . ref' dt = 0, or int_0^1 (u - ref) . ref' dt = 0 */
        double *br = s->brow + (size_t)bi * stride;
        double val = 0.0;
        for (int j = 0; j < s->ntst; j++) {
            const double h = x->mesh[j + 1] - x->mesh[j];
            const double *R = ref->u + (size_t)j * ncol * n;
            for (int l = 0; l <= ncol; l++) {
                const long g = ((long)j * ncol + l) * n;
                for (int i = 0; i < n; i++) {
                    double dr = 0.0;
                    for (int q = 0; q <= ncol; q++)
                        dr += s->b.Dn[l][q] * R[(size_t)q * n + i];
                    const double c = s->b.w[l] * dr; /* h w_l times ref'(node) = dr / h */
                    br[g + i] += c;
                    const double r0 = p->phase == 2 ? R[(size_t)l * n + i] : 0.0;
                    val += c * (x->u[g + i] - r0);
                }
            }
            (void)h;
        }
        br[s->Nx] = -val;
        bi++;
    }
    if (arc) { /* <x - x0, t> - ds */
        double *br = s->brow + (size_t)bi * stride;
        double val = 0.0;
        const dyn_colloc_sol *t = arc->tangent, *x0 = arc->x0;
        for (int j = 0; j < s->ntst; j++) {
            const double h = x->mesh[j + 1] - x->mesh[j];
            for (int l = 0; l <= ncol; l++) {
                const long g = ((long)j * ncol + l) * n;
                for (int i = 0; i < n; i++) {
                    const double c = h * s->b.w[l] * t->u[g + i];
                    br[g + i] += c;
                    val += c * (x->u[g + i] - x0->u[g + i]);
                }
            }
        }
        for (int k = 0; k < npar; k++) {
            br[s->Nu + k] = t->par[k];
            val += t->par[k] * (x->par[k] - x0->par[k]);
        }
        br[s->Nx] = -(val - arc->ds);
    }
    return 0;
}

/* the reduced system and the solve; dx (Nx) the solution for the right-hand side kept in
 * the blocks' last column and the border rows' last entry */
static int reduced_solve(colloc_sys *s, double *dx)
{
    const int n = s->n, ntst = s->ntst, W = s->W, m = s->m, npar = s->npar;
    const int nx = ntst * n, ny = n + npar;
    if (n < 1 || ntst < 1 || npar < 0)
        return DYN_COLLOC_ERR_ARG;
    const int lower = 2 * n - 1, upper = n - 1, ldab = 2 * lower + upper + 1;
    const size_t nxs = (size_t)nx, nys = (size_t)ny;
    double *ab = calloc(nxs * ldab, sizeof(double));
    double *E = calloc(nxs * (nys + 1), sizeof(double)); /* columns: y then rhs */
    double *F = calloc(nys * nxs, sizeof(double));
    double *G = calloc(nys * (nys + 1), sizeof(double));
    int *piv = malloc((nxs + nys) * sizeof(int));
    double *col = malloc(nxs * sizeof(double));
    int st = 0;
    if (!ab || !E || !F || !G || !piv || !col) {
        st = DYN_COLLOC_ERR_NOMEM;
        goto done;
    }
#define AB(i, jj) ab[(size_t)(jj) * ldab + lower + upper + (i) - (jj)]
    for (int j = 0; j < ntst; j++) {
        const double *A = s->blk + (size_t)j * s->rows * W;
        for (int r = 0; r < n; r++) {
            const double *row = A + (size_t)(m + r) * W;
            const int R = j * n + r;
            for (int q = 0; q < n; q++) {
                if (j == 0)
                    E[(size_t)q * nxs + R] = row[m + q];
                else
                    AB(R, (j - 1) * n + q) = row[m + q];
                AB(R, j * n + q) = row[m + n + q];
            }
            for (int k = 0; k < npar; k++)
                E[(size_t)(n + k) * nxs + R] = row[m + 2 * n + k];
            E[nys * nxs + R] = row[W - 1];
        }
    }
    for (int bi = 0; bi < ny; bi++) {
        const double *br = s->brow + (size_t)bi * (s->Nx + 1);
        for (int j = 0; j <= ntst; j++)
            for (int q = 0; q < n; q++) {
                const double v = br[(long)j * s->ncol * n + q];
                if (j == 0)
                    G[(size_t)bi * (nys + 1) + q] = v;
                else
                    F[(size_t)bi * nxs + (size_t)(j - 1) * n + q] = v;
            }
        for (int k = 0; k < npar; k++)
            G[(size_t)bi * (nys + 1) + n + k] = br[s->Nu + k];
        G[(size_t)bi * (nys + 1) + nys] = br[s->Nx];
    }
#undef AB
    if (dyn_band_lu_factor(nx, lower, upper, ab, ldab, piv)) {
        st = DYN_COLLOC_ERR_SINGULAR;
        goto done;
    }
    for (int j = 0; j < nx; j++)
        det_factor(s, ab[(size_t)j * ldab + lower + upper], piv[j] != j);
    for (int c = 0; c <= ny; c++)
        dyn_band_lu_solve(nx, lower, upper, ab, ldab, piv, E + (size_t)c * nxs);
    /* S = G - F Z and s = rhs_y - F z, in G (ny x (ny + 1)) */
    for (int bi = 0; bi < ny; bi++)
        for (int c = 0; c <= ny; c++) {
            double acc = 0.0;
            const double *fr = F + (size_t)bi * nxs, *zc = E + (size_t)c * nxs;
            for (size_t i = 0; i < nxs; i++)
                acc += fr[i] * zc[i];
            G[(size_t)bi * (nys + 1) + c] -= acc;
        }
    double *S = malloc(nys * nys * sizeof(double)), *y = malloc(nys * sizeof(double));
    if (!S || !y) {
        free(S);
        free(y);
        st = DYN_COLLOC_ERR_NOMEM;
        goto done;
    }
    for (int r = 0; r < ny; r++) {
        for (int c = 0; c < ny; c++)
            S[(size_t)r * nys + c] = G[(size_t)r * (nys + 1) + c];
        y[r] = G[(size_t)r * (nys + 1) + nys];
    }
    if (dyn_lu_factor(ny, S, piv + nxs)) {
        free(S);
        free(y);
        st = DYN_COLLOC_ERR_SINGULAR;
        goto done;
    }
    for (int r = 0; r < ny; r++)
        det_factor(s, S[(size_t)r * nys + r], piv[nxs + r] != r);
    dyn_lu_solve(ny, S, piv + nxs, y);
    /* mesh points and free scalars */
    for (int q = 0; q < n; q++)
        dx[q] = y[q];
    for (int k = 0; k < npar; k++)
        dx[s->Nu + k] = y[n + k];
    for (size_t i = 0; i < nxs; i++) {
        double v = E[nys * nxs + i];
        for (int c = 0; c < ny; c++)
            v -= E[(size_t)c * nxs + i] * y[c];
        const int j = (int)(i / (size_t)n) + 1, q = (int)(i % (size_t)n);
        dx[(long)j * s->ncol * n + q] = v;
    }
    free(S);
    free(y);
    /* interior nodes by back substitution */
    for (int j = 0; j < ntst; j++) {
        const double *A = s->blk + (size_t)j * s->rows * W;
        for (int c = m - 1; c >= 0; c--) {
            const double *row = A + (size_t)c * W;
            double v = row[W - 1];
            for (int q = c + 1; q < W - 1; q++)
                v -= row[q] * dx[gcol(s, j, q)];
            dx[gcol(s, j, c)] = v / row[c];
        }
    }
    for (long i = 0; i < s->Nx; i++)
        if (!isfinite(dx[i])) {
            st = DYN_COLLOC_ERR_SINGULAR;
            break;
        }
done:
    free(ab);
    free(E);
    free(F);
    free(G);
    free(piv);
    free(col);
    return st;
}

/* the linear system at x with its residual, solved into dx; *res: max |residual| */
static int linear_step(colloc_sys *s, const dyn_colloc_sol *x, const dyn_colloc_sol *ref,
                       const dyn_colloc_arc *arc, double *dx, double *res)
{
    int st = assemble_border(s, x, ref, arc);
    for (int j = 0; j < s->ntst && !st; j++)
        st = assemble_interval(s, x, j);
    if (st)
        return st;
    double r = 0.0;
    for (int j = 0; j < s->ntst; j++)
        for (int i = 0; i < s->rows; i++)
            r = fmax(r, fabs(s->blk[((size_t)j * s->rows + i) * s->W + s->W - 1]));
    for (int bi = 0; bi < s->nb; bi++)
        r = fmax(r, fabs(s->brow[(size_t)bi * (s->Nx + 1) + s->Nx]));
    *res = r;
    for (int j = 0; j < s->ntst && !st; j++)
        st = condense_interval(s, j);
    if (st)
        return st;
    return reduced_solve(s, dx);
}

int dyn_colloc_solve(const dyn_colloc_problem *p, dyn_colloc_sol *x, const dyn_colloc_sol *ref,
                     const dyn_colloc_arc *arc, const dyn_colloc_opts *o,
                     dyn_colloc_info *info)
{
    colloc_sys s;
    int st = sys_init(&s, p, x, arc ? 1 : 0);
    if (st)
        return st;
    if (p->phase && !ref) {
        sys_free(&s);
        return DYN_COLLOC_ERR_ARG;
    }
    const double tol = o && o->tol > 0 ? o->tol : 1e-10;
    const int max_iter = o && o->max_iter > 0 ? o->max_iter : 20;
    double *dx = malloc((size_t)s.Nx * sizeof(double));
    if (!dx) {
        sys_free(&s);
        return DYN_COLLOC_ERR_NOMEM;
    }
    dyn_colloc_info inf = {0, 0, 0};
    st = DYN_COLLOC_ERR_NEWTON;
    for (int it = 1; it <= max_iter; it++) {
        double res;
        int ls = linear_step(&s, x, ref, arc, dx, &res);
        if (ls) {
            st = ls;
            break;
        }
        double step = 0.0, size = 0.0;
        for (long i = 0; i < s.Nu; i++) {
            x->u[i] += dx[i];
            step = fmax(step, fabs(dx[i]));
            size = fmax(size, fabs(x->u[i]));
        }
        for (int k = 0; k < s.npar; k++) {
            x->par[k] += dx[s.Nu + k];
            step = fmax(step, fabs(dx[s.Nu + k]));
            size = fmax(size, fabs(x->par[k]));
        }
        inf.iterations = it;
        inf.step = step;
        inf.residual = res;
        if (step <= tol * (1.0 + size)) {
            st = 0;
            break;
        }
        if (!(step < 1e8 * (1.0 + size))) /* diverged */
            break;
    }
    free(dx);
    sys_free(&s);
    if (info)
        *info = inf;
    return st;
}

/* the Jacobian at x bordered by the arclength row of t, solved for the right-hand side rhs
 * (the collocation rows interval by interval, then the border rows; NULL: the arclength
 * row's 1, zero elsewhere) into dx (s->Nx, allocated here); s is initialised here and freed
 * by the caller when s->blk is set */
static int bordered_solve(colloc_sys *s, const dyn_colloc_problem *p, const dyn_colloc_sol *x,
                          const dyn_colloc_sol *ref, const dyn_colloc_sol *t,
                          const double *rhs, double **dx)
{
    *dx = NULL;
    int st = sys_init(s, p, x, 1);
    if (st) {
        memset(s, 0, sizeof *s); /* freed, or never allocated */
        return st;
    }
    *dx = malloc((size_t)s->Nx * sizeof(double));
    if (!*dx)
        return DYN_COLLOC_ERR_NOMEM;
    /* the arclength row <x - x, t> - (-1): its coefficients are t's; the right-hand side
     * replaces every residual */
    dyn_colloc_arc arc = {x, t, -1.0};
    st = assemble_border(s, x, ref, &arc);
    for (int j = 0; j < s->ntst && !st; j++)
        st = assemble_interval(s, x, j);
    if (st)
        return st;
    const long nrows = (long)s->ntst * s->rows;
    for (int j = 0; j < s->ntst; j++)
        for (int i = 0; i < s->rows; i++) {
            const long e = (long)j * s->rows + i;
            s->blk[(size_t)e * s->W + s->W - 1] = rhs ? rhs[e] : 0.0;
        }
    for (int bi = 0; bi < s->nb; bi++)
        s->brow[(size_t)bi * (s->Nx + 1) + s->Nx] =
            rhs ? rhs[nrows + bi] : bi == s->nb - 1 ? 1.0 : 0.0;
    for (int j = 0; j < s->ntst && !st; j++)
        st = condense_interval(s, j);
    if (!st)
        st = reduced_solve(s, *dx);
    return st;
}

int dyn_colloc_tangent(const dyn_colloc_problem *p, const dyn_colloc_sol *x,
                       const dyn_colloc_sol *ref, const dyn_colloc_sol *told,
                       dyn_colloc_sol *t)
{
    int st = dyn_colloc_sol_alloc(t, x->n, x->ntst, x->ncol, x->npar);
    if (st)
        return st;
    memcpy(t->mesh, x->mesh, ((size_t)x->ntst + 1) * sizeof(double));
    if (told) {
        memcpy(t->u, told->u, (size_t)dyn_colloc_nodes(x) * x->n * sizeof(double));
        memcpy(t->par, told->par, (size_t)x->npar * sizeof(double));
    } else if (x->npar > 0) {
        t->par[x->npar - 1] = 1.0;
    }
    /* J t = 0 with <t, t_old> = 1 */
    colloc_sys s;
    double *dx;
    st = bordered_solve(&s, p, x, ref, t, NULL, &dx);
    if (!st) {
        memcpy(t->u, dx, (size_t)s.Nu * sizeof(double));
        memcpy(t->par, dx + s.Nu, (size_t)s.npar * sizeof(double));
        const double nrm = sqrt(dyn_colloc_dot(t, t));
        if (!(nrm > 0) || !isfinite(nrm)) {
            st = DYN_COLLOC_ERR_SINGULAR;
        } else {
            for (long i = 0; i < s.Nu; i++)
                t->u[i] /= nrm;
            for (int k = 0; k < s.npar; k++)
                t->par[k] /= nrm;
        }
    }
    free(dx);
    if (s.blk)
        sys_free(&s);
    if (st)
        dyn_colloc_sol_free(t);
    return st;
}

int dyn_colloc_bordered(const dyn_colloc_problem *p, const dyn_colloc_sol *x,
                        const dyn_colloc_sol *ref, const dyn_colloc_sol *t, const double *rhs,
                        double *sol, int *det_sign, double *det_log)
{
    colloc_sys s;
    double *dx;
    int st = bordered_solve(&s, p, x, ref, t, rhs, &dx);
    if (!st) {
        if (sol)
            memcpy(sol, dx, (size_t)s.Nx * sizeof(double));
        *det_sign = s.det_sign;
        *det_log = s.det_log;
    }
    free(dx);
    if (s.blk)
        sys_free(&s);
    return st;
}

int dyn_colloc_monodromy(const dyn_colloc_problem *p, const dyn_colloc_sol *x, double *M)
{
    /* the interval rows alone: no border, so sys_init is told the counts fit */
    dyn_colloc_problem q = *p;
    q.nbc = p->n + p->npar - (p->phase ? 1 : 0);
    colloc_sys s;
    int st = sys_init(&s, &q, x, 0);
    if (st)
        return st;
    s.nb = 0;
    const int n = s.n, m = s.m, W = s.W;
    const size_t nn = (size_t)n;
    double *Phi = malloc(nn * nn * sizeof(double)), *B = malloc(nn * nn * sizeof(double));
    double *T = malloc(nn * nn * sizeof(double)), *c = malloc(nn * sizeof(double));
    int *piv = malloc(nn * sizeof(int));
    if (!Phi || !B || !T || !c || !piv)
        st = DYN_COLLOC_ERR_NOMEM;
    for (size_t i = 0; i < nn * nn; i++)
        if (M)
            M[i] = (i % (nn + 1)) == 0 ? 1.0 : 0.0;
    for (int j = 0; j < s.ntst && !st; j++) {
        st = assemble_interval(&s, x, j);
        if (!st)
            st = condense_interval(&s, j);
        if (st)
            break;
        const double *A = s.blk + (size_t)j * s.rows * W;
        /* A_j w_j + B_j w_j+1 = 0: Phi_j = -B_j^-1 A_j; M := Phi_j M */
        for (int r = 0; r < n; r++)
            for (int q2 = 0; q2 < n; q2++) {
                B[(size_t)r * nn + q2] = A[(size_t)(m + r) * W + m + n + q2];
                Phi[(size_t)r * nn + q2] = -A[(size_t)(m + r) * W + m + q2];
            }
        if (dyn_lu_factor(n, B, piv)) {
            st = DYN_COLLOC_ERR_SINGULAR;
            break;
        }
        for (int q2 = 0; q2 < n; q2++) { /* column q2 of Phi */
            for (int r = 0; r < n; r++)
                c[r] = Phi[(size_t)r * nn + q2];
            dyn_lu_solve(n, B, piv, c);
            for (int r = 0; r < n; r++)
                Phi[(size_t)r * nn + q2] = c[r];
        }
        for (int r = 0; r < n; r++)
            for (int q2 = 0; q2 < n; q2++) {
                double acc = 0.0;
                for (int k = 0; k < n; k++)
                    acc += Phi[(size_t)r * nn + k] * M[(size_t)k * nn + q2];
                T[(size_t)r * nn + q2] = acc;
            }
        memcpy(M, T, nn * nn * sizeof(double));
    }
    free(Phi);
    free(B);
    free(T);
    free(c);
    free(piv);
    sys_free(&s);
    return st;
}
