#!/usr/bin/env python3
"""The period doublings of the Hodgkin-Huxley cycles, checked by shooting (docs/analysis.md,
"Checks"): dynkit continue finds, on the unstable cycles from the first Hopf point, two PD
points between the folds of cycles (LPC) at iapp = 7.8423 and 7.9178. Each PD orbit (from
the diagram's page) is solved again here by multiple shooting at the same period with SciPy
(solve_ivp, DOP853, rtol 1e-11; the Jacobian by SymPy from the formulas, independent of
dynkit's), and its monodromy matrix, the product of the segments' variational matrices,
gives the multipliers: one is -1 within 1e-5 at dynkit's point and the parameter agrees
within 1e-7; between periods on either side of it (0.05% away: the second fold is 0.12%
away) a real multiplier passes -1 (prod (mu + 1) changes sign). The run also states that
the cycles from the second Hopf point are those from the first (computed once) and that the
period-doubled branch, a closed loop, ends when it is back on its own orbits. Failures keep the page under ARTIFACTS.
Usage: hh_period_doubling.py DYNKIT MODEL ARTIFACTS"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

try:
    import numpy as np
    import sympy as sp
    from scipy.integrate import solve_ivp
except ImportError as e:
    print(f"skipped: {e} (scripts/install-deps.sh installs NumPy, SciPy and SymPy)")
    sys.exit(77)

dynkit, model, artifacts = sys.argv[1:4]
failures = []
work = tempfile.mkdtemp(prefix="dynkit-hh-pd-")

# the model's right-hand side and its Jacobians in the states and in iapp, by SymPy
v, m, h, n, I = sp.symbols("v m h n iapp")
gna, ena, gk, ek, gl, el = 120.0, 50.0, 36.0, -77.0, 0.3, -54.387
an = 0.01 * (v + 55) / (1 - sp.exp(-(v + 55) / 10))
bn = 0.125 * sp.exp(-(v + 65) / 80)
am = 0.1 * (v + 40) / (1 - sp.exp(-(v + 40) / 10))
bm = 4 * sp.exp(-(v + 65) / 18)
ah = 0.07 * sp.exp(-(v + 65) / 20)
bh = 1 / (1 + sp.exp(-(v + 35) / 10))
F = sp.Matrix([I - gna * m**3 * h * (v - ena) - gk * n**4 * (v - ek) - gl * (v - el),
               am * (1 - m) - bm * m, ah * (1 - h) - bh * h, an * (1 - n) - bn * n])
X = sp.Matrix([v, m, h, n])
fjq = sp.lambdify((v, m, h, n, I), [list(F), F.jacobian(X).tolist(), list(F.diff(I))],
                  "math")


def rhs(t, y, iapp):
    f, J, q = fjq(y[0], y[1], y[2], y[3], iapp)
    J = np.array(J, dtype=float)
    P = y[4:20].reshape(4, 4)
    return np.concatenate([np.ravel(np.array(f, dtype=float)), (J @ P).ravel(),
                           J @ y[20:24] + np.ravel(np.array(q, dtype=float))])


def segment(x0, iapp, dt):
    """the flow over dt from x0, its derivatives in x0 and in iapp"""
    y0 = np.concatenate([x0, np.eye(4).ravel(), np.zeros(4)])
    s = solve_ivp(rhs, (0.0, dt), y0, args=(iapp,), method="DOP853", rtol=1e-11, atol=1e-12)
    y = s.y[:, -1]
    return y[:4], y[4:20].reshape(4, 4), y[20:24]


def shoot(U, iapp, T):
    """the periodic orbit of period T through K points U (at t = k T/K, v at the first one
    held), iapp free: Newton on the matching conditions; the points, iapp, multipliers"""
    K = len(U)
    U = U.copy()
    for it in range(12):
        A = np.zeros((4 * K + 1, 4 * K + 1))
        r = np.zeros(4 * K + 1)
        for j in range(K):
            xe, M, q = segment(U[j], iapp, T / K)
            jn = (j + 1) % K
            r[4 * j:4 * j + 4] = xe - U[jn]
            A[4 * j:4 * j + 4, 4 * j:4 * j + 4] = M
            A[4 * j:4 * j + 4, 4 * jn:4 * jn + 4] -= np.eye(4)
            A[4 * j:4 * j + 4, -1] = q
        A[-1, 0] = 1.0
        d = np.linalg.solve(A, -r)
        U += d[:-1].reshape(K, 4)
        iapp += d[-1]
        if np.max(np.abs(d)) < 1e-10 * (1 + np.max(np.abs(U))):
            break
    else:
        return None
    mono = np.eye(4)
    for j in range(K):
        mono = segment(U[j], iapp, T / K)[1] @ mono
    return U, iapp, np.linalg.eigvals(mono)


def nearest_minus_one(mu):
    real = [z.real for z in mu if abs(z.imag) <= 1e-9 * abs(z)]
    return min(real, key=lambda x: abs(x + 1)) if real else None


html = os.path.join(work, "hh.html")
out = subprocess.run([dynkit, "continue", model, "--par", "iapp", "--output", html],
                     capture_output=True, text=True)
summary = subprocess.run([dynkit, "continue", model, "--par", "iapp", "--json"],
                         capture_output=True, text=True)
if out.returncode or summary.returncode:
    failures.append(f"dynkit continue: exit {out.returncode}, {summary.returncode}: "
                    f"{out.stderr}{summary.stderr}")
else:
    page = open(html).read()
    data = json.loads(re.search(r'<script id="dynkit-data" type="application/json">(.*?)'
                                r'</script>', page, re.S).group(1))
    d = json.loads(summary.stdout)
    periodic = [b for b in d["branches"] if b["kind"] == "periodic"]
    first = [b for b in periodic if b["parent"] == 1]
    hb = sorted(p["iapp"] for p in d["branches"][0]["points"] if p["label"] == "HB")
    said = re.search(r"the cycles from HB at (\S+) are those from HB at (\S+)$",
                     first[0]["stop"]) if len(first) == 1 else None
    if len(hb) != 2 or not said or \
            any(abs(float(said.group(k + 1)) - hb[1 - k]) > 1e-8 * hb[1 - k] for k in (0, 1)):
        failures.append(f"the cycles from the Hopf points {hb}: expected one branch from the "
                        "first, ending at the second: "
                        f"{[(b['branch'], b['stop']) for b in first]}")
    doubled = [b for b in periodic if b["parent"] != 1]
    if not doubled or not doubled[0]["stop"].startswith("closed: back on the orbits") \
            or len(doubled[0]["points"]) >= d["settings"]["nmax"]:
        failures.append("the period-doubled branch: expected a closed loop ended on its "
                        f"orbits: {[(b['branch'], len(b['points']), b['stop']) for b in doubled]}")
    lpc = sorted(p["iapp"] for p in first[0]["points"] if p["label"] == "LPC") if first else []
    pds = [o for o in data["orbits"] if first and o["branch"] == first[0]["branch"]
           and o["label"] == "PD"]
    if len(pds) != 2 or len(lpc) < 2 or not all(lpc[-2] < o["par"] < lpc[-1] for o in pds):
        failures.append(f"expected two PD points between the folds {lpc}: "
                        f"{[o['par'] for o in pds]}")
    for o in pds:
        s, u = np.array(o["s"]), np.array(o["u"])
        K = 12
        U = np.array([[np.interp(k / K, s, u[i]) for i in range(4)] for k in range(K)])
        T = o["period"]
        got = shoot(U, o["par"], T)
        if got is None:
            failures.append(f"PD at {o['par']}: shooting did not converge")
            continue
        U, iapp, mu = got
        g = nearest_minus_one(mu)
        print(f"PD at iapp = {o['par']:.10f}, period {T:.8f}: shooting iapp = {iapp:.10f}, "
              f"multipliers {np.round(mu, 6)}")
        if not abs(iapp - o["par"]) <= 1e-7 * abs(iapp):
            failures.append(f"PD at {o['par']!r}: shooting gives iapp = {iapp!r}")
        if g is None or not abs(g + 1) <= 1e-5:
            failures.append(f"PD at {o['par']!r}: shooting's multipliers {mu}, none at -1")
        # a real multiplier through -1: prod (mu + 1) changes sign (a complex pair's factor
        # |mu + 1|^2 is positive)
        sides = []
        for dT in (-5e-4 * T, 5e-4 * T):
            near = shoot(U, iapp, T + dT)
            pm = np.prod(near[2] + 1).real if near else None
            print(f"  period {T + dT:.8f}: iapp = {near[1] if near else None}, "
                  f"multipliers {np.round(near[2], 6) if near else None}")
            sides.append(pm)
        if None in sides or not sides[0] * sides[1] < 0:
            failures.append(f"PD at {o['par']!r}: prod (mu + 1) at periods {T:.6g} -+ 0.05%: "
                            f"{sides}, no multiplier through -1 between them")

if failures:
    dest = os.path.join(artifacts, "continuation-hh-pd")
    shutil.rmtree(dest, ignore_errors=True)
    shutil.copytree(work, dest)
    for f in failures:
        print("FAIL:", f)
shutil.rmtree(work, ignore_errors=True)
sys.exit(1 if failures else 0)
