#!/usr/bin/env python3
"""dynkit continue against AUTO-07p: the same problems in both programs (an AUTO equations
file and constants file written here from the same formulas as the .ode file), the labels
LP, HB and BP of the equilibrium branch compared, and their parameter values within AUTO's
own accuracy (EPSS = 1e-7 here: 1e-6 relative). Everything of a failed problem is kept
under ARTIFACTS/<problem>/. Exit 77 (skipped) when auto-07p or gfortran is missing.
Usage: auto_check.py DYNKIT ARTIFACTS"""
import json
import os
import shutil
import subprocess
import sys
import tempfile


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
}


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
    failures = []
    for name, pb in PROBLEMS.items():
        work = tempfile.mkdtemp(prefix=f"auto-{name}-")
        for fname, text in (("pb.f90", fortran(pb)), ("c.pb", constants(pb)),
                            ("run.auto", RUN_AUTO % pb["icp"]), (f"{name}.ode", ode(pb))):
            with open(os.path.join(work, fname), "w") as f:
                f.write(text)
        problems = []
        a = subprocess.run(["auto-07p", "run.auto"], cwd=work, capture_output=True, text=True,
                           timeout=600)
        with open(os.path.join(work, "auto.out"), "w") as f:
            f.write(a.stdout + a.stderr)
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
        if problems:
            dest = os.path.join(artifacts, f"continuation-auto-{name}")
            shutil.rmtree(dest, ignore_errors=True)
            os.makedirs(artifacts, exist_ok=True)
            shutil.copytree(work, dest)
            failures += [f"{name}: {p} (kept in {dest})" for p in problems]
        else:
            print(f"{name}: {auto} agree")
        shutil.rmtree(work, ignore_errors=True)

    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
