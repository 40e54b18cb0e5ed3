#!/usr/bin/env python3
"""Branch points of periodic orbits (BP on a periodic branch, docs/analysis.md "Periodic
orbits") and the switch onto the other family of cycles there.

Closed forms (models/cycle_pitchfork.ode, cycle_transcritical.ode; c = 0.5 and, with
--set, c = 0.3): r' = r (mu - r^2), theta' = 1 in Cartesian form with z' = (mu - c) z - z^3
or (mu - c) z - z^2. The cycles r = sqrt(mu), z = 0 from the Hopf point mu = 0 have the
multiplier exp(2 pi (mu - c)), through 1 at mu = c: one BP there (within 1e-8), no LPC,
and the branches switched to hold z^2 = mu - c (pitchfork: z = +-sqrt(mu - c), one each
way) or z = mu - c (transcritical: one branch above c, one below it to the Hopf point
mu = 0 of the equilibria z = mu - c, where it ends within 0.01), with r = sqrt(mu) and
period 2 pi at every point (1e-8).

AUTO-07p (part "auto"): its demo tor (models/tor.ode, the demo's constants c.tor) run as
the demo's tor.auto does: the cycles from the Hopf point to their first BP, then from the
BP with ISW = -1 to the switched branch's TR and PD. The same labels (AUTO-07p's LP is
dynkit's LPC), the parameter and period within 1e-6 on the first branch and on both of
dynkit's switched branches (the two directions: mirror images, the system being odd).

Usage: cycle_bp.py DYNKIT MODELS ARTIFACTS [closed|auto]. A failed case's files are kept
under ARTIFACTS/continuation-cycle-bp-<case>/."""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import keep

HERE = os.path.dirname(os.path.abspath(__file__))


def near(v, w, tol):
    return abs(v - w) <= tol * max(1.0, abs(w))


def run_dynkit(dynkit, work, model, args):
    d = subprocess.run([dynkit, "continue", model, "--par", args[0], "--json", *args[1:]],
                       cwd=work, capture_output=True, text=True)
    with open(os.path.join(work, "dynkit.json"), "w") as f:
        f.write(d.stdout + d.stderr)
    if d.returncode != 0:
        return None, [f"dynkit's exit status {d.returncode}: {d.stderr.strip()[-300:]}"]
    return json.loads(d.stdout)["branches"], []


def closed_form(dynkit, models, kind, c):
    """the cycles of cycle_<kind>.ode at c: their BP and the switched branches"""
    work = tempfile.mkdtemp(prefix=f"cycle-bp-{kind}-")
    model = f"cycle_{kind}.ode"
    shutil.copy(os.path.join(models, model), work)
    branches, problems = run_dynkit(dynkit, work, model, ["mu", "--set", f"c={c!r}"])
    if branches is None:
        return work, problems, ""
    cycles = next(b for b in branches if b["kind"] == "periodic" and b["parent"] == 1)
    labels = [(p["label"], p["mu"]) for p in cycles["points"] if p["label"] not in ("", "EP")]
    if [l for l, _ in labels] != ["BP"] or not near(labels[0][1], c, 1e-8):
        problems.append(f"the cycles from the Hopf point: labels {labels}, a BP at mu = {c} "
                        "alone expected")
        return work, problems, ""
    k = next(i for i, p in enumerate(cycles["points"]) if p["label"] == "BP")
    switched = [b for b in branches if b["parent"] == cycles["branch"] and
                b["parent_point"] == k]
    if len(switched) != 2:
        problems.append(f"{len(switched)} branches switched to at the BP, 2 expected")
    sides = []
    for b in switched:
        pts = b["points"]
        if b["stop"].startswith("the orbit shrank"):
            pts = pts[:-1]  # located where the oscillation vanishes, or the point before
            if not abs(b["points"][-1]["mu"]) <= 0.01:
                problems.append(f"branch {b['branch']} ends at mu = {b['points'][-1]['mu']}, "
                                "not at the Hopf point mu = 0")
        z = [p["max"]["z"] for p in pts]
        want = [(math.sqrt(max(p["mu"] - c, 0.0)) if kind == "pitchfork" else p["mu"] - c)
                for p in pts]
        if kind == "pitchfork" and z[-1] < 0:
            want = [-w for w in want]
        worst = max(max(abs(p["max"]["z"] - w), abs(p["min"]["z"] - w),
                        abs(p["max"]["x"] - math.sqrt(p["mu"])),
                        abs(p["period"] - 2 * math.pi))
                    for p, w in zip(pts, want))
        if not worst <= 1e-8 or len(pts) < 5:
            problems.append(f"branch {b['branch']}: {len(pts)} points, off the closed form by "
                            f"{worst:.3g}")
        sides.append(1 if (z[-1] if kind == "pitchfork" else pts[-1]["mu"] - c) > 0 else -1)
    if sorted(sides) != [-1, 1]:
        problems.append(f"the switched branches go to the sides {sides}, one each way "
                        "expected")
    return work, problems, f"{kind} c = {c}: BP at {labels[0][1]!r}, switched branches on " \
                           "the closed form"


RUN_TOR = """r1 = run(e='pb', c='pb')
r2 = run(r1('HB1'), IPS=2, ICP=['rn', 11])
r3 = run(r2('BP1'), ISW=-1, NMX=90)
for k, r in ((2, r2), (3, r3)):
    for p in r():
        if p['TY'] in ('LP', 'BP', 'PD', 'TR'):
            print('LABEL', k, p['TY'], repr(p['rn']), repr(p['PAR(11)']))
"""
# the demo's c.tor (JAC = 0: the equations alone are written)
TOR_CONSTANTS = """parnames = {1: 'rn', 2: 'be', 3: 'ga', 4: 'r', 5: 'a3', 6: 'b3'}
unames = {1: 'x', 2: 'y', 3: 'z'}
NDIM=3, IPS=1, IRS=0, ILP=1
ICP=['rn']
NTST=25, NCOL=4, IAD=3, ISP=2, ISW=1, IPLT=0, NBC=0, NINT=0
NMX=125, NPR=500, MXBF=10, IID=0, ITMX=8, ITNW=5, NWTN=3, JAC=0
EPSL=1e-07, EPSU=1e-07, EPSS=1e-05
DS=0.001, DSMIN=0.00001, DSMAX=0.01, IADS=1
NPAR=11, THL={11: 0.0}, THU={}
UZSTOP={'rn': [-0.9, -0.4]}
"""


def upto(labels, last):
    """labels up to and including the first `last`"""
    out = []
    for x in labels:
        out.append(x)
        if x[0] == last:
            break
    return out


def same(what, ours, theirs, problems):
    if [l for l, _, _ in ours] != [l for l, _, _ in theirs] or not all(
            near(v, w, 1e-6) and near(t, u, 1e-6) for (_, v, t), (_, w, u) in
            zip(ours, theirs)):
        problems.append(f"{what}: dynkit {ours}, AUTO-07p {theirs}")


def tor_auto(dynkit, models):
    sys.path.insert(0, HERE)
    import auto_check  # its Fortran writer, its batch runner and the demo's equations
    work = tempfile.mkdtemp(prefix="cycle-bp-tor-")
    shutil.copy(os.path.join(models, "tor.ode"), work)
    a = auto_check.run_auto(work, (("pb.f90", auto_check.fortran(auto_check.PROBLEMS["tor"])),
                                   ("c.pb", TOR_CONSTANTS), ("run.auto", RUN_TOR)))
    if a.returncode != 0:
        return work, [f"auto-07p's exit status {a.returncode}"], ""
    auto = {2: [], 3: []}
    for l in a.stdout.splitlines():
        if l.startswith("LABEL "):
            k, lab, v, t = l.split()[1:]
            auto[int(k)].append(("LPC" if lab == "LP" else lab, float(v), float(t)))
    branches, problems = run_dynkit(dynkit, work, "tor.ode", ["rn"])
    if branches is None:
        return work, problems, ""
    cycles = next(b for b in branches if b["kind"] == "periodic" and b["parent"] == 1)
    ours = upto([(p["label"], p["rn"], p["period"]) for p in cycles["points"]
                 if p["label"] in ("LPC", "BP", "PD", "TR")], "BP")
    same("the cycles from the Hopf point", ours, upto(auto[2], "BP"), problems)
    if not ours or ours[-1][0] != "BP":
        return work, problems + ["no BP on the cycles from the Hopf point"], ""
    k = next(i for i, p in enumerate(cycles["points"]) if p["label"] == "BP")
    switched = [b for b in branches if b["parent"] == cycles["branch"] and
                b["parent_point"] == k]
    if len(switched) != 2:
        problems.append(f"{len(switched)} branches switched to at the BP, 2 expected")
    theirs = upto(auto[3], "PD")
    for b in switched:
        mine = upto([(p["label"], p["rn"], p["period"]) for p in b["points"]
                     if p["label"] in ("LPC", "BP", "PD", "TR")], "PD")
        same(f"the switched branch {b['branch']}", mine, theirs, problems)
    if len(theirs) < 2:
        problems.append(f"AUTO-07p's switched branch: {auto[3]}, a TR and a PD expected")
    return work, problems, f"tor: {ours} and switched {theirs} agree with AUTO-07p"


def main():
    dynkit, models = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    artifacts = os.path.abspath(sys.argv[3])
    part = sys.argv[4] if len(sys.argv) > 4 else "closed"
    failures = []
    if part == "auto":
        if not shutil.which("auto-07p") or not shutil.which("gfortran"):
            print("skipped: auto-07p or gfortran is not installed (scripts/install-deps.sh)")
            sys.exit(77)
        work, problems, agreed = tor_auto(dynkit, models)
        failures += keep.settle(work, artifacts, "continuation-cycle-bp-tor", "tor", problems,
                                agreed)
    else:
        for kind in ("pitchfork", "transcritical"):
            for c in (0.5, 0.3):
                work, problems, agreed = closed_form(dynkit, models, kind, c)
                failures += keep.settle(work, artifacts, f"continuation-cycle-bp-{kind}-{c}",
                                        f"{kind} c = {c}", problems, agreed)
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
