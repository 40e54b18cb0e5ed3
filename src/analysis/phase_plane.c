/* SPDX-License-Identifier: BSD-3-Clause */
/* A model's phase plane in two states (dynkit/phase_plane.h): the nullclines by marching
 * squares (Lorensen & Cline's cases in two dimensions, a cell's saddle resolved by the sign
 * at its centre) with each vertex located on its cell edge by the Illinois method (Dowell &
 * Jarratt, BIT 11 (1971) 168), and the equilibria of the plane by damped Newton steps with
 * their type from the trace and determinant of the 2x2 Jacobian (Strogatz, "Nonlinear
 * Dynamics and Chaos", sec. 5.2). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/phase_plane.h"

/* workspace: y (n), f (n), the full Jacobian (n x n), then the grid's values of f_ix and
 * f_iy ((nx + 1) (ny + 1) each) */
size_t dyn_plane_work_size(int n_states, int nx, int ny)
{
    const size_t n = (size_t)(n_states > 0 ? n_states : 0);
    const size_t g = nx > 0 && ny > 0 ? (size_t)(nx + 1) * (size_t)(ny + 1) : 0;
    return 2 * n + n * n + 2 * g;
}

int dyn_plane_rates(const dyn_plane *p, double x, double y, double *work, double *fx,
                    double *fy)
{
    const int n = p->model->n_states;
    double *yy = work, *f = work + n;
    memcpy(yy, p->y, (size_t)n * sizeof *yy);
    yy[p->ix] = x;
    yy[p->iy] = y;
    const int rc = p->model->rhs(p->t, yy, f, (void *)p->par);
    *fx = rc ? NAN : f[p->ix];
    *fy = rc ? NAN : f[p->iy];
    return rc;
}

/* f_which at (x, y), NaN when the right-hand side fails or is not finite */
static double rate(const dyn_plane *p, int which, double x, double y, double *work)
{
    double fx, fy;
    dyn_plane_rates(p, x, y, work, &fx, &fy);
    const double v = which ? fy : fx;
    return isfinite(v) ? v : NAN;
}

typedef struct grid {
    int nx, ny;
    double dx, dy;
} grid;

static double gx(const dyn_plane *p, const grid *g, int i)
{
    return i == g->nx ? p->xhi : p->xlo + i * g->dx;
}

static double gy(const dyn_plane *p, const grid *g, int j)
{
    return j == g->ny ? p->yhi : p->ylo + j * g->dy;
}

/* The zero of f_which on the segment from (x0, y0) (value v0) to (x1, y1) (value v1, of the
 * other sign): the Illinois method on s in [0, 1] to rounding. */
static void edge_zero(const dyn_plane *p, int which, double x0, double y0, double v0, double x1,
                      double y1, double v1, double *work, double *xz, double *yz)
{
    double a = 0.0, b = 1.0, fa = v0, fb = v1;
    int side = 0;
    for (int it = 0; it < 100; it++) {
        const double s = (a * fb - b * fa) / (fb - fa);
        const double xs = x0 + s * (x1 - x0), ys = y0 + s * (y1 - y0);
        const double fs = rate(p, which, xs, ys, work);
        if (!isfinite(fs) || fs == 0.0 || b - a <= 4 * DBL_EPSILON) {
            a = b = s;
            break;
        }
        if ((fs > 0) == (fb > 0)) {
            b = s;
            fb = fs;
            if (side == -1)
                fa *= 0.5;
            side = -1;
        } else {
            a = s;
            fa = fs;
            if (side == 1)
                fb *= 0.5;
            side = 1;
        }
        if (b - a <= 4 * DBL_EPSILON * fmax(1.0, fabs(s)))
            break;
    }
    const double s = fabs(fa) < fabs(fb) ? a : b;
    *xz = x0 + s * (x1 - x0);
    *yz = y0 + s * (y1 - y0);
}

static int check_plane(const dyn_plane *p, int nx, int ny, char *err, size_t errlen)
{
    const int n = p->model ? p->model->n_states : 0;
    if (!p->model || !p->y || p->ix < 0 || p->iy < 0 || p->ix >= n || p->iy >= n ||
        p->ix == p->iy) {
        snprintf(err, errlen, "the plane needs two different states of the model");
        return -1;
    }
    if (!(p->xhi > p->xlo) || !(p->yhi > p->ylo) || !isfinite(p->xhi - p->xlo) ||
        !isfinite(p->yhi - p->ylo)) {
        snprintf(err, errlen, "the window [%g, %g] x [%g, %g] needs lo < hi, finite", p->xlo,
                 p->xhi, p->ylo, p->yhi);
        return -1;
    }
    if (nx < 1 || ny < 1 || nx > 100000 || ny > 100000) {
        snprintf(err, errlen, "the grid needs 1 to 100000 cells a side, not %d x %d", nx, ny);
        return -1;
    }
    return 0;
}

/* The values of f_ix and f_iy at the grid points into work's grid part. */
static double *grid_values(const dyn_plane *p, const grid *g, double *work)
{
    const int n = p->model->n_states;
    double *v = work + 2 * n + (size_t)n * (size_t)n;
    const size_t np = (size_t)(g->nx + 1) * (size_t)(g->ny + 1);
    for (int j = 0; j <= g->ny; j++)
        for (int i = 0; i <= g->nx; i++) {
            double fx, fy;
            dyn_plane_rates(p, gx(p, g, i), gy(p, g, j), work, &fx, &fy);
            const size_t k = (size_t)j * (size_t)(g->nx + 1) + (size_t)i;
            v[k] = isfinite(fx) ? fx : NAN;
            v[np + k] = isfinite(fy) ? fy : NAN;
        }
    return v;
}

int dyn_plane_nullclines(const dyn_plane *p, int nx, int ny, double *work, dyn_segment_fn emit,
                         void *ctx, char *err, size_t errlen)
{
    if (check_plane(p, nx, ny, err, errlen))
        return -1;
    grid g = {nx, ny, (p->xhi - p->xlo) / nx, (p->yhi - p->ylo) / ny};
    const double *v = grid_values(p, &g, work);
    const size_t np = (size_t)(nx + 1) * (size_t)(ny + 1), row = (size_t)(nx + 1);
    for (int which = 0; which < 2; which++) {
        const double *f = v + (size_t)which * np;
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) {
                /* corners: 0 (i, j), 1 (i+1, j), 2 (i+1, j+1), 3 (i, j+1) */
                const int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
                double c[4], cx[4], cy[4];
                int bad = 0;
                for (int k = 0; k < 4; k++) {
                    c[k] = f[(size_t)cj[k] * row + (size_t)ci[k]];
                    cx[k] = gx(p, &g, ci[k]);
                    cy[k] = gy(p, &g, cj[k]);
                    bad |= !isfinite(c[k]);
                }
                if (bad)
                    continue;
                /* a vertex on each edge k (corner k to corner k+1) whose ends differ */
                double ex[4], ey[4];
                int has[4], count = 0;
                for (int k = 0; k < 4; k++) {
                    const int l = (k + 1) % 4;
                    has[k] = (c[k] > 0) != (c[l] > 0);
                    if (has[k]) {
                        edge_zero(p, which, cx[k], cy[k], c[k], cx[l], cy[l], c[l], work, &ex[k],
                                  &ey[k]);
                        count++;
                    }
                }
                if (count == 2) {
                    int a = -1, b = -1;
                    for (int k = 0; k < 4; k++)
                        if (has[k]) {
                            if (a < 0)
                                a = k;
                            else
                                b = k;
                        }
                    emit(which, ex[a], ey[a], ex[b], ey[b], ctx);
                } else if (count == 4) {
                    /* a saddle cell: corners 0 and 2 of one sign; the centre decides
                     * whether they are joined (then corners 1 and 3 are cut off) */
                    const double mid = rate(p, which, 0.5 * (cx[0] + cx[2]),
                                            0.5 * (cy[0] + cy[2]), work);
                    if ((mid > 0) == (c[0] > 0)) {
                        emit(which, ex[0], ey[0], ex[1], ey[1], ctx); /* around corner 1 */
                        emit(which, ex[2], ey[2], ex[3], ey[3], ctx); /* around corner 3 */
                    } else {
                        emit(which, ex[3], ey[3], ex[0], ey[0], ctx); /* around corner 0 */
                        emit(which, ex[1], ey[1], ex[2], ey[2], ctx); /* around corner 2 */
                    }
                }
            }
    }
    return 0;
}

const char *dyn_plane_point_name(dyn_plane_point_type type)
{
    switch (type) {
    case DYN_PLANE_SADDLE: return "saddle";
    case DYN_PLANE_STABLE_NODE: return "stable node";
    case DYN_PLANE_UNSTABLE_NODE: return "unstable node";
    case DYN_PLANE_STABLE_FOCUS: return "stable focus";
    case DYN_PLANE_UNSTABLE_FOCUS: return "unstable focus";
    case DYN_PLANE_CENTER: return "centre";
    case DYN_PLANE_DEGENERATE: return "degenerate";
    }
    return "?";
}

/* The 2x2 Jacobian of (f_ix, f_iy) in (x, y) at (x, y): the model's, else central
 * differences (step cbrt(eps) times the coordinate's scale). 0, or -1. */
static int plane_jacobian(const dyn_plane *p, double x, double y, double *work, double J[4])
{
    const dyn_model *m = p->model;
    const int n = m->n_states;
    if (m->jacobian) {
        double *yy = work, *Jn = work + 2 * n;
        memcpy(yy, p->y, (size_t)n * sizeof *yy);
        yy[p->ix] = x;
        yy[p->iy] = y;
        if (m->jacobian(p->t, yy, Jn, (void *)p->par) == 0) {
            J[0] = Jn[p->ix * n + p->ix];
            J[1] = Jn[p->ix * n + p->iy];
            J[2] = Jn[p->iy * n + p->ix];
            J[3] = Jn[p->iy * n + p->iy];
            if (isfinite(J[0]) && isfinite(J[1]) && isfinite(J[2]) && isfinite(J[3]))
                return 0;
        }
    }
    const double hx = cbrt(DBL_EPSILON) * fmax(fabs(x), 1e-3 * (p->xhi - p->xlo));
    const double hy = cbrt(DBL_EPSILON) * fmax(fabs(y), 1e-3 * (p->yhi - p->ylo));
    double a[2], b[2], c[2], d[2];
    dyn_plane_rates(p, x + hx, y, work, &a[0], &a[1]);
    dyn_plane_rates(p, x - hx, y, work, &b[0], &b[1]);
    dyn_plane_rates(p, x, y + hy, work, &c[0], &c[1]);
    dyn_plane_rates(p, x, y - hy, work, &d[0], &d[1]);
    J[0] = (a[0] - b[0]) / (2 * hx);
    J[2] = (a[1] - b[1]) / (2 * hx);
    J[1] = (c[0] - d[0]) / (2 * hy);
    J[3] = (c[1] - d[1]) / (2 * hy);
    return isfinite(J[0]) && isfinite(J[1]) && isfinite(J[2]) && isfinite(J[3]) ? 0 : -1;
}

static void classify(dyn_plane_point *pt)
{
    const double *J = pt->jac;
    const double tr = J[0] + J[3], det = J[0] * J[3] - J[1] * J[2];
    const double disc = 0.25 * tr * tr - det;
    if (disc >= 0) {
        const double r = sqrt(disc);
        /* the larger root without cancellation, the other from the product det */
        const double big = 0.5 * tr + (tr >= 0 ? r : -r);
        const double small = big != 0.0 ? det / big : 0.0;
        pt->re[0] = fmin(big, small);
        pt->re[1] = fmax(big, small);
        pt->im[0] = pt->im[1] = 0.0;
    } else {
        pt->re[0] = pt->re[1] = 0.5 * tr;
        pt->im[0] = -sqrt(-disc);
        pt->im[1] = sqrt(-disc);
    }
    const double norm = fmax(fabs(J[0]) + fabs(J[1]), fabs(J[2]) + fabs(J[3]));
    const double tol = 1e-8 * fmax(norm, DBL_MIN);
    if (fabs(det) <= tol * tol * 1e4 || fabs(det) <= 1e-12 * norm * norm)
        pt->type = DYN_PLANE_DEGENERATE;
    else if (det < 0)
        pt->type = DYN_PLANE_SADDLE;
    else if (fabs(tr) <= tol)
        pt->type = DYN_PLANE_CENTER;
    else if (disc >= 0)
        pt->type = tr < 0 ? DYN_PLANE_STABLE_NODE : DYN_PLANE_UNSTABLE_NODE;
    else
        pt->type = tr < 0 ? DYN_PLANE_STABLE_FOCUS : DYN_PLANE_UNSTABLE_FOCUS;
}

int dyn_plane_equilibrium(const dyn_plane *p, double x, double y, double *work,
                          dyn_plane_point *pt)
{
    char err[8];
    if (check_plane(p, 1, 1, err, sizeof err))
        return -1;
    const double wx = p->xhi - p->xlo, wy = p->yhi - p->ylo;
    double fx, fy, J[4];
    if (dyn_plane_rates(p, x, y, work, &fx, &fy) || !isfinite(fx) || !isfinite(fy))
        return -1;
    int converged = 0;
    for (int it = 0; it < 60 && !converged; it++) {
        if (plane_jacobian(p, x, y, work, J))
            return -1;
        const double det = J[0] * J[3] - J[1] * J[2];
        if (det == 0.0 || !isfinite(det))
            return -1;
        const double dx = -(J[3] * fx - J[1] * fy) / det, dy = -(-J[2] * fx + J[0] * fy) / det;
        const double norm0 = hypot(fx, fy);
        double lambda = 1.0, nx = x, ny = y, gfx = fx, gfy = fy;
        for (int k = 0; k < 30; k++, lambda *= 0.5) { /* halve until |f| decreases */
            nx = x + lambda * dx;
            ny = y + lambda * dy;
            if (dyn_plane_rates(p, nx, ny, work, &gfx, &gfy) == 0 && isfinite(gfx) &&
                isfinite(gfy) && hypot(gfx, gfy) < norm0)
                break;
        }
        const double step = fmax(fabs(nx - x) / wx, fabs(ny - y) / wy);
        x = nx;
        y = ny;
        fx = gfx;
        fy = gfy;
        if (!isfinite(fx) || !isfinite(fy))
            return -1;
        converged = step <= 1e-14 || (fx == 0.0 && fy == 0.0);
        if (fabs(x - p->xlo) > 100 * wx || fabs(y - p->ylo) > 100 * wy)
            return -1;
    }
    if (plane_jacobian(p, x, y, work, J))
        return -1;
    /* |f| small against what the Jacobian makes of a step of rounding's size */
    const double scale = (fabs(J[0]) + fabs(J[1])) * fmax(fabs(x), wx) +
                         (fabs(J[2]) + fabs(J[3])) * fmax(fabs(y), wy);
    if (!(hypot(fx, fy) <= 1e-10 * fmax(scale, DBL_MIN)))
        return -1;
    const double gx_ = wx / 8, gy_ = wy / 8; /* the window, enlarged a little */
    if (x < p->xlo - gx_ || x > p->xhi + gx_ || y < p->ylo - gy_ || y > p->yhi + gy_)
        return -1;
    pt->x = x;
    pt->y = y;
    memcpy(pt->jac, J, sizeof J);
    classify(pt);
    return 0;
}

static int differ(const double *v, const size_t *k)
{
    int pos = 0, neg = 0;
    for (int i = 0; i < 4; i++) {
        if (!isfinite(v[k[i]]))
            return 0;
        pos |= v[k[i]] > 0;
        neg |= v[k[i]] <= 0;
    }
    return pos && neg;
}

int dyn_plane_equilibria(const dyn_plane *p, int nx, int ny, double *work, dyn_plane_point *pts,
                         int max, char *err, size_t errlen)
{
    if (check_plane(p, nx, ny, err, errlen))
        return -1;
    grid g = {nx, ny, (p->xhi - p->xlo) / nx, (p->yhi - p->ylo) / ny};
    const double *v = grid_values(p, &g, work);
    const size_t np = (size_t)(nx + 1) * (size_t)(ny + 1), row = (size_t)(nx + 1);
    int count = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            const size_t k[4] = {(size_t)j * row + (size_t)i, (size_t)j * row + (size_t)i + 1,
                                 (size_t)(j + 1) * row + (size_t)i + 1,
                                 (size_t)(j + 1) * row + (size_t)i};
            if (!differ(v, k) || !differ(v + np, k))
                continue;
            dyn_plane_point pt;
            if (dyn_plane_equilibrium(p, gx(p, &g, i) + 0.5 * g.dx, gy(p, &g, j) + 0.5 * g.dy,
                                      work, &pt))
                continue;
            if (pt.x < p->xlo || pt.x > p->xhi || pt.y < p->ylo || pt.y > p->yhi)
                continue;
            int dup = 0;
            for (int q = 0; q < count && !dup; q++)
                dup = fabs(pts[q].x - pt.x) <= 1e-7 * (p->xhi - p->xlo) &&
                      fabs(pts[q].y - pt.y) <= 1e-7 * (p->yhi - p->ylo);
            if (dup || count >= max)
                continue;
            /* sorted by x, then y */
            int at = count;
            while (at > 0 && (pts[at - 1].x > pt.x || (pts[at - 1].x == pt.x && pts[at - 1].y > pt.y))) {
                pts[at] = pts[at - 1];
                at--;
            }
            pts[at] = pt;
            count++;
        }
    return count;
}
