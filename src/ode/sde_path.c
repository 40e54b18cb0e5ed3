/* SPDX-License-Identifier: BSD-3-Clause */
/* The kept Brownian path of the adaptive methods for noise (sde_path.h).
 *
 * The path is kept: every value of W drawn at a time ahead stays in a sorted list
 * until the run passes it, and a value between two known ones comes from the Brownian bridge
 *   W(s) = W(a) + (s - a)/(b - a) (W(b) - W(a)) + sqrt((s - a)(b - s)/(b - a)) z,
 * so a rejected step leaves the path a sample of Brownian motion (Rackauckas and Nie 2017,
 * rejection sampling with memory). SRIW1 also needs the time integral of W over a step:
 * each segment between two kept points carries J = int (W(s) - W(left)) ds over it, drawn
 * with the increment dW over a length H as J = (H dW + sqrt(H^3/3) xi)/2, xi a standard
 * normal independent of dW (Var J = H^3/3, Cov(J, dW) = H^2/2, as the Gaussian pair requires),
 * and split at a new point by the bridge of the pair (W, J): with theta the point's fraction
 * of the segment, u = 1 - theta, and dW, J in units of sqrt(H) and H^(3/2),
 *   dW1 = theta (3 theta - 2) dW + 6 theta u J + sqrt(theta u q) z1,          q = 1 - 3 theta u,
 *   J1 = -theta^2 u dW + theta^2 (3 - 2 theta) J + theta^2 u^2 (1 - 2 theta)/(2 sqrt(theta u q)) z1
 *        + sqrt(theta^3 u^3 / (12 q)) z2,
 * the conditional law of the first part given the whole (the covariance of the pair over a
 * length s is [[s, s^2/2], [s^2/2, s^3/3]]); the second part is dW - dW1 and
 * J - J1 - dW1 (1 - theta).
 *
 * The numbers are drawn in a fixed order (per noise: dW's normal, then with area J's), so a
 * run's path is fixed by its seed and stream. */
#include <math.h>
#include <string.h>

#include "sde_path.h"

/* A new segment of length H beyond the last point for noise j: its increment into *dw and,
 * with area, its time integral J into *area (two normals, dW's first). */
static void segment_draw(dyn_bpath *p, double H, double *dw, double *area)
{
    const double z1 = dyn_rng_normal(p->rng);
    *dw = sqrt(H) * z1;
    if (p->area)
        *area = 0.5 * (H * *dw + sqrt(H * H * H / 3.0) * dyn_rng_normal(p->rng));
}

/* The bridge of (W, J) over a segment of length H with increment dw and integral area: the
 * part up to the fraction theta into *dw1, *area1 (the file's comment gives the law). */
static void segment_split(dyn_bpath *p, double H, double theta, double dw, double area,
                          double *dw1, double *area1)
{
    const double u = 1.0 - theta, q = 1.0 - 3.0 * theta * u, sh = sqrt(H);
    const double w = dw / sh, j = area / (H * sh);
    const double s11 = sqrt(theta * u * q);
    const double z1 = dyn_rng_normal(p->rng), z2 = dyn_rng_normal(p->rng);
    const double w1 = theta * (3.0 * theta - 2.0) * w + 6.0 * theta * u * j + s11 * z1;
    const double j1 = -theta * theta * u * w + theta * theta * (3.0 - 2.0 * theta) * j +
                      theta * theta * u * u * (1.0 - 2.0 * theta) / (2.0 * s11) * z1 +
                      sqrt(theta * theta * theta * u * u * u / (12.0 * q)) * z2;
    *dw1 = sh * w1;
    *area1 = H * sh * j1;
}

/* W at time s > tc into out (m values): a point already drawn, a bridge between the known
 * neighbours, or a new increment beyond the last one; the point is kept. */
int dyn_bpath_at(dyn_bpath *p, double s, double *out)
{
    const int m = p->m;
    int i = 0;
    while (i < p->np && p->tq[i] < s)
        i++;
    if (i < p->np && p->tq[i] == s) {
        memcpy(out, p->wq + (size_t)i * (size_t)m, (size_t)m * sizeof *out);
        return 0;
    }
    if (p->np == DYN_SDE_MAX_POINTS)
        return 1;
    const double tl = i == 0 ? p->tc : p->tq[i - 1];
    const double *wl = i == 0 ? p->wc : p->wq + (size_t)(i - 1) * (size_t)m;
    double *al = p->anew; /* the new segment's J */
    if (i == p->np) {
        for (int j = 0; j < m; j++) {
            double d;
            segment_draw(p, s - tl, &d, &al[j]);
            out[j] = wl[j] + d;
        }
    } else {
        const double tr = p->tq[i];
        const double *wr = p->wq + (size_t)i * (size_t)m;
        double *ar = p->aq + (size_t)i * (size_t)m;
        const double f = (s - tl) / (tr - tl);
        if (p->area) {
            for (int j = 0; j < m; j++) {
                double d1;
                segment_split(p, tr - tl, f, wr[j] - wl[j], ar[j], &d1, &al[j]);
                out[j] = wl[j] + d1;
                ar[j] -= al[j] + d1 * (tr - s);
            }
        } else {
            const double sd = sqrt((s - tl) * (tr - s) / (tr - tl));
            for (int j = 0; j < m; j++)
                out[j] = wl[j] + f * (wr[j] - wl[j]) + sd * dyn_rng_normal(p->rng);
        }
    }
    const size_t M = (size_t)m, I = (size_t)i, rest = (size_t)(p->np - i);
    memmove(p->tq + I + 1, p->tq + I, rest * sizeof *p->tq);
    memmove(p->wq + (I + 1) * M, p->wq + I * M, rest * M * sizeof *p->wq);
    p->tq[i] = s;
    memcpy(p->wq + I * M, out, M * sizeof *out);
    if (p->area) {
        memmove(p->aq + (I + 1) * M, p->aq + I * M, rest * M * sizeof *p->aq);
        memcpy(p->aq + I * M, al, M * sizeof *al);
    }
    p->np++;
    return 0;
}

/* After dyn_bpath_at(s): the increments dW (into dw) and the time integrals of W - W(tc) (into
 * i10) from tc to the point s. */
void dyn_bpath_increments(const dyn_bpath *p, double s, double *dw, double *i10)
{
    const int m = p->m;
    for (int j = 0; j < m; j++)
        i10[j] = 0.0;
    double tl = p->tc;
    const double *wl = p->wc;
    for (int i = 0; i < p->np && p->tq[i] <= s; i++) {
        const double *wi = p->wq + (size_t)i * (size_t)m, *ai = p->aq + (size_t)i * (size_t)m;
        for (int j = 0; j < m; j++) {
            i10[j] += ai[j] + (wl[j] - p->wc[j]) * (p->tq[i] - tl);
            dw[j] = wi[j] - p->wc[j];
        }
        tl = p->tq[i];
        wl = wi;
    }
}

/* The run reached t (a point of the path): W there becomes the current value. */
void dyn_bpath_advance(dyn_bpath *p, double t)
{
    const int m = p->m;
    int i = 0;
    while (i < p->np && p->tq[i] <= t)
        i++;
    if (i > 0)
        memcpy(p->wc, p->wq + (size_t)(i - 1) * (size_t)m, (size_t)m * sizeof *p->wc);
    memmove(p->tq, p->tq + i, (size_t)(p->np - i) * sizeof *p->tq);
    memmove(p->wq, p->wq + (size_t)i * (size_t)m, (size_t)(p->np - i) * (size_t)m * sizeof *p->wq);
    if (p->area)
        memmove(p->aq, p->aq + (size_t)i * (size_t)m,
                (size_t)(p->np - i) * (size_t)m * sizeof *p->aq);
    p->np -= i;
    p->tc = t;
}

