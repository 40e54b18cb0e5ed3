#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The differential-algebraic examples of Debian's xppaut package (dae.ode, dae_ex1.ode,
dae_ex2.ode: one state x, one algebraic variable solved from a 0= equation) against an
independent reference: SciPy's DOP853 at rtol 1e-12 on x' = f(x, w(x)), with w(x) found by
Brent's method (brentq, to 1e-15) at every evaluation. Both dynkit's run of the file (its
defaults) and XPPAUT's (`xppaut FILE -silent`, when installed) are compared with it, state
and algebraic variable (through the file's aux output), at every sample.

dynkit must be within 1e-6 of the reference; XPPAUT's errors are printed beside (it solves
the algebraic equations only to its Newton tolerance). Exit status 0 when dynkit is, 1 when
not, 77 (skipped) without the examples or SciPy.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compat  # noqa: E402  (same directory: keep_artifacts)

try:
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq
except ImportError:
    print("SKIP: SciPy is missing (python3-scipy)")
    sys.exit(77)

EXAMPLES = "/usr/share/doc/xppaut/examples/ode"

# file: x0, t1, the derivative of x from (x, w), the residual of w
CASES = {
    "dae.ode": (3.0, 20.0, lambda x, w: w, lambda x, w: x + w + w**3 + w**5),
    "dae_ex1.ode": (1.0, 20.0, lambda x, w: -x, lambda x, w: x + w - 1.0),
    "dae_ex2.ode": (-3.7182, 20.0, lambda x, w: w, lambda x, w: w + np.exp(w) + x),
}


def solve_w(res, x):
    return brentq(lambda w: res(x, w), -50.0, 50.0, xtol=1e-15, rtol=1e-15)


def reference(case):
    x0, t1, dx, res = case
    sol = solve_ivp(lambda t, s: [dx(s[0], solve_w(res, s[0]))], [0.0, t1], [x0],
                    method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    return sol.sol


def errors(table, case, sol):
    """Largest error of x (column 1) and of w (column 2, the file's first aux output) against
    the reference."""
    t, x, w = table[:, 0], table[:, 1], table[:, 2]
    xr = sol(t)[0]
    wr = np.array([solve_w(case[3], v) for v in xr])
    return float(np.max(np.abs(x - xr))), float(np.max(np.abs(w - wr)))


def main():
    dynkit = sys.argv[1] if len(sys.argv) > 1 else "dynkit"
    if not os.path.isdir(EXAMPLES):
        print("SKIP: %s is missing (apt-get install xppaut)" % EXAMPLES)
        return 77
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for name, case in CASES.items():
            path = os.path.join(EXAMPLES, name)
            sol = reference(case)
            out = subprocess.run([dynkit, "run", path, "--outputs"], capture_output=True,
                                 text=True, check=True).stdout
            with open(os.path.join(tmp, name + ".dynkit.csv"), "w") as f:
                f.write(out)
            dyn = np.loadtxt(out.splitlines()[1:], delimiter=",", ndmin=2)
            ex, ew = errors(dyn, case, sol)
            worst = max(worst, ex, ew)
            line = "%-12s dynkit: error of x %.1e, of the algebraic variable %.1e" % (name, ex, ew)
            xpp = os.path.join(tmp, name + ".dat")
            try:
                subprocess.run(["xppaut", path, "-silent", "-outfile", xpp], cwd=tmp,
                               capture_output=True, timeout=60)
                if os.path.exists(xpp):
                    tx, tw = errors(np.loadtxt(xpp, ndmin=2), case, sol)
                    line += "; XPPAUT: %.1e, %.1e" % (tx, tw)
            except (OSError, subprocess.TimeoutExpired):
                pass
            print(line, flush=True)
        if worst > 1e-6:
            print("inputs and outputs kept in %s" % compat.keep_artifacts(
                dynkit, "xppaut-dae", [tmp] + [os.path.join(EXAMPLES, n) for n in CASES]))
    if worst > 1e-6:
        print("dynkit is %.1e from the reference (at most 1e-6 expected)" % worst)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
