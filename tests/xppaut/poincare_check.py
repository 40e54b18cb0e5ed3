#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Poincaré maps as XPPAUT writes them (docs/model-files.md, "Poincaré maps").

1. The harmonic oscillator (tests/xppaut/poincare/oscillator.ode, x = cos t): its maxima are at
   t = 2 pi k with x = 1, its minima at pi + 2 pi k with x = -1, the section x = 0 rising at
   3 pi / 2 + 2 pi k with v = 1, the period of that section 2 pi; dynkit (dp45, rtol 1e-12)
   within 1e-9 of each. --section on the command line gives the file's rows; poistop=1 (and
   :stop) the first row only; every crossing of a state lies on its section (1e-12).
2. Duffing's stroboscope (a section in t) and Roessler's section x = 0, each with the poimap
   variants (poisgn 1, -1, 0; max, min, both; period): dynkit and XPPAUT (`xppaut -silent`,
   both RK4 at the file's dt = 0.01) write the same number of rows, the states within
   10 dt^2 max(1, |value|) (XPPAUT interpolates them linearly inside its step) and the times
   too, except poimap=period: XPPAUT writes the time between the ends of the steps that
   cross (a multiple of dt), dynkit between the crossings: within dt + 10 dt^2.

Exit status 0 when all agree, 1 when not. What differs is kept in
build/tests/artifacts/poincare/ (the argument after the dynkit path).
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
FILES = os.path.join(HERE, "poincare")

VARIANTS = {
    "duffing.ode": ["section,poivar=t,poipln=6.283185307179586",
                    "section,poivar=x,poipln=1,poisgn=1",
                    "section,poivar=x,poipln=1,poisgn=-1",
                    "section,poivar=x,poipln=1,poisgn=0",
                    "max,poivar=x,poisgn=1", "max,poivar=x,poisgn=-1", "max,poivar=v,poisgn=0",
                    "period,poivar=x,poipln=1,poisgn=1"],
    "rossler.ode": ["section,poivar=x,poipln=1,poisgn=1",
                    "section,poivar=y,poipln=-2,poisgn=-1",
                    "max,poivar=z,poisgn=1", "period,poivar=x,poipln=1,poisgn=1"],
}


def table(text):
    lines = text.splitlines()[1:]
    return np.loadtxt(lines, delimiter=",", ndmin=2) if lines else np.zeros((0, 1))


def dynkit_run(dynkit, path, *args):
    p = subprocess.run([dynkit, "run", path] + list(args), capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("dynkit run %s %s failed: %s" % (path, " ".join(args), p.stderr))
    return table(p.stdout)


def xppaut_run(path, tmp):
    out = os.path.join(tmp, "out.dat")
    if os.path.exists(out):
        os.unlink(out)
    subprocess.run(["xppaut", path, "-silent", "-outfile", out], cwd=tmp, capture_output=True,
                   timeout=120)
    return np.loadtxt(out, ndmin=2) if os.path.exists(out) else None


def check_oscillator(dynkit):
    path = os.path.join(FILES, "oscillator.ode")
    tight = ["--rtol", "1e-12", "--atol", "1e-12"]
    ok = True
    k = np.arange(1, 7)
    cases = [("max:x", 2 * math.pi * k, 1, 1.0), ("min:x", math.pi + 2 * math.pi * (k - 1), 1, -1.0),
             ("x=0:+", 1.5 * math.pi + 2 * math.pi * (k - 1), 2, 1.0)]
    for spec, times, col, value in cases:
        rows = dynkit_run(dynkit, path, "--section", spec, *tight)
        n = len(times)
        e = max(float(np.max(np.abs(rows[:n, 0] - times))),
                float(np.max(np.abs(rows[:n, col] - value))))
        print("oscillator --section %-6s %2d rows (expected %d), within %.1e of the closed form"
              % (spec, len(rows), int(40 / (2 * math.pi)) + (spec == "max:x" and 0), e))
        ok = ok and e < 1e-9 and len(rows) >= n
    per = dynkit_run(dynkit, path, "--section", "period:x=0", *tight)
    e = float(np.max(np.abs(per[:, 0] - 2 * math.pi)))
    print("oscillator --section period:x=0: %d periods within %.1e of 2 pi" % (len(per), e))
    ok = ok and e < 1e-9 and len(per) >= 5
    # the file's own poimap=max, and --section max:x, give the same rows
    a = dynkit_run(dynkit, path, *tight)
    b = dynkit_run(dynkit, path, "--section", "max:x", *tight)
    same = a.shape == b.shape and np.array_equal(a, b)
    stop = dynkit_run(dynkit, path, "--section", "max:x:stop", *tight)
    print("oscillator: the file's poimap=max %s --section max:x; :stop writes %d row%s"
          % ("equals" if same else "DIFFERS FROM", len(stop), "" if len(stop) == 1 else "s"))
    ok = ok and same and len(stop) == 1 and np.array_equal(stop[0], a[0])
    whole = dynkit_run(dynkit, path, "--section", "none", "--step", "0.5")
    print("oscillator --section none: the time series (%d rows)" % len(whole))
    return ok and len(whole) == 81


def compare(name, spec, dyn, xpp, dt, artifacts):
    period = spec.startswith("period")
    tol = 10 * dt * dt
    if len(dyn) != len(xpp):
        bad = "%d rows, XPPAUT %d" % (len(dyn), len(xpp))
    else:
        scale = np.maximum(1.0, np.abs(xpp))
        d = np.abs(dyn - xpp) / scale
        dt_err = float(np.max(d[:, 0])) if len(d) else 0.0
        dx_err = float(np.max(d[:, 1:])) if len(d) else 0.0
        bad = None
        if dx_err > tol or dt_err > (dt + tol if period else tol):
            bad = "states within %.1e, times within %.1e" % (dx_err, dt_err)
        print("%-12s %-42s %3d rows; states within %.1e, times within %.1e%s"
              % (name, spec, len(dyn), dx_err, dt_err, " (XPPAUT: step ends)" if period else ""))
    if bad:
        print("%-12s %-42s DIFFERS: %s" % (name, spec, bad))
        os.makedirs(artifacts, exist_ok=True)
        stem = os.path.join(artifacts, "%s-%s" % (name, spec.replace(",", "_").replace("=", "")))
        np.savetxt(stem + ".dynkit.txt", dyn)
        np.savetxt(stem + ".xppaut.txt", xpp)
        return False
    return True


def check_against_xppaut(dynkit, artifacts):
    if not shutil.which("xppaut"):
        print("xppaut is not installed: the comparison with XPPAUT is skipped")
        return True
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        for name, specs in VARIANTS.items():
            with open(os.path.join(FILES, name)) as f:
                text = f.read()
            for spec in specs:
                lines = [("@ poimap=" + spec) if l.startswith("@ poimap") else l
                         for l in text.splitlines()]
                path = os.path.join(tmp, name)
                with open(path, "w") as f:
                    f.write("\n".join(lines) + "\n")
                dyn = dynkit_run(dynkit, path)
                xpp = xppaut_run(path, tmp)
                if xpp is None:
                    print("%s %s: XPPAUT wrote nothing" % (name, spec))
                    ok = False
                    continue
                ok = compare(name, spec, dyn, xpp, 0.01, artifacts) and ok
                # a state's crossings lie on its section (located on the dense output)
                opts = dict(kv.split("=") for kv in spec.split(",")[1:])
                var = opts.get("poivar")
                if spec.startswith("section") and var != "t":
                    names = [l.split("'")[0] for l in text.splitlines() if "'=" in l]
                    col = 1 + names.index(var)
                    off = float(np.max(np.abs(dyn[:, col] - float(opts["poipln"]))))
                    if off > 1e-12 * max(1.0, float(np.max(np.abs(dyn[:, col])))):
                        print("%s %s: a crossing lies %.1e off its section" % (name, spec, off))
                        ok = False
    return ok


def main():
    dynkit = sys.argv[1] if len(sys.argv) > 1 else "dynkit"
    artifacts = sys.argv[2] if len(sys.argv) > 2 else os.path.join(tempfile.gettempdir(),
                                                                    "poincare-artifacts")
    ok = check_oscillator(dynkit)
    ok = check_against_xppaut(dynkit, artifacts) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
