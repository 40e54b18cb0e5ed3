#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dynkit steady against closed forms: the heavy top of examples/mechanisms/top.mech at
theta = 30 deg and phi' = 100 rad/s precesses steadily at the two roots of
(I1 - I3) cos(theta) psi'^2 - I3 phi' psi' + m g L = 0 (I1 = A + m L^2, I3 = C; the
Lagrangian's theta equation with theta' = 0); the spherical pendulum's cone psi'^2 =
g / (L cos theta) and its eigenvalues against a hand linearization (the nutation pair
+-i sqrt(psi'^2 (1 + 3 cos^2 theta)) ... compared through NumPy on the reduced equations);
the rolling disk's steady turn (C + m r^2) Omega w3 cos(theta) - A Omega^2 sin(theta)
cos(theta) + m g r sin(theta) = 0, w3 = phi' + Omega sin(theta) (docs/mechanisms.md), its
dependent speeds from the rolling constraints (dx = r phi', dy = 0 heading along x); an .ode model (a particle in a central
field in polar coordinates: the circular orbit theta'^2 = k / r^3, theta cyclic) with a
parameter as the unknown; the JSON contract; bad input refused with exit status 2. Exit
0 when all hold, 1 when not, 77 (skipped) when dynkit is built without LAPACK.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from analysis_common import Checks  # noqa: E402

DYNKIT = sys.argv[1] if len(sys.argv) > 1 else "dynkit"
SOURCE = sys.argv[2] if len(sys.argv) > 2 else "."
MECH = os.path.join(SOURCE, "examples", "mechanisms")
CHECKS = Checks(DYNKIT, "steady")
run, check = CHECKS.run, CHECKS.check


def steady(*args):
    p = run(*args, "--json")
    return json.loads(p.stdout) if p.returncode == 0 else None


def main():
    p = subprocess.run([DYNKIT, "steady", os.path.join(MECH, "spherical_pendulum.mech"),
                        "--unknown", "dpsi", "--init", "dpsi=4"], capture_output=True, text=True)
    if "need LAPACK" in p.stderr:
        print("SKIP: dynkit is built without LAPACK (liblapack-dev)")
        return 77

    # the heavy top: both precession rates
    m, L, A, C, g = 1.0, 0.1, 0.002, 0.004, 9.81
    th, dphi = math.radians(30), 100.0
    I1, I3 = A + m * L * L, C
    a, b, c = (I1 - I3) * math.cos(th), -I3 * dphi, m * g * L
    roots = sorted((-b + s * math.sqrt(b * b - 4 * a * c)) / (2 * a) for s in (-1, 1))
    for guess, want in (("1", roots[0]), ("50", roots[1])):
        d = steady(os.path.join(MECH, "top.mech"), "--unknown", "dpsi", "--init", "dpsi=" + guess)
        got = d["state"]["dpsi"] if d else float("nan")
        check(abs(got - want) <= 1e-10 * want,
              f"top: precession {got!r} = {want!r} (guess {guess})")
        if d:
            check(d["cyclic"] == ["psi", "phi"] and d["state"]["theta"] == th and
                  d["state"]["dphi"] == dphi and abs(d["residual"]) < 1e-9,
                  f"top: cyclic psi, phi; theta and dphi kept ({d['cyclic']}, {d['residual']})")
            # the steady state is a relative equilibrium: every eigenvalue on the axis
            check(len(d["eigenvalues"]) == 6 and
                  all(abs(re) < 1e-6 for re, im in d["eigenvalues"]),
                  f"top at {want:.4f}: eigenvalues on the imaginary axis ({d['eigenvalues']})")

    # the spherical pendulum's cone
    for th in (0.3, 0.6, 1.2):
        d = steady(os.path.join(MECH, "spherical_pendulum.mech"), "--unknown", "dpsi",
                   "--init", f"theta={th}", "--init", "dpsi=4")
        want = math.sqrt(9.81 / (1.0 * math.cos(th)))
        got = d["state"]["dpsi"] if d else float("nan")
        check(abs(got - want) <= 1e-10 * want, f"spherical pendulum at theta = {th}: "
              f"psi' = {got!r}, sqrt(g/(L cos theta)) = {want!r}")
        if d:
            # small oscillations about the cone: theta'' = -(psi'^2 (1 + 3 cos^2)) ... in
            # closed form w^2 = W^2 (1 + 3 cos^2 theta), W the cone's rate
            w = want * math.sqrt(1 + 3 * math.cos(th) ** 2)
            ims = sorted(abs(im) for re, im in d["eigenvalues"])
            check(abs(ims[-1] - w) <= 1e-7 * w,
                  f"spherical pendulum at theta = {th}: nutation {ims[-1]!r} = {w!r}")

    # the rolling disk's steady turn: phi' from theta and Omega
    mm, r, g = 1.0, 0.3, 9.81
    Ad, Cd = mm * r * r / 4, mm * r * r / 2
    for th, Om in ((0.3, 2.0), (0.5, 3.0), (-0.2, 1.5)):
        d = steady(os.path.join(MECH, "rolling_disk.mech"), "--unknown", "dphi", "--init",
                   f"theta={th}", "--init", f"dpsi={Om}")
        if not d:
            check(False, f"rolling disk at theta = {th}")
            continue
        ph = d["state"]["dphi"]
        w3 = ph + Om * math.sin(th)
        res = (Cd + mm * r * r) * Om * w3 * math.cos(th) - Ad * Om ** 2 * math.sin(th) * \
            math.cos(th) + mm * g * r * math.sin(th)
        check(abs(res) <= 1e-10 * mm * g * r, f"rolling disk theta = {th}, Omega = {Om}: "
              f"phi' = {ph!r}, the closed form's residual {res:.2e}")
        check(d["cyclic"] == ["x", "y", "psi", "phi"] and
              abs(d["state"]["dx"] - r * ph) < 1e-12 * abs(r * ph) + 1e-15 and
              abs(d["state"]["dy"]) < 1e-12,
              f"rolling disk: cyclic x, y, psi, phi; rolling: dx = r phi', dy = 0 at psi = 0 "
              f"({d['cyclic']}, "
              f"{d['state']['dx']})")

    # the lean as the unknown, from a spin that the file's initial dx does not roll with
    # (the dependent speeds are solved, not checked)
    d = steady(os.path.join(MECH, "rolling_disk.mech"), "--unknown", "theta", "--init",
               "theta=0.2", "--init", "dpsi=2", "--init", "dphi=-3.864298798513792")
    check(d is not None and abs(d["state"]["theta"] - 0.3) < 1e-9,
          f"rolling disk: the lean 0.3 of the turn at Omega = 2, phi' = -3.8643 "
          f"({d and d['state']['theta']})")
    p = run(os.path.join(MECH, "top.mech"), "--unknown", "dpsi", "--init", "g=3", status=2)
    check("give it with --set" in p.stderr, f"refused: --init g=3 ({p.stderr.strip()[:70]})")

    # an .ode model: a particle in a central field k / r^2, theta cyclic; the unknown k
    with tempfile.TemporaryDirectory() as tmp:
        orbit = os.path.join(tmp, "orbit.ode")
        with open(orbit, "w") as f:
            f.write("par k=1\ninit r=2, th=0, vr=0, w=0.5\nr'=vr\nth'=w\n"
                    "vr'=r*w^2-k/r^2\nw'=-2*vr*w/r\ndone\n")
        d = steady(orbit, "--unknown", "k")
        check(d is not None and d["cyclic"] == ["th"] and
              abs(d["parameters"]["k"] - 0.5 ** 2 * 2 ** 3) < 1e-12,
              f"circular orbit: k = w^2 r^3 = 2 ({d and d['parameters']})")
        d = steady(orbit, "--unknown", "w", "--init", "w=0.3")
        check(d is not None and abs(d["state"]["w"] - math.sqrt(1 / 8)) < 1e-12,
              f"circular orbit: w = sqrt(k / r^3) ({d and d['state']['w']})")
        for args, word in (((orbit, "--unknown", "th"), "cyclic"),
                           ((orbit, "--unknown", "nope"), "no state or parameter 'nope'"),
                           ((orbit,), "missing --unknown"),
                           ((orbit, "--unknown", "k", "--output", "s.csv"), ".json")):
            p = run(*args, status=2)
            check(word in p.stderr, f"refused: {' '.join(args[1:])} ({p.stderr.strip()[:70]})")
        far = os.path.join(tmp, "none.ode")
        with open(far, "w") as f:
            f.write("par a=1\ninit x=1\nx'=x*x+a*a+1\ndone\n")
        p = run(far, "--unknown", "a", status=1)
        check("no step lowers" in p.stderr or "no steady motion" in p.stderr,
              f"no steady motion: x' = x^2 + a^2 + 1 ({p.stderr.strip()[:70]})")

    CHECKS.help_examples(SOURCE)
    return CHECKS.finish()


if __name__ == "__main__":
    sys.exit(main())
