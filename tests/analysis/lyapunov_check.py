#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dynkit lyapunov against known values: Lorenz at sigma = 10, rho = 28, beta = 8/3 (the
largest exponent 0.9056, Sprott, Chaos and Time-Series Analysis, 2003, table; the middle
one 0; the sum -(sigma + 1 + beta) exactly, the trace of the Jacobian being constant); a
linear system x' = A x (the exponents are the real parts of A's eigenvalues, here -0.5 twice
and -2, numpy.linalg.eigvals); the logistic map at r = 4 (ln 2); the Henon map at a = 1.4,
b = 0.3 (0.41922, Sprott's table; the sum ln b exactly, the Jacobian's determinant being
-b); a model without an exact Jacobian (the built-in pendulum: both exponents 0 on a
periodic orbit, their sum 0; van der Pol's limit cycle over a short span, 0 within its
error and a note that says so); the JSON contract; bad input refused with exit status 2.
The estimates must agree within four times their own error estimate plus 0.005 (the
table's rounding and the bias of a finite average). Exit 0 when all hold, 1 when not, 77
(skipped) without NumPy.
"""
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
EX = os.path.join(SOURCE, "examples", "models")
CHECKS = Checks(DYNKIT, "lyapunov")
run, check = CHECKS.run, CHECKS.check


def exps(*args):
    p = run(*args, "--json")
    return json.loads(p.stdout) if p.returncode == 0 else {"exponents": [], "errors": []}


def agree(got, err, want):
    return abs(got - want) <= 4 * err + 0.005


def main():
    s, b = 10.0, 8.0 / 3.0
    d = exps(os.path.join(EX, "lorenz.ode"), "--spectrum", "--tspan", "0:2000")
    ex, er = d["exponents"], d["errors"]
    check(len(ex) == 3 and d["jacobian"] == "exact" and ex == sorted(ex, reverse=True),
          f"Lorenz: three exponents, largest first, exact Jacobian ({ex})")
    if len(ex) == 3:
        check(agree(ex[0], er[0], 0.9056) and er[0] < 0.02,
              f"Lorenz: largest {ex[0]:.5f} +- {er[0]:.2g} = 0.9056")
        check(agree(ex[1], er[1], 0.0), f"Lorenz: middle {ex[1]:.5f} +- {er[1]:.2g} = 0")
        check(abs(sum(ex) + (s + 1 + b)) <= 1e-9 * (s + 1 + b),
              f"Lorenz: sum {sum(ex):.12f} = -(sigma+1+beta) = {-(s + 1 + b):.12f}")
    # the default span (0..40) is short for Lorenz: a note says so and gives a span that
    # brings the error to about 2%; that span's estimate is within its error and has no note
    p = run(os.path.join(EX, "lorenz.ode"))
    span = p.stderr.split("--tspan ")[-1].split(")")[0] if "--tspan" in p.stderr else ""
    check("error estimate is" in p.stderr and span.startswith("0:"),
          f"Lorenz, default span: a note with a longer span ({p.stderr.strip()[:120]})")
    if span.startswith("0:"):
        p = run(os.path.join(EX, "lorenz.ode"), "--tspan", span, "--json")
        d1 = json.loads(p.stdout) if p.returncode == 0 else {"exponents": [0], "errors": [1]}
        check("note" not in p.stderr and d1["errors"][0] < 0.035 * d1["exponents"][0] and
              agree(d1["exponents"][0], d1["errors"][0], 0.9056),
              f"Lorenz over {span}: {d1['exponents']} +- {d1['errors']} = 0.9056, no note")
    # van der Pol's limit cycle over a short span: the largest exponent (0) within its
    # error of 0: the note says so, with no relative error of a value that may be 0
    p = run("vanderpol", "--tspan", "0:20", "--json")
    d1 = json.loads(p.stdout) if p.returncode == 0 else {"exponents": [1], "errors": [0]}
    check(abs(d1["exponents"][0]) <= d1["errors"][0] and "0 within its error" in p.stderr and
          "%" not in p.stderr,
          f"van der Pol over 0:20: {d1['exponents']} +- {d1['errors']}, note "
          f"{p.stderr.strip()[:100]!r}")
    # the largest alone (another step sequence: another chaotic trajectory, the same value)
    d1 = exps(os.path.join(EX, "lorenz.ode"), "--tspan", "0:2000")
    check(len(d1["exponents"]) == 1 and agree(d1["exponents"][0], d1["errors"][0], 0.9056),
          f"Lorenz: the largest alone {d1['exponents']} +- {d1['errors']} = 0.9056")

    with tempfile.TemporaryDirectory() as tmp:
        lin = os.path.join(tmp, "linear.ode")
        A = np.array([[-0.5, 2.0, 0.0], [-2.0, -0.5, 0.0], [1.0, 0.0, -2.0]])
        with open(lin, "w") as f:
            f.write("init x=1, y=0, z=1\nx'=-0.5*x+2*y\ny'=-2*x-0.5*y\nz'=x-2*z\ndone\n")
        want = sorted(np.linalg.eigvals(A).real, reverse=True)
        d = exps(lin, "--spectrum", "--tspan", "0:500")
        check(len(d["exponents"]) == 3 and
              all(agree(g, e, w) for g, e, w in zip(d["exponents"], d["errors"], want)),
              f"linear system: {d['exponents']} = real parts {want}")
        logistic = os.path.join(tmp, "logistic.ode")
        with open(logistic, "w") as f:
            f.write("par r=4\ninit x=0.3\nx(t+1)=r*x*(1-x)\n@ total=100\ndone\n")
        d = exps(logistic, "--tspan", "0:100000")
        check(d["map"] and len(d["exponents"]) == 1 and
              agree(d["exponents"][0], d["errors"][0], math.log(2)),
              f"logistic map r = 4: {d['exponents']} = ln 2")

    d = exps(os.path.join(EX, "henon.ode"), "--spectrum", "--tspan", "0:100000")
    ex, er = d["exponents"], d["errors"]
    check(len(ex) == 2 and agree(ex[0], er[0], 0.41922),
          f"Henon map: largest {ex[:1]} +- {er[:1]} = 0.41922")
    check(len(ex) == 2 and abs(sum(ex) - math.log(0.3)) < 1e-12,
          f"Henon map: sum {sum(ex)!r} = ln b = {math.log(0.3)!r}")

    d = exps("pendulum", "--spectrum", "--tspan", "0:500")
    ex, er = d["exponents"], d["errors"]
    check(d.get("jacobian") == "differences" and len(ex) == 2 and
          all(abs(x) < 0.02 for x in ex) and abs(sum(ex)) < 1e-6,
          f"pendulum (differences): a periodic orbit's exponents 0, 0 ({ex}), sum 0")

    for args, word in ((("pendulum", "--spectrum", "--exponents", "1"), "one of them"),
                       (("pendulum", "--exponents", "3"), "from 1 to 2"),
                       (("pendulum", "--tau", "0"), "--tau"),
                       (("pendulum", "--transient", "20"), "less than the span"),
                       (("pendulum", "--output", "l.csv"), ".json"),
                       ((os.path.join(EX, "mackey_glass.ode"),), "delay")):
        p = run(*args, status=2)
        check(word in p.stderr, f"refused: {' '.join(args)} ({p.stderr.strip()[:70]})")

    CHECKS.help_examples(SOURCE)
    return CHECKS.finish()


if __name__ == "__main__":
    sys.exit(main())
