#!/usr/bin/env python3
"""The Hopf curve of Lorenz-84 (tests/continuation/models/lorenz84.ode) in (g, f) through its
fold-Hopf point, where a real eigenvalue passes through zero while a pair stays on the
imaginary axis: the first Lyapunov coefficient has a pole there (its formula solves with
the Jacobian) and changes sign through it, which is no generalized Hopf point. dynkit
reports no GH on the curve, and ZH at the fold-Hopf point on the Hopf and fold curves
within 1e-9 of it; the fold-Hopf point, solved to 30 digits (f = 0, tr J = 0,
det J = 0) by mpmath on SymPy's derivatives, lies between two consecutive points of the
curve where the real eigenvalue changes sign; and l1 at the curve's points near it agrees
within 1e-8 with Kuznetsov's formula 3.20 evaluated to 30 digits at the same (g, f)
(AUTO-07p reports ZH there and a GH at g = 1.69429, f = 1.69159, where l1 = 231.5).
Exit 77 without SymPy. Usage: zero_hopf.py DYNKIT MODELS_DIR"""
import json
import subprocess
import sys

try:
    import mpmath as mp
    import sympy as sp
except ImportError:
    print("skipped: SymPy is not installed")
    sys.exit(77)

dynkit, models = sys.argv[1:3]
mp.mp.dps = 30
x, y, z, g, F = sp.symbols("x y z g f")
X = [x, y, z]
rhs = sp.Matrix([-y**2 - z**2 - sp.Rational(1, 4) * x + sp.Rational(1, 4) * F,
                 x * y - 4 * x * z - y + g, 4 * x * y + x * z - z])
J = rhs.jacobian(X)
args = X + [g, F]
L = lambda e: sp.lambdify(args, e, "mpmath")
fF, JF, TR, DET = L(list(rhs)), L(J), L(J.trace()), L(J.det())
H2 = L(sp.Array([[[sp.diff(rhs[i], X[j], X[k]) for k in range(3)] for j in range(3)]
                  for i in range(3)]))
H3 = L(sp.Array([[[[sp.diff(rhs[i], X[j], X[k], X[m]) for m in range(3)] for k in range(3)]
                   for j in range(3)] for i in range(3)]))


def null(M):
    """a null vector of a 3 x 3 matrix of rank 2: the cross product of two rows"""
    r, s = [M[0, j] for j in range(3)], [M[1, j] for j in range(3)]
    return mp.matrix([r[1] * s[2] - r[2] * s[1], r[2] * s[0] - r[0] * s[2],
                      r[0] * s[1] - r[1] * s[0]])


def l1_at(zz, w):
    """Kuznetsov, Elements, (3.20) with <q, q> = 1, <p, q> = 1"""
    A = mp.matrix(JF(*zz))
    H, G = H2(*zz), H3(*zz)
    ip = lambda u, v: sum(mp.conj(u[i]) * v[i] for i in range(3))
    B = lambda u, v: mp.matrix([sum(H[i][j][k] * u[j] * v[k] for j in range(3)
                                    for k in range(3)) for i in range(3)])
    q = null(A - 1j * w * mp.eye(3))
    q = q / mp.sqrt(ip(q, q).real)
    p = null(A.T + 1j * w * mp.eye(3))
    p = p / mp.conj(ip(p, q))
    qb = mp.matrix([mp.conj(c) for c in q])
    C = mp.matrix([sum(G[i][j][k][m] * q[j] * q[k] * qb[m] for j in range(3)
                       for k in range(3) for m in range(3)) for i in range(3)])
    r1 = mp.lu_solve(A, B(q, qb))
    r2 = mp.lu_solve(2j * w * mp.eye(3) - A, B(q, q))
    return mp.re(ip(p, C) - 2 * ip(p, B(q, r1)) + ip(p, B(qb, r2))) / (2 * w)


out = subprocess.run([dynkit, "continue", f"{models}/lorenz84.ode", "--par", "g", "--par2",
                      "f", "--json"], capture_output=True, text=True)
failures = []
if out.returncode != 0:
    print(f"FAIL: dynkit exit {out.returncode}: {out.stderr}")
    sys.exit(1)
hopf = [b for b in json.loads(out.stdout)["branches"] if b["kind"] == "hopf"]
gh = [(p["g"], p["f"]) for b in hopf for p in b["points"] if p["label"] == "GH"]
if gh:
    failures.append(f"GH at {gh} on the Hopf curves: none is there")
zh = mp.findroot(lambda *v: fF(*v) + [TR(*v), DET(*v)], (1.98, 0.3, 0.3, 1.683, 1.684))
zg, zf = float(zh[3]), float(zh[4])
crossed, compared = False, 0
for b in hopf:
    pts = b["points"]
    for p, q in zip(pts, pts[1:]):
        real = [min((e for e in r["eigenvalues"] if e[1] == 0), key=lambda e: abs(e[0]))[0]
                for r in (p, q)]
        if real[0] * real[1] < 0:
            crossed = True
            if not (min(p["g"], q["g"]) <= zg <= max(p["g"], q["g"])):
                failures.append(f"the real eigenvalue changes sign between g = {p['g']} and "
                                f"{q['g']}, the fold-Hopf point is at g = {zg!r}")
        for r in (p, q):
            if abs(r["g"] - zg) < 0.05 and r.get("l1") is not None and r["omega2"] > 0:
                s = mp.findroot(lambda *v: fF(*v, r["g"], r["f"]),
                                [r["state"][n] for n in "xyz"], tol=1e-20)
                want = l1_at((s[0], s[1], s[2], r["g"], r["f"]), mp.sqrt(r["omega2"]))
                compared += 1
                if not abs(r["l1"] - want) <= 1e-8 * abs(want):
                    failures.append(f"l1 at g = {r['g']}: {r['l1']!r}, 30 digits {want}")
if not crossed:
    failures.append("no Hopf curve passes the fold-Hopf point")
# the fold-Hopf point labelled ZH on the Hopf curves and the fold curves that pass it, there
# alone (1e-9)
branches = json.loads(out.stdout)["branches"]
for kind in ("hopf", "fold"):
    zhs = [(p["g"], p["f"]) for b in branches if b["kind"] == kind for p in b["points"]
           if p["label"] == "ZH"]
    if not zhs or any(abs(a - zg) > 1e-9 or abs(b - zf) > 1e-9 for a, b in zhs):
        failures.append(f"ZH on the {kind} curves at {zhs}, the fold-Hopf point is at "
                        f"({zg!r}, {zf!r})")
for f in failures:
    print("FAIL:", f)
if compared < 4:
    failures.append(f"l1 compared at {compared} points of the curve near the fold-Hopf point")
print(f"lorenz84: fold-Hopf point at g = {zg:.12f}, f = {zf:.12f}, l1 compared at {compared} "
      f"points; {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
