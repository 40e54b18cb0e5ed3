#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dynkit bvp on XPPAUT's hom_bcs (projection conditions of connecting orbits) against
closed forms and SciPy.

- The closed forms, checked by SymPy: x = 3/2 sech^2(t/2) solves x'' = x - x^2 (the
  homoclinic orbit of examples/models/homoclinic.ode and Debian's tsthomi.ode at a = 0,
  sig = 0); u = 1/(1 + exp(t/sqrt 2)) solves u'' + c u' + u (1 - u)(u - a) = 0 with
  c = (1 - 2a)/sqrt 2 (the heteroclinic front of tstheti.ode, from u = 1 to u = 0).
- examples/models/homoclinic.ode (20 time units): sig = 0 and the orbit is the sech^2
  pulse, shifted, within the truncation's error; from 10 to 80 mesh intervals the orbit and
  sig converge at the collocation's order (against 320 intervals).
- At a = 0.2 (no closed form) against SciPy's solve_bvp on the same truncated problem (the
  same projections, the phase fixed by x(1/4) from dynkit's solution).
- Debian's tsthomi.ode (as written: per = 8.1 on [0, 1]) gives the pulse within its
  truncation error; tstheti.ode gives the front with c = 0 at a = 0.5 and, over 40 time
  units, c = (1 - 2a)/sqrt 2 at a = 0.3 and 0.5.
- --guess FILE: from one solution to the next, tstheti.ode to 40 time units and a = 0.3
  (c against its closed form), homoclinic.ode from a = 0 to 0.2; bad tables refused.
- dynkit run of such a file integrates the initial-value problem with a note; bad hom_bcs
  lines and unusable layouts are refused with their line; every bvp command of the docs
  runs (tests/analysis/bvp_check.py runs the section's commands).

XPPAUT cannot be the oracle: its -silent mode does not solve boundary-value problems, and
its hom_bcs settings live in a dialog. Exit 0 when all hold, 1 when not, 77 (skipped)
without NumPy/SciPy/SymPy. What failed is kept under build/tests/artifacts/hom_check/.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from analysis_common import Checks  # noqa: E402

try:
    import numpy as np
    import sympy as sp
    from scipy.integrate import solve_bvp
except ImportError:
    print("SKIP: NumPy, SciPy or SymPy is missing (python3-numpy, python3-scipy, "
          "python3-sympy)")
    sys.exit(77)

DYNKIT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "dynkit")
SOURCE = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else ".")
ARTIFACTS = sys.argv[3] if len(sys.argv) > 3 else None
DEBIAN = "/usr/share/doc/xppaut/examples/ode"
HOM = os.path.join(SOURCE, "examples", "models", "homoclinic.ode")
CHECKS = Checks(DYNKIT, "bvp")
check = CHECKS.check


def solve(path, *extra):
    """dynkit bvp PATH --json: (t, states dict, the whole answer) or None"""
    p = CHECKS.run(path, "--json", *extra)
    if p.returncode:
        return None
    d = json.loads(p.stdout)
    return np.array(d["t"]), {k: np.array(v) for k, v in d["states"].items()}, d


def closed_forms():
    t, a, c = sp.symbols("t a c", real=True)
    x = sp.Rational(3, 2) * sp.sech(t / 2) ** 2
    r = sp.simplify((sp.diff(x, t, 2) - (x - x ** 2)).rewrite(sp.exp))
    check(r == 0, "SymPy: x = 3/2 sech^2(t/2) solves x'' = x - x^2")
    u = 1 / (1 + sp.exp(t / sp.sqrt(2)))
    cf = (1 - 2 * a) / sp.sqrt(2)
    r = sp.simplify((sp.diff(u, t, 2) + cf * sp.diff(u, t) + u * (1 - u) * (u - a))
                    .rewrite(sp.exp))
    check(r == 0, "SymPy: u = 1/(1 + exp(t/sqrt 2)) solves u'' + c u' + u(1-u)(u-a) = 0 "
          "with c = (1 - 2a)/sqrt 2")


def pulse_error(s, x, per):
    """max |x - 3/2 sech^2((per s - tc)/2)| with tc the time of the maximum (fitted)"""
    k = int(np.argmax(x))
    # the maximum from the parabola through the three samples around it, then refined by
    # least squares on the whole orbit (a one-dimensional search)
    tc = per * s[k]
    grid = np.linspace(tc - 0.05, tc + 0.05, 2001)
    errs = [np.max(np.abs(x - 1.5 / np.cosh((per * s - g) / 2) ** 2)) for g in grid]
    best = grid[int(np.argmin(errs))]
    from scipy.optimize import minimize_scalar
    m = minimize_scalar(lambda g: np.max(np.abs(x - 1.5 / np.cosh((per * s - g) / 2) ** 2)),
                        bracket=(best - 1e-4, best, best + 1e-4), tol=1e-14)
    return float(m.fun), float(m.x)


def homoclinic_example():
    got = solve(HOM, "--step", "0.001")
    if not got:
        return
    s, st, d = got
    sig = st["sig"][0]
    err, tc = pulse_error(s, st["x"], 20.0)
    check(abs(sig) < 1e-6 and err < 1e-6 and d["projections"]["left"]["conditions"] == 1
          and d["projections"]["right"]["conditions"] == 1
          and max(abs(c["residual"]) for c in d["conditions"]) < 1e-9,
          f"homoclinic.ode (20 time units): sig = {sig:.2e}, max |x - 3/2 sech^2((t - "
          f"{tc:.4f})/2)| = {err:.1e}, 1 + 1 projections")
    # convergence at the collocation's order against 320 intervals
    ref = solve(HOM, "--ntst", "320", "--step", "0.01")
    if not ref:
        return
    errs, sigs = [], []
    for ntst in (10, 20, 40, 80):
        got = solve(HOM, "--ntst", str(ntst), "--step", "0.01")
        if not got:
            return
        errs.append(max(float(np.max(np.abs(got[1][k] - ref[1][k]))) for k in ("x", "y")))
        sigs.append(abs(got[1]["sig"][0] - ref[1]["sig"][0]))
    orders = [math.log2(errs[k] / errs[k + 1]) for k in range(3)]
    text = ", ".join(f"{e:.1e}" for e in errs)
    check(all(o > 3.5 for o in orders[:2]) and errs[-1] < 1e-8,
          f"homoclinic.ode from 10 to 80 intervals (ncol 4): orbit errors {text}, observed "
          f"orders {', '.join(f'{o:.2f}' for o in orders)}")
    text = ", ".join(f"{e:.1e}" for e in sigs)
    check(sigs[-1] < 1e-9 and sigs[0] / sigs[1] > 8,
          f"homoclinic.ode: sig's errors {text}")


def scipy_connecting(rhs, jac_left, jac_right, x_left, x_right, per, s_q, x_q, guess):
    """solve_bvp on a truncated connecting orbit z' = per rhs(z, p) on [0, 1] of two
    states: z(0) - x_left on the unstable line of jac_left(p), z(1) - x_right on the stable
    line of jac_right(p) (the projections), the phase z_0(s_q) = x_q (splitting [0, 1] at
    s_q: four states); guess(s) gives the first guess on [0, 1]"""

    def line(J, pick):
        lam, V = np.linalg.eig(J)
        return np.real(V[:, int(pick(np.real(lam)))])

    def f(s, z, p):
        out = []
        for half, (lo, hi) in enumerate(((0.0, s_q), (s_q, 1.0))):
            out += list(per * (hi - lo) * rhs(z[2 * half:2 * half + 2], p))
        return np.vstack(out)

    def bc(za, zb, p):
        vu = line(jac_left(p), np.argmax)
        vs = line(jac_right(p), np.argmin)
        return np.array([vu[1] * (za[0] - x_left[0]) - vu[0] * (za[1] - x_left[1]),
                         vs[1] * (zb[2] - x_right[0]) - vs[0] * (zb[3] - x_right[1]),
                         zb[0] - za[2], zb[1] - za[3],  # the halves join
                         zb[0] - x_q])                   # the phase

    s = np.linspace(0, 1, 400)
    z = np.vstack([guess(s_q * s), guess(s_q + (1 - s_q) * s)])
    return solve_bvp(f, bc, s, z, p=[0.0], tol=1e-10, max_nodes=500000)


def cross_check(path, sets, par, per, s_q, rhs, jac_left, jac_right, x_left, x_right,
                guess, extra=()):
    """dynkit bvp PATH and solve_bvp on the same truncated problem: the free constant par
    and the orbit's first state; the phase condition of solve_bvp is dynkit's first state
    at s_q (which dynkit's solution satisfies, selecting the same solution)"""
    args = [a for k, v in sets.items() for a in ("--set", f"{k}={v}")]
    got = solve(path, *args, *extra, "--ntst", "160", "--step", str(1 / 320))
    if not got:
        return
    s, st, d = got
    names = list(st)
    k = int(np.argmin(np.abs(s - s_q)))
    b = scipy_connecting(rhs, jac_left, jac_right, x_left, x_right, per, s_q,
                         st[names[0]][k], guess)
    what = f"{os.path.basename(path)} at {', '.join(f'{k} = {v}' for k, v in sets.items())}"
    if b.status != 0:
        check(False, f"{what}: solve_bvp: {b.message}")
        return
    p_d, p_s = st[par][0], float(b.p[0])
    xs = np.where(s <= s_q, b.sol(np.clip(s / s_q, 0, 1))[0],
                  b.sol(np.clip((s - s_q) / (1 - s_q), 0, 1))[2])
    err = float(np.max(np.abs(xs - st[names[0]])))
    check(abs(p_d - p_s) < 1e-7 and err < 1e-6,
          f"{what}: {par} = {p_d:.10f}, SciPy's solve_bvp {p_s:.10f}; max |{names[0]} - "
          f"SciPy's| = {err:.1e}")
    return p_d


def melnikov_sig(a):
    """the first-order prediction of sig at small a: along the a = sig = 0 orbit the
    energy's change int y^2 (sig x - a) dt vanishes"""
    t = sp.symbols("t", real=True)
    x = sp.Rational(3, 2) * sp.sech(t / 2) ** 2
    y = sp.diff(x, t)
    i2 = sp.Integral(y ** 2, (t, -sp.oo, sp.oo)).evalf(30)
    i3 = sp.Integral(x * y ** 2, (t, -sp.oo, sp.oo)).evalf(30)
    return float(a * i2 / i3)


def scipy_cross_check():
    a = 0.2
    guess_sig = melnikov_sig(a)
    check(abs(guess_sig - 7 * a / 6) < 1e-12,
          f"Melnikov's prediction at a = {a}: sig = 7a/6 = {guess_sig:.6f}")

    def hom_rhs(z, p):
        return np.array([z[1], z[0] * (1 - z[0]) - a * z[1] + p[0] * z[0] * z[1]])

    def hom_guess(s):
        t = 20.0 * (s - 0.5)
        x = 1.5 / np.cosh(t / 2) ** 2
        return np.vstack([x, -x * np.tanh(t / 2)])

    saddle = np.array([[0.0, 1.0], [1.0, -a]])  # at (0, 0), sig x y is of second order
    sig = cross_check(HOM, {"a": a}, "sig", 20.0, 0.25, hom_rhs, lambda p: saddle,
                      lambda p: saddle, (0, 0), (0, 0), hom_guess,
                      ("--init", f"sig={guess_sig:.4f}"))
    if sig is not None:
        check(abs(sig - guess_sig) < 0.05 * a,
              f"homoclinic.ode at a = {a}: sig = {sig:.6f} within 5% of a of Melnikov's "
              f"{guess_sig:.6f}")
    tstheti = os.path.join(DEBIAN, "tstheti.ode")
    if not os.path.exists(tstheti):
        return
    for a_h in (0.4, 0.45):
        def het_rhs(z, p, a_h=a_h):
            return np.array([z[1], -p[0] * z[1] - z[0] * (1 - z[0]) * (z[0] - a_h)])

        def het_guess(s):
            u = 1 / (1 + np.exp(6.67 * (s - 0.5) / math.sqrt(2)))
            return np.vstack([u, -u * (1 - u) / math.sqrt(2)])

        cross_check(tstheti, {"a": a_h}, "c", 6.67, 0.5, het_rhs,
                    lambda p, a_h=a_h: np.array([[0.0, 1.0], [1 - a_h, -p[0]]]),
                    lambda p, a_h=a_h: np.array([[0.0, 1.0], [a_h, -p[0]]]),
                    (1, 0), (0, 0), het_guess)


def debian():
    tsthomi = os.path.join(DEBIAN, "tsthomi.ode")
    got = solve(tsthomi, "--step", "0.001")
    if got:
        s, st, d = got
        err, tc = pulse_error(s, st["x"], 8.1)
        check(abs(st["sig"][0]) < 1e-2 and err < 2e-2 and d["t1"] == 1,
              f"tsthomi.ode as written (per = 8.1, AUTO's [0, 1]): sig = {st['sig'][0]:.2e}, "
              f"max |x - 3/2 sech^2| = {err:.1e} (the truncation's error)")
    got = solve(tsthomi, "--set", "per=24", "--init", "x=1.5e-4", "--init", "y=1.5e-4")
    if got:
        s, st, d = got
        err, tc = pulse_error(s, st["x"], 24.0)
        check(abs(st["sig"][0]) < 1e-7 and err < 1e-6,
              f"tsthomi.ode over 24 time units: sig = {st['sig'][0]:.1e}, max |x - 3/2 "
              f"sech^2| = {err:.1e}")
    tstheti = os.path.join(DEBIAN, "tstheti.ode")
    got = solve(tstheti)
    if got:
        s, st, d = got
        c = st["c"][0]
        check(abs(c) < 1e-3 and abs(st["u"][0] - 1) < 0.1 and abs(st["u"][-1]) < 0.1,
              f"tstheti.ode as written (a = 0.5, per = 6.67): c = {c:.2e} (the front "
              f"stands: c = 0)")
    for a in (0.5,):
        got = solve(tstheti, "--set", f"a={a}", "--set", "per=40", "--init", "u=0.99997",
                    "--init", "up=-2.1e-5")
        if got:
            s, st, d = got
            c, exact = st["c"][0], (1 - 2 * a) / math.sqrt(2)
            check(abs(c - exact) < 1e-7,
                  f"tstheti.ode at a = {a} over 40 time units: c = {c:.10f}, closed form "
                  f"(1 - 2a)/sqrt 2 = {exact:.10f}")


def continuation(tmp):
    """--guess FILE: each solution the next one's first guess (AUTO's continuation, by hand)
    where the initial-value problem is too far: tstheti.ode from per = 6.67 to 40 time
    units at a = 0.4, then to a = 0.3, against the closed form c = (1 - 2a)/sqrt 2;
    homoclinic.ode from a = 0 to 0.2 against the solve started at Melnikov's sig"""
    def step(path, out, guess, *sets):
        args = [x for kv in sets for x in ("--set", kv)]
        if guess:
            args += ["--guess", guess]
        p = CHECKS.run(path, *args, "--step", "0.005", "-o", out)
        return not p.returncode

    tstheti = os.path.join(DEBIAN, "tstheti.ode")
    if os.path.exists(tstheti):
        prev, ok = None, True
        for k, (a, per) in enumerate([(0.4, 6.67), (0.4, 10), (0.4, 15), (0.4, 20), (0.4, 30),
                                      (0.4, 40), (0.35, 40), (0.3, 40)]):
            out = os.path.join(tmp, f"het{k}.csv")
            ok = ok and step(tstheti, out, prev, f"a={a}", f"per={per}")
            prev = out
            if ok and per == 40 and a in (0.4, 0.3):
                c = float(np.loadtxt(out, delimiter=",", skiprows=1)[0, -1])
                exact = (1 - 2 * a) / math.sqrt(2)
                check(abs(c - exact) < 1e-9,
                      f"tstheti.ode continued to per = 40, a = {a} (--guess): c = {c:.12f}, "
                      f"closed form {exact:.12f}")
        check(ok, "tstheti.ode: every step of the continuation converges")
    prev, ok = None, True
    for a in (0.0, 0.1, 0.2):
        out = os.path.join(tmp, f"hom{a}.csv")
        ok = ok and step(HOM, out, prev, f"a={a}")
        prev = out
    direct = solve(HOM, "--set", "a=0.2", "--init", "sig=0.2333")
    if ok and direct:
        sig = float(np.loadtxt(prev, delimiter=",", skiprows=1)[0, -1])
        check(abs(sig - direct[1]["sig"][0]) < 1e-9,
              f"homoclinic.ode continued from a = 0 to 0.2 (--guess): sig = {sig:.10f}, from "
              f"Melnikov's first guess {direct[1]['sig'][0]:.10f}")
    check(ok, "homoclinic.ode: every step of the continuation converges")
    bad = os.path.join(tmp, "bad.csv")
    for text, words in (("t,x\n0,1\n1,2\n", "no column for the state y"),
                        ("t,x,y,xe,ye,sig\n1,0,0,0,0,0\n0,0,0,0,0,0\n", ":3: t goes back"),
                        ("t,x,y,xe,ye,sig\n0,0,0,0,0,0\n1,0,zz,0,0,0\n", "'zz' is not a "
                         "number")):
        with open(bad, "w") as f:
            f.write(text)
        p = CHECKS.run(HOM, "--guess", bad, status=2)
        check(words in p.stderr, f"--guess refused: {p.stderr.strip()[:120]}")


def messages():
    p = subprocess.run([DYNKIT, "run", HOM, "--tspan", "0:1"], capture_output=True, text=True)
    check("hom_bcs" in p.stderr and "bvp" in p.stderr,
          "run of homoclinic.ode integrates the initial-value problem with a note")
    with tempfile.TemporaryDirectory() as tmp:
        cases = {
            "bad_index.ode": ("x'=y\ny'=x-x^2\nxe'=0\nye'=0\ns'=0\nbdry xe\nbdry ye\n"
                              "bdry hom_bcs(0)\nbdry hom_bcs(3)\ndone\n", 2, "hom_bcs(0) to "
                              "hom_bcs(1) once each; the file has 2, line 9: hom_bcs(3)"),
            "in_formula.ode": ("x'=y\ny'=x\nxe'=0\nbdry xe+hom_bcs(0)\nbdry x\ndone\n", 2,
                               "whole boundary condition"),
            "count.ode": ("x'=y\ny'=x\nxe'=0\nye'=0\nbdry xe\nbdry ye\nbdry hom_bcs(0)\n"
                          "bdry hom_bcs(1)\nbdry x\ndone\n", 2, "one condition fewer"),
            "no_index.ode": ("x'=y\ny'=x\nbdry hom_bcs(x)\ndone\n", 2, "whole number"),
        }
        for name, (text, status, words) in cases.items():
            path = os.path.join(tmp, name)
            with open(path, "w") as f:
                f.write(text)
            p = CHECKS.run(path, status=status)
            check(words in p.stderr and (status == 1 or f"{name}:" in p.stderr),
                  f"{name}: refused with status {status}: {p.stderr.strip()[:150]}")


def main():
    closed_forms()
    homoclinic_example()
    scipy_cross_check()
    if os.path.isdir(DEBIAN):
        debian()
    else:
        print(f"note: {DEBIAN} is missing (Debian's xppaut): its examples are not checked")
    messages()
    with tempfile.TemporaryDirectory() as tmp:
        continuation(tmp)
    CHECKS.keep(ARTIFACTS, "hom_check")
    return CHECKS.finish()


if __name__ == "__main__":
    sys.exit(main())
