#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dynkit linearize against closed forms and NumPy: the pendulum at the bottom (+-i
sqrt(g/l), marginal) and the top (+-sqrt(g/l), unstable); van der Pol at the origin
(mu/2 +- i sqrt(1 - mu^2/4) for mu < 2, two real roots above, unstable); Lorenz
(examples/models/lorenz.ode) at the origin (-beta and the roots of
l^2 + (sigma+1) l + sigma (1-rho)) and at C+- (the roots of l^3 + (sigma+beta+1) l^2 +
beta (sigma+rho) l + 2 sigma beta (rho-1): unstable at rho = 28, stable at rho = 20, below
the Hopf value sigma (sigma+beta+3)/(sigma-beta-1) = 24.74); a linear model file x' = A x
against numpy.linalg.eigvals; the differences against the model file's analytic Jacobian;
the --vary table (N*n rows, columns NAME,re,im), --matrix and --json; bad input refused
with exit status 2; every command docs/analysis.md shows runs. Exit 0 when all hold, 1 when not, 77 (skipped) without NumPy or when
dynkit is built without LAPACK.
"""
import csv
import io
import json
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

try:
    import numpy as np
except ImportError:
    print("SKIP: NumPy is missing (python3-numpy)")
    sys.exit(77)

DYNKIT = sys.argv[1] if len(sys.argv) > 1 else "dynkit"
SOURCE = sys.argv[2] if len(sys.argv) > 2 else "."
LORENZ = os.path.join(SOURCE, "examples", "models", "lorenz.ode")
FAILED = []


def run(*args, status=0):
    p = subprocess.run([DYNKIT, "linearize", *args], capture_output=True, text=True)
    if p.returncode != status:
        FAILED.append(f"linearize {' '.join(args)}: exit {p.returncode}, expected {status}:"
                      f" {p.stderr.strip()}")
    return p


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        FAILED.append(what)


def eig(*args):
    """The first point of --json: (eigenvalues as complex numbers, the point)."""
    p = run(*args, "--json")
    doc = json.loads(p.stdout)
    pt = doc["points"][0]
    return np.array(pt["re"]) + 1j * np.array(pt["im"]), pt


def close(got, want, tol):
    """Sorted like dynkit (by im, then re), then compared."""
    want = sorted(want, key=lambda z: (z.imag, z.real))
    return len(got) == len(want) and max(abs(a - b) for a, b in zip(got, want)) <= tol


def main():
    p = subprocess.run([DYNKIT, "linearize", "pendulum", "--json"], capture_output=True,
                       text=True)
    if "need LAPACK" in p.stderr:
        print("SKIP: dynkit is built without LAPACK (liblapack-dev)")
        return 77
    g, l = 9.81, 2.0
    w = math.sqrt(g / l)
    ev, pt = eig("pendulum", "--set", "l=2", "--init", "phi=0", "--init", "dphi=0")
    check(close(ev, [1j * w, -1j * w], 1e-12 * w) and pt["stability"] == "marginal",
          f"pendulum at the bottom: +-i sqrt(g/l) = +-{w:.6f}i, marginal ({ev})")
    ev, pt = eig("pendulum", "--set", "l=2", "--init", "phi=pi", "--init", "dphi=0")
    check(close(ev, [w, -w], 1e-12 * w) and pt["stability"] == "unstable",
          f"pendulum at the top: +-sqrt(g/l), unstable ({ev})")

    # van der Pol at the origin over mu: one block per value, N*n rows
    mus = [0.5, 1.0, 1.5, 2.5, 4.0]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "vdp.csv")
        run("vanderpol", "--init", "y1=0", "--init", "y2=0", "--vary",
            "mu=" + ",".join(map(str, mus)), "--output", out)
        with open(out) as f:
            rows = list(csv.reader(f))
    check(rows[0] == ["mu", "re", "im"], f"--vary table header mu,re,im ({rows[0]})")
    check(len(rows) - 1 == 2 * len(mus), f"--vary table: N*n = {2 * len(mus)} rows")
    for mu in mus:
        got = [complex(float(r[1]), float(r[2])) for r in rows[1:] if float(r[0]) == mu]
        d = complex(mu * mu / 4 - 1) ** 0.5
        check(close(got, [mu / 2 + d, mu / 2 - d], 1e-13),
              f"van der Pol at the origin, mu = {mu}: mu/2 +- sqrt(mu^2/4 - 1)")
    p = run("vanderpol", "--init", "y1=0", "--output", "-")
    check(p.stdout.splitlines()[0] == "re,im" and len(p.stdout.splitlines()) == 3,
          "--output -: the table re,im on standard output")
    p = run("vanderpol", "--init", "y1=0", "--init", "y2=0", "--vary", "mu=0.5:3:6")
    check(p.stdout.count("stability: unstable") == 6, "van der Pol's origin is unstable for mu > 0")

    # Lorenz at the origin and at C+-
    sigma, rho, beta = 10.0, 28.0, 2.6666666666666665
    ev, pt = eig(LORENZ, "--init", "x=0", "--init", "y=0", "--init", "z=0")
    want = list(np.roots([1, sigma + 1, sigma * (1 - rho)])) + [-beta]
    check(close(ev, want, 1e-12 * 30) and pt["jacobian"] == "analytic",
          f"Lorenz at the origin: -beta and the roots of the quadratic ({ev})")
    for r, stab in ((28.0, "unstable"), (20.0, "asymptotically stable")):
        for sign in (1, -1):
            c = sign * math.sqrt(beta * (r - 1))
            args = (LORENZ, "--set", f"rho={r!r}", "--init", f"x={c!r}", "--init",
                    f"y={c!r}", "--init", f"z={r - 1!r}")
            ev, pt = eig(*args)
            want = np.roots([1, sigma + beta + 1, beta * (sigma + r), 2 * sigma * beta * (r - 1)])
            check(close(ev, want, 1e-11 * 30) and pt["stability"] == stab
                  and max(abs(v) for v in pt["f"]) < 1e-12,
                  f"Lorenz at C{'+' if sign > 0 else '-'}, rho = {r}: the cubic's roots, {stab}")
            _, pd = eig(*args, "--jacobian", "richardson")
            A, D = np.array(pt["A"]), np.array(pd["A"])
            rel = np.max(np.abs(A - D)) / np.max(np.abs(A))
            check(pd["jacobian"] == "richardson" and rel < 1e-12,
                  f"Lorenz at C+-: differences within {rel:.1e} of the analytic Jacobian")

    # --equilibrium: C+ found from a guess, followed along rho across the Hopf value 24.74
    rhos = [20.0, 24.5, 25.0, 28.0]
    doc = json.loads(run(LORENZ, "--equilibrium", "--init", "x=8", "--init", "y=8", "--init",
                         "z=25", "--vary", "rho=" + ",".join(map(repr, rhos)), "--json").stdout)
    for r, q in zip(rhos, doc["points"]):
        c = math.sqrt(beta * (r - 1))
        err = max(abs(q["y"][0] - c), abs(q["y"][1] - c), abs(q["y"][2] - (r - 1)))
        stab = "asymptotically stable" if r < 24.74 else "unstable"
        check(err < 1e-12 * 30 and q["stability"] == stab and q["equilibrium"]["iterations"] <= 6,
              f"--equilibrium, rho = {r}: C+ to {err:.1e}, {stab}")
    # van der Pol with omega = 6.6 from (2, 0): Levenberg-Marquardt follows a valley of |f|
    # towards x = infinity; the Gauss-Newton steps from the guess find the origin, whose
    # eigenvalues are omega (mu/2 +- i sqrt(1 - mu^2/4)) = 3.3 +- 5.7158i
    vdp = os.path.join(SOURCE, "examples", "models", "vdp_bvp.ode")
    p = run(vdp, "--equilibrium", "--json")
    pt = json.loads(p.stdout)["points"][0] if p.returncode == 0 else {"y": [1], "re": [], "im": []}
    ev = [complex(a, b) for a, b in zip(pt["re"], pt["im"])]
    w = 6.6 * math.sqrt(0.75)
    check(max(abs(v) for v in pt["y"]) < 1e-12 and close(ev, [3.3 + 1j * w, 3.3 - 1j * w], 1e-12 * 30),
          f"--equilibrium, van der Pol (omega 6.6) from (2, 0): the origin ({pt['y']}), {ev}")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "push.ode")
        with open(path, "w") as f:
            f.write("# pushed harder the further it goes: no equilibrium\ninit x=0.5\n"
                    "x'=1+x^2\ndone\n")
        p = run(path, "--equilibrium", status=1)
        check("no step lowers |f|" in p.stderr and "|f|_inf = 1" in p.stderr,
              f"--equilibrium without one: refused with the residual ({p.stderr.strip()[:90]})")

    # a mechanism file (examples/mechanisms/double_pendulum.mech, m = l = 1) hanging at rest:
    # the two modes of the double pendulum, omega^2 = (g/l) (2 -+ sqrt 2)
    mech = os.path.join(SOURCE, "examples", "mechanisms", "double_pendulum.mech")
    if os.path.exists(mech):
        ev, pt = eig(mech, "--init", "phi1=0", "--init", "phi2=0")
        w = [math.sqrt(9.81 * (2 - math.sqrt(2))), math.sqrt(9.81 * (2 + math.sqrt(2)))]
        check(close(ev, [1j * w[0], -1j * w[0], 1j * w[1], -1j * w[1]], 1e-12 * w[1])
              and pt["stability"] == "marginal",
              f"double_pendulum.mech at rest: +-i sqrt(g (2 -+ sqrt 2) / l) ({ev.imag})")
        # --equilibrium finds the equilibrium near the guess: hanging from (30, -20) deg,
        # both rods upright from (170, 160) deg, there +-sqrt(g (2 -+ sqrt 2) / l), unstable
        ev, pt = eig(mech, "--init", "phi1=30deg", "--init", "phi2=-20deg", "--equilibrium")
        check(max(abs(v) for v in pt["y"]) < 1e-12 and pt["stability"] == "marginal",
              f"double_pendulum.mech --equilibrium from (30, -20) deg: hanging ({pt['y']})")
        ev, pt = eig(mech, "--init", "phi1=170deg", "--init", "phi2=160deg", "--equilibrium")
        up = max(abs(pt["y"][0] - math.pi), abs(pt["y"][1] - math.pi))
        check(up < 1e-12 and close(ev, [w[0], -w[0], w[1], -w[1]], 1e-12 * w[1])
              and pt["stability"] == "unstable",
              f"double_pendulum.mech --equilibrium from (170, 160) deg: upright to {up:.1e}")

    # the heavy top of examples/mechanisms/: precession and spin angles are ignorable (they
    # enter the derived f only through terms that cancel): their eigenvalues exactly 0
    top = os.path.join(SOURCE, "examples", "mechanisms", "top.mech")
    if os.path.exists(top):
        ev, pt = eig(top)
        A = np.array(pt["A"])
        check(pt["jacobian"] == "richardson" and not A[:, 0].any() and not A[:, 2].any()
              and sum(1 for v in ev if v == 0) >= 2 and pt["stability"] == "marginal",
              f"top.mech: psi and phi columns exactly 0, eigenvalues exactly 0 ({ev})")

    # mechanisms with constraints: the eigenvalues of A_min on the admissible directions are
    # among NumPy's eigenvalues of the full A (which adds Baumgarte's and the violations')
    for name, extra, k in (("cartesian_pendulum.mech", (), 2),
                           ("rolling_disk.mech", ("--set", "W=3.4"), 8)):
        path = os.path.join(SOURCE, "examples", "mechanisms", name)
        if not os.path.exists(path):
            continue
        ev, pt = eig(path, *extra)
        full = np.linalg.eigvals(np.array(pt["A"]))
        scale = np.abs(np.array(pt["A"])).sum(axis=1).max()
        check(len(ev) == k == len(pt["kept"]) and len(pt["A"]) > k
              and all(min(abs(full - v)) < 1e-6 * scale for v in ev),
              f"{name}: {k} eigenvalues of A_min among those of A ({ev}, {full})")

    # the extension in capitals is a mechanism file too (as for run): reduced the same way
    path = os.path.join(SOURCE, "examples", "mechanisms", "cartesian_pendulum.mech")
    with tempfile.TemporaryDirectory() as tmp:
        upper = os.path.join(tmp, "CP.MECH")
        shutil.copy(path, upper)
        ev, pt = eig(upper)
        check(len(ev) == 2 == len(pt["kept"]),
              f"CP.MECH: reduced to the 2 states of cartesian_pendulum.mech ({ev})")

    # a linear model file x' = A x against NumPy
    A = np.array([[-0.5, 2.0, 0.0, 1.0, 0.3],
                  [-3.0, -0.1, 0.7, 0.0, 0.0],
                  [0.2, 0.0, 0.4, -5.0, 1.0],
                  [0.0, 1.5, 4.0, -0.2, 0.0],
                  [1.0, 0.0, 0.0, 0.5, -2.0]])
    n = len(A)
    names = [f"x{i + 1}" for i in range(n)]
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "linear5.ode")
        with open(path, "w") as f:
            f.write("# x' = A x\n")
            for i in range(n):
                terms = "+".join(f"({A[i, j]!r})*{names[j]}" for j in range(n))
                f.write(f"{names[i]}'={terms}\n")
            f.write("done\n")
        ev, pt = eig(path)
        want = np.linalg.eigvals(A)
        check(close(ev, list(want), 1e-12 * np.abs(A).sum(axis=1).max()),
              f"linear model file: numpy.linalg.eigvals ({want})")
        m = run(path, "--matrix").stdout
        rows = list(csv.reader(io.StringIO(m)))
        got = np.array([[float(v) for v in r[1:]] for r in rows[1:]])
        check(rows[0] == ["state"] + names and [r[0] for r in rows[1:]] == names
              and np.array_equal(got, A), "--matrix: A exactly, rows and columns named")
        p = run(path, "--vary", "x1=0:1:3", "--json")
        doc = json.loads(p.stdout)
        check(doc["vary"] == "x1" and len(doc["points"]) == 3
              and [q["x1"] for q in doc["points"]] == [0, 0.5, 1],
              "--json with --vary: one point per value")

    # an ignorable coordinate (x does not appear in f): its eigenvalue is exactly zero
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "slide.ode")
        with open(path, "w") as f:
            f.write("# a block sliding with viscous friction\npar c=0.7\ninit x=3, v=2\n"
                    "x'=v\nv'=-c*v\ndone\n")
        for scheme in ("analytic", "richardson"):
            ev, pt = eig(path, "--jacobian", scheme)
            check(ev[1] == 0 and abs(ev[0] + 0.7) < 1e-14 and pt["stability"] == "marginal",
                  f"ignorable coordinate ({scheme}): eigenvalues exactly 0, and -c, marginal")

    # a state varied: the pendulum from the bottom to the top
    p = run("pendulum", "--init", "dphi=0", "--vary", "phi=0:pi:5", "--output", "-",
            "--matrix")
    check(len(p.stdout.strip().split("\n")) == 1 + 5 * 2, "--matrix with --vary: n rows per value")

    # bad input: exit status 2 with the reason
    for args, word in ((("pendulum", "--bogus"), "unknown option"),
                       (("pendulum", "--vary", "q=1:2:3"), "neither a parameter"),
                       (("pendulum", "--vary", "l=1:2"), "A:B:N"),
                       (("pendulum", "--jacobian", "analytic"), "no analytic Jacobian"),
                       (("pendulum", "--jacobian", "exact"), "accepted: auto"),
                       (("pendulum", "--matrix", "--json"), "one of them"),
                       (("pendulum", "--output", "eig.txt"), ".csv"),
                       (("pendulum", "--t", "soon"), "--t")):
        p = run(*args, status=2)
        check(word in p.stderr, f"refused: {' '.join(args)} ({p.stderr.strip()[:70]})")

    # every command of docs/analysis.md and of the examples of --help, in a scratch
    # directory with examples/ and tests/ linked in
    with open(os.path.join(SOURCE, "docs", "analysis.md")) as f:
        doc = f.read()
    blocks = [b.replace("\\\n", " ") for b in re.findall(r"```sh\n(.*?)```", doc, re.S)]
    lines = [l.split("#")[0].strip() for b in blocks for l in b.splitlines()
             if l.startswith("dynkit ")]
    check(len(lines) >= 6, f"docs/analysis.md shows {len(lines)} commands")
    shown = run("--help").stdout.split("Examples:")[1]
    lines += [l.split("#")[0].strip() for l in shown.splitlines() if l.strip()]
    check(len(lines) >= 11, "--help shows five examples")
    with tempfile.TemporaryDirectory() as tmp:
        for sub in ("examples", "tests"):
            os.symlink(os.path.join(os.path.abspath(SOURCE), sub), os.path.join(tmp, sub))
        for line in lines:
            args = shlex.split(line)[1:]
            p = subprocess.run([os.path.abspath(DYNKIT), *args], capture_output=True, text=True,
                               cwd=tmp)
            check(p.returncode == 0, f"shown: {line} ({p.stderr.strip()[:60]})")

    for f in FAILED:
        print("FAILED:", f)
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
