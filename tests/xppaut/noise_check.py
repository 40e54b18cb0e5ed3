#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Noise read as XPPAUT reads it (docs/model-files.md, "Noise"), checked on the files of
tests/xppaut/noise/ against XPPAUT itself (when installed) and the closed forms, by
statistics (the two programs draw other random numbers):

- em_ou.ode: y' = w has increments of variance dt (w = z/sqrt(dt)), and x' = -x + 0.5 w by
  Euler (Euler-Maruyama) has the stationary variance of the scheme, s^2 / (2 th - th^2 dt);
- draws.ode: normal(1, 2) has mean 1 and standard deviation 2, ran(3) is uniform on [0, 3);
- tables.ode: tables of ran(3) and normal(1, 2), computed once (2001 points each, every one
  a draw of its own), have the same statistics; in dynkit --seed fixes them (the same table
  twice with one seed, another with another seed).

Each statistic must be within 6 of its standard errors of the closed form, for dynkit and for
XPPAUT. Usage: noise_check.py DYNKIT
"""
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compat  # noqa: E402  (same directory: keep_artifacts)

HERE = os.path.dirname(os.path.abspath(__file__))


def run_dynkit(dynkit, path, work, seed=5):
    out = os.path.join(work, "dynkit-%s-seed%d.csv" % (os.path.basename(path), seed))
    subprocess.run([dynkit, "run", path, "--seed", str(seed), "--quiet", "--outputs",
                    "--output", out], check=True, cwd=work,
                   env=dict(os.environ, DYNKIT_CACHE_DIR=os.path.join(work, "cache")))
    return np.loadtxt(out, delimiter=",", skiprows=1)


def run_xppaut(path, work):
    xdir = os.path.join(work, "x-" + os.path.basename(path))
    os.makedirs(xdir, exist_ok=True)
    shutil.copy(path, xdir)
    subprocess.run(["xppaut", os.path.basename(path), "-silent"], cwd=xdir, timeout=300,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return np.loadtxt(os.path.join(xdir, "output.dat"))


def check(name, value, want, se, failures):
    ok = abs(value - want) <= 6 * se
    print("%s %-44s %.5f (closed form %.5f, 6 standard errors %.5f)"
          % ("ok  " if ok else "FAIL", name, value, want, 6 * se))
    if not ok:
        failures.append(name)


def em_ou(d, who, failures):
    dt, th, s = 0.01, 1.0, 0.5
    t, x, y = d[:, 0], d[:, 1], d[:, 2]
    assert abs(t[1] - t[0] - dt) < 1e-9 and abs(t[-1] - 2000) < 1e-6, "%s: the grid" % who
    inc = np.diff(y) / np.sqrt(dt)
    n = len(inc)
    check(who + ": Var(dW) / dt", inc.var(), 1.0, np.sqrt(2.0 / n), failures)
    # stationary after t = 10; samples correlated over 1/th: about th T independent ones
    xs = x[t >= 10]
    var = s * s / (2 * th - th * th * dt)
    check(who + ": Var(x), stationary", xs.var(), var, var * np.sqrt(2.0 / (th * 1990)),
          failures)


def draws(d, who, failures):
    z, u = d[1:, 1], d[1:, 2]
    n = len(z)
    check(who + ": mean of normal(1,2)", z.mean(), 1.0, 2.0 / np.sqrt(n), failures)
    check(who + ": standard deviation of normal(1,2)", z.std(), 2.0, 2.0 / np.sqrt(2 * n),
          failures)
    check(who + ": mean of ran(3)", u.mean(), 1.5, 3.0 / np.sqrt(12 * n), failures)
    if not (u.min() >= 0 and u.max() < 3):
        failures.append(who + ": ran(3) outside [0, 3)")


def tables(d, who, failures):
    """Columns t, x, u(t), z(t): one point of each table per row."""
    u, z = d[:, 2], d[:, 3]
    n = len(u)
    check(who + ": mean of a table of ran(3)", u.mean(), 1.5, 3.0 / np.sqrt(12 * n), failures)
    check(who + ": mean of a table of normal(1,2)", z.mean(), 1.0, 2.0 / np.sqrt(n), failures)
    check(who + ": standard deviation of a table of normal(1,2)", z.std(), 2.0,
          2.0 / np.sqrt(2 * n), failures)
    if not (u.min() >= 0 and u.max() < 3 and len(set(u)) == n):
        failures.append(who + ": a table of ran(3): not n distinct numbers in [0, 3)")


def main():
    dynkit = os.path.abspath(sys.argv[1])
    failures = []
    have_xpp = shutil.which("xppaut") is not None
    with tempfile.TemporaryDirectory() as work:
        for name, fn in (("em_ou.ode", em_ou), ("draws.ode", draws), ("tables.ode", tables)):
            path = os.path.join(HERE, "noise", name)
            fn(run_dynkit(dynkit, path, work), "dynkit " + name, failures)
            if have_xpp:
                fn(run_xppaut(path, work), "xppaut " + name, failures)
        path = os.path.join(HERE, "noise", "tables.ode")
        a, b, c = (run_dynkit(dynkit, path, work, s) for s in (5, 5, 6))
        if not np.array_equal(a, b) or np.array_equal(a[:, 2:], c[:, 2:]):
            failures.append("dynkit tables.ode: the seed does not fix the tables")
        else:
            print("ok   dynkit tables.ode: the same tables with --seed 5 twice, others with 6")
        if failures:
            print("inputs and outputs kept in %s" % compat.keep_artifacts(
                dynkit, "xppaut-noise", [work, os.path.join(HERE, "noise")]))
    if not have_xpp:
        print("xppaut is not installed: dynkit against the closed forms only")
    print("%d failed" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
