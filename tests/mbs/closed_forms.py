#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Mechanisms with closed-form answers, written from docs/mechanisms.md alone (tests/mbs/closed):

- physical_pendulum: a uniform rod about one end, `linearize` gives +-i sqrt(m g d / I_O),
  d = L/2, I_O = m L^2/3; `inverse --prescribe` its torque I_O th'' + m g d sin(th);
- hoop_bead: a bead on a hoop of radius R turning at W about the vertical, at rest relative
  to the hoop at cos(th) = g/(W^2 R) (f = 0) with small swings at W sin(th); below the
  critical W^2 = g/R the bottom is stable, swinging at sqrt(g/R - W^2);
- incline_cylinder: a solid cylinder rolling down an incline, a = g sin(al)/(1 + 1/2), the
  normal force m g cos(al) and the friction m g sin(al)/3 as the constraints' multipliers;
- slider_crank: the crank driven at th = w t, the piston at
  r cos(th) + sqrt(l^2 - r^2 sin(th)^2); the driving torque's work equals the energy's change;
- spherical_pendulum: conical motion at psi' = sqrt(g/(L cos(theta))), theta kept;
- bead_on_rod: a bead free on a rod turned at W (prismatic joint on a revolute one), at
  s0 cosh(W t), the drive's torque (rod's inertia constant) 2 m W s s';
- cart_double_pendulum: a cart on a rail with two uniform links: the horizontal momentum
  kept, and `linearize` at rest gives the frequencies of M q'' + K q = 0 formed by hand;
- torque_free_quat: a free asymmetric body by Euler parameters, started turning about its
  intermediate axis with a small disturbance: the energy and |I w| (w = 2 vec(conj(q) q'))
  kept, the norm kept, and the spin about that axis reverses (the intermediate-axis
  instability).

Usage: closed_forms.py DYNKIT DIR
"""
import csv
import io
import math
import os
import re
import subprocess
import sys

DYN, DIR = sys.argv[1], sys.argv[2]
fails = []


def check(what, got, want, tol):
    ok = abs(got - want) <= tol
    print(f"{'ok  ' if ok else 'FAIL'} {what}: {got!r} against {want!r} (tol {tol})")
    if not ok:
        fails.append(what)


def dyn(*args):
    return subprocess.run([DYN, *args], check=True, capture_output=True, text=True).stdout


def eig_im(out):
    ims = []
    lines = out.splitlines()
    k = next(i for i, s in enumerate(lines) if s.startswith("eigenvalues:"))
    for s in lines[k + 2:]:
        parts = s.split()
        if len(parts) < 2 or not re.match(r"^-?[0-9]", parts[0]):
            break
        ims.append(float(parts[1]))
    return sorted(ims)


def table(out):
    return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(io.StringIO(out))]


g = 9.81
# physical pendulum
m, L = 2.0, 1.5
w = math.sqrt(m * g * (L / 2) / (m * L * L / 3))
check("physical pendulum frequency", eig_im(dyn("linearize", f"{DIR}/physical_pendulum.mech",
                                               "--init", "th=0"))[-1], w, 1e-9 * w)

# its inverse dynamics: the torque that drives th = 0.5 sin(2 t) is I_O th'' + m g d sin(th)
rows = table(dyn("inverse", f"{DIR}/physical_pendulum.mech", "--prescribe", "th=0.5*sin(2*t)",
                 "--tspan", "0:2", "--step", "0.25", "--method", "dop853", "--rtol", "1e-12",
                 "--atol", "1e-12", "--quiet"))
err = max(abs(row["Q_th"] - (m * L * L / 3 * -2 * math.sin(2 * row["t"])
                             + m * g * L / 2 * math.sin(0.5 * math.sin(2 * row["t"]))))
          for row in rows)
check("physical pendulum: inverse dynamics' torque", err, 0, 1e-9)

# bead on a turning hoop
R, W = 0.5, 10.0
th = math.acos(g / (W * W * R))
out = dyn("linearize", f"{DIR}/hoop_bead.mech", "--init", f"th={th!r}")
check("hoop bead: relative rest", float(re.search(r"dth +=.*f = (\S+)", out).group(1)), 0, 1e-9)
check("hoop bead: swing about the rest", eig_im(out)[-1], W * math.sin(th), 1e-8)
out = dyn("linearize", f"{DIR}/hoop_bead.mech", "--init", "th=0", "--set", "W=3")
check("hoop bead: swing at the bottom below the critical speed", eig_im(out)[-1],
      math.sqrt(g / R - 9), 1e-8)

# cylinder rolling down an incline
m, al = 2.0, 0.5
rows = table(dyn("run", f"{DIR}/incline_cylinder.mech", "--outputs", "--tspan", "0:1",
                 "--step", "0.5", "--method", "dop853", "--rtol", "1e-12", "--atol", "1e-12"))
a = g * math.sin(al) / 1.5
check("incline: distance in 1 s", rows[-1]["x"], a / 2, 1e-10)
check("incline: normal force", rows[-1]["normal"], m * g * math.cos(al), 1e-9)
check("incline: friction force", abs(rows[-1]["roll"]), m * g * math.sin(al) / 3, 1e-9)

# slider-crank
r, l, wc = 0.1, 0.3, 2.0
rows = table(dyn("run", f"{DIR}/slider_crank.mech", "--outputs", "--project-init",
                 "--tspan", "0:3", "--step", "0.001", "--method", "dop853",
                 "--rtol", "1e-12", "--atol", "1e-12"))
err = max(abs(row["s"] - r * math.cos(row["th"]) - math.sqrt(l * l - (r * math.sin(row["th"])) ** 2))
          for row in rows)
check("slider-crank: piston against the closed form", err, 0, 1e-10)
work = sum((rows[i]["drive"] + rows[i + 1]["drive"]) / 2 * wc * (rows[i + 1]["t"] - rows[i]["t"])
           for i in range(len(rows) - 1))
check("slider-crank: the drive's work is the energy's change", work,
      rows[-1]["energy"] - rows[0]["energy"], 1e-7)

# dynkit derive prints the slider-crank's rows though its file leaves the speeds at 0 (the
# drive's rate then does not hold): each row is the gradient of its loop equation
rowsD = {}
for line in dyn("derive", f"{DIR}/slider_crank.mech").splitlines():
    mm = re.match(r"D\[(\w+),(\w+)\] = (.*)$", line)
    if mm:
        rowsD[(mm.group(1), mm.group(2))] = mm.group(3)
env = {"sin": math.sin, "cos": math.cos, "r": r, "l": l, "th": 0.7, "ph": 0.2}
want = {("loop_x", "th"): -r * math.sin(0.7), ("loop_x", "ph"): -l * math.sin(0.2),
        ("loop_x", "s"): -1, ("loop_y", "th"): r * math.cos(0.7),
        ("loop_y", "ph"): -l * math.cos(0.2), ("loop_y", "s"): 0, ("drive", "th"): 1}
for key, val in want.items():
    check(f"derive: D[{key[0]},{key[1]}]", eval(rowsD[key].replace("^", "**"), env), val, 1e-15)

# dynkit info describes it too (a description, not a run): the drive of an angle is a torque
info = dyn("info", f"{DIR}/slider_crank.mech")
check("info: the drive's multiplier is a torque in N m",
      float(re.search(r"^  drive +N m +force of the constraint drive", info, re.M) is not None),
      1.0, 0)

# a loop without a declared unit takes its formula's: r*sin(th) = l*sin(ph) is in m, so N
check("info: the loop's multiplier without a declared unit is a force in N",
      float(re.search(r"^  loop_y +N +force of the constraint loop_y", info, re.M) is not None),
      1.0, 0)

# spherical pendulum, conical motion
L, th = 1.0, 0.6
Om = math.sqrt(g / (L * math.cos(th)))
rows = table(dyn("run", f"{DIR}/spherical_pendulum.mech", "--init", f"dpsi={Om!r}",
                 "--tspan", "0:5", "--step", "0.5", "--method", "dop853", "--rtol", "1e-12",
                 "--atol", "1e-12"))
check("spherical pendulum: cone angle kept", max(abs(row["theta"] - th) for row in rows), 0,
      1e-10)

# bead on a turning rod
m, W, s0 = 0.2, 3.0, 0.1
rows = table(dyn("run", f"{DIR}/bead_on_rod.mech", "--outputs", "--project-init",
                 "--tspan", "0:1", "--step", "0.25", "--method", "dop853",
                 "--rtol", "1e-12", "--atol", "1e-12"))
for row in rows[1:]:
    t = row["t"]
    s, ds = s0 * math.cosh(W * t), s0 * W * math.sinh(W * t)
    check(f"bead on rod: s at t={t}", row["s"], s, 1e-10 * s)
    check(f"bead on rod: torque at t={t}", row["turn"], 2 * m * W * s * ds, 1e-9 * s * ds)

# double pendulum on a cart
mc, m1, m2, l1, l2 = 2.0, 1.0, 0.5, 0.8, 0.6
rows = table(dyn("run", f"{DIR}/cart_double_pendulum.mech", "--outputs", "--tspan", "0:10",
                 "--step", "0.5", "--method", "dop853", "--rtol", "1e-12", "--atol", "1e-12"))
p = max(abs((mc + m1 + m2) * r["dx"] + m1 * l1 / 2 * math.cos(r["a1"]) * r["da1"]
            + m2 * (l1 * math.cos(r["a1"]) * r["da1"]
                    + l2 / 2 * math.cos(r["a1"] + r["a2"]) * (r["da1"] + r["da2"])))
        for r in rows)
check("cart double pendulum: horizontal momentum kept", p, 0, 1e-10)
try:
    import numpy as np
    c = l1 + l2 / 2
    M = np.array([[mc + m1 + m2, m1 * l1 / 2 + m2 * c, m2 * l2 / 2],
                  [m1 * l1 / 2 + m2 * c, m1 * l1 ** 2 / 3 + m2 * c * c + m2 * l2 ** 2 / 12,
                   m2 * c * l2 / 2 + m2 * l2 ** 2 / 12],
                  [m2 * l2 / 2, m2 * c * l2 / 2 + m2 * l2 ** 2 / 12, m2 * l2 ** 2 / 3]])
    K = g * np.array([[0, 0, 0], [0, m1 * l1 / 2 + m2 * c, m2 * l2 / 2],
                      [0, m2 * l2 / 2, m2 * l2 / 2]])
    w = sorted(np.sqrt(np.abs(np.linalg.eigvals(np.linalg.solve(M, K)).real)))
    ims = eig_im(dyn("linearize", f"{DIR}/cart_double_pendulum.mech", "--init", "a1=0",
                     "--init", "a2=0"))
    check("cart double pendulum: slow swing", ims[-2], w[1], 1e-8)
    check("cart double pendulum: fast swing", ims[-1], w[2], 1e-8)
except ImportError:
    print("NumPy missing: the cart double pendulum's frequencies are not checked")

# torque-free asymmetric body by Euler parameters
try:
    import numpy as np
    rows = table(dyn("run", f"{DIR}/torque_free_quat.mech", "--outputs", "--tspan", "0:30",
                     "--step", "0.5", "--method", "dop853", "--rtol", "1e-12", "--atol", "1e-12"))
    In = np.array([1.0, 2.0, 3.0])
    Hs, w2 = [], []
    for row in rows:
        w, x, y, z = (row[k] for k in ("qw", "qx", "qy", "qz"))
        dw, dx_, dy_, dz = (row["d" + k] for k in ("qw", "qx", "qy", "qz"))
        # body-frame angular velocity: 2 vec(conj(q) * q')
        wb = 2 * np.array([w * dx_ - x * dw - y * dz + z * dy_,
                           w * dy_ + x * dz - y * dw - z * dx_,
                           w * dz - x * dy_ + y * dx_ - z * dw])
        Hs.append(np.linalg.norm(In * wb))
        w2.append(wb[1])
    check("torque-free body: |H| kept", max(Hs) - min(Hs), 0, 1e-10)
    check("torque-free body: energy kept",
          max(r["energy"] for r in rows) - min(r["energy"] for r in rows), 0, 1e-10)
    check("torque-free body: norm kept", max(abs(r["qw"] ** 2 + r["qx"] ** 2 + r["qy"] ** 2
                                                 + r["qz"] ** 2 - 1) for r in rows), 0, 1e-10)
    check("torque-free body: the intermediate axis flips (least w2 below -0.9)",
          float(min(w2) < -0.9), 1.0, 0)
except ImportError:
    print("NumPy missing: the torque-free body is not checked")

# a mass on a hardening spring law F(x, v) = k x + k3 x^3 (Duffing), no gravity
m, k, k3, L, A = 2.0, 3.0, 5.0, 1.0, 0.8
DUF = os.path.join(DIR, "..", "..", "..", "examples", "mechanisms", "duffing_spring.mech")
acc = ["--method", "dop853", "--rtol", "1e-12", "--atol", "1e-12", "--quiet"]
rows = table(dyn("run", DUF, "--outputs", "--tspan", "0:10",
                 "--step", "0.1", *acc))
err = max(abs(r["energy"] - (m * r["ds"] ** 2 / 2 + k * (r["s"] - L) ** 2 / 2
                             + k3 * (r["s"] - L) ** 4 / 4)) for r in rows)
check("Duffing spring: energy is m v^2/2 + k x^2/2 + k3 x^4/4", err, 0, 1e-12)
check("Duffing spring: energy kept", max(r["energy"] for r in rows)
      - min(r["energy"] for r in rows), 0, 1e-10)
force = table(dyn("run", f"{DIR}/duffing_force.mech", "--tspan", "0:10", "--step", "0.1", *acc))
check("Duffing spring: the law as an applied force", max(
    abs(a[q] - b[q]) for a, b in zip(rows, force) for q in ("s", "ds")), 0, 1e-10)
lin = [table(dyn("run", f, *sets, "--tspan", "0:10", "--step", "0.1", *acc))
       for f, sets in ((DUF, ("--set", "k3=0")), (f"{DIR}/duffing_linear.mech", ()))]
check("Duffing spring: k3 = 0 as a linear spring", max(
    abs(a[q] - b[q]) for a, b in zip(*lin) for q in ("s", "ds")), 0, 1e-10)
lin = [table(dyn("run", f, *sets, "--set", "c=0.7", "--tspan", "0:10", "--step", "0.1", *acc))
       for f, sets in ((DUF, ("--set", "k3=0")), (f"{DIR}/duffing_linear.mech", ()))]
check("Duffing spring: k3 = 0, c = 0.7 as a linear spring and damper", max(
    abs(a[q] - b[q]) for a, b in zip(*lin) for q in ("s", "ds")), 0, 1e-10)
# the damped linear oscillator from rest: x = A e^(-g t) (cos(wd t) + g/wd sin(wd t))
gam = 0.7 / (2 * m)
wd = math.sqrt(k / m - gam ** 2)
check("Duffing spring: k3 = 0, c = 0.7 against the damped oscillator's closed form", max(
    abs(r["s"] - L - A * math.exp(-gam * r["t"]) * (math.cos(wd * r["t"])
                                                   + gam / wd * math.sin(wd * r["t"])))
    for r in lin[0]), 0, 1e-9)
# the period from rest at amplitude A: with x = A sin(th), V(A) - V(x) = cos(th)^2 (k A^2/2
# + k3 A^4 (1 + sin(th)^2)/4), T = 4 int_0^pi/2 A dth / sqrt(2/m (...)); the midpoint rule
# converges geometrically for this smooth even periodic integrand
nq = 400
T = 4 * sum(A / math.sqrt(2 / m * (k * A ** 2 / 2 + k3 * A ** 4
                                   * (1 + math.sin((j + 0.5) * math.pi / 2 / nq) ** 2) / 4))
            for j in range(nq)) * math.pi / 2 / nq
quarter = table(dyn("run", DUF, "--tspan", f"0:{T!r}", "--step",
                    repr(T / 4), *acc))
for j, want in ((1, L), (2, L - A), (4, L + A)):
    check(f"Duffing spring: s at {j}/4 of the period {T:.12g} s", quarter[j]["s"], want, 1e-9)

sys.exit(1 if fails else 0)
