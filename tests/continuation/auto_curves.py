#!/usr/bin/env python3
"""dynkit continue --par2 (curves of folds and Hopf points) against AUTO-07p and against the
special points solved to 30 digits: the Bogdanov-Takens points (f = 0, tr J = 0, det J = 0),
the cusps (f = 0, det J = 0, w . B(v, v) = 0) and the generalized Hopf points (f = 0,
tr J = 0, l1 = 0 by Kuznetsov's formula 3.20 with exact derivatives) of planar models,
solved by mpmath's Newton method on SymPy's derivatives. AUTO-07p continues the same
folds and Hopf points with ISW = 2 both ways. BT and CP agree with AUTO-07p within 1e-6,
every BT, CP and GH dynkit finds with the 30-digit point within 1e-9, and where a curve
ends on a bound of a parameter the other agrees with AUTO-07p's within 1e-6.
AUTO-07p's GH is located by its own l1 and moves by up to 1e-3 with its step: it is printed,
not compared. Called by auto_check.py, whose run_auto and fortran it uses; a failed
problem's files are kept under ARTIFACTS/continuation-auto-curves-<problem>/."""
import json
import os
import shutil
import subprocess
import tempfile

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "models")

# name: the .ode file and dynkit's arguments, the same model for AUTO-07p (parameters and
# start as in the file or the --set/--init arguments), the two parameters and their
# windows, AUTO's steps on the curves, the special points expected with a guess for the
# 30-digit solve (x, y, p1, p2; the first parameter of the pair as continued)
CASES = {
    "cstr": dict(
        ode="cstr.ode", args=["--par", "d", "--par2", "b"],
        pars=[("d", 0.0), ("b", 20.0), ("beta", 3.0)], states=[("u1", 0.0), ("u2", 0.0)],
        rhs=["-u1+d*(1-u1)*exp(u2)", "-u2+d*b*(1-u1)*exp(u2)-beta*u2"],
        p=("d", "b"), win=((0.0, 0.5), (0.0, 40.0)), ds=0.01, dsmax=0.05, nmx=1000,
        expect={"BT": [(0.25, 1.333, 0.0879, 21.33)], "CP": [(0.5, 2.0, 0.135, 16.0)],
                "GH": [(0.578, 1.593, 0.279, 11.0)]}),
    "bazykin": dict(
        ode="bazykin.ode", args=["--par", "alpha", "--par2", "delta"],
        pars=[("alpha", 0.3), ("delta", 0.2), ("eps", 0.01), ("gamma", 1.0)],
        states=[("x", 2.1980329113406416), ("y", 1.6229354982507762)],
        rhs=["x-x*y/(1+alpha*x)-eps*x**2", "-gamma*y+x*y/(1+alpha*x)-delta*y**2"],
        p=("alpha", "delta"), win=((0.0, 1.0), (0.0, 1.0)), ds=0.01, dsmax=0.02, nmx=3000,
        expect={"BT": [(6.27, 3.60, 0.4536, 0.1751), (42.69, 21.63, 0.8607, 0.00606)],
                "CP": [(32.59, 20.47, 0.9012, 0.003568)],
                "GH": [(48.29, 24.40, 0.9566, 0.00095)]}),
    # the same model from alpha = 0.95 in delta: its Hopf point's curve reaches the GH point
    # one way (AUTO-07p stops a Hopf curve at a BT point), the second BT point the other
    "bazykin_gh": dict(
        ode="bazykin.ode",
        args=["--par", "delta", "--par2", "alpha", "--set", "alpha=0.95", "--set", "delta=0",
              "--init", "x=20", "--init", "y=16", "--opt", "parmax=0.02", "--opt", "dsmax=0.5",
              "--opt", "nmax=200"],
        pars=[("delta", 0.0), ("alpha", 0.95), ("eps", 0.01), ("gamma", 1.0)],
        states=[("x", 20.0), ("y", 16.0)],
        rhs=["x-x*y/(1+alpha*x)-eps*x**2", "-gamma*y+x*y/(1+alpha*x)-delta*y**2"],
        p=("delta", "alpha"), win=((0.0, 0.02), (0.0, 1.0)), ds=0.01, dsmax=0.5, nmx=200,
        expect={"BT": [(42.69, 21.63, 0.00606, 0.8607)], "GH": [(48.29, 24.40, 0.00095, 0.9566)]}),
}

RUN_AUTO = """r = run(e='pb', c='pb')
for lab in ('LP', 'HB'):
    for s in r(lab):
        for sgn in (1, -1):
            c = run(s, ISW=2, ICP=['%(p1)s', '%(p2)s'], DS=sgn*%(ds)r, DSMAX=%(dsmax)r, NMX=%(nmx)d)
            for p in c():
                if p['TY'] in ('BT', 'CP', 'GH', 'UZ'):
                    print('CURVE', lab, p['TY'], repr(p['%(p1)s']), repr(p['%(p2)s']))
"""


def constants(cs):
    pn = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(cs["pars"]))
    un = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(cs["states"]))
    (lo, hi), (lo2, hi2) = cs["win"]
    p1, p2 = cs["p"]
    # ITNW = 12, NWTN = 5: with AUTO's usual 7 and 3 its fold curves of bazykin stop (MX)
    # at their second point
    return "\n".join([
        f"parnames = {{{pn}}}", f"unames = {{{un}}}",
        f"NDIM={len(cs['states'])}, IPS=1, IRS=0, ILP=1", f"ICP=['{p1}']",
        "NTST=15, NCOL=4, IAD=3, ISP=2, ISW=1, IPLT=0, NBC=0, NINT=0",
        f"NMX={cs['nmx']}, NPR=100000, MXBF=0, IID=0, ITMX=12, ITNW=12, NWTN=5, JAC=0",
        "EPSL=1e-9, EPSU=1e-9, EPSS=1e-7",
        f"DS={cs['ds']}, DSMIN=1e-5, DSMAX={cs['dsmax']}, IADS=1", "THL={}, THU={}",
        f"UZSTOP={{'{p1}': [{lo}, {hi}], '{p2}': [{lo2}, {hi2}]}}", ""])


def reference(cs):
    """the special points of cs['expect'] solved to 30 digits: {label: [(p1, p2), ...]}"""
    import mpmath as mp
    import sympy as sp
    mp.mp.dps = 30
    X = sp.symbols([n for n, _ in cs["states"]])
    P = {n: sp.Symbol(n) for n, _ in cs["pars"]}
    fixed = {P[n]: sp.nsimplify(v) for n, v in cs["pars"] if n not in cs["p"]}
    loc = {**{str(s): s for s in X}, **{n: s for n, s in P.items()}}
    f = sp.Matrix([sp.sympify(r, locals=loc).subs(fixed) for r in cs["rhs"]])
    J = f.jacobian(X)
    args = list(X) + [P[cs["p"][0]], P[cs["p"][1]]]
    lam = lambda e: sp.lambdify(args, e, "mpmath")
    F, JF, TR, DET = lam(list(f)), lam(J), lam(J.trace()), lam(J.det())
    H2 = lam(sp.Array([[[sp.diff(f[i], X[j], X[k]) for k in range(2)] for j in range(2)]
                       for i in range(2)]))
    H3 = lam(sp.Array([[[[sp.diff(f[i], X[j], X[k], X[m]) for m in range(2)] for k in range(2)]
                        for j in range(2)] for i in range(2)]))

    def B(H, a, b):
        return [sum(H[i][j][k] * a[j] * b[k] for j in range(2) for k in range(2))
                for i in range(2)]

    def dot(a, b):  # <a, b> = conj(a) . b
        return sum(mp.conj(ai) * bi for ai, bi in zip(a, b))

    def l1(*z):  # Kuznetsov, Elements, (3.20), <q, q> = 1, <p, q> = 1
        A = mp.matrix(JF(*z))
        H, G = H2(*z), H3(*z)
        w = mp.sqrt(mp.det(A))
        q = [A[0, 1], 1j * w - A[0, 0]]
        nq = mp.sqrt(abs(q[0]) ** 2 + abs(q[1]) ** 2)
        q = [c / nq for c in q]
        pv = [-(A[1, 0]), A[0, 0] + 1j * w]  # A^T p = -i w p
        s = mp.conj(dot(pv, q))
        pv = [c / s for c in pv]
        qb = [mp.conj(c) for c in q]
        C = [sum(G[i][j][k][m] * q[j] * q[k] * qb[m] for j in range(2) for k in range(2)
                 for m in range(2)) for i in range(2)]
        r1 = mp.lu_solve(A, mp.matrix(B(H, q, qb)))
        r2 = mp.lu_solve(2j * w * mp.eye(2) - A, mp.matrix(B(H, q, q)))
        val = dot(pv, C) - 2 * dot(pv, B(H, q, list(r1))) + dot(pv, B(H, qb, list(r2)))
        return mp.re(val) / (2 * w)

    def cusp_test(*z):  # w . B(v, v) with J v = 0, w^T J = 0 (rows/columns of the 2x2 J)
        A = mp.matrix(JF(*z))
        v = [-A[0, 1], A[0, 0]] if abs(A[0, 0]) + abs(A[0, 1]) > abs(A[1, 0]) + abs(A[1, 1]) \
            else [-A[1, 1], A[1, 0]]
        w = [-A[1, 0], A[0, 0]] if abs(A[0, 0]) + abs(A[1, 0]) > abs(A[0, 1]) + abs(A[1, 1]) \
            else [-A[1, 1], A[0, 1]]
        bv = B(H2(*z), v, v)
        return (w[0] * bv[0] + w[1] * bv[1]) / (mp.norm(mp.matrix(v)) ** 2 *
                                                 mp.norm(mp.matrix(w)))

    last = {"BT": lambda *z: [TR(*z), DET(*z)], "CP": lambda *z: [DET(*z), cusp_test(*z)],
            "GH": lambda *z: [TR(*z), l1(*z)]}
    out = {}
    for label, guesses in cs["expect"].items():
        for g in guesses:
            z = mp.findroot(lambda *z: F(*z) + last[label](*z), g)
            out.setdefault(label, []).append((float(z[2]), float(z[3])))
    return out


def near(a, b, tol):
    return all(abs(u - v) <= tol * max(1.0, abs(v)) for u, v in zip(a, b))


def check_case(dynkit, name, cs, run_auto, fortran):
    work = tempfile.mkdtemp(prefix=f"auto-curves-{name}-")
    shutil.copy(os.path.join(MODELS, cs["ode"]), work)
    p1, p2 = cs["p"]
    a = run_auto(work, (("pb.f90", fortran(cs)), ("c.pb", constants(cs)),
                        ("run.auto", RUN_AUTO % dict(p1=p1, p2=p2, ds=cs["ds"],
                                                      dsmax=cs["dsmax"], nmx=cs["nmx"]))))
    auto = [(l.split()[2], float(l.split()[3]), float(l.split()[4]))
            for l in a.stdout.splitlines() if l.startswith("CURVE ")]
    d = subprocess.run([dynkit, "continue", cs["ode"], "--json", *cs["args"]], cwd=work,
                       capture_output=True, text=True)
    with open(os.path.join(work, "dynkit.json"), "w") as f:
        f.write(d.stdout + d.stderr)
    problems = []
    if d.returncode != 0 or a.returncode != 0:
        return work, [f"exit statuses: dynkit {d.returncode}, auto-07p {a.returncode}"]
    curves = [b for b in json.loads(d.stdout)["branches"] if b["kind"] in ("fold", "hopf")]
    ours = [(p["label"], p[p1], p[p2]) for b in curves for p in b["points"]
            if p["label"] in ("BT", "CP", "GH")]
    ref = reference(cs)
    # every special point dynkit finds is one of the 30-digit ones, and each of those found
    for lab, v, w in ours:
        if not any(near((v, w), r, 1e-9) for r in ref.get(lab, [])):
            problems.append(f"{lab} at ({v!r}, {w!r}): none of the exact {lab} {ref.get(lab)}")
    for lab, pts in ref.items():
        for r in pts:
            if not any(l == lab and near((v, w), r, 1e-9) for l, v, w in ours):
                problems.append(f"{lab} at {r} (30 digits) not found")
    # AUTO-07p's BT and CP within 1e-6 of dynkit's, and dynkit's each found by AUTO-07p
    for lab in ("BT", "CP"):
        theirs = [(v, w) for l, v, w in auto if l == lab]
        mine = [(v, w) for l, v, w in ours if l == lab]
        for t in theirs:
            if not any(near(t, m, 1e-6) for m in mine):
                problems.append(f"AUTO-07p's {lab} at {t} is none of dynkit's {mine}")
        for m in mine:
            if not any(near(m, t, 1e-6) for t in theirs):
                problems.append(f"dynkit's {lab} at {m} is none of AUTO-07p's {theirs}")
    # where a curve ends on a bound of a parameter, AUTO-07p's curve ends there too (a Hopf
    # curve only before any BT point: AUTO-07p ends it there, dynkit goes on as neutral
    # saddles and, past a second BT point, as Hopf points again)
    bounds = [(p1, v) for v in cs["win"][0]] + [(p2, v) for v in cs["win"][1]]
    ends = [(b["points"][-1][p1], b["points"][-1][p2]) for b in curves
            if b["points"][-1]["label"] == "EP"
            and any(abs(b["points"][-1][n] - v) < 1e-9 for n, v in bounds)
            and not (b["kind"] == "hopf" and any(p["label"] == "BT" for p in b["points"]))]
    for e in ends:
        if not any(near((v, w), e, 1e-6) for l, v, w in auto if l == "UZ"):
            problems.append(f"the curve's end at {e}: AUTO-07p's ends "
                            f"{[(v, w) for l, v, w in auto if l == 'UZ']}")
    gh = [(v, w) for l, v, w in auto if l == "GH"]
    print(f"{name}: BT {sorted(set((round(v, 12), round(w, 12)) for l, v, w in ours if l == 'BT'))}"
          f", CP {[(v, w) for l, v, w in ours if l == 'CP'][:1]}, GH "
          f"{[(v, w) for l, v, w in ours if l == 'GH']} (AUTO-07p's GH {gh}), "
          f"{len(ends)} curve ends compared")
    return work, problems


def check(dynkit, artifacts, run_auto, fortran):
    failures = []
    try:
        import mpmath  # noqa: F401
        import sympy  # noqa: F401
    except ImportError:
        print("two-parameter curves skipped: SymPy is not installed")
        return failures
    for name, cs in CASES.items():
        work, problems = check_case(dynkit, name, cs, run_auto, fortran)
        if problems:
            dest = os.path.join(artifacts, f"continuation-auto-curves-{name}")
            shutil.rmtree(dest, ignore_errors=True)
            os.makedirs(artifacts, exist_ok=True)
            shutil.copytree(work, dest)
            failures += [f"{name}: {p} (kept in {dest})" for p in problems]
        shutil.rmtree(work, ignore_errors=True)
    return failures
