#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dynkit against sympy.physics.mechanics on the same pendulums of N point masses on
massless rods (absolute angles from the downward vertical, as
examples/mechanisms/double_pendulum.mech, which is the case N = 2):

- time to derive: dynkit's text to C (bench_mech --file), then compiling it with the system
  compiler and with libtcc, against SymPy's KanesMethod (kanes_equations) and lambdify of
  its full mass matrix and forcing vector (to NumPy);
- time of one evaluation of the derived right-hand side: dynkit's compiled C against SymPy's
  lambdified M and F with numpy.linalg.solve;
- the trajectories: dynkit run (dop853, rtol = atol = 1e-12) against SciPy's DOP853 on
  SymPy's equations at the same tolerances over 1 s: the largest difference of the states at
  the end must be under 1e-8 (exit status 1 otherwise).

All times are CPU seconds (the compiler's included), so a loaded machine changes them little.

Usage: bench_mech_sympy.py BENCH_MECH DYNKIT [--links N,...] [--check]
  BENCH_MECH  the bench_mech program (build-bench/bench/bench_mech)
  DYNKIT      the dynkit program
  --links     the pendulums (default 2,20)
  --check     only the trajectories (a test: seconds)
Exit status 77 when SymPy, NumPy or SciPy is missing."""
import os
import subprocess
import sys
import tempfile
import time

try:
    import numpy as np
    import sympy as sp
    import sympy.physics.mechanics as me
    from scipy.integrate import solve_ivp
except ImportError:
    print("SKIP: SymPy, NumPy or SciPy is missing")
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
T_END = 1.0


def mech_text(n):
    """the pendulum of n links as a mechanism file (double_pendulum.mech for n = 2)"""
    if n == 2:
        with open(os.path.join(HERE, "..", "examples", "mechanisms", "double_pendulum.mech")) as f:
            return f.read()
    lines = ["# a pendulum of %d point masses on massless rods, absolute angles" % n]
    lines.append("coord " + ", ".join("phi%d=%s [rad]" % (i, "90deg" if i == 1 else "0")
                                     for i in range(1, n + 1)))
    lines.append("par " + ", ".join("m%d=1 [kg], l%d=1 [m]" % (i, i) for i in range(1, n + 1))
                 + ", g=9.81 [m/s^2]")
    lines.append("gravity 0, -g, 0")
    x, y = [], []
    for i in range(1, n + 1):
        x.append("l%d*sin(phi%d)" % (i, i))
        y.append("l%d*cos(phi%d)" % (i, i))
        lines.append("point bob%d mass=m%d at (%s, -(%s), 0)" % (i, i, " + ".join(x),
                                                                  " + ".join(y)))
    return "\n".join(lines) + "\n"


def kane(n):
    """SymPy's equations of the same pendulum: (CPU seconds to derive, to lambdify, the
    right-hand side f(y))"""
    t0 = time.process_time()
    q = me.dynamicsymbols("q1:%d" % (n + 1))
    u = me.dynamicsymbols("u1:%d" % (n + 1))
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    P, parts, loads = O, [], []
    for i in range(n):
        Pi = P.locatenew("P%d" % i, sp.sin(q[i]) * N.x - sp.cos(q[i]) * N.y)  # l = 1
        Pi.set_vel(N, Pi.pos_from(O).dt(N).subs({a.diff(): b for a, b in zip(q, u)}))
        parts.append(me.Particle("b%d" % i, Pi, 1))  # m = 1
        loads.append((Pi, -9.81 * N.y))
        P = Pi
    km = me.KanesMethod(N, q_ind=q, u_ind=u, kd_eqs=[a.diff() - b for a, b in zip(q, u)])
    km.kanes_equations(parts, loads)
    M, F = km.mass_matrix_full, km.forcing_full
    t1 = time.process_time()
    Mf = sp.lambdify([q + u], M, "numpy")
    Ff = sp.lambdify([q + u], F, "numpy")
    t2 = time.process_time()

    def rhs(t, y):
        return np.linalg.solve(Mf(y), Ff(y).ravel())
    return t1 - t0, t2 - t1, rhs


def dynkit_final(dynkit, path, n):
    out = subprocess.run([dynkit, "run", path, "--method", "dop853", "--rtol", "1e-12",
                          "--atol", "1e-12", "--tspan", "0:%g" % T_END, "--step", str(T_END)],
                         check=True, capture_output=True, text=True).stdout.splitlines()
    head, last = out[0].split(","), [float(v) for v in out[-1].split(",")]
    assert len(head) == 2 * n + 1 and abs(last[0] - T_END) < 1e-12, out[-1]
    return np.array(last[1:])


def main():
    args = sys.argv[1:]
    if len(args) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    bench, dynkit = args[0], args[1]
    links, check_only = [2, 20], False
    i = 2
    while i < len(args):
        if args[i] == "--links" and i + 1 < len(args):
            links = [int(v) for v in args[i + 1].split(",")]
            i += 2
        elif args[i] == "--check":
            check_only = True
            i += 1
        else:
            print("unknown argument %s" % args[i], file=sys.stderr)
            return 2
    failed = False
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, DYNKIT_CACHE_DIR=os.path.join(tmp, "cache"))
        os.environ["DYNKIT_CACHE_DIR"] = env["DYNKIT_CACHE_DIR"]
        for n in links:
            path = os.path.join(tmp, "pendulum%d.mech" % n)
            with open(path, "w") as f:
                f.write(mech_text(n))
            derive_s, lambdify_s, rhs = kane(n)
            y0 = np.zeros(2 * n)
            y0[0] = np.pi / 2
            sol = solve_ivp(rhs, (0, T_END), y0, method="DOP853", rtol=1e-12, atol=1e-12)
            diff = float(np.max(np.abs(sol.y[:, -1] - dynkit_final(dynkit, path, n))))
            ok = diff < 1e-8
            failed |= not ok
            print("%s %d links: the states at t = %g s agree within %.2g (dynkit dop853 and "
                  "SciPy DOP853 on SymPy's equations, rtol = atol = 1e-12)"
                  % ("ok    " if ok else "FAILED", n, T_END, diff))
            if check_only:
                continue
            calls = 2000 if n < 10 else 300
            t0 = time.process_time()
            for _ in range(calls):
                rhs(0.0, y0)
            sympy_rhs = (time.process_time() - t0) / calls
            out = subprocess.run([bench, "--file", path], check=True, capture_output=True,
                                 text=True, env=env).stdout.split()
            val = {out[k]: float(out[k + 1]) for k in range(1, len(out) - 1, 2)}
            rows.append((n, derive_s, lambdify_s, sympy_rhs, val))
    if rows:
        print()
        print("| links | SymPy KanesMethod [s] | + lambdify [s] | dynkit derive [s] | "
              "+ cc [s] | + libtcc [s] | C [kB] |")
        print("|---|---|---|---|---|---|---|")
        for n, d, l, _, v in rows:
            print("| %d | %.2f | %.2f | %.3f | %.2f | %.3f | %.0f |"
                  % (n, d, l, v["derive"], v["compile_cc"], v["compile_tcc"], v["bytes"] / 1e3))
        print()
        print("| links | SymPy lambdified M, F + numpy.linalg.solve [us] | dynkit, cc [us] | "
              "dynkit, libtcc [us] | SymPy / dynkit cc |")
        print("|---|---|---|---|---|")
        for n, _, _, s, v in rows:
            print("| %d | %.1f | %.3f | %.3f | %.0f |"
                  % (n, 1e6 * s, v["rhs_cc"] / 1e3, v["rhs_tcc"] / 1e3, 1e9 * s / v["rhs_cc"]))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
