"""Discrete maps in AUTO-07p (IPS = -1, its demos log and hen) and in dynkit continue (a
.ode file with x(t+1)= lines and @ meth=discrete): the labels BP, LP, PD and TR of the first
branch compared, their parameter values within 1e-6 relative (EPSS = 1e-7 here). Called by
auto_check.py, whose run_auto and fortran it uses; everything of a failed problem is kept
under ARTIFACTS/continuation-auto-map-<problem>/. The logistic map's cascade: the first
four PDs of the cycles of period 1, 2, 4, 8, each switched to at the PD before, as AUTO-07p's
demo log does."""
import json
import os
import subprocess
import tempfile

import keep

# name: parameters, states (name, start), the map's formulas (Fortran and .ode), the
# continued parameter, the first step, the range
MAPS = {
    # AUTO-07p's demo log from its start (mu = 0, x = 0) with the branch switched at the BP
    # one way (MXBF = -1): x = 0 with the BP at mu = 1, then x = 1 - 1/mu with PD at mu = 3
    "log": dict(
        pars=[("mu", 0.0)], states=[("x", 0.0)], rhs=["mu*x*(1-x)"], icp="mu", ds=0.02,
        dsmax=0.05, range=(0.0, 3.6), switch=True),
    # AUTO-07p's demo hen (x, y) -> (y, alpha - beta x - y^2) in alpha at beta = 0 (its fourth
    # run, but on past the fold): PD at alpha = 3/4, LP at alpha = -1/4
    "hen_alpha": dict(
        pars=[("alpha", 2.0), ("beta", 0.0)], states=[("x", 1.0), ("y", 1.0)],
        rhs=["y", "alpha-beta*x-y**2"], icp="alpha", ds=-0.02, dsmax=0.1, range=(-0.5, 3.0)),
    # its first run, in beta at alpha = 2: PD at beta = sqrt(8/3) - 1, the Neimark-Sacker
    # point (TR) at beta = 1
    "hen_beta": dict(
        pars=[("alpha", 2.0), ("beta", 0.0)], states=[("x", 1.0), ("y", 1.0)],
        rhs=["y", "alpha-beta*x-y**2"], icp="beta", ds=0.02, dsmax=0.1, range=(0.0, 1.5)),
    # the delayed logistic map: TR at r = 2
    "delayed_logistic": dict(
        pars=[("r", 1.5)], states=[("x", 1.0 / 3.0), ("y", 1.0 / 3.0)],
        rhs=["r*x*(1-y)", "x"], icp="r", ds=0.02, dsmax=0.1, range=(1.1, 2.5)),
}

LABELS = ("BP", "LP", "PD", "TR")

RUN = """r = run(e='pb', c='pb')
for p in r():
    if p['TY name'] in %r:
        print('LABEL', p['TY name'], repr(p['%s']))
"""


def constants(pb):
    pn = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(pb["pars"]))
    un = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(pb["states"]))
    lo, hi = pb["range"]
    return "\n".join([
        f"parnames = {{{pn}}}", f"unames = {{{un}}}",
        f"NDIM={len(pb['states'])}, IPS=-1, IRS=0, ILP=1", f"ICP=['{pb['icp']}']",
        "NTST=15, NCOL=4, IAD=3, ISP=1, ISW=1, IPLT=0, NBC=0, NINT=0",
        f"NMX=400, NPR=1000, MXBF={-1 if pb.get('switch') else 0}, IID=0, ITMX=8, ITNW=7, "
        "NWTN=3, JAC=0",
        "EPSL=1e-9, EPSU=1e-9, EPSS=1e-7",
        f"DS={pb['ds']}, DSMIN=0.001, DSMAX={pb['dsmax']}, IADS=1",
        "THL={}, THU={}", f"UZSTOP={{'{pb['icp']}': [{lo}, {hi}]}}", ""])


def ode(pb):
    lines = ["par " + ", ".join(f"{n}={v!r}" for n, v in pb["pars"]),
             "init " + ", ".join(f"{n}={v!r}" for n, v in pb["states"])]
    lines += [f"{n}(t+1)={r.replace('**', '^')}" for (n, _), r in zip(pb["states"], pb["rhs"])]
    lo, hi = pb["range"]
    lines += ["@ meth=discrete",
              f"@ ds={pb['ds']}, dsmin=0.001, dsmax={pb['dsmax']}, nmax=400, parmin={lo}, "
              f"parmax={hi}", "done", ""]
    return "\n".join(lines)


def near(v, w):
    return abs(v - w) <= 1e-6 * max(1.0, abs(w))


# the logistic map's period-doubling cascade: AUTO-07p's demo log switches at each PD to the
# cycles of twice the period (ISW = -1), four times here; dynkit follows every PD the same
# way: the first PD of the branches of period 1, 2, 4, 8 compared
CASCADE = dict(pars=[("mu", 2.5)], states=[("x", 0.6)], rhs=["mu*x*(1-x)"], icp="mu",
               ds=0.001, dsmax=0.02, range=(2.0, 3.6))
RUN_CASCADE = """r = run(e='pb', c='pb', DSMIN=0.0001)
for i in range(4):
    p = r('PD1')
    print('LABEL', 'PD', repr(p['mu']))
    r = run(p, ISW=-1, SP=['BP0'])
"""


def cascade(dynkit, artifacts, run_auto, fortran):
    work = tempfile.mkdtemp(prefix="auto-map-cascade-")
    pb = CASCADE
    a = run_auto(work, (("pb.f90", fortran(pb)), ("c.pb", constants(pb)),
                        ("run.auto", RUN_CASCADE), ("cascade.ode", ode(pb))))
    auto = [float(l.split()[2]) for l in a.stdout.splitlines() if l.startswith("LABEL ")]
    d = subprocess.run([dynkit, "continue", "cascade.ode", "--par", "mu", "--json"], cwd=work,
                       capture_output=True, text=True)
    with open(os.path.join(work, "dynkit.json"), "w") as f:
        f.write(d.stdout + d.stderr)
    problems = []
    if d.returncode != 0 or a.returncode != 0 or len(auto) != 4:
        problems.append(f"exit statuses: dynkit {d.returncode}, auto-07p {a.returncode}; "
                        f"AUTO-07p's PDs {auto}")
    else:
        ours = []
        for period in (1, 2, 4, 8):
            pds = [p["mu"] for b in json.loads(d.stdout)["branches"] for k, p in
                   enumerate(b["points"]) if p["label"] == "PD" and p["period"] == period
                   and k > 0]
            ours.append(pds[0] if pds else None)
        if not all(v is not None and near(v, w) for v, w in zip(ours, auto)):
            problems.append(f"the cascade's PDs: dynkit {ours}, AUTO-07p {auto}")
    return keep.settle(work, artifacts, "continuation-auto-map-cascade", "map cascade",
                       problems, f"map cascade: {auto} agree")


def check(dynkit, artifacts, run_auto, fortran):
    failures = cascade(dynkit, artifacts, run_auto, fortran)
    for name, pb in MAPS.items():
        work = tempfile.mkdtemp(prefix=f"auto-map-{name}-")
        a = run_auto(work, (("pb.f90", fortran(pb)), ("c.pb", constants(pb)),
                            ("run.auto", RUN % (LABELS, pb["icp"])), (f"{name}.ode", ode(pb))))
        auto = sorted((l.split()[1], float(l.split()[2])) for l in a.stdout.splitlines()
                      if l.startswith("LABEL "))
        d = subprocess.run([dynkit, "continue", f"{name}.ode", "--par", pb["icp"], "--json"],
                           cwd=work, capture_output=True, text=True)
        with open(os.path.join(work, "dynkit.json"), "w") as f:
            f.write(d.stdout + d.stderr)
        problems = []
        if d.returncode != 0 or a.returncode != 0:
            problems.append(f"exit statuses: dynkit {d.returncode}, auto-07p {a.returncode}")
        else:
            branches = json.loads(d.stdout)["branches"]
            # AUTO-07p's branches: the first, and with MXBF = -1 the one switched to at its
            # BP one way, the way dynkit's last branch from the BP goes (up in mu)
            use = [branches[0]]
            if pb.get("switch"):
                use += [b for b in branches if b["parent"] == branches[0]["branch"]][-1:]
            ours = []
            for b in use:
                ours += [(p["label"], p[pb["icp"]]) for p in b["points"]
                         if p["label"] in LABELS]
            # the BP once (it starts the switched branch)
            ours = sorted(set((l, round(v, 10)) for l, v in ours))
            auto = sorted(set((l, round(v, 10)) for l, v in auto))
            if [l for l, _ in ours] != [l for l, _ in auto] or not all(
                    near(v, w) for (_, v), (_, w) in zip(ours, auto)):
                problems.append(f"labels: dynkit {ours}, AUTO-07p {auto}")
            if not auto:
                problems.append("AUTO-07p found no special point: the comparison would be empty")
        failures += keep.settle(work, artifacts, f"continuation-auto-map-{name}", f"map {name}",
                                problems, f"map {name}: {auto} agree")
    return failures
