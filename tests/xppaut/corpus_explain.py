#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Independent solves of the published files that separate from XPPAUT (corpus/manifest.tsv).

wcth.ode and tb2.ode (youngmp/park_ermentrout_chaos_2018) are spiking models whose `global`
lines reset a phase or raise a synaptic variable when a voltage crosses a threshold;
feedback.ode (artielbm/artielbm.github.io, Models/Insulin) reads x19 at t - 1.5 through
`delay`. dynkit and XPPAUT agree on each of them for a while and then separate
(corpus_check.py). Here each model is solved a third way, written apart from dynkit from
the file's text:

- wcth, tb2: an event simulation under XPPAUT's rules for globals (sign 1: the condition
  goes from negative to positive; the reset at that instant, then on from the reset state),
  with SciPy's DOP853 at rtol = atol = 1e-12 and its event location (root finding on the
  dense output) from event to event;
- feedback: the method of steps with SciPy's DOP853 at rtol 1e-10, segment by segment
  between the breaking points k * 1.5 and heav's jump at t = 15, the delayed x19 read from
  the dense output (order 7) of the segments before, and the switches of the right-hand
  side (k5's `if`, effect's `min`) located as events. Its own error, in x3's fast start,
  is about 5e-6 of x3's scale (3.5e-5 at rtol 1e-9), hence the bound 2e-5.

Asserted: dynkit's accurate run (dop853 at tight tolerances) and the run compared with
XPPAUT (rk4 at the file's dt) stay within the stated fraction of each column's largest
magnitude over the stated interval. XPPAUT's run is measured against the same solution when
xppaut is installed (printed: where it leaves it by 1e-3 of a column's scale), not asserted.

Exit status: 77 (skipped) without $DYNKIT_ODE_CORPUS (or --dir), 1 when a file is missing,
differs from its SHA-256 or dynkit leaves the independent solution, else 0.
"""
import argparse
import bisect
import hashlib
import itertools
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compat  # noqa: E402  (same directory)
import corpus_check  # noqa: E402

PI = np.pi


# ---- wcth.ode: two theta neurons with slow synapses ----

def wcth_solve(T, dt=0.05):
    ae, be, ce, ai, bi, ci, eps, tau = .5, 7, 6.5, 1.1, 25, 25.1, .005, 1.5

    def f(u, i):
        return PI * (1 - np.cos(u) + (1 + np.cos(u)) * i)

    def rhs(t, y):
        se, si, u, v = y
        return [-se * eps, -si * eps / tau, f(u, ae + be * se - ce * si),
                f(v, ai + bi * se - ci * si)]

    def spike(k):
        def g(t, y):
            return y[k] - PI
        g.direction, g.terminal = 1, True
        return g

    # `globa1 1 u-pi {u=-pi;se=se+eps}`, `globa1 1 v-pi {v=-pi;si=si+eps/tau}`
    def reset(k, y):  # event k: u (k = 0) or v (k = 1)
        y[2 + k] = -PI
        y[k] += eps if k == 0 else eps / tau
    return events_run(rhs, [spike(2), spike(3)], reset, [1., 1., 2., 0.], T, dt)


# ---- tb2.ode: two Traub neurons driving a slow synapse str ----

def tb2_solve(T, dt=0.01):
    exp = np.exp
    mux, eps, gee, gei = 1., .005, 1, 2.1
    it = 6.0415 - .05 * (gee - gei)
    ekt, enat, elt, eca, glt, gkt, gnat, gm, ct = -100, 50, -67, 120, .2, 80, 100, 0, 1
    gahp, gca, kd, alpha, tauca, vshp, vlth, vsshp, vthr = .5, 1, 1, .002, 80, 2.5, -25, 2, -10
    betas, alphas, vwt, tauw = .1, 2, -35, 100

    def cell(v, m, n, h, w, s, ca, strv):
        am = .32 * (54 + v) / (1 - exp(-(v + 54) / 4))
        bm = .28 * (v + 27) / (exp((v + 27) / 5) - 1)
        ah = .128 * exp(-(50 + v) / 18)
        bh = 4 / (1 + exp(-(v + 27) / 5))
        an = .032 * (v + 52) / (1 - exp(-(v + 52) / 5))
        bn = .5 * exp(-(57 + v) / 40)
        tw = tauw / (3.3 * exp((v - vwt) / 20.0) + exp(-(v - vwt) / 20.0))
        winf = 1.0 / (1.0 + exp(-(v - vwt) / 10.0))
        ica = gca / (1 + exp(-(v - vlth) / vshp)) * (v - eca)
        iahp = gahp * (ca / (ca + kd)) * (v - ekt)
        itrb = gnat * h * m**3 * (v - enat) + gkt * n**4 * (v - ekt) + glt * (v - elt)
        return [-(itrb - (it + gee * strv) + ica + iahp + gm * w * (v - ekt)) / ct,
                am * (1 - m) - bm * m, an * (1 - n) - bn * n, ah * (1 - h) - bh * h,
                (winf - w) / tw, alphas * (1 - s) / (1 + exp(-(v - vthr) / vsshp)) - betas * s,
                -alpha * ica - ca / tauca]

    def rhs(t, y):
        return cell(*y[0:7], y[14]) + cell(*y[7:14], y[14]) + [-eps * y[14] / mux]

    # `global 1 vt-0 {str=str+eps/(2*mux)}` and the same for vtp
    def reset(k, y):
        y[14] += eps / (2 * mux)
    y0 = [42.68904, .9935, .4645, .47785, .268, .2917, .294,
          -90, 0, 0.2, .8, .3, .5, .2, .05]
    return events_run(rhs, [(0, 1), (7, 1)], reset, y0, T, dt)


def events_run(rhs, events, reset, y0, T, dt):
    """Samples at k*dt of a run with global events (reset(k, y) applies event k's
    assignments). An event is a terminal SciPy event function, or (i, 1): state i rising
    through 0. A global of sign 1 fires when its condition goes from negative to positive,
    so after it fired an (i, 1) event is armed again only when state i has fallen through 0
    (the first crossing of 0 downwards is watched in its place)."""
    funcs, armed = [], []
    for e in events:
        if callable(e):
            funcs.append(e)
            armed.append(None)
        else:
            funcs.append(None)
            armed.append(y0[e[0]] < 0)

    def threshold(k):
        i = events[k][0]

        def g(t, y):
            return y[i]
        g.direction, g.terminal = (1 if armed[k] else -1), True
        return g
    ts = np.arange(0, round(T / dt) + 1) * dt
    y, t, out, last = np.array(y0, float), 0.0, [], -1.0
    while t < T:
        evs = [f if f is not None else threshold(k) for k, f in enumerate(funcs)]
        s = solve_ivp(rhs, (t, T), y, method="DOP853", rtol=1e-12, atol=1e-12,
                      events=evs, dense_output=True)
        t_end = s.t[-1] if s.status == 1 else T
        for tt in ts[(ts > last) & (ts >= t - 1e-12) & (ts <= t_end)]:
            out.append([tt] + list(s.sol(tt)))
            last = tt
        if s.status != 1:
            break
        y, t = s.y[:, -1].copy(), t_end
        k = next(j for j in range(len(evs)) if len(s.t_events[j]))
        if armed[k] is None or armed[k]:
            reset(k, y)
        if armed[k] is not None:
            armed[k] = not armed[k]
    return np.array(out)


# ---- feedback.ode: insulin signalling with a delayed PKC feedback ----

def feedback_solve(T, dt=0.02, rtol=1e-10):
    negfeed, posfeed, Vmax, tau, kd, n, insstep, stepdur = 1, 1, 20, 1.5, 12, 4, 1e-7, 15.0
    k1, km1, km4, km5, k3, k4p, km4p, k6 = 6e7, .2, .003, 1.66667e-18, 2500., 2.1e-3, 2.1e-4, .461
    km8, km10, km11, km12, km13, km14 = 10., 2.77, 6.93, 6.93, .167, .001155
    PTEN, SHIP, IRp = 1, 1, 8.97e-13
    k2, km2, k4, km3, k7 = k1, 100 * km1, km4 / 9, km1, 4.16
    km7, k8 = (2.5 / 7.45) * k7, km8 * 5.00e12 / 70.775
    k9stim = 1.39
    km9 = (94 / 3.1) * k9stim
    k9basal, k10 = (0.31 / 99.4) * km9, km10 * (3.1 / 2.9)
    APequil, k13, k14 = 100 / 11, (4 / 96) * km13, 96 * km14
    k7p = np.log(2) / 2 if negfeed else 0
    km7p = k7p * ((2.5 / 7.45) * 3.7e-13) / (6.27e-13 - (2.5 / 7.45) * 3.7e-13) if negfeed else 0
    PI3K = (k8 * 3.7e-13 * 1e-13) / (k8 * 3.7e-13 + km8) if negfeed else 5.0e-15
    seg_t, seg_sol = [], []

    def x19_before(s):  # x19(0)=0: the history is 0
        if s <= 0:
            return 0.0
        return seg_sol[bisect.bisect_right(seg_t, s) - 1](s)[17]

    def rhs(t, y, high):
        (x2, x3, x4, x5, x6, x7, x8, x9, x10, x11, x12, x13, x14, x15, x16, x17, x18, x19, x20,
         x21, x10a) = y
        x1 = insstep if t < stepdur else 0.0
        k5 = 10 * km5 if high else 60 * km5
        k9 = (k9stim - k9basal) * (x12 / PI3K) + k9basal
        k11 = 0.1 * km11 * (x13 - 0.31) / (3.10 - 0.31)
        k12 = 0.1 * km12 * (x13 - 0.31) / (3.10 - 0.31)
        k13p = (40 / 60 - 4 / 96) * km13 * min((0.2 * x17 + 0.8 * x19) / APequil, 1)
        PTP = max(1 - 0.25 * x17 / APequil, 0) if posfeed else 1.0
        d = x19_before(t - tau)
        PKC = Vmax * d**n / (d**n + kd**n)
        return [km1 * x3 + km3 * PTP * x5 - k1 * x1 * x2 + km4 * x6 - k4 * x2,
                k1 * x1 * x2 - km1 * x3 - k3 * x3,
                k2 * x1 * x5 - km2 * x4 + km4p * x7 - k4p * x4,
                k3 * x3 + km2 * x4 - k2 * x1 * x5 - km3 * PTP * x5 + km4p * x8 - k4p * x5,
                k5 - km5 * x6 + k6 * PTP * (x7 + x8) + k4 * x2 - km4 * x6,
                k4p * x4 - km4p * x7 - k6 * PTP * x7,
                k4p * x5 - km4p * x8 - k6 * PTP * x8,
                km7 * PTP * x10 - k7 * x9 * (x4 + x5) / IRp + km7p * x10a - k7p * PKC * x9,
                k7 * x9 * (x4 + x5) / IRp + km8 * x12 - (km7 * PTP + k8 * x11) * x10,
                km8 * x12 - k8 * x10 * x11, k8 * x10 * x11 - km8 * x12,
                k9 * x14 + k10 * x15 - (km9 * PTEN + km10 * SHIP) * x13,
                km9 * PTEN * x13 - k9 * x14, km10 * SHIP * x13 - k10 * x15,
                km11 * x17 - k11 * x16, k11 * x16 - km11 * x17,
                km12 * x19 - k12 * x18, k12 * x18 - km12 * x19,
                km13 * x21 - (k13 + k13p) * x20 + k14 - km14 * x20,
                (k13 + k13p) * x20 - km13 * x21,
                k7p * PKC * x9 - km7p * x10a]

    # the switches: k5's if (x6+x7+x8 > 1e-13), effect's min(.., 1)
    def g_k5(t, y, high):
        return (y[4] + y[5] + y[6]) / 1e-13 - 1

    def g_eff(t, y, high):
        return (0.2 * y[15] + 0.8 * y[17]) / APequil - 1
    g_k5.terminal = g_eff.terminal = True
    y = np.array([9e-13, 0, 0, 0, 1e-13, 0, 0, 1e-12, 0, 1e-13, 0, .31, 99.4, .29, 100, 0, 100,
                  0, 96, 4, 0.])
    # absolute tolerances by the states' sizes: x2 ... x12 near 1e-13 (x3 near 1e-15), the
    # others of order 1 to 100
    atol = rtol * np.array([1e-15] * 11 + [1e-3] * 10)
    # x6+x7+x8 = 1e-13 at t = 0 and rises at once (x6' = 60 km5 > 0): k5 = 10 km5 after it
    high, saturated, t = True, False, 0.0
    for b in sorted(set([k * tau for k in range(1, int(T / tau) + 1)] + [stepdur, T])):
        while t < b:
            g_k5.direction = -1 if high else 1  # the way out of the current branch
            g_eff.direction = -1 if saturated else 1
            s = solve_ivp(rhs, (t, b), y, method="DOP853", rtol=rtol, atol=atol,
                          dense_output=True, events=[g_k5, g_eff], args=(high,))
            seg_t.append(t)
            seg_sol.append(s.sol)
            y, t = s.y[:, -1].copy(), s.t[-1]
            if s.status == 1:
                high ^= len(s.t_events[0]) > 0
                saturated ^= len(s.t_events[1]) > 0
        t = b
    ts = np.arange(0, round(T / dt) + 1) * dt
    return np.array([[tt] + list(seg_sol[max(bisect.bisect_right(seg_t, tt) - 1, 0)](tt))
                     for tt in ts])


# ---- Debian's delay examples: the method of steps for constant lags ----

def dde_solve(rhs, lags, history, y0, T, dt, rtol=1e-12, atol=1e-12, levels=8):
    """Samples at k*dt of y' = rhs(t, y, Z), Z(lag) the state at t - lag (history(s) for
    s <= 0): DOP853 segment by segment, no segment longer than the shortest lag, and the
    breaking points k_1 lag_1 + k_2 lag_2 + ... (k_1 + k_2 + ... <= levels) segment ends."""
    seg_t, seg_sol = [], []

    def past(s):
        if s <= 0:
            return np.asarray(history(s), float)
        return seg_sol[max(bisect.bisect_right(seg_t, s) - 1, 0)](s)

    def f(t, y):
        return rhs(t, y, lambda lag: past(t - lag))
    ends = {T} | {k * min(lags) for k in range(1, int(T / min(lags)) + 1)}
    for ks in itertools.product(range(levels + 1), repeat=len(lags)):
        if 0 < sum(ks) <= levels:
            ends.add(round(sum(k * lag for k, lag in zip(ks, lags)), 12))
    t, y = 0.0, np.array(y0, float)
    for b in sorted(e for e in ends if e <= T):
        s = solve_ivp(f, (t, b), y, method="DOP853", rtol=rtol, atol=atol, dense_output=True)
        seg_t.append(t)
        seg_sol.append(s.sol)
        y, t = s.y[:, -1], b
    ts = np.arange(0, round(T / dt) + 1) * dt
    return np.array([[tt] + list(seg_sol[max(bisect.bisect_right(seg_t, tt) - 1, 0)](tt)
                                 if tt > 0 else list(y0)) for tt in ts])


def dde_ode(T):  # x'=-x+tanh(5x-5 delay(x,5)), init x=.5: the history 0
    return dde_solve(lambda t, y, Z: [-y[0] + np.tanh(5 * y[0] - 5 * Z(5)[0])], [5],
                     lambda s: [0.0], [.5], T, 0.05)


def delay_ode(T):  # x'=-x+f(4x-4.8 delay(x,3)-.8), f logistic; x(0)=1-t, init x=1
    return dde_solve(lambda t, y, Z: [-y[0] + 1 / (1 + np.exp(-(4 * y[0] - 4.8 * Z(3)[0] - .8)))],
                     [3], lambda s: [1 - s], [1.], T, 0.05)


def myret_ode(T):  # lags 1 and 10 of y1, init y0=5,y1=.1,y2=1: the history 0
    def rhs(t, y, Z):
        a, b = Z(1)[1], Z(10)[1]
        return [-y[0] * a + b, y[0] * a - y[1], y[1] - b]
    return dde_solve(rhs, [1, 10], lambda s: [0., 0., 0.], [5, .1, 1], T, 0.05)


# ---- the checks ----

# file, its solver, interval, dynkit's accurate run (options, tolerance), the run compared
# with XPPAUT (options, tolerance); tolerances are fractions of each column's largest
# magnitude over the interval
DEBIAN = compat.DEBIAN_EXAMPLES
ACCURATE = ["--method", "dop853", "--rtol", "1e-12", "--atol", "1e-12"]
CASES = (
    # the event simulation resets at the crossing, dynkit at XPPAUT's instant, a relative
    # 1e-10 of the step after it: over wcth's hundreds of resets (steps of up to ~0.3 at
    # these tolerances) the phases drift by up to ~1e-8 (2.4e-9 of the scale measured)
    ("youngmp/park_ermentrout_chaos_2018/ode/wcth.ode", wcth_solve, 250.0,
     ACCURATE, 1e-8, ["--method", "rk4"], 1e-4),
    ("youngmp/park_ermentrout_chaos_2018/ode/tb2.ode", tb2_solve, 200.0,
     ACCURATE, 1e-8, ["--method", "rk4"], 2e-2),
    ("artielbm/artielbm.github.io/Models/Insulin/feedback.ode", feedback_solve, 20.0,
     ["--method", "dop853", "--rtol", "1e-11", "--atol", "1e-25", "--step", "0.001"], 2e-5,
     [], 1e-2),
    # Debian's examples (installed with xppaut), their default runs: dp45 at rtol 1e-3
    (DEBIAN + "/dde.ode", dde_ode, 50.0, ACCURATE, 1e-9, [], 3e-5),
    (DEBIAN + "/delay.ode", delay_ode, 20.0, ACCURATE, 1e-9, [], 1e-5),
    (DEBIAN + "/myret.ode", myret_ode, 50.0, ACCURATE, 1e-9, [], 1e-5),
)


def deviation(ref, run):
    """Per sample of ref: the largest |run - ref| over the columns ref has, as a fraction of
    each column's largest |ref|; run's samples are matched to ref's times."""
    idx = np.searchsorted(run[:, 0], ref[:, 0] - 1e-6 * (1 + np.abs(ref[:, 0])))
    idx = np.minimum(idx, len(run) - 1)
    if np.any(np.abs(run[idx, 0] - ref[:, 0]) > 1e-5 * (1 + np.abs(ref[:, 0]))):
        raise SystemExit("the run has no sample at some of the reference's times")
    nc = ref.shape[1]
    scale = np.maximum(np.max(np.abs(ref[:, 1:]), axis=0), 1e-300)
    return np.max(np.abs(run[idx, 1:nc] - ref[:, 1:]) / scale, axis=1)


def dynkit_run(dynkit, path, opts, T, env):
    cmd = [dynkit, "run", path, "--quiet", "--tspan", "0:%g" % T] + opts
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
    if p.returncode:
        raise SystemExit("%s: %s" % (" ".join(cmd), p.stderr.strip()))
    return np.loadtxt(p.stdout.splitlines()[1:], delimiter=",", ndmin=2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dynkit", help="the dynkit binary")
    ap.add_argument("--dir", default=os.environ.get("DYNKIT_ODE_CORPUS"),
                    help="the directory of the files (default: $DYNKIT_ODE_CORPUS)")
    ap.add_argument("--only", nargs="*", help="base names of the files to check (default: all)")
    args = ap.parse_args()
    have_corpus = bool(args.dir) and os.path.isdir(args.dir)
    if not have_corpus and not os.path.isdir(DEBIAN):
        print("SKIP: DYNKIT_ODE_CORPUS is not a directory (see corpus_check.py) and %s "
              "is missing" % DEBIAN)
        return 77
    if not have_corpus:
        print("DYNKIT_ODE_CORPUS is not a directory: Debian's examples only")
    sums = {"%s/%s" % (r["repo"], r["path"]): r["sha256"]
            for r in corpus_check.read_manifest(corpus_check.MANIFEST)}
    env = dict(os.environ)
    failed = []
    with tempfile.TemporaryDirectory() as work:
        env.setdefault("DYNKIT_CACHE_DIR", os.path.join(work, "cache"))
        for name, solve, T, acc_opts, acc_tol, cmp_opts, cmp_tol in CASES:
            if args.only and os.path.basename(name) not in args.only:
                continue
            debian = name.startswith(DEBIAN)
            if not debian and not have_corpus:
                continue
            path = name if debian else os.path.join(args.dir, name)
            if not os.path.isfile(path):
                print("%s: missing" % name)
                failed.append(name)
                continue
            with open(path, "rb") as f:
                if not debian and hashlib.sha256(f.read()).hexdigest() != sums[name]:
                    print("%s: differs from its sha256" % name)
                    failed.append(name)
                    continue
            ref = solve(T)
            base = os.path.basename(name)
            for what, opts, tol in (("dynkit " + " ".join(acc_opts), acc_opts, acc_tol),
                                    ("dynkit " + (" ".join(cmp_opts) or "(the file's run)"),
                                     cmp_opts, cmp_tol)):
                dev = deviation(ref, dynkit_run(args.dynkit, path, opts, T, env))
                ok = dev.max() <= tol
                print("%-13s %-62s largest difference %.2g of the scale over [0, %g] "
                      "(at most %g)%s" % (base, what, dev.max(), T, tol,
                                          "" if ok else "  FAILED"), flush=True)
                if not ok:
                    failed.append(name)
            if compat.shutil.which("xppaut"):
                with open(path, errors="replace") as f:
                    text = f.read()
                meth = compat.file_method(text)
                own = meth is not None and meth not in compat.FIXED_STEP
                xdir = os.path.join(work, base)
                os.makedirs(xdir)
                xpp, why = compat.run_xppaut(path, xdir, 600,
                                             compat.rk4_everywhere(text) if own else None)
                if xpp is None:
                    print("%-13s xppaut: %s" % (base, why))
                    continue
                xpp = xpp[xpp[:, 0] <= T + 1e-9]
                dev = deviation(ref[np.searchsorted(ref[:, 0], xpp[0, 0] - 1e-9):
                                    np.searchsorted(ref[:, 0], xpp[-1, 0] + 1e-6)], xpp)
                t = xpp[:, 0]
                away = t[np.argmax(dev > 1e-3)] if np.any(dev > 1e-3) else None
                print("%-13s %-62s largest difference %.2g of the scale over [0, %g]%s"
                      % (base, "xppaut -silent (rk4 at the file's dt)" if own else "xppaut -silent", dev.max(), t[-1],
                         "" if away is None else "; 1e-3 first at t = %g" % away), flush=True)
        if failed:  # XPPAUT's outputs, the inputs (dynkit's runs are in the log above)
            print("inputs and outputs kept in %s" % compat.keep_artifacts(
                args.dynkit, "xppaut-corpus-explain",
                [work] + [n if n.startswith(DEBIAN) else os.path.join(args.dir, n)
                          for n in sorted(set(failed))]))
    if failed:
        print("dynkit leaves the independent solution: " + ", ".join(failed))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
