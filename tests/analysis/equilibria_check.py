#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dynkit equilibria against closed forms: Lorenz's three equilibria (the origin, a saddle
with eigenvalues -beta and the roots of l^2 + (sigma+1) l + sigma (1-rho); C+- =
(+-sqrt(beta (rho-1)), +-sqrt(beta (rho-1)), rho-1), saddle-foci with the roots of
l^3 + (sigma+beta+1) l^2 + beta (sigma+rho) l + 2 sigma beta (rho-1)) from the default box;
the undamped Duffing oscillator x'' = x - x^3 (a saddle at 0 with +-1, centres at +-1 with
+-i sqrt 2); the pendulum's saddles at +-pi (+-sqrt(g/l)) and centre at 0; the Henon map's
two fixed points x = (-(1-b) +- sqrt((1-b)^2 + 4a)) / 2a, y = b x, with multipliers
-a x +- sqrt(a^2 x^2 + b); the logistic map at r = 4 (0 and 3/4, multipliers 4 and -2); a
mechanism with a constraint judged on its minimal coordinates (the Cartesian pendulum:
+-i sqrt(g/l) hanging, +-sqrt(g/l) upright); the JSON and CSV contracts; bad input
refused with exit status 2. Exit 0 when all hold, 1 when not, 77 (skipped) without NumPy
or when dynkit is built without LAPACK.
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

try:
    import numpy as np
except ImportError:
    print("SKIP: NumPy is missing (python3-numpy)")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from analysis_common import Checks  # noqa: E402

DYNKIT = sys.argv[1] if len(sys.argv) > 1 else "dynkit"
SOURCE = sys.argv[2] if len(sys.argv) > 2 else "."
EX = os.path.join(SOURCE, "examples")
CHECKS = Checks(DYNKIT, "equilibria")
run, check = CHECKS.run, CHECKS.check


def found(*args):
    p = run(*args, "--json")
    if p.returncode != 0:
        return []
    return json.loads(p.stdout)["equilibria"]


def eigs(e):
    return np.sort_complex(np.array([complex(re, im) for re, im in e["eigenvalues"]]))


def close_eigs(e, expected, rtol):
    got, want = eigs(e), np.sort_complex(np.array(expected, dtype=complex))
    return len(got) == len(want) and np.max(np.abs(got - want)) <= rtol * max(1, np.max(np.abs(want)))


def main():
    p = subprocess.run([DYNKIT, "equilibria", "pendulum", "--box", "phi=-1:1", "--json"],
                       capture_output=True, text=True)
    if "need LAPACK" in p.stderr:
        print("SKIP: dynkit is built without LAPACK (liblapack-dev)")
        return 77

    # Lorenz, from the default box (the range of the default run)
    s, r, b = 10.0, 28.0, 2.6666666666666665
    eq = found(os.path.join(EX, "models", "lorenz.ode"))
    check(len(eq) == 3, f"Lorenz: 3 equilibria in the default box (got {len(eq)})")
    if len(eq) == 3:
        c = math.sqrt(b * (r - 1))
        for e, sign in zip(eq, (-1, 0, 1)):
            y = [e["state"][k] for k in ("x", "y", "z")]
            want = [sign * c, sign * c, r - 1] if sign else [0, 0, 0]
            check(max(abs(u - v) for u, v in zip(y, want)) <= 1e-12 * 27,
                  f"Lorenz equilibrium {want}: {y}")
            if sign:
                ev = np.roots([1, s + b + 1, b * (s + r), 2 * s * b * (r - 1)])
                kind = "saddle-focus"
                dims = (1, 2, 0)
            else:
                ev = [-b] + list(np.roots([1, s + 1, s * (1 - r)]))
                kind = "saddle"
                dims = (2, 1, 0)
            check(close_eigs(e, ev, 1e-12), f"Lorenz at {want}: eigenvalues {eigs(e)}")
            check(e["type"] == kind and (e["stable"], e["unstable"], e["centre"]) == dims,
                  f"Lorenz at {want}: {e['type']} {e['stable']},{e['unstable']},{e['centre']}")

    # undamped Duffing: x'' = x - x^3
    eq = found(os.path.join(EX, "models", "duffing.ode"), "--set", "gamma=0", "--set",
               "delta=0", "--box", "x=-2:2,v=-1:1")
    check([round(e["state"]["x"], 12) for e in eq] == [-1, 0, 1],
          f"Duffing: x = -1, 0, 1 ({[e['state']['x'] for e in eq]})")
    if len(eq) == 3:
        for e, kind, ev in ((eq[0], "centre", [1j * 2**0.5, -1j * 2**0.5]),
                            (eq[1], "saddle", [1, -1]),
                            (eq[2], "centre", [1j * 2**0.5, -1j * 2**0.5])):
            check(e["type"] == kind and close_eigs(e, ev, 1e-12),
                  f"Duffing at x = {e['state']['x']:.3g}: {e['type']} {eigs(e)}")

    # the built-in pendulum (no analytic Jacobian: Richardson's differences)
    eq = found("pendulum", "--box", "phi=-4:4,dphi=-1:1")
    w = math.sqrt(9.81 / 9.81)
    check([e["type"] for e in eq] == ["saddle", "centre", "saddle"] and len(eq) == 3 and
          abs(eq[0]["state"]["phi"] + math.pi) < 1e-12 and abs(eq[2]["state"]["phi"] - math.pi) < 1e-12,
          f"pendulum: saddle at -pi, centre at 0, saddle at pi ({[e['type'] for e in eq]})")
    if len(eq) == 3:
        check(close_eigs(eq[0], [w, -w], 1e-10) and close_eigs(eq[1], [1j * w, -1j * w], 1e-10),
              f"pendulum: +-sqrt(g/l) and +-i sqrt(g/l) ({eigs(eq[0])}, {eigs(eq[1])})")

    # the Henon map's fixed points and multipliers
    a, bb = 1.4, 0.3
    eq = found(os.path.join(EX, "models", "henon.ode"), "--box", "x=-3:3,y=-3:3")
    xs = sorted((-(1 - bb) + sg * math.sqrt((1 - bb) ** 2 + 4 * a)) / (2 * a) for sg in (-1, 1))
    check(len(eq) == 2, f"Henon: 2 fixed points ({len(eq)})")
    for e, x in zip(eq, xs):
        check(abs(e["state"]["x"] - x) < 1e-14 and abs(e["state"]["y"] - bb * x) < 1e-14,
              f"Henon fixed point x = {x}: {e['state']}")
        mu = [-a * x + sg * math.sqrt(a * a * x * x + bb) for sg in (-1, 1)]
        check(close_eigs(e, mu, 1e-13) and e["type"] == "saddle",
              f"Henon at x = {x:.4f}: multipliers {eigs(e)} = {mu}, {e['type']}")

    with tempfile.TemporaryDirectory() as tmp:
        logistic = os.path.join(tmp, "logistic.ode")
        with open(logistic, "w") as f:
            f.write("par r=4\ninit x=0.3\nx(t+1)=r*x*(1-x)\n@ total=100\ndone\n")
        eq = found(logistic, "--box", "x=-0.5:1.5")
        check([e["state"]["x"] for e in eq] == [0, 0.75] and
              [e["eigenvalues"] for e in eq] == [[[4, 0]], [[-2, 0]]] and
              all(e["type"] == "unstable node" for e in eq),
              f"logistic map r = 4: 0 and 3/4, multipliers 4 and -2 ({eq})")
        # the CSV table: one row per equilibrium
        out = os.path.join(tmp, "eq.csv")
        run(os.path.join(EX, "models", "lorenz.ode"), "--output", out)
        with open(out) as f:
            rows = list(csv.DictReader(f))
        check(len(rows) == 3 and rows[1]["type"] == "saddle" and abs(float(rows[1]["z"])) < 1e-12 and
              list(rows[0].keys()) == ["type", "stable", "unstable", "centre", "x", "y", "z",
                                       "residual"], f"--output eq.csv: {rows[:1]}")

    # a constrained mechanism: the reduced eigenvalues
    eq = found(os.path.join(EX, "mechanisms", "cartesian_pendulum.mech"), "--box",
               "x=-0.5:0.5,y=-3:3,dx=-1:1,dy=-1:1")
    w = math.sqrt(9.81 / 2)
    check([e["type"] for e in eq] == ["centre", "saddle"] and
          abs(eq[0]["state"]["y"] + 2) < 1e-12 and abs(eq[1]["state"]["y"] - 2) < 1e-12,
          f"Cartesian pendulum: hanging centre, upright saddle ({[e['type'] for e in eq]})")
    if len(eq) == 2:
        check(close_eigs(eq[0], [1j * w, -1j * w], 1e-8) and close_eigs(eq[1], [w, -w], 1e-8),
              f"Cartesian pendulum: 2 reduced eigenvalues each +-i w, +-w ({eigs(eq[0])}, {eigs(eq[1])})")

    # refused
    for args, word in ((("pendulum", "--box", "foo=1:2"), "no state 'foo'"),
                       (("pendulum", "--box", "phi=2:1"), "A <= B"),
                       (("pendulum", "--starts", "0"), "--starts"),
                       (("pendulum", "--output", "eq.txt"), ".csv"),
                       ((os.path.join(EX, "models", "mackey_glass.ode"),), "delays")):
        p = run(*args, status=2)
        check(word in p.stderr, f"refused: {' '.join(args)} ({p.stderr.strip()[:70]})")

    CHECKS.help_examples(SOURCE)
    return CHECKS.finish()


if __name__ == "__main__":
    sys.exit(main())
