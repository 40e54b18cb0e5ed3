/* SPDX-License-Identifier: BSD-3-Clause */
/* Event location on the dense output of a step.
 *
 * Detection: g is sampled at samples + 1 equally spaced points of the step (the ends are
 * exact states, the inner points come from the interpolant). A sign change between two
 * samples brackets a crossing. A pair of crossings between two samples of the same sign
 * (g dips across zero and back) is looked for with a parabola through three neighbouring
 * samples: when its extremum lies between the two samples and is across zero, g is
 * evaluated there, which splits the pair into two brackets (repeated up to three times).
 * This is the strategy of Shampine & Thompson ("Event location for ordinary differential
 * equations", Comput. Math. Appl. 39 (2000) 43-54), who sample g on the interpolant, with a
 * quadratic test added between samples. Pairs of roots closer than the sampling resolves
 * (about h/samples) whose dip the parabola does not see can still be missed.
 * Location: Brent's method (Brent, "Algorithms for Minimization without Derivatives",
 * 1973, ch. 4, zeroin) on t -> g(t, y(t)) with y(t) the interpolant, to a bracket of a few
 * ulps of t; the end of the final bracket on the side of the new sign is reported.
 * A zero at the start and a touch of zero without a sign change are not events.
 * Instants (dyn_events_instant) and cascades (dyn_events_cascade) follow XPPAUT 6.11's
 * globals (flags.c, one_flag_step): a reset's instant is the earliest crossing in the step
 * moved past it by a relative DYN_EVENTS_STOL of the step's part before it, so that every
 * event crossing within that moved instant fires in it, its condition already just past
 * zero; after the resets at an instant, an event whose g the resets carried onto or across
 * zero (by more than DYN_EVENTS_TOL) fires at the same instant, each event at most once per
 * instant, g compared between the state at the instant before any reset and the state after
 * the resets so far.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "ode/events.h"

#define MAX_REFINE 3

size_t dyn_events_work(int n, int n_events, int samples)
{
    /* G (ne x (samples + 1)), y (n), points t and g (2 x (samples + 1 + MAX_REFINE samples)) */
    return (size_t)n_events * ((size_t)samples + 1) + (size_t)n +
           2 * ((size_t)samples + 1 + MAX_REFINE * (size_t)samples);
}

int dyn_events_max_hits(int n_events, int samples)
{
    return n_events * (1 + MAX_REFINE) * samples;
}

static int sign_of(double g) { return g > 0.0 ? 1 : g < 0.0 ? -1 : 0; }

double dyn_events_instant(double ta, double te, double tb)
{
    const double h = tb - ta, frac = (te - ta) / h;
    if (!(h > 0.0) || !(frac < 1.0))
        return te;
    const double moved = frac < DYN_EVENTS_STOL ? DYN_EVENTS_STOL : frac * (1.0 + DYN_EVENTS_STOL);
    const double t = ta + h * moved;
    return t < tb ? t : tb;
}

int dyn_events_cascade(const dyn_event *ev, int ne, void *par, double t, const double *y,
                       const double *g0, const double *g_end, double tol, double *fired,
                       int cycle)
{
    int count = 0;
    for (int i = 0; i < ne; i++) {
        if (fired[i] != 0.0)
            continue;
        const double a = g0[i], b = ev[i].g(t, y, par);
        const int dir = ev[i].direction;
        /* XPPAUT's test: a change of more than tol; rising when a <= 0 <= b,
         * falling when a >= 0 >= b; a DYN_EVENT_JUMPS event (sign 0) when a and b have
         * opposite signs or one of them is zero, except when its g is zero at the step's end
         * (XPPAUT takes sign 0 sitting on zero there as hit in that step) */
        if (!(fabs(b - a) > tol))
            continue;
        if (dir == DYN_EVENT_JUMPS && g_end && fabs(g_end[i]) < DYN_EVENTS_ZERO)
            continue;
        const int up = a <= 0.0 && b >= 0.0, down = a >= 0.0 && b <= 0.0;
        if ((up && dir != -1) || (down && dir != 1)) {
            fired[i] = up ? cycle : -cycle;
            count++;
        }
    }
    return count;
}

int dyn_events_report(int index, double t, const double *y, int direction, void *ctx)
{
    const dyn_event_sink *sink = ctx;
    dyn_result *res = sink->res;
    res->events++;
    int terminal = sink->events[index].terminal;
    if (sink->on_event && sink->on_event(index, t, y, direction, sink->event_ctx))
        terminal = 1;
    if (terminal) {
        res->stopped_by_event = 1;
        res->event_index = index;
    }
    return terminal;
}

int dyn_events_cascades(const dyn_event *ev, int ne, void *par, double t,
                        const double *y_before, double *y, const double *hits, int nh,
                        const double *g_end, double tol, double *casc, dyn_events_report_fn report, void *ctx, long *count,
                        int *which, int *status)
{
    double *g0 = casc, *fired = casc + ne;
    for (int i = 0; i < ne; i++) {
        g0[i] = ev[i].g(t, y_before, par);
        fired[i] = 0.0;
    }
    for (int k = 0; k < nh && DYN_HIT_T(hits, k) <= t; k++)
        fired[DYN_HIT_INDEX(hits, k)] = 1.0;
    for (int cycle = 2; dyn_events_cascade(ev, ne, par, t, y, g0, g_end, tol, fired, cycle); cycle++)
        for (int i = 0; i < ne; i++) {
            if (fabs(fired[i]) != (double)cycle)
                continue;
            (*count)++;
            if (report(i, t, y, fired[i] > 0 ? 1 : -1, ctx)) {
                *which = i;
                return DYN_CASCADES_STOPPED;
            }
            if (ev[i].reset && (*status = ev[i].reset(t, y, par)) != 0) {
                *which = i;
                return DYN_CASCADES_RESET_FAILED;
            }
        }
    return DYN_CASCADES_DONE;
}

void dyn_events_restart(const dyn_event *ev, int ne, void *par, double t,
                        const double *y_before, const double *y, const double *hits, int nh,
                        double *memo)
{
    dyn_events_start(ev, ne, par, t, y, memo);
    for (int k = 0; k < nh && DYN_HIT_T(hits, k) <= t; k++) {
        const int i = DYN_HIT_INDEX(hits, k);
        if (ev[i].g(t, y_before, par) == memo[i])
            memo[i] = memo[ne + i] = 0.0;
    }
}

void dyn_events_start(const dyn_event *ev, int ne, void *par, double t0, const double *y0,
                      double *memo)
{
    for (int i = 0; i < ne; i++) {
        const double g = ev[i].g(t0, y0, par);
        memo[i] = g;
        memo[ne + i] = sign_of(g); /* NaN: 0 */
    }
}

/* g of event e at time t on the interpolant (the exact end state at t1). */
typedef struct probe {
    const dyn_event *e;
    void *par;
    const dyn_dense *d;
    double t1;
    const double *y1;
    double *y;
    long *calls;
} probe;

static double probe_g(const probe *p, double t)
{
    if (p->calls)
        (*p->calls)++;
    if (t == p->t1)
        return p->e->g(t, p->y1, p->par);
    dyn_dense_eval(p->d, t, p->y);
    return p->e->g(t, p->y, p->par);
}

/* Root of g in the bracket [a, b] (fa, fb of opposite signs, not zero); returns the end of
 * the final bracket where g has the sign of fb (or is zero). */
static double brent(const probe *p, double a, double fa, double b, double fb)
{
    const int new_sign = sign_of(fb);
    double c = a, fc = fa, d = b - a, e = d;
    for (int it = 0; it < 200; it++) {
        if ((fb > 0.0 && fc > 0.0) || (fb < 0.0 && fc < 0.0)) {
            c = a;
            fc = fa;
            d = e = b - a;
        }
        if (fabs(fc) < fabs(fb)) {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        const double tol = 2.0 * DBL_EPSILON * fabs(b) + DBL_MIN;
        const double xm = 0.5 * (c - b);
        if (fabs(xm) <= tol || fb == 0.0)
            break;
        if (fabs(e) >= tol && fabs(fa) > fabs(fb)) {
            double s = fb / fa, pp, q;
            if (a == c) {
                pp = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                const double qq = fa / fc, r = fb / fc;
                pp = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if (pp > 0.0)
                q = -q;
            else
                pp = -pp;
            if (2.0 * pp < fmin(3.0 * xm * q - fabs(tol * q), fabs(e * q))) {
                e = d;
                d = pp / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += fabs(d) > tol ? d : copysign(tol, xm);
        fb = probe_g(p, b);
        if (isnan(fb))
            break;
    }
    if (fb == 0.0 || sign_of(fb) == new_sign)
        return b;
    return c;
}

/* Vertex of the parabola through three points, or NAN when it has no extremum of the
 * wanted kind (want > 0: a minimum, want < 0: a maximum); *pv its value there. */
static double vertex(double x0, double g0, double x1, double g1, double x2, double g2, int want,
                     double *pv)
{
    const double d01 = (g1 - g0) / (x1 - x0), d12 = (g2 - g1) / (x2 - x1);
    const double d012 = (d12 - d01) / (x2 - x0);
    if (!(d012 != 0.0) || sign_of(d012) != want)
        return NAN;
    const double xs = 0.5 * (x0 + x1) - d01 / (2.0 * d012);
    *pv = g0 + d01 * (xs - x0) + d012 * (xs - x0) * (xs - x1);
    return xs;
}

int dyn_events_step(const dyn_event *ev, int ne, void *par, const dyn_dense *d, double t1,
                    const double *y1, int samples, double *memo, double *work, double *hits,
                    long *g_calls, int restart)
{
    const int M = samples, np0 = M + 1;
    const double ta = d->t0, h = t1 - ta;
    double *G = work;
    double *y = G + (size_t)ne * (size_t)np0;
    double *pt = y + d->n, *pg = pt + (M + 1 + MAX_REFINE * M);
    int nh = 0;

    /* g of every event at the samples: y from the interpolant inside, exact at the ends */
    for (int j = 1; j <= M; j++) {
        const double tj = j < M ? ta + h * ((double)j / (double)M) : t1;
        const double *yj = y1;
        if (j < M) {
            dyn_dense_eval(d, tj, y);
            yj = y;
        }
        for (int i = 0; i < ne; i++)
            G[(size_t)i * (size_t)np0 + (size_t)j] = ev[i].g(tj, yj, par);
        if (g_calls)
            *g_calls += ne;
    }
    for (int i = 0; i < ne; i++) {
        double *Gi = G + (size_t)i * (size_t)np0;
        Gi[0] = memo[i];
        probe p = {&ev[i], par, d, t1, y1, y, g_calls};
        /* the points, with extra ones where a parabola suggests a hidden pair of roots */
        int np = 0;
        for (int j = 0; j <= M; j++) {
            pt[np] = j == 0 ? ta : j < M ? ta + h * ((double)j / (double)M) : t1;
            pg[np++] = Gi[j];
            if (j == M)
                break;
            if (j == 0 && restart && Gi[0] == 0.0 && memo[ne + i] == 0.0 && Gi[1] != 0.0 &&
                !isnan(Gi[1])) {
                /* a restart on the event's zero: an excursion to the other side before the
                 * first sample (a short bounce) is looked for at the vertex of the parabola
                 * through the zero and the next two samples */
                const int s1 = sign_of(Gi[1]);
                const double x1 = M > 1 ? ta + h / (double)M : t1;
                const double x2 = M > 2 ? ta + h * (2.0 / (double)M) : t1;
                double pv = 0.0;
                const double xs = vertex(ta, 0.0, x1, Gi[1], x2, Gi[2], s1, &pv);
                if (xs > ta && xs < x1 && sign_of(pv) == -s1) {
                    const double gs = probe_g(&p, xs);
                    if (sign_of(gs) == -s1) {
                        pt[np] = xs;
                        pg[np++] = gs;
                    }
                }
                continue;
            }
            const int sj = sign_of(Gi[j]);
            if (sj == 0 || sign_of(Gi[j + 1]) != sj)
                continue;
            double xa = pt[np - 1], ga = Gi[j];
            const double xb = j + 1 < M ? ta + h * ((double)(j + 1) / (double)M) : t1;
            const double gb = Gi[j + 1];
            double xs = NAN, pv = 0.0;
            if (j >= 1) { /* (j-1, j, j+1) */
                const double xl = j - 1 == 0 ? ta : ta + h * ((double)(j - 1) / (double)M);
                xs = vertex(xl, Gi[j - 1], xa, ga, xb, gb, sj, &pv);
                if (!(xs > xa && xs < xb && sign_of(pv) != sj))
                    xs = NAN;
            }
            if (isnan(xs) && j + 2 <= M) { /* (j, j+1, j+2) */
                const double xr = j + 2 < M ? ta + h * ((double)(j + 2) / (double)M) : t1;
                xs = vertex(xa, ga, xb, gb, xr, Gi[j + 2], sj, &pv);
                if (!(xs > xa && xs < xb && sign_of(pv) != sj))
                    xs = NAN;
            }
            /* evaluate at the vertex; while g keeps its sign there, fit the parabola through
             * the smallest |g| found in the sub-interval and its neighbours, and try again */
            double sx[MAX_REFINE + 2] = {xa, xb}, sg[MAX_REFINE + 2] = {ga, gb};
            int ns = 2, split = 0;
            for (int r = 0; r < MAX_REFINE && !isnan(xs) && !split; r++) {
                const double gs = probe_g(&p, xs);
                if (isnan(gs))
                    break;
                int at = ns; /* keep sx sorted */
                while (at > 0 && sx[at - 1] > xs) {
                    sx[at] = sx[at - 1];
                    sg[at] = sg[at - 1];
                    at--;
                }
                sx[at] = xs;
                sg[at] = gs;
                ns++;
                split = sign_of(gs) != sj;
                int mi = 0;
                for (int q = 1; q < ns; q++)
                    if (fabs(sg[q]) < fabs(sg[mi]))
                        mi = q;
                const int lo = mi == 0 ? 0 : mi == ns - 1 ? ns - 3 : mi - 1;
                xs = vertex(sx[lo], sg[lo], sx[lo + 1], sg[lo + 1], sx[lo + 2], sg[lo + 2], sj, &pv);
                if (!(xs > sx[lo] && xs < sx[lo + 2] && sign_of(pv) != sj))
                    xs = NAN;
            }
            for (int q = 1; q < ns - 1; q++) { /* the inner points, in time order */
                pt[np] = sx[q];
                pg[np++] = sg[q];
            }
        }
        /* scan for sign changes */
        int s = (int)memo[ne + i];
        int last_nz = sign_of(pg[0]) != 0 && !isnan(pg[0]) ? 0 : -1;
        int zero_at = pg[0] == 0.0 ? 0 : -1;
        for (int k = 1; k < np; k++) {
            const double gk = pg[k];
            if (isnan(gk))
                continue;
            const int sk = sign_of(gk);
            if (sk == 0) {
                if (zero_at < 0)
                    zero_at = k;
                continue;
            }
            if (s != 0 && sk != s) {
                double te;
                if (zero_at >= 0)
                    te = pt[zero_at];
                else
                    te = brent(&p, pt[last_nz >= 0 ? last_nz : 0], pg[last_nz >= 0 ? last_nz : 0],
                               pt[k], gk);
                if (ev[i].direction == 0 || ev[i].direction == sk) { /* not DYN_EVENT_JUMPS */
                    hits[3 * nh] = te;
                    hits[3 * nh + 1] = i;
                    hits[3 * nh + 2] = sk;
                    nh++;
                }
            }
            s = sk;
            last_nz = k;
            zero_at = -1;
        }
        memo[ne + i] = s;
        memo[i] = Gi[M];
    }
    /* time order (stable: events of equal time by index) */
    for (int a = 1; a < nh; a++) {
        const double xt = hits[3 * a], xi = hits[3 * a + 1], xd = hits[3 * a + 2];
        int b = a - 1;
        while (b >= 0 && (hits[3 * b] > xt || (hits[3 * b] == xt && hits[3 * b + 1] > xi))) {
            memcpy(hits + 3 * (b + 1), hits + 3 * b, 3 * sizeof *hits);
            b--;
        }
        hits[3 * (b + 1)] = xt;
        hits[3 * (b + 1) + 1] = xi;
        hits[3 * (b + 1) + 2] = xd;
    }
    return nh;
}
