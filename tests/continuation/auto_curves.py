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

import keep

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "models")

# name: the .ode file, the same model for AUTO-07p (parameters and start as in the file),
# the two parameters (in this order everywhere) and their windows, the special points
# expected with a guess for the 30-digit solve (x, y, p1, p2), and the runs: dynkit's
# arguments, the parameter continued first (0 or 1), AUTO-07p's changes to the start and
# the windows (as --set, --init and --opt change them) and its steps on the curves
CASES = {
    "cstr": dict(
        ode="cstr.ode", pars=[("d", 0.0), ("b", 20.0), ("beta", 3.0)],
        states=[("u1", 0.0), ("u2", 0.0)],
        rhs=["-u1+d*(1-u1)*exp(u2)", "-u2+d*b*(1-u1)*exp(u2)-beta*u2"],
        p=("d", "b"), win=((0.0, 0.5), (0.0, 40.0)),
        expect={"BT": [(0.25, 1.333, 0.0879, 21.33)], "CP": [(0.5, 2.0, 0.135, 16.0)],
                "GH": [(0.578, 1.593, 0.279, 11.0)]},
        runs=[dict(args=["--par", "d", "--par2", "b"], first=0, ds=0.01, dsmax=0.05,
                   nmx=1000)]),
    "bazykin": dict(
        ode="bazykin.ode", pars=[("alpha", 0.3), ("delta", 0.2), ("eps", 0.01), ("gamma", 1.0)],
        states=[("x", 2.1980329113406416), ("y", 1.6229354982507762)],
        rhs=["x-x*y/(1+alpha*x)-eps*x**2", "-gamma*y+x*y/(1+alpha*x)-delta*y**2"],
        p=("alpha", "delta"), win=((0.0, 1.0), (0.0, 1.0)),
        expect={"BT": [(6.27, 3.60, 0.4536, 0.1751), (42.69, 21.63, 0.8607, 0.00606)],
                "CP": [(32.59, 20.47, 0.9012, 0.003568)],
                "GH": [(48.29, 24.40, 0.9566, 0.00095)]},
        runs=[dict(args=["--par", "alpha", "--par2", "delta"], first=0, ds=0.01, dsmax=0.02,
                   nmx=3000),
              # from alpha = 0.95 in delta: the Hopf point's curve reaches the GH point one
              # way (AUTO-07p stops a Hopf curve at a BT point), the second BT point the other
              dict(args=["--par", "delta", "--par2", "alpha", "--set", "alpha=0.95", "--set",
                         "delta=0", "--init", "x=20", "--init", "y=16", "--opt", "parmax=0.02",
                         "--opt", "dsmax=0.5", "--opt", "nmax=200"],
                   first=1, start="PAR={'alpha': 0.95, 'delta': 0.0}, U={'x': 20.0, 'y': 16.0}",
                   win=((0.0, 1.0), (0.0, 0.02)), ds=0.01, dsmax=0.5, nmx=200)]),
    # the Gray-Scott autocatalator (gray_scott.ode) in (k, feed): BT at k = feed = 1/16,
    # where both curves turn in k: AUTO-07p labels the point LP on each (bt_as_lp)
    "gray_scott": dict(
        ode="gray_scott.ode", pars=[("k", 0.05), ("feed", 0.04)],
        states=[("x", 0.2820550528229663), ("y", 0.3190866431897928)],
        rhs=["feed*(1-x)-x*y**2", "x*y**2-(feed+k)*y"],
        p=("k", "feed"), win=((0.0, 0.2), (0.001, 0.3)), bt_as_lp=True,
        expect={"BT": [(0.5, 0.25, 0.0625, 0.0625)], "GH": [(0.25, 0.19, 0.035, 0.0117)]},
        runs=[dict(args=["--par", "k", "--par2", "feed", "--opt", "nmax=300", "--opt",
                         "par2min=0.001", "--opt", "par2max=0.3"], first=0,
                   ds=0.002, dsmax=0.005, nmx=300)]),
}

# each run: the first branch in the parameter continued first, then from each of its LP and
# HB points the curve both ways
RUN_AUTO = """r = run(e='pb', c='pb', ICP=['%(q1)s'], DS=%(ds)r, DSMAX=%(dsmax)r, NMX=%(nmx)d,
        UZSTOP={'%(p1)s': %(w1)r, '%(p2)s': %(w2)r}%(start)s)
for lab in ('LP', 'HB'):
    for s in r(lab):
        for sgn in (1, -1):
            c = run(s, ISW=2, ICP=['%(q1)s', '%(q2)s'], DS=sgn*%(ds)r)
            for p in c():
                if p['TY'] in ('BT', 'CP', 'GH', 'UZ', 'LP'):
                    print('CURVE', %(k)d, p['TY'], repr(p['%(p1)s']), repr(p['%(p2)s']))
"""


def constants(cs):
    pn = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(cs["pars"]))
    un = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(cs["states"]))
    # ITNW = 12, NWTN = 5: with AUTO's usual 7 and 3 its fold curves of bazykin stop (MX)
    # at their second point
    return "\n".join([
        f"parnames = {{{pn}}}", f"unames = {{{un}}}",
        f"NDIM={len(cs['states'])}, IPS=1, IRS=0, ILP=1", f"ICP=['{cs['p'][0]}']",
        "NTST=15, NCOL=4, IAD=3, ISP=2, ISW=1, IPLT=0, NBC=0, NINT=0",
        "NMX=1000, NPR=100000, MXBF=0, IID=0, ITMX=12, ITNW=12, NWTN=5, JAC=0",
        "EPSL=1e-9, EPSU=1e-9, EPSS=1e-7",
        "DS=0.01, DSMIN=1e-5, DSMAX=0.05, IADS=1", "THL={}, THU={}", ""])


def auto_script(cs):
    runs = []
    for k, rn in enumerate(cs["runs"]):
        q = cs["p"] if rn["first"] == 0 else cs["p"][::-1]
        w1, w2 = rn.get("win", cs["win"])
        runs.append(RUN_AUTO % dict(q1=q[0], q2=q[1], p1=cs["p"][0], p2=cs["p"][1],
                                    w1=list(w1), w2=list(w2), ds=rn["ds"], dsmax=rn["dsmax"],
                                    nmx=rn["nmx"], k=k,
                                    start=", " + rn["start"] if "start" in rn else ""))
    return "".join(runs)


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
                        ("run.auto", auto_script(cs))))
    auto = [(int(l.split()[1]), l.split()[2], float(l.split()[3]), float(l.split()[4]))
            for l in a.stdout.splitlines() if l.startswith("CURVE ")]
    # a curve's LP (where it turns in the first parameter) is AUTO-07p's label of a BT
    # point where both curves turn there; elsewhere it is no special point of the curve
    auto = [(j, "BT" if l == "LP" else l, v, w) for j, l, v, w in auto
            if l != "LP" or cs.get("bt_as_lp")]
    if a.returncode != 0:
        return work, [f"auto-07p's exit status {a.returncode}"]
    problems, ours, ends = [], [], 0
    for k, rn in enumerate(cs["runs"]):
        d = subprocess.run([dynkit, "continue", cs["ode"], "--json", *rn["args"]], cwd=work,
                           capture_output=True, text=True)
        with open(os.path.join(work, f"dynkit{k}.json"), "w") as f:
            f.write(d.stdout + d.stderr)
        if d.returncode != 0:
            problems.append(f"dynkit {' '.join(rn['args'])}: exit status {d.returncode}")
            continue
        curves = [b for b in json.loads(d.stdout)["branches"] if b["kind"] in ("fold", "hopf")]
        ours += [(p["label"], p[p1], p[p2]) for b in curves for p in b["points"]
                 if p["label"] in ("BT", "CP", "GH")]
        # where a curve ends on a bound of a parameter, AUTO-07p's curve ends there too (a
        # Hopf curve only before any BT point: AUTO-07p ends it there, dynkit goes on as
        # neutral saddles and, past a second BT point, as Hopf points again)
        (lo1, hi1), (lo2, hi2) = rn.get("win", cs["win"])
        bounds = [(p1, lo1), (p1, hi1), (p2, lo2), (p2, hi2)]
        for b in curves:
            e = b["points"][-1]
            if e["label"] != "EP" or not any(abs(e[n] - v) < 1e-9 for n, v in bounds) or (
                    b["kind"] == "hopf" and any(p["label"] == "BT" for p in b["points"])):
                continue
            ends += 1
            theirs = [(v, w) for j, l, v, w in auto if j == k and l == "UZ"]
            if not any(near(t, (e[p1], e[p2]), 1e-6) for t in theirs):
                problems.append(f"the curve's end at {(e[p1], e[p2])}: AUTO-07p's {theirs}")
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
        theirs = [(v, w) for _, l, v, w in auto if l == lab]
        mine = [(v, w) for l, v, w in ours if l == lab]
        for t in theirs:
            if not any(near(t, m, 1e-6) for m in mine):
                problems.append(f"AUTO-07p's {lab} at {t} is none of dynkit's {mine}")
        for m in mine:
            if not any(near(m, t, 1e-6) for t in theirs):
                problems.append(f"dynkit's {lab} at {m} is none of AUTO-07p's {theirs}")
    gh = [(v, w) for _, l, v, w in auto if l == "GH"]
    print(f"{name}: BT {sorted(set((round(v, 12), round(w, 12)) for l, v, w in ours if l == 'BT'))}"
          f", CP {[(v, w) for l, v, w in ours if l == 'CP'][:1]}, GH "
          f"{[(v, w) for l, v, w in ours if l == 'GH']} (AUTO-07p's GH {gh}), "
          f"{ends} curve ends compared")
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
        failures += keep.settle(work, artifacts, f"continuation-auto-curves-{name}", name,
                                problems)
    return failures
