#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dynkit derive against sympy.physics.mechanics: the mass matrix M and the forces F that
dynkit derives by TMT from examples/mechanisms/double_pendulum.mech and top.mech agree with
Lagrange's equations formed by SymPy (LagrangesMethod) for the same coordinates, at random
coordinates, speeds and parameters (relative difference under 1e-12).

Usage: sympy_check.py DYNKIT EXAMPLES_DIR   (exit 77 when SymPy is missing)
"""
import random
import re
import subprocess
import sys

try:
    import sympy as sp
    import sympy.physics.mechanics as me
except ImportError:
    print("SKIP: SymPy is missing (Debian: python3-sympy)")
    sys.exit(77)


def derived(dynkit, path, names):
    out = subprocess.run([dynkit, "derive", path], check=True, capture_output=True,
                         text=True).stdout
    M, F = {}, {}
    for line in out.splitlines():
        m = re.match(r"([MF])\[([^\]]+)\] = (.*)$", line)
        if m:
            # every name a plain symbol (SymPy reads I, E, N, S, ... as its own)
            expr = sp.sympify(m.group(3).replace("^", "**"),
                              locals={k: sp.Symbol(k) for k in names})
            (M if m.group(1) == "M" else F)[m.group(2)] = expr
    return M, F


def lagrange(L, qs, forces=None):
    lm = me.LagrangesMethod(L, qs)
    lm.form_lagranges_equations()
    return lm.mass_matrix, lm.forcing


def double_pendulum():
    phi1, phi2 = me.dynamicsymbols("phi1 phi2")
    m1, m2, l1, l2, g = sp.symbols("m1 m2 l1 l2 g")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    P1 = O.locatenew("P1", l1 * sp.sin(phi1) * N.x - l1 * sp.cos(phi1) * N.y)
    P2 = P1.locatenew("P2", l2 * sp.sin(phi2) * N.x - l2 * sp.cos(phi2) * N.y)
    P1.set_vel(N, P1.pos_from(O).dt(N))
    P2.set_vel(N, P2.pos_from(O).dt(N))
    b1, b2 = me.Particle("b1", P1, m1), me.Particle("b2", P2, m2)
    b1.potential_energy = m1 * g * P1.pos_from(O).dot(N.y)
    b2.potential_energy = m2 * g * P2.pos_from(O).dot(N.y)
    L = me.Lagrangian(N, b1, b2)
    return [phi1, phi2], ["phi1", "phi2"], lagrange(L, [phi1, phi2]), \
        {"m1": (0.1, 3), "m2": (0.1, 3), "l1": (0.2, 2), "l2": (0.2, 2), "g": (1, 20)}


def top():
    psi, theta, phi = me.dynamicsymbols("psi theta phi")
    m, Lc, A, C, g = sp.symbols("m L A C g")
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Body", [psi, theta, phi], "ZXZ")
    O = me.Point("O")
    O.set_vel(N, 0)
    G = O.locatenew("G", Lc * B.z)
    G.set_vel(N, G.pos_from(O).dt(N))
    body = me.RigidBody("top", G, B, m, (me.inertia(B, A, A, C), G))
    body.potential_energy = m * g * G.pos_from(O).dot(N.z)
    L = me.Lagrangian(N, body)
    return [psi, theta, phi], ["psi", "theta", "phi"], lagrange(L, [psi, theta, phi]), \
        {"m": (0.1, 3), "L": (0.05, 1), "A": (0.001, 0.1), "C": (0.001, 0.1), "g": (1, 20)}


def compare(dynkit, path, case, speeds):
    qs, names, (Ms, Fs), pars = case()
    Md, Fd = derived(dynkit, path, list(pars) + names + speeds)
    n = len(qs)
    # SymPy's q(t), q'(t) as plain symbols named as in the file
    qsym = {q: sp.Symbol(nm) for q, nm in zip(qs, names)}
    usym = {q.diff(): sp.Symbol(s) for q, s in zip(qs, speeds)}
    rnd = random.Random(7)
    worst = 0.0
    for trial in range(20):
        vals = {sp.Symbol(k): rnd.uniform(*r) for k, r in pars.items()}
        for nm in names + speeds:
            vals[sp.Symbol(nm)] = rnd.uniform(-3, 3)
        def num_sympy(e):
            return float(e.subs(usym).subs(qsym).subs(vals))
        def num_dynkit(e):
            return float(e.subs(vals))
        scale = 0.0
        diffs = []
        for i in range(n):
            for k in range(i + 1):
                a = num_dynkit(Md["%s,%s" % (names[i], names[k])])
                b = num_sympy(Ms[i, k])
                diffs.append(abs(a - b)); scale = max(scale, abs(b))
            a = num_dynkit(Fd[names[i]])
            b = num_sympy(Fs[i])
            diffs.append(abs(a - b)); scale = max(scale, abs(b))
        worst = max(worst, max(diffs) / scale)
    print("%s: largest relative difference to SymPy's Lagrange equations %.3g" % (path, worst))
    return worst < 1e-12


def main():
    dynkit, ex = sys.argv[1], sys.argv[2]
    ok = compare(dynkit, ex + "/double_pendulum.mech", double_pendulum, ["dphi1", "dphi2"])
    ok &= compare(dynkit, ex + "/top.mech", top, ["dpsi", "dtheta", "dphi"])
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
