#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dynkit bvp against closed forms and SciPy: examples/models/cable.ode (lam2 v'' = v,
v(0) = v0, a v(1) + b v'(1) = 0) against its cosh/sinh solution for a killed end (a = 1,
b = 0) and a sealed end (a = 0, b = 1) and lam2 = 0.25; Debian's XPPAUT examples with bdry
lines: gberg.ode (a spiral wave's boundary-value problem with a free frequency) against
scipy.integrate.solve_bvp, lecar.ode (periodic conditions over 30 time units: the
equilibrium) against the right-hand side's zero, cable.ode over XPPAUT's default total 20
(tstheti.ode and tsthomi.ode, with hom_bcs, are tests/analysis/hom_check.py's); vdp.ode and
lamomeg.ode (periodic conditions at a free frequency): without --free exit status 1 naming --free, with
--free om lamomeg's om = pi (the closed form: 4 q om = 2 pi k turns in its total 4) on the
unit circle, vdp's om = the period of van der Pol's cycle (vdp.ode over [0, 1] and
examples/models/vdp_bvp.ode) against SciPy's solve_ivp (the time between crossings), SciPy's
solve_bvp with om free and dynkit run's own section period, and converging at the
collocation's order; run of a bdry file notes the lines it ignores; --json and the output
files; every command of docs/analysis.md's boundary-value section runs. XPPAUT's
-silent mode does not solve boundary-value problems (it integrates the initial-value
problem), so it is no oracle here. Exit 0 when all hold, 1 when not, 77 (skipped) without
NumPy/SciPy. What failed is kept under build/tests/artifacts/bvp_check/.
"""
import csv
import io
import json
import math
import os
import re
import shlex
import subprocess
import sys
import tempfile

try:
    import numpy as np
    from scipy.integrate import solve_bvp, solve_ivp
except ImportError:
    print("SKIP: NumPy or SciPy is missing (python3-numpy, python3-scipy)")
    sys.exit(77)

DYNKIT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "dynkit")
SOURCE = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else ".")
ARTIFACTS = sys.argv[3] if len(sys.argv) > 3 else None
DEBIAN = "/usr/share/doc/xppaut/examples/ode"
CABLE = os.path.join(SOURCE, "examples", "models", "cable.ode")
FAILED = []
KEPT = {}


def run(*args, status=0):
    p = subprocess.run([DYNKIT, *args], capture_output=True, text=True)
    if p.returncode != status:
        FAILED.append(f"{' '.join(args)}: exit {p.returncode}, expected {status}: "
                      f"{p.stderr.strip()[:200]}")
        KEPT[" ".join(args)] = p.stdout + "\n--- stderr ---\n" + p.stderr
    return p


def check(cond, what, detail=""):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        FAILED.append(what)
        if detail:
            KEPT[what] = detail


def table(text):
    rows = list(csv.reader(io.StringIO(text)))
    head = rows[0]
    data = np.array([[float(v) for v in r] for r in rows[1:]])
    return {h: data[:, k] for k, h in enumerate(head)}


def cable_closed(x, a, b, v0, lam2):
    l = math.sqrt(lam2)
    L = 1.0 / l  # x in units of the length constant
    K = (a * math.cosh(L) + b * math.sinh(L) / l) / (a * math.sinh(L) + b * math.cosh(L) / l)
    return v0 * (np.cosh(x / l) - K * np.sinh(x / l))


def vdp_reference():
    """the period of van der Pol's limit cycle (mu = 1) and its state at y = 0, x > 0: by
    SciPy's solve_ivp (DOP853, rtol 1e-13) as the time between two upward crossings of
    x = 0 after a transient, and by solve_bvp with the period free"""
    f = lambda t, u: [u[1], (1 - u[0] ** 2) * u[1] - u[0]]
    up = lambda t, u: u[0]
    up.direction = 1
    s = solve_ivp(f, (0, 80), [2.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-13,
                  events=up)
    crossings = s.t_events[0]
    t_ivp = float(crossings[-1] - crossings[-2])

    def g(t, u, p):
        return p[0] * np.vstack([u[1], (1 - u[0] ** 2) * u[1] - u[0]])

    def bc(ua, ub, p):
        return np.array([ua[0] - ub[0], ua[1] - ub[1], ua[1]])

    t = np.linspace(0, 1, 400)
    guess = np.vstack([2 * np.cos(2 * np.pi * t), -2 * np.sin(2 * np.pi * t)])
    b = solve_bvp(g, bc, t, guess, p=[6.6], tol=1e-10, max_nodes=200000)
    return t_ivp, (float(b.p[0]) if b.status == 0 else math.nan), b


def vdp_period(path, xs, ys, extra):
    """dynkit bvp PATH --free om: om is the period, at the collocation's order"""
    t_ivp, t_bvp, b = vdp_reference()
    p = run("run", os.path.join(SOURCE, "examples", "models", "vanderpol.ode"), "--section",
            "period:y1=0:+", "--tspan", "0:100", "--method", "dop853", "--rtol", "1e-13",
            "--atol", "1e-13")
    t_run = table(p.stdout)["t"][-1] if p.returncode == 0 else math.nan
    name = os.path.basename(path)
    check(abs(t_ivp - t_bvp) < 1e-9 and abs(t_ivp - t_run) < 1e-10,
          f"van der Pol's period: solve_ivp {t_ivp:.13f}, solve_bvp {t_bvp:.13f}, dynkit run "
          f"--section period {t_run:.13f}")
    errs = []
    for ntst in ("40", "80", "160"):
        p = run("bvp", path, "--free", "om", "--ntst", ntst, "--json", *extra)
        if p.returncode:
            return
        d = json.loads(p.stdout)
        om = d["free"]["om"]
        errs.append(abs(om - t_ivp))
        check(errs[-1] < 1e-9 and errs[-1] < 10 * d["error_estimate"] + 1e-12 and
              d["section"]["state"] == ys and d["section"]["value"] == 0,
              f"{name} --free om, {ntst} intervals: om = {om:.13f}, |om - T| = "
              f"{errs[-1]:.1e}, error estimate {d['error_estimate']:.1e}, section "
              f"{ys}(0) = 0", p.stdout)
        if ntst == "160":  # the orbit against solve_bvp's, its phase fixed the same way
            ref = b.sol(np.array(d["t"]))
            diff = max(float(np.max(np.abs(np.array(d["states"][xs]) - ref[0]))),
                       float(np.max(np.abs(np.array(d["states"][ys]) - ref[1]))))
            check(diff < 1e-7, f"{name}: the orbit within {diff:.1e} of solve_bvp's")
    if len(errs) == 3 and errs[1] > 0:
        order = math.log2(errs[0] / errs[1])
        check(order > 6, f"{name}: the period's error falls by 2^{order:.1f} from 40 to 80 "
              "intervals (superconvergence: 2^8 at 4 Gauss points)")


def main():
    # cable: closed forms
    for a, b, lam2 in ((1, 0, 1), (0, 1, 1), (1, 0, 0.25), (1, 2, 0.5)):
        p = run("bvp", CABLE, "--set", f"a={a}", "--set", f"b={b}", "--set", f"lam2={lam2}")
        if p.returncode:
            continue
        t = table(p.stdout)
        err = float(np.max(np.abs(t["v"] - cable_closed(t["t"], a, b, 1.0, lam2))))
        m = re.search(r"error estimate (\S+)", p.stderr)
        est = float(m.group(1)) if m else math.inf
        check(err < 1e-10 and err < 10 * est + 1e-13,
              f"cable a={a} b={b} lam2={lam2}: max |v - closed form| = {err:.2e}, within 10 "
              f"times the error estimate {est:.2e}", p.stdout + p.stderr)

    # --json, output files
    p = run("bvp", CABLE, "--json")
    doc = json.loads(p.stdout) if p.returncode == 0 else {}
    check(len(doc.get("conditions", [])) == 2 and
          all(abs(c["residual"]) < 1e-12 for c in doc["conditions"]) and
          doc["conditions"][0]["condition"].endswith("v-v0"),
          "--json: two conditions, as written, with residuals below 1e-12")
    check(len(doc.get("t", [])) == 21 and abs(doc["states"]["v"][0] - 1) < 1e-14,
          "--json: 21 samples of dt = 0.05, v(0) = v0")
    with tempfile.TemporaryDirectory() as tmp:
        for ext in ("csv", "json"):
            out = os.path.join(tmp, "cable." + ext)
            run("bvp", CABLE, "-o", out)
            check(os.path.exists(out) and os.path.getsize(out) > 100, f"-o cable.{ext} written")
    p = run("bvp", CABLE, "-o", "cable.txt", status=2)
    check(".csv" in p.stderr, "-o cable.txt refused, naming .csv")
    p = run("bvp", os.path.join(SOURCE, "examples", "models", "lorenz.ode"), status=2)
    check("no boundary conditions" in p.stderr, "a file without bdry lines refused")
    p = run("bvp", CABLE, "--ncol", "9", status=2)
    check("--ncol" in p.stderr and "7" in p.stderr, "--ncol 9 refused with the range")

    # run of a bdry file: the initial-value problem, with a note naming the lines
    p = run("run", CABLE, "--final")
    check("boundary conditions are not used by run" in p.stderr and "line 13: v-v0" in p.stderr,
          "run notes the bdry lines it ignores")

    if os.path.isdir(DEBIAN):
        # gberg.ode against SciPy's solve_bvp
        p = run("bvp", os.path.join(DEBIAN, "gberg.ode"))
        if p.returncode == 0:
            t = table(p.stdout)
            d, q = 0.177, 0.5

            def f(x, y):
                a, ap, k, om = y
                return np.vstack([ap, a * k * k - ap / x + a / (x * x) - a * (1 - a * a) / d,
                                  -k / x - 2 * k * ap / a - (om + q * a * a) / d, 0 * x])

            def bc(ya, yb):
                return np.array([ya[0] - 0.01 * ya[1], ya[2], yb[1], yb[2]])

            x = np.linspace(0.01, 1, 200)
            guess = np.vstack([0.0118 + 0.7 * (x - 0.01), 1.18 + 0 * x, 0 * x, -0.19 + 0 * x])
            s = solve_bvp(f, bc, x, guess, tol=1e-10, max_nodes=100000)
            check(s.status == 0, "SciPy's solve_bvp converged on gberg")
            ref = s.sol(t["t"])
            errs = {n: float(np.max(np.abs(t[n] - ref[k])))
                    for k, n in enumerate(("a", "ap", "k", "omeg"))}
            check(max(errs.values()) < 1e-7,
                  f"gberg against solve_bvp: omeg {t['omeg'][0]:.12f}, max differences "
                  + ", ".join(f"{n} {e:.1e}" for n, e in errs.items()), p.stdout)
        # lecar.ode: periodic conditions over 30 time units; the equilibrium
        p = run("bvp", os.path.join(DEBIAN, "lecar.ode"))
        if p.returncode == 0:
            t = table(p.stdout)
            v, w = t["v"], t["w"]
            # Morris-Lecar's right-hand side (the file's parameters, iapp = 0)
            v1, v2, v3, v4, gca, vk, vl, gk, gl, phi = (-.01, .15, .1, .145, 1.33, -.7, -.5,
                                                        2.0, .5, .333)
            minf = .5 * (1 + np.tanh((v - v1) / v2))
            ninf = .5 * (1 + np.tanh((v - v3) / v4))
            lamn = phi * np.cosh((v - v3) / (2 * v4))
            fv = gl * (vl - v) + gk * w * (vk - v) - gca * minf * (v - 1)
            fw = lamn * (ninf - w)
            check(max(np.max(np.abs(fv)), np.max(np.abs(fw))) < 1e-9
                  and abs(v[0] - v[-1]) < 1e-12,
                  f"lecar: the solution is the equilibrium v = {v[0]:.10f}, w = {w[0]:.3e}")
        for ntst in ("40", "160"):
            p = run("bvp", os.path.join(DEBIAN, "cable.ode"), "--ntst", ntst)
            if p.returncode == 0:
                t = table(p.stdout)
                x = t["t"]
                closed = np.sinh(20 - x) / np.sinh(20)  # cosh x - coth 20 sinh x
                err = float(np.max(np.abs(t["v"] - closed)))
                m = re.search(r"error estimate (\S+)", p.stderr)
                est = float(m.group(1)) if m else math.inf
                check(t["t"][-1] == 20 and err < 1e-6 and err < 10 * est + 1e-13,
                      f"Debian's cable.ode on [0, 20], {ntst} intervals: max |v - closed "
                      f"form| = {err:.1e}, error estimate {est:.1e}")
        for name in ("vdp", "lamomeg"):
            p = run("bvp", os.path.join(DEBIAN, name + ".ode"), status=1)
            check("Newton" in p.stderr and "--free" in p.stderr,
                  f"{name}.ode without --free: no solution found, why, and --free named")
        # lamomeg: x' = (x (1 - r^2) + q r^2 y) om, ... : on r = 1 the angle turns at -q om,
        # so 4 units of time make k turns for om = k pi / (2 q) = pi (k = 4, q = 2)
        p = run("bvp", os.path.join(DEBIAN, "lamomeg.ode"), "--free", "om", "--ntst", "80",
                "--json")
        if p.returncode == 0:
            d = json.loads(p.stdout)
            om = d["free"]["om"]
            r = np.hypot(d["states"]["x"], d["states"]["y"])
            rerr = float(np.max(np.abs(r - 1)))
            check(abs(om - math.pi) < 1e-10 and rerr < 1e-8 and
                  max(abs(om - math.pi), rerr) < 10 * d["error_estimate"] + 1e-13,
                  f"lamomeg.ode --free om: om - pi = {om - math.pi:.1e}, max |r - 1| = "
                  f"{rerr:.1e}, error estimate "
                  f"{d['error_estimate']:.1e}, section {d['section']}", p.stdout)
        vdp_period(os.path.join(DEBIAN, "vdp.ode"), "x", "xp", ("--tspan", "0:1"))
    else:
        print(f"note: {DEBIAN} is missing (Debian's xppaut): its examples are not checked")
    vdp_period(os.path.join(SOURCE, "examples", "models", "vdp_bvp.ode"), "x", "y", ())
    p = run("bvp", CABLE, "--free", "nosuch", status=2)
    check("nosuch" in p.stderr and "parameter" in p.stderr, "--free nosuch refused, naming it")
    p = run("bvp", CABLE, "--section", "v=1", status=2)
    check("--free" in p.stderr, "--section without --free refused")
    p = run("bvp", CABLE, "--free", "a", "--section", "zz=1", status=2)
    check("zz" in p.stderr and "states" in p.stderr, "--section zz=1 refused: not a state")

    # every command of docs/analysis.md's boundary-value section
    with open(os.path.join(SOURCE, "docs", "analysis.md")) as f:
        doc = f.read()
    part = doc.split("## Boundary-value problems", 1)[-1].split("\n## ", 1)[0]
    blocks = [b.replace("\\\n", " ") for b in re.findall(r"```sh\n(.*?)```", part, re.S)]
    lines = [l.split("#")[0].strip() for b in blocks for l in b.splitlines()
             if l.startswith("dynkit ")]
    shown = run("bvp", "--help").stdout.split("Examples:")[1]
    lines += [l.split("#")[0].strip() for l in shown.splitlines() if l.strip()]
    check(len(lines) >= 4, f"{len(lines)} commands shown")
    with tempfile.TemporaryDirectory() as tmp:
        os.symlink(os.path.join(SOURCE, "examples"), os.path.join(tmp, "examples"))
        for line in lines:
            args = shlex.split(line)[1:]
            p = subprocess.run([DYNKIT, *args], capture_output=True, text=True, cwd=tmp)
            check(p.returncode == 0, f"shown: {line} ({p.stderr.strip()[:60]})")

    if FAILED and ARTIFACTS:
        d = os.path.join(ARTIFACTS, "bvp_check")
        os.makedirs(d, exist_ok=True)
        for k, (what, text) in enumerate(KEPT.items()):
            with open(os.path.join(d, f"failed-{k}.txt"), "w") as f:
                f.write(what + "\n" + text)
        print(f"kept in {d}")
    for f in FAILED:
        print("FAILED:", f)
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
