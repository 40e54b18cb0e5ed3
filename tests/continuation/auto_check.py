#!/usr/bin/env python3
"""dynkit continue against AUTO-07p: the same problems in both programs (an AUTO equations
file and constants file written here from the same formulas as the .ode file), the labels
LP, HB and BP of the equilibrium branch compared, and their parameter values within AUTO's
own accuracy (EPSS = 1e-7 here: 1e-6 relative). Everything of a failed problem is kept
under ARTIFACTS/<problem>/. Discrete maps (IPS = -1): auto_maps.py; curves of folds and Hopf
points in two parameters: auto_curves.py; period doublings and torus bifurcations:
auto_cycles.py. Exit 77 (skipped) when auto-07p or gfortran is
missing.
Usage: auto_check.py DYNKIT ARTIFACTS [equilibria|models_a|models_b|orbits]"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import auto_curves
import auto_cycles
import auto_maps
import keep


# name: parameters (name, start value), states (name, start value), right-hand sides as
# Fortran and as .ode formulas (the same text where the languages agree), the continued
# parameter, the first step and the range
PROBLEMS = {
    "brusselator": dict(
        pars=[("a", 1.0), ("b", 1.0)], states=[("x", 1.0), ("y", 1.0)],
        rhs=["a-(b+1)*x+x**2*y", "b*x-x**2*y"], icp="b", ds=0.05, dsmax=0.2,
        range=(0.0, 4.0)),
    "lorenz": dict(
        pars=[("sigma", 10.0), ("rho", 28.0), ("beta", 8.0 / 3.0)],
        states=[("x", (8.0 / 3.0 * 27.0) ** 0.5), ("y", (8.0 / 3.0 * 27.0) ** 0.5),
                ("z", 27.0)],
        rhs=["sigma*(y-x)", "x*(rho-z)-y", "x*y-beta*z"], icp="rho", ds=-0.5, dsmax=1.0,
        range=(0.5, 40.0)),
    "fold": dict(
        pars=[("p", 1.0)], states=[("x", 1.0)], rhs=["p-x**2"], icp="p", ds=-0.02,
        dsmax=0.1, range=(-1.0, 2.0)),
    "cubic": dict(
        pars=[("p", -2.0), ("q", 1.0)], states=[("x", -2.35530139760812)],
        rhs=["p+q*x-x**3/3"], icp="p", ds=0.05, dsmax=0.1, range=(-2.0, 2.0)),
    # AUTO-07p's demo pp2 (predator-prey with harvesting) on its trivial branch u2 = 0: a
    # transcritical branch point at p1 = 0.6 where u2's equation u2' = (p4 u1 - 1) u2
    # decouples from the rest
    "pp2": dict(
        pars=[("p1", 0.0), ("p2", 3.0), ("p3", 5.0), ("p4", 3.0)],
        states=[("u1", 0.0), ("u2", 0.0)],
        rhs=["p2*u1*(1-u1)-u1*u2-p1*(1-exp(-p3*u1))", "-u2+p4*u1*u2"], icp="p1", ds=0.02,
        dsmax=0.06, range=(0.0, 1.0)),
    # AUTO-07p's demo tor (Freire, Rodriguez-Luis, Gamero, Ponce) on x = y = z = 0: a Hopf
    # point and a pitchfork at rn = -0.5
    "tor": dict(
        pars=[("rn", -0.9), ("be", 0.5), ("ga", -0.6), ("r", 0.6), ("a3", 0.328578),
              ("b3", 0.933578)],
        states=[("x", 0.0), ("y", 0.0), ("z", 0.0)],
        rhs=["(-(be+rn)*x+be*y-a3*x**3+b3*(y-x)**3)/r", "be*x-(be+ga)*y-z-b3*(y-x)**3", "y"],
        icp="rn", ds=0.001, dsmax=0.01, range=(-0.9, -0.4)),
    # AUTO-07p's demos pp3 and ppp (two predators, one harvested) from the prey alone,
    # u = (1, 0, 0): the branch point where u2's rate -p2 + p4 - p1 p6 vanishes
    "pp3": dict(
        part="models_a",
        pars=[("p1", 0.0), ("p2", 0.25), ("p3", 0.5), ("p4", 4.0), ("p5", 3.0), ("p6", 5.0)],
        states=[("u1", 1.0), ("u2", 0.0), ("u3", 0.0)],
        rhs=["u1*(1-u1)-p4*u1*u2", "-p2*u2+p4*u1*u2-p5*u2*u3-p1*(1-exp(-p6*u2))",
             "-p3*u3+p5*u2*u3"], icp="p1", ds=0.01, dsmax=0.02, range=(0.0, 1.0),
        exact={"BP": [(4.0 - 0.25) / 5.0]}),
    "ppp": dict(
        part="models_a",
        pars=[("p1", 0.0), ("p2", 0.25), ("p3", 0.5), ("p4", 3.0), ("p5", 3.0), ("p6", 5.0)],
        states=[("u1", 1.0), ("u2", 0.0), ("u3", 0.0)],
        rhs=["u1*(1-u1)-p4*u1*u2", "-p2*u2+p4*u1*u2-p5*u2*u3-p1*(1-exp(-p6*u2))",
             "-p3*u3+p5*u2*u3"], icp="p1", ds=0.01, dsmax=0.02, range=(0.0, 0.6),
        exact={"BP": [(3.0 - 0.25) / 5.0]}),
    # AUTO-07p's demo plp (an enzyme with substrate inhibition, in rho): two Hopf points
    "plp": dict(
        part="models_a",
        pars=[("s0", 110.0), ("a0", 500.0), ("al", 0.2), ("rh", 2.021628), ("rk", 0.1)],
        states=[("s", 45.559739051380326), ("a", 177.79869525690165)],
        rhs=["(s0-s)-rh*s*a/(1+s+rk*s**2)", "al*(a0-a)-rh*s*a/(1+s+rk*s**2)"], icp="rh",
        ds=0.1, dsmax=1.0, range=(0.0, 6.0)),
    # AUTO-07p's demo tfc (a tritrophic food chain, prey and predator in logarithms) without
    # the top predator z: Rosenzweig-MacArthur's Hopf point where the prey X = 1/3 sits at
    # the top of its isocline (1 - X)(1 + b1 X)/a1, d1 = a1 X/(1 + b1 X) = 5/6
    "tfc": dict(
        part="models_a",
        pars=[("a1", 5.0), ("b1", 3.0), ("d1", 1.1083), ("a2", 0.1), ("b2", 2.0), ("d2", 0.01)],
        states=[("x", -0.41304879168158637), ("y", -1.5995370877568378), ("z", 0.0)],
        rhs=["(1-exp(x))-a1*exp(y)/(1+b1*exp(x))",
             "a1*exp(x)/(1+b1*exp(x))-d1-a2*z/(1+b2*exp(y))", "z*(a2*exp(y)/(1+b2*exp(y))-d2)"],
        icp="d1", ds=-0.01, dsmax=0.1, range=(0.1, 2.0), exact={"HB": [5.0 / 6.0]}),
    # Rosenzweig-MacArthur x' = x(1 - x/k) - xy/(1 + x), y' = e xy/(1 + x) - m y: the Hopf
    # point where the prey's isocline peaks at the predator's x = m/(e - m), k = 2x + 1, and
    # (downwards) the transcritical point k = m/(e - m) where the predator dies out
    "rosenzweig_macarthur": dict(
        part="models_a",
        pars=[("k", 1.5), ("e", 0.5), ("m", 0.2)], states=[("x", 2 / 3), ("y", 25 / 27)],
        rhs=["x*(1-x/k)-x*y/(1+x)", "e*x*y/(1+x)-m*y"], icp="k", ds=0.02, dsmax=0.1,
        range=(0.5, 4.0), exact={"HB": [7.0 / 3.0]}),
    "rosenzweig_macarthur_down": dict(
        part="models_a",
        pars=[("k", 1.5), ("e", 0.5), ("m", 0.2)], states=[("x", 2 / 3), ("y", 25 / 27)],
        rhs=["x*(1-x/k)-x*y/(1+x)", "e*x*y/(1+x)-m*y"], icp="k", ds=-0.02, dsmax=0.1,
        range=(0.5, 4.0), exact={"BP": [2.0 / 3.0]}),
    # Lengyel-Epstein (the CIMA reaction), a = 10: Hopf point at b = 3a/5 - 25/a
    "lengyel_epstein": dict(
        part="models_b",
        pars=[("b", 1.0), ("a", 10.0)], states=[("x", 2.0), ("y", 5.0)],
        rhs=["a-x-4*x*y/(1+x**2)", "b*(x-x*y/(1+x**2))"], icp="b", ds=0.05, dsmax=0.2,
        range=(0.5, 6.0), exact={"HB": [3.0 * 10 / 5 - 25.0 / 10]}),
    # Schnakenberg, a = 0.1: tr J = 0 where s = a + b solves s^3 - s + 2a = 0
    "schnakenberg": dict(
        part="models_b",
        pars=[("b", 0.05), ("a", 0.1)], states=[("x", 0.15), ("y", 0.05 / 0.15 ** 2)],
        rhs=["a-x+x**2*y", "b-x**2*y"], icp="b", ds=0.01, dsmax=0.05, range=(0.01, 2.0),
        exact={"HB": "schnakenberg"}),
    # the Brusselator in a (b = 3): Hopf point at a = sqrt(b - 1)
    "brusselator_a": dict(
        part="models_b",
        pars=[("a", 2.5), ("b", 3.0)], states=[("x", 2.5), ("y", 1.2)],
        rhs=["a-(b+1)*x+x**2*y", "b*x-x**2*y"], icp="a", ds=-0.02, dsmax=0.1,
        range=(0.5, 3.0), exact={"HB": [2.0 ** 0.5]}),
    # Goodwin's oscillator with equal rates b and Hill exponent n = 10: the secant condition
    # n z^n/(1 + z^n) = 8 gives z^n = 8/(n - 8) = 4 and b^3 = 1/(z (1 + z^n))
    "goodwin": dict(
        part="models_b",
        pars=[("b", 0.2), ("n", 10.0)],
        states=[("x", 0.06197203663361557), ("y", 0.30986018316807784), ("z", 1.549300915840389)],
        rhs=["1/(1+z**n)-b*x", "x-b*y", "y-b*z"], icp="b", ds=0.01, dsmax=0.05,
        range=(0.1, 1.0), exact={"HB": [(5.0 * 4.0 ** 0.1) ** (-1.0 / 3.0)]}),
    # the Gray-Scott autocatalator (feed 0.04) in k: the fold where feed = 4 (feed + k)^2,
    # the Hopf point where tr J = k - v^2 = 0 on (feed + k) v^2 - feed v + feed (feed + k) = 0
    "gray_scott": dict(
        part="models_b",
        pars=[("k", 0.05), ("feed", 0.04)], states=[("x", 0.2820550528229663),
                                                   ("y", 0.3190866431897928)],
        rhs=["feed*(1-x)-x*y**2", "x*y**2-(feed+k)*y"], icp="k", ds=0.002, dsmax=0.005,
        range=(0.0, 0.2), exact={"LP": [0.1 - 0.04], "HB": "gray_scott"}),
    # Hindmarsh-Rose (r = 0.01, s = 4, xr = -1.6) in the current i: two Hopf points
    "hindmarsh_rose": dict(
        part="models_b",
        pars=[("i", 0.0), ("a", 1.0), ("b", 3.0), ("c", 1.0), ("d", 5.0), ("r", 0.01),
              ("s", 4.0), ("xr", -1.6)],
        states=[("x", -1.6045345328021474), ("y", -11.872655334773027),
                ("z", -0.018138131208589498)],
        rhs=["y-a*x**3+b*x**2-z+i", "c-d*x**2-y", "r*(s*(x-xr)-z)"], icp="i", ds=0.05,
        dsmax=0.2, range=(-2.0, 6.0)),
    # Roessler's system in a (b = 2, c = 4) from the equilibrium near the origin
    "roessler_a": dict(
        part="models_b",
        pars=[("a", 0.1), ("b", 2.0), ("c", 4.0)],
        states=[("x", 0.05064113103820722), ("y", -0.5064113103820722),
                ("z", 0.5064113103820722)],
        rhs=["-y-z", "x+a*y", "b+z*(x-c)"], icp="a", ds=0.01, dsmax=0.05, range=(0.0, 1.0)),
}


def bisect(g, lo, hi):
    """the root of g in [lo, hi] (a sign change) to rounding"""
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if (g(lo) > 0) == (g(mid) > 0):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def exact_values(name):
    """the closed forms that are roots of a scalar equation"""
    if name == "schnakenberg":  # b = s - a, s^3 - s + 2a = 0 (a = 0.1), its two positive roots
        g = lambda s: s ** 3 - s + 0.2
        return [bisect(g, 0.15, 0.5) - 0.1, bisect(g, 0.5, 1.0) - 0.1]
    if name == "gray_scott":  # v = sqrt(k) on the upper equilibrium (feed = 0.04)
        g = lambda k: (0.04 + k) * k - 0.04 * k ** 0.5 + 0.04 * (0.04 + k)
        return [bisect(g, 0.05, 0.0599)]
    raise KeyError(name)


def fortran(pb):
    decl = ", ".join(n for n, _ in pb["pars"] + pb["states"])
    body = [f"  {n}=PAR({i + 1})" for i, (n, _) in enumerate(pb["pars"])]
    body += [f"  {n}=U({i + 1})" for i, (n, _) in enumerate(pb["states"])]
    body += [f"  F({i + 1})={r}" for i, r in enumerate(pb["rhs"])]
    start = [f"  PAR({i + 1})={v!r}d0" for i, (_, v) in enumerate(pb["pars"])]
    start += [f"  U({i + 1})={v!r}d0" for i, (_, v) in enumerate(pb["states"])]
    return "\n".join([
        "SUBROUTINE FUNC(NDIM,U,ICP,PAR,IJAC,F,DFDU,DFDP)",
        "  IMPLICIT NONE",
        "  INTEGER, INTENT(IN) :: NDIM, ICP(*), IJAC",
        "  DOUBLE PRECISION, INTENT(IN) :: U(NDIM), PAR(*)",
        "  DOUBLE PRECISION, INTENT(OUT) :: F(NDIM)",
        "  DOUBLE PRECISION, INTENT(INOUT) :: DFDU(NDIM,NDIM), DFDP(NDIM,*)",
        f"  DOUBLE PRECISION {decl}", *body,
        "END SUBROUTINE FUNC",
        "SUBROUTINE STPNT(NDIM,U,PAR,T)",
        "  IMPLICIT NONE",
        "  INTEGER, INTENT(IN) :: NDIM",
        "  DOUBLE PRECISION, INTENT(INOUT) :: U(NDIM),PAR(*)",
        "  DOUBLE PRECISION, INTENT(IN) :: T", *start,
        "END SUBROUTINE STPNT",
        *[f"SUBROUTINE {s}\nEND SUBROUTINE {s}" for s in ("BCND", "ICND", "FOPT", "PVLS")],
        ""])


def constants(pb):
    pn = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(pb["pars"]))
    un = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(pb["states"]))
    lo, hi = pb["range"]
    return "\n".join([
        f"parnames = {{{pn}}}", f"unames = {{{un}}}",
        f"NDIM={len(pb['states'])}, IPS=1, IRS=0, ILP=1", f"ICP=['{pb['icp']}']",
        "NTST=15, NCOL=4, IAD=3, ISP=1, ISW=1, IPLT=0, NBC=0, NINT=0",
        "NMX=400, NPR=1000, MXBF=0, IID=0, ITMX=8, ITNW=7, NWTN=3, JAC=0",
        "EPSL=1e-9, EPSU=1e-9, EPSS=1e-7",
        f"DS={pb['ds']}, DSMIN=0.001, DSMAX={pb['dsmax']}, IADS=1",
        "THL={}, THU={}", f"UZSTOP={{'{pb['icp']}': [{lo}, {hi}]}}", ""])


def ode(pb):
    lines = ["par " + ", ".join(f"{n}={v!r}" for n, v in pb["pars"]),
             "init " + ", ".join(f"{n}={v!r}" for n, v in pb["states"])]
    lines += [f"{n}'={r.replace('**', '^')}" for (n, _), r in zip(pb["states"], pb["rhs"])]
    lo, hi = pb["range"]
    lines += [f"@ ds={pb['ds']}, dsmin=0.001, dsmax={pb['dsmax']}, nmax=400, parmin={lo}, "
              f"parmax={hi}", "done", ""]
    return "\n".join(lines)


# AUTO-07p's demo enz with the demo's constants (c.enz: EPSS = 1e-5, DSMIN = 0.01, its
# switching on, MXBF = -1: the branch from each BP one way) but NMX = 400 and no STOP: the
# symmetric branch s1 = s2 with its two pitchforks, and the asymmetric loop through both.
# (With EPSS = 1e-7 and DSMIN = 0.001 AUTO-07p's first branch passes the second pitchfork
# without a BP and its second jumps back to the symmetric branch.)
ENZ = dict(
    pars=[("s0", 0.0), ("mu", 0.0), ("rho", 100.0), ("kappa", 1.0)],
    states=[("s1", 0.0), ("s2", 0.0)],
    rhs=["(s0-s1)+(s2-s1)-rho*s1/(1+s1+kappa*s1**2)",
         "(s0+mu-s2)+(s1-s2)-rho*s2/(1+s2+kappa*s2**2)"])
ENZ_CONSTANTS = """parnames = {1: 's0', 2: 'mu', 3: 'rho', 4: 'kappa'}
unames = {1: 's1', 2: 's2'}
NDIM=2, IPS=1, IRS=0, ILP=1
ICP=['s0']
NTST=15, NCOL=4, IAD=3, ISP=1, ISW=1, IPLT=0, NBC=0, NINT=0
NMX=400, NPR=1000, MXBF=-1, IID=0, ITMX=8, ITNW=5, NWTN=3, JAC=0
EPSL=1e-7, EPSU=1e-7, EPSS=1e-5
DS=0.1, DSMIN=0.01, DSMAX=0.25, IADS=1
THL={}, THU={}
"""
RUN_ENZ = """r = run(e='pb', c='pb')
for b in r:
    for p in b:
        if p['TY'] in ('LP', 'BP'):
            print('LABEL', b['BR'], p['TY'], repr(p['s0']), repr(p['s1']), repr(p['s2']))
"""


def run_auto(work, files):
    """AUTO-07p's batch run of work/run.auto after writing files ((name, text) pairs) into
    work; its output kept in work/auto.out"""
    for fname, text in files:
        with open(os.path.join(work, fname), "w") as f:
            f.write(text)
    a = subprocess.run(["auto-07p", "run.auto"], cwd=work, capture_output=True, text=True,
                       timeout=600)
    with open(os.path.join(work, "auto.out"), "w") as f:
        f.write(a.stdout + a.stderr)
    return a


def enz_check(dynkit, artifacts):
    """AUTO-07p's branches 1 (symmetric) and 2 (asymmetric, from the first BP) against
    dynkit's: the same BP and LP values within 1e-6; dynkit's switched branch asymmetric,
    closed (ended where it started) and computed once"""
    work = tempfile.mkdtemp(prefix="auto-enz-")
    models = os.path.join(os.path.dirname(os.path.abspath(__file__)), "models")
    shutil.copy(os.path.join(models, "enz.ode"), work)
    a = run_auto(work, (("pb.f90", fortran(ENZ)), ("c.pb", ENZ_CONSTANTS),
                        ("run.auto", RUN_ENZ)))
    problems = []
    auto = [l.split()[1:] for l in a.stdout.splitlines() if l.startswith("LABEL ")]
    d = subprocess.run([dynkit, "continue", "enz.ode", "--par", "s0", "--json"], cwd=work,
                       capture_output=True, text=True)
    with open(os.path.join(work, "dynkit.json"), "w") as f:
        f.write(d.stdout + d.stderr)

    def near(v, w):
        return abs(v - w) <= 1e-6 * max(1.0, abs(w))

    if d.returncode != 0 or a.returncode != 0:
        problems.append(f"exit statuses: dynkit {d.returncode}, auto-07p {a.returncode}")
    else:
        branches = json.loads(d.stdout)["branches"]
        first = branches[0]
        # branch 1: both pitchforks and the two folds of the symmetric branch
        ours = sorted((p["label"], p["s0"]) for p in first["points"] if p["label"] in ("LP", "BP"))
        theirs = sorted((l, float(v)) for br, l, v, _, _ in auto if br == "1")
        if [l for l, _ in ours] != [l for l, _ in theirs] or not all(
                near(v, w) for (_, v), (_, w) in zip(ours, theirs)):
            problems.append(f"branch 1: dynkit {ours}, AUTO-07p {theirs}")
        # the branch switched to at the first pitchfork: the asymmetric loop
        switched = [b for b in branches if b["parent"] == first["branch"]]
        if len(switched) != 1:
            problems.append(f"{len(switched)} branches switched to, expected one (the loop "
                            "once, not again from the second pitchfork nor the other way)")
        else:
            loop = switched[0]
            asym = max(abs(p["state"]["s1"] - p["state"]["s2"]) for p in loop["points"])
            if not asym > 1.0:
                problems.append(f"the switched branch is not the asymmetric one (max |s1 - s2| "
                                f"= {asym})")
            if not loop["stop"].startswith("closed") or not (
                    near(loop["points"][-1]["s0"], loop["points"][0]["s0"])):
                problems.append(f"the loop is not ended where it started: {loop['stop']}")
            # its folds off the symmetric branch (AUTO-07p's LPs at the pitchforks aside),
            # each value twice (s1 > s2 and s1 < s2) in both programs
            mine = sorted(p["s0"] for p in loop["points"] if p["label"] == "LP"
                          and abs(p["state"]["s1"] - p["state"]["s2"]) > 1e-3)
            theirs2 = sorted(float(v) for br, l, v, s1, s2 in auto if br == "2" and l == "LP"
                             and abs(float(s1) - float(s2)) > 1e-3)
            if len(mine) != 4 or len(mine) != len(theirs2) or not all(
                    near(v, w) for v, w in zip(mine, theirs2)):
                problems.append(f"the loop's folds: dynkit {mine}, AUTO-07p {theirs2}")
            # where the loop turns at the second pitchfork it meets the symmetric branch: a
            # BP there (the bordered matrix is singular: located from Moore's system), at
            # the first branch's BP within 1e-10 and at AUTO-07p's second branch's BP
            second = [v for l, v in ours if l == "BP" and v < 30.0]
            turn = [p["s0"] for p in loop["points"][1:-1] if p["label"] == "BP"]
            theirs_bp = [float(v) for br, l, v, _, _ in auto if br == "2" and l == "BP"
                         and float(v) < 30.0]
            if (len(turn) != 1 or len(second) != 1 or not theirs_bp or
                    abs(turn[0] - second[0]) > 1e-10 * second[0] or
                    not near(turn[0], theirs_bp[0])):
                problems.append(f"the loop's BP at the second pitchfork: dynkit {turn}, the "
                                f"first branch's {second}, AUTO-07p {theirs_bp}")
    return keep.settle(work, artifacts, "continuation-auto-enz", "enz", problems,
                       "enz: the pitchforks, the folds and the asymmetric loop agree")


RUN_AUTO = """r = run(e='pb', c='pb')
for lab in ('HB', 'LP', 'BP'):
    for p in r(lab):
        print('LABEL', lab, repr(p['%s']))
"""

def main():
    dynkit, artifacts = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    if not shutil.which("auto-07p") or not shutil.which("gfortran"):
        print("skipped: auto-07p or gfortran is not installed (scripts/install-deps.sh)")
        sys.exit(77)
    # PART: "equilibria" (the first problems here, enz, the maps), "models_a" and "models_b"
    # (the models from outside marked so: two parts to keep each run short), "orbits" (the
    # curves in two parameters and the periodic orbits' PD and TR), or all when not given
    part = sys.argv[3] if len(sys.argv) > 3 else "all"
    failures = []
    for name, pb in PROBLEMS.items():
        if part != "all" and pb.get("part", "equilibria") != part:
            continue
        work = tempfile.mkdtemp(prefix=f"auto-{name}-")
        a = run_auto(work, (("pb.f90", fortran(pb)), ("c.pb", constants(pb)),
                            ("run.auto", RUN_AUTO % pb["icp"]), (f"{name}.ode", ode(pb))))
        problems = []
        auto = sorted((l.split()[1], float(l.split()[2])) for l in a.stdout.splitlines()
                      if l.startswith("LABEL "))
        d = subprocess.run([dynkit, "continue", f"{name}.ode", "--par", pb["icp"], "--json",
                            "--output", "dynkit.csv"], cwd=work, capture_output=True, text=True)
        with open(os.path.join(work, "dynkit.json"), "w") as f:
            f.write(d.stdout + d.stderr)
        if d.returncode != 0 or a.returncode != 0:
            problems.append(f"exit statuses: dynkit {d.returncode}, auto-07p {a.returncode}")
        else:
            # AUTO follows one branch and does not switch here (MXBF=0): dynkit's first branch
            first = json.loads(d.stdout)["branches"][0]
            # where C+ of Lorenz's system meets the origin (a pitchfork seen from its side, the
            # branch turning in rho there) AUTO-07p reports LP and dynkit BP: both hold, so BP
            # and LP at the same value count as one label
            ours = sorted((p["label"], p[pb["icp"]]) for p in first["points"]
                          if p["label"] in ("HB", "LP", "BP"))
            for i, (l, v) in enumerate(ours):
                if l == "BP" and any(m == "LP" and abs(w - v) <= 1e-6 * max(1.0, abs(w))
                                     for m, w in auto):
                    ours[i] = ("LP", v)
            ours.sort()
            if [l for l, _ in ours] != [l for l, _ in auto]:
                problems.append(f"labels: dynkit {ours}, AUTO-07p {auto}")
            else:
                for (l, v), (_, w) in zip(ours, auto):
                    if not abs(v - w) <= 1e-6 * max(1.0, abs(w)):
                        problems.append(f"{l}: dynkit {v!r}, AUTO-07p {w!r}")
            if not auto:
                problems.append("AUTO-07p found no special point: the comparison would be empty")
            # the closed forms: dynkit's labels within 1e-9 (AUTO-07p's within its 1e-6 above)
            for lab, want in pb.get("exact", {}).items():
                want = exact_values(want) if isinstance(want, str) else want
                got = [v for l, v in ours if l == lab]
                if len(got) != len(want) or not all(
                        abs(g - w) <= 1e-9 * max(1.0, abs(w)) for g, w in zip(got, want)):
                    problems.append(f"{lab} at {got}, the closed form {want!r}")
        failures += keep.settle(work, artifacts, f"continuation-auto-{name}", name, problems,
                                f"{name}: {auto} agree")

    if part in ("all", "equilibria"):
        failures += enz_check(dynkit, artifacts)
        failures += auto_maps.check(dynkit, artifacts, run_auto, fortran)  # discrete maps
    if part in ("all", "orbits"):
        failures += auto_curves.check(dynkit, artifacts, run_auto, fortran)  # two parameters
        failures += auto_cycles.check(dynkit, artifacts, run_auto, fortran)  # PD, TR
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
