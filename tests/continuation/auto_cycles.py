#!/usr/bin/env python3
"""Periodic orbits of dynkit continue against AUTO-07p: Morris-Lecar's classes II and I and
Sel'kov's glycolysis (their Hopf points, folds of cycles, and the cycles from the first
Hopf point ended at the second where there is one; Sel'kov's Hopf points in closed form);
the torus bifurcation (TR) on the
cycles of Langford's system (tests/continuation/models/langford.ode), where with eta = 0
it has a closed form, and with eta = 0.1 (Aizawa's attractor) where it has none; the
period doublings of Chua's circuit (chua.ode, AUTO-07p's demo chu from an outer
equilibrium): the PD on the cycles from the Hopf point, and on the branch switched to there
(AUTO-07p: ISW = -1) its first PD and its folds. The values agree within 1e-6 (NTST 100 for
Chua: with 50 both programs are 1e-6 from the shooting values, on either side); dynkit
also reports a PD next to each of the doubled branch's two folds, which AUTO-07p does
not (shooting with SciPy: a real multiplier through -1 there, docs/analysis.md). Called by
auto_check.py, whose run_auto and fortran it uses; a failed problem's files are kept under
ARTIFACTS/continuation-auto-cycles-<problem>/."""
import json
import math
import os
import shutil
import subprocess
import tempfile

import keep

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "models")
A, B, E = 0.95, 0.7, 0.25  # langford.ode's a, b, e
# |s| smoothed as 2 s atan(k s)/pi, as in chua.ode
CHUA_H = ("a1*x+0.5d0*(a0-a1)*(2*(x+1)*atan(k*(x+1))-2*(x-1)*atan(k*(x-1)))"
          "/(4*atan(1d0))")

# name: the .ode file, the same model for AUTO-07p, the continued parameter, its window,
# the collocation mesh, the steps; the runs: dynkit's extra arguments, AUTO-07p's changes
# to the start, what is known exactly
CASES = {
    "langford": dict(
        ode="langford.ode", icp="c", range=(-0.6, 2.0), ntst=20, nmx=400, nmx1=400,
        eq_ds=-0.01, ds=0.01, dsmax=0.05,
        pars=[("c", -0.43333333333333335), ("a", A), ("b", B), ("w", 3.5), ("e", E),
              ("eta", 0.0)],
        states=[("x", 0.0), ("y", 0.0), ("z", 0.5)],
        rhs=["(z-b)*x-w*y", "w*x+(z-b)*y", "c+a*z-z**3/3-(x**2+y**2)*(1+e*z)+eta*z*x**3"],
        runs=[dict(args=[], exact={"HB": B ** 3 / 3 - A * B,
                                   "TR": (A - B * B) * (1 + E * B) / E - A * B + B ** 3 / 3},
                   period=2 * math.pi / 3.5),
              dict(args=["--set", "eta=0.1"], start="PAR={'eta': 0.1}")]),
    # Morris-Lecar's classes II and I (PAR(11) is AUTO-07p's period: the parameters after
    # the tenth move up by three); AUTO-07p's cycles go on through the second Hopf point (a
    # BP there) and back, dynkit's end there
    "morris_lecar": dict(
        ode="morris_lecar.ode", icp="i", range=(-100.0, 300.0), ntst=60, nmx=300, nmx1=300,
        eq_ds=0.1, ds=0.5, dsmax=2.0, upto_bp=True,
        pars=[("i", 0.0), ("cm", 20.0), ("gca", 4.4), ("gk", 8.0), ("gl", 2.0),
              ("vca", 120.0), ("vk", -84.0), ("vl", -60.0), ("v1", -1.2), ("v2", 18.0),
              ("unused11", 0.0), ("unused12", 0.0), ("unused13", 0.0), ("v3", 2.0),
              ("v4", 30.0), ("phi", 0.04)],
        states=[("v", -60.85538223230949), ("w", 0.014915024953999372)],
        rhs=["(i-gl*(v-vl)-gca*0.5d0*(1+tanh((v-v1)/v2))*(v-vca)-gk*w*(v-vk))/cm",
             "phi*(0.5d0*(1+tanh((v-v3)/v4))-w)*cosh((v-v3)/(2*v4))"],
        runs=[dict(args=[], hopf_end=True),
              dict(args=["--set", "gca=4", "--set", "v3=12", "--set", "v4=17.4", "--set",
                         "phi=0.0666666666666667", "--init", "v=-59.47399786678871", "--init",
                         "w=0.00027038262491296935"],
                   start="PAR={'gca': 4.0, 'v3': 12.0, 'v4': 17.4, 'phi': 0.0666666666666667}, "
                         "U={'v': -59.47399786678871, 'w': 0.00027038262491296935}",
                   nmx1=60)]),
    "selkov": dict(
        ode="selkov.ode", icp="b", range=(0.1, 1.2), ntst=40, nmx=300, nmx1=300, eq_ds=0.01,
        ds=0.01, dsmax=0.1, upto_bp=True, pars=[("b", 0.1), ("a", 0.08)],
        states=[("x", 0.1), ("y", 1.1111111111111112)],
        rhs=["-x+a*y+x**2*y", "b-a*y-x**2*y"],
        runs=[dict(args=[], hopf_end=True,
                   exact={"HB": [math.sqrt((1 - 0.16 - math.sqrt(1 - 0.64)) / 2),
                                 math.sqrt((1 - 0.16 + math.sqrt(1 - 0.64)) / 2)]})]),
    # the first periodic run of AUTO-07p to its PD only (point 30 of 35), the doubled
    # branch to its second fold (point 55 of 60)
    "chua": dict(
        ode="chua.ode", icp="alpha", range=(5.0, 12.0), ntst=100, nmx=60, nmx1=35,
        eq_ds=0.01, ds=0.01, dsmax=0.1, switch=True,
        pars=[("alpha", 5.0), ("beta", 14.3), ("k", 10.0), ("a0", -1 / 7), ("a1", 2 / 7)],
        states=[("x", 1.4994022335769977), ("y", 0.0), ("z", -1.4994022335769977)],
        rhs=[f"alpha*(y-({CHUA_H}))", "x-y+z", "-beta*y"], runs=[dict(args=[])]),
    # the cycles from a subcritical Hopf point of a small frequency (period 148): started
    # with the file's dsmin = 0.001, their period at k = 0.05825 (UZ)
    "gray_scott": dict(
        ode="gray_scott.ode", icp="k", range=(0.0, 0.2), ntst=40, nmx=100, nmx1=100,
        eq_ds=0.002, ds=0.002, dsmax=0.005, at=[0.05825], pars=[("k", 0.05), ("ff", 0.04)],
        states=[("x", 0.2820550528229663), ("y", 0.3190866431897928)],
        rhs=["ff*(1-x)-x*y**2", "x*y**2-(ff+k)*y"], runs=[dict(args=[])]),
}

RUN_AUTO = """r = run(e='pb', c='pb'%(start)s)
for p in r('HB'):
    print('LABEL', %(k)d, 'EQ HB', repr(p['%(icp)s']), 0)
ps = run(r('HB')[0], IPS=2, ICP=['%(icp)s', 11], NMX=%(nmx1)d, DS=%(ds)r, DSMAX=%(dsmax)r)
for p in ps():
    if p['TY'] in ('LP', 'PD', 'TR', 'BP') or (p['TY'] == 'UZ' and %(at)r):
        print('LABEL', %(k)d, 'PO', p['TY'], repr(p['%(icp)s']), repr(p['PAR(11)']))
if %(switch)r:
    d = run(ps('PD')[0], ISW=-1, NMX=%(nmx)d, DS=%(ds)r, DSMAX=%(dsmax)r)
    for p in d():
        if p['TY'] in ('LP', 'PD', 'TR'):
            print('LABEL', %(k)d, 'P2', p['TY'], repr(p['%(icp)s']), repr(p['PAR(11)']))
"""


def constants(cs):
    pn = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(cs["pars"])
                   if not n.startswith("unused"))
    un = ", ".join(f"{i + 1}: '{n}'" for i, (n, _) in enumerate(cs["states"]))
    lo, hi = cs["range"]
    return "\n".join([
        f"parnames = {{{pn}}}", f"unames = {{{un}}}",
        f"NDIM={len(cs['states'])}, IPS=1, IRS=0, ILP=1", f"ICP=['{cs['icp']}']",
        f"NTST={cs['ntst']}, NCOL=4, IAD=3, ISP=2, ISW=1, IPLT=0, NBC=0, NINT=0",
        "NMX=400, NPR=100000, MXBF=0, IID=0, ITMX=8, ITNW=7, NWTN=3, JAC=0",
        "EPSL=1e-9, EPSU=1e-9, EPSS=1e-7",
        f"DS={cs['eq_ds']}, DSMIN=1e-4, DSMAX={cs['dsmax']}, IADS=1", "THL={}, THU={}",
        f"UZSTOP={{'{cs['icp']}': [{lo}, {hi}]}}",
        f"UZR={{'{cs['icp']}': {cs['at']}}}" if cs.get("at") else "UZR={}", ""])


def near(v, w, tol=1e-6):
    return abs(v - w) <= tol * max(1.0, abs(w))


def same(what, ours, theirs, problems):
    """the same labels in the same order along the branch, the values within 1e-6"""
    if [l for l, _, _ in ours] != [l for l, _, _ in theirs] or not all(
            near(v, w) and near(t, u) for (_, v, t), (_, w, u) in zip(ours, theirs)):
        problems.append(f"{what}: dynkit {ours}, AUTO-07p {theirs}")


def check_case(dynkit, name, cs, run_auto, fortran):
    work = tempfile.mkdtemp(prefix=f"auto-cycles-{name}-")
    shutil.copy(os.path.join(MODELS, cs["ode"]), work)
    icp = cs["icp"]
    script = "".join(RUN_AUTO % dict(icp=icp, nmx=cs["nmx"], nmx1=rn.get("nmx1", cs["nmx1"]),
                                     ds=cs["ds"], at=bool(cs.get("at")),
                                     dsmax=cs["dsmax"], switch=cs.get("switch", False), k=k,
                                     start=", " + rn["start"] if "start" in rn else "")
                     for k, rn in enumerate(cs["runs"]))
    a = run_auto(work, (("pb.f90", fortran(cs)), ("c.pb", constants(cs)),
                        ("run.auto", script)))
    if a.returncode != 0:
        return work, [f"auto-07p's exit status {a.returncode}"], ""
    problems, summary = [], []
    for k, rn in enumerate(cs["runs"]):
        auto = {}
        for l in a.stdout.splitlines():
            if l.startswith(f"LABEL {k} "):
                where, lab, v, t = l.split()[2:]
                auto.setdefault(where, []).append(("LPC" if lab == "LP" else lab, float(v),
                                                   float(t)))
        at = ["--at", f"{icp}=" + ",".join(map(repr, cs["at"]))] if cs.get("at") else []
        d = subprocess.run([dynkit, "continue", cs["ode"], "--par", icp, "--json",
                            *rn["args"], *at], cwd=work, capture_output=True, text=True)
        with open(os.path.join(work, f"dynkit{k}.json"), "w") as f:
            f.write(d.stdout + d.stderr)
        if d.returncode != 0:
            problems.append(f"dynkit {rn['args']}: exit status {d.returncode}")
            continue
        problems += compare(cs, rn, json.loads(d.stdout)["branches"], auto, summary)
    return work, problems, f"{name}: " + "; ".join(summary)


def compare(cs, rn, branches, auto, summary):
    """dynkit's branches against AUTO-07p's labels of one run"""
    icp, problems = cs["icp"], []
    hb = [(p["label"], p[icp], 0.0) for p in branches[0]["points"] if p["label"] == "HB"]
    same("HB", hb, auto.get("EQ", []), problems)
    cycles = next((b for b in branches if b["kind"] == "periodic" and b["parent"] == 1), None)
    if cycles is None:
        return problems + ["no periodic branch from the first Hopf point"]
    po = [(p["label"], p[icp], p["period"]) for p in cycles["points"]
          if p["label"] in ("LPC", "PD", "TR") or (p["label"] == "UZ" and cs.get("at"))]
    theirs = auto.get("PO", [])
    if cs.get("upto_bp"):
        # AUTO-07p's cycles go on through the second Hopf point (a BP) and back along the
        # same family: its labels up to the first that repeats one (the BP aside)
        once = []
        for x in theirs:
            if x[0] != "BP" and any(y[0] == x[0] and near(x[1], y[1]) for y in once):
                break
            once += [x] if x[0] != "BP" else []
        theirs = once
    same("the cycles from the Hopf point", po, theirs, problems)
    if rn.get("hopf_end") and not cycles["stop"].startswith("the orbit shrank to the HB at"):
        problems.append(f"the cycles from the first Hopf point stopped: {cycles['stop']}, "
                        "not at the second")
    for lab, want in rn.get("exact", {}).items():
        got = [v for l, v, _ in hb + po if l == lab]
        want = want if isinstance(want, list) else [want]
        if len(got) != len(want) or not all(near(g, x, 1e-9) for g, x in zip(got, want)):
            problems.append(f"{lab} at {got}, exactly {want!r}")
    if "period" in rn and not all(near(p["period"], rn["period"], 1e-9)
                                  for p in cycles["points"]):
        problems.append(f"a period other than 2 pi / w = {rn['period']!r}")
    summary.append(f"{rn['args']} {[(l, v) for l, v, _ in hb + po]}")
    if cs.get("switch"):
        doubled = [b for b in branches if b["parent"] == cycles["branch"]]
        ours = [(p["label"], p[icp], p["period"]) for b in doubled[:1] for p in b["points"]
                if p["label"] in ("LPC", "PD", "TR")]
        # a PD next to each fold (within 1e-4 relative in the parameter): found by dynkit
        # alone (a real multiplier through -1 by shooting); the rest label for label
        shared = [x for i, x in enumerate(ours)
                  if not (x[0] == "PD" and any(y[0] == "LPC" and near(x[1], y[1], 1e-4)
                                               for y in ours[max(i - 1, 0):i + 2]))]
        same("the doubled cycles", shared, auto.get("P2", []), problems)
        if len(ours) - len(shared) != 2:
            problems.append(f"the doubled cycles' labels {ours}: expected a PD next to "
                            "each of its two folds")
        summary.append(f"doubled {[(l, v) for l, v, _ in ours]}")
    return problems


def check(dynkit, artifacts, run_auto, fortran):
    failures = []
    for name, cs in CASES.items():
        work, problems, summary = check_case(dynkit, name, cs, run_auto, fortran)
        failures += keep.settle(work, artifacts, f"continuation-auto-cycles-{name}", name,
                                problems, f"{summary} agree")
    return failures
