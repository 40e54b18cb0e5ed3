#!/usr/bin/env python3
"""The period doublings of Roessler's cycles in a (b = 2, c = 4), checked by shooting
(docs/analysis.md, "Checks"): dynkit continue finds on the cycles from the Hopf point a PD at
a = 0.3348566226 (AUTO-07p's too) and a second at a = 0.8477977541, 4e-4 before the cycles'
fold (LPC) at 0.8481894965, which AUTO-07p does not report (it reports the fold). Each PD
orbit (from the diagram's page) is solved again here by single shooting with SciPy
(solve_ivp, DOP853, rtol 1e-11, the variational equations with the Jacobian written out)
at dynkit's parameter: a real multiplier is -1 within 1e-6 and the period agrees within
1e-7; at 2e-4 in a on either side a real multiplier lies on either side of -1
(prod (mu + 1) changes sign). No PD, LPC or TR of the page is called stable. Failures
keep the page under ARTIFACTS.
Usage: roessler_period_doubling.py DYNKIT MODEL ARTIFACTS"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

try:
    import numpy as np
    from scipy.integrate import solve_ivp
except ImportError as e:
    print(f"skipped: {e} (scripts/install-deps.sh installs NumPy and SciPy)")
    sys.exit(77)

dynkit, model, artifacts = sys.argv[1:4]
B, C = 2.0, 4.0  # the file's b and c
failures = []
work = tempfile.mkdtemp(prefix="dynkit-roessler-pd-")


def flow(x0, a, T):
    """x(T) from x0 and the monodromy d x(T)/d x0"""
    def rhs(t, z):
        x, P = z[:3], z[3:].reshape(3, 3)
        J = np.array([[0.0, -1.0, -1.0], [1.0, a, 0.0], [x[2], 0.0, x[0] - C]])
        return np.concatenate([[-x[1] - x[2], x[0] + a * x[1], B + x[2] * (x[0] - C)],
                               (J @ P).ravel()])
    s = solve_ivp(rhs, (0.0, T), np.concatenate([x0, np.eye(3).ravel()]), method="DOP853",
                  rtol=1e-11, atol=1e-13)
    return s.y[:3, -1], s.y[3:, -1].reshape(3, 3)


def periodic_orbit(x0, T, a):
    """Newton's method on x(T) = x0 with the phase f(x_guess).(x0 - x_guess) = 0: the
    start, the period and the multipliers"""
    def f(x):
        return np.array([-x[1] - x[2], x[0] + a * x[1], B + x[2] * (x[0] - C)])
    xg, fg = x0.copy(), f(x0)
    for _ in range(30):
        xe, M = flow(x0, a, T)
        A = np.zeros((4, 4))
        A[:3, :3], A[:3, 3], A[3, :3] = M - np.eye(3), f(xe), fg
        d = np.linalg.solve(A, -np.concatenate([xe - x0, [fg @ (x0 - xg)]]))
        x0, T = x0 + d[:3], T + d[3]
        if np.max(np.abs(d)) < 1e-11 * (1.0 + np.max(np.abs(x0))):
            break
    return x0, T, np.linalg.eigvals(flow(x0, a, T)[1])


page = os.path.join(work, "roessler.html")
d = subprocess.run([dynkit, "continue", model, "--par", "a", "--html", page],
                   capture_output=True, text=True)
if d.returncode != 0:
    failures.append(f"dynkit continue: exit {d.returncode}: {d.stderr}")
else:
    text = open(page).read()
    data = json.loads(re.search(r'<script id="dynkit-data" type="application/json">(.*?)'
                                r'</script>', text, re.S).group(1))
    orbits = [o for o in data["orbits"] if o["branch"] == 2]
    labels = [(o["label"], o["par"]) for o in orbits if o["label"] in ("PD", "LPC")]
    print("dynkit's labels on the cycles:", labels)
    if [l for l, _ in labels[:3]] != ["PD", "PD", "LPC"]:
        failures.append(f"the cycles' first labels {labels}: expected PD, PD, LPC")
    # a located PD or LPC has a multiplier on the unit circle: never asymptotically stable
    # (the second PD's computed multiplier is -0.9999999999994)
    called_stable = [(o["label"], o["par"]) for o in data["orbits"]
                     if o["label"] in ("PD", "LPC", "TR") and o["stable"]]
    if called_stable:
        failures.append(f"located points called stable: {called_stable}")
    for o in [o for o in orbits if o["label"] == "PD"][:2]:
        a = o["par"]
        x0 = np.array([u[0] for u in o["u"]])
        x1, T, mu = periodic_orbit(x0, o["period"], a)
        flip = min(abs(m + 1) for m in mu if abs(m.imag) < 1e-9)
        print(f"PD at a = {a!r}: shooting's period {T!r} (dynkit {o['period']!r}), the "
              f"multipliers {np.round(mu, 9)}")
        if not flip < 1e-6 or not abs(T - o["period"]) < 1e-7 * T:
            failures.append(f"PD at a = {a}: shooting's multipliers {mu}, period {T} "
                            f"(dynkit {o['period']})")
        signs = []
        for da in (-2e-4, 2e-4):
            _, _, mu2 = periodic_orbit(x1, T, a + da)
            signs.append(np.prod(mu2 + 1.0).real)
            print(f"   a {da:+g}: multipliers {np.round(mu2, 6)}")
        if not signs[0] * signs[1] < 0:
            failures.append(f"PD at a = {a}: no multiplier through -1 between a -+ 2e-4")
for f in failures:
    print("FAIL:", f)
if failures:
    dest = os.path.join(artifacts, "continuation-roessler-period-doubling")
    shutil.rmtree(dest, ignore_errors=True)
    shutil.copytree(work, dest)
    print("kept in", dest)
else:
    shutil.rmtree(work, ignore_errors=True)
sys.exit(1 if failures else 0)
