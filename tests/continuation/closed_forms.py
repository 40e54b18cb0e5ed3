#!/usr/bin/env python3
"""dynkit continue against closed forms (docs/analysis.md, "Continuation"): the normal forms
of the fold (LP at p = 0), the transcritical and pitchfork bifurcations (BP at p = 0, the
other branch x = p or x^2 = p followed), two branches crossing at a small angle (x = p and
x = b p, the other one followed from the BP), the Hopf bifurcation (HB at p = 0 with frequency w
and first Lyapunov coefficient 2 s / w, Kuznetsov's formula with <q, q> = 1), the
Brusselator (HB at b = 1 + a^2, omega = a) and Lorenz's system (HB at
rho = sigma (sigma + beta + 3) / (sigma - beta - 1), subcritical); in two parameters the
normal forms of the cusp (folds on 27 a^2 = 4 b^3, CP at 0), of the Bogdanov-Takens point
(folds on b1 = 0, Hopf points on b1 = -b2^2, BT at 0 on both) and of the generalized Hopf
point (Hopf points on b1 = 0 with l1 = 2 b2, GH at b2 = 0), also moved off the origin; the
default window widened to contain the start, and a window given that excludes it refused;
and the orbits the diagram's page holds, on the Hopf normal form's circles x^2 + y^2 = p of
period 2 pi / w; the subcritical Hopf point of bautin.ode at b2 = 1 (LPC at b1 = -1/4,
UZ on the periodic branch on both sides of the fold, radius and period 2 pi exact); the
cycles of hopf_pair.ode from one Hopf point to the other, ended there and computed once; the
multipliers at TR and PD on Roessler's cycles in c (no TR where a real pair turns complex); no
PD, TR or fold of cycles on the CSTR's cycles (a planar flow, cstr.ode). Usage:
closed_forms.py DYNKIT MODELS_DIR LORENZ_ODE BT_ODE"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

dynkit, models, lorenz, bt_model = sys.argv[1:5]
failures = []
tmp = tempfile.mkdtemp(prefix="dynkit-continue-")


def run(path, *args):
    cmd = [dynkit, "continue", path, "--json", *args]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        failures.append(f"{' '.join(cmd)}: exit {out.returncode}: {out.stderr.strip()}")
        return None
    return json.loads(out.stdout)


def points(d, label):
    return [(b, p) for b in d["branches"] for p in b["points"] if p["label"] == label]


def check(what, got, want, tol):
    if not abs(got - want) <= tol * max(1.0, abs(want)):
        failures.append(f"{what}: {got!r}, expected {want!r} (tolerance {tol:g} relative)")


def only(d, label, what):
    pts = points(d, label) if d else []
    if len({round(p[1][d['parameters'][0]], 8) for p in pts}) != 1:
        failures.append(f"{what}: expected one {label}, found {len(pts)}")
        return None
    return pts[0][1]


d = run(f"{models}/fold.ode", "--par", "p")
p = only(d, "LP", "fold")
if p:
    check("fold: p at LP", p["p"], 0.0, 1e-10)
    check("fold: x at LP", p["state"]["x"], 0.0, 1e-6)

for name, residual in (("transcritical", lambda x, p: x - p), ("pitchfork", lambda x, p: x * x - p)):
    d = run(f"{models}/{name}.ode", "--par", "p")
    p = only(d, "BP", name)
    if p:
        check(f"{name}: p at BP", p["p"], 0.0, 1e-10)
        # the switched branches: every point on x = p (or x^2 = p), x != 0 somewhere
        switched = [b for b in d["branches"] if b["parent"] is not None]
        if len(switched) != 2:
            failures.append(f"{name}: expected two switched branches, found {len(switched)}")
        for b in switched:
            for q in b["points"]:
                x, pv = q["state"]["x"], q["p"]
                if not abs(residual(x, pv)) <= 1e-8:
                    failures.append(f"{name}: branch {b['branch']} point x = {x} at p = {pv}")
                    break

# two branches crossing at a small angle (small_angle.ode: x = p and x = b p, about 0.046
# rad apart at b = 1.1, 0.005 rad at b = 1.01): one BP at p = 0; switched both ways onto x = b p
# (every point within 1e-8, the first step from the BP at most dsmax = 0.1 long), the first
# branch on x = p
for bval in (1.1, 1.01):
    d = run(f"{models}/small_angle.ode", "--par", "p", "--set", f"b={bval}")
    p = only(d, "BP", f"small angle b={bval}")
    if p:
        check(f"small angle b={bval}: p at BP", p["p"], 0.0, 1e-10)
        first = d["branches"][0]
        if any(abs(q["state"]["x"] - q["p"]) > 1e-8 for q in first["points"]):
            failures.append(f"small angle b={bval}: the first branch leaves x = p")
        switched = [b for b in d["branches"] if b["parent"] is not None]
        if len(switched) != 2:
            failures.append(f"small angle b={bval}: expected two switched branches, found "
                            f"{len(switched)}")
        for b in switched:
            pts = b["points"]
            off = max(abs(q["state"]["x"] - bval * q["p"]) for q in pts)
            first_step = math.hypot(pts[1]["p"] - pts[0]["p"],
                                    pts[1]["state"]["x"] - pts[0]["state"]["x"])
            if not (off <= 1e-8 and first_step <= 0.1 + 1e-12 and
                    max(abs(q["p"]) for q in pts) > 0.99):
                failures.append(f"small angle b={bval}: branch {b['branch']} off x = b p by "
                                f"{off:g}, first step {first_step:g}")

# branches that touch (tangent_branches.ode): no BP where a step lands on the other branch
# x = -p^2, and the branch followed reaches x = 1 at p = 1 on x = p^2
d = run(f"{models}/tangent_branches.ode", "--par", "p")
if d:
    if points(d, "BP") or len(d["branches"]) != 1:
        failures.append(f"tangent branches: {len(points(d, 'BP'))} BP, {len(d['branches'])} "
                        f"branches (expected none and one)")
    # a step that lands on x = -p^2 changes the BP test's sign where nothing can be
    # located: it is taken again shorter, down to dsmin, and what is left is noted
    off = max(abs(q["state"]["x"] - q["p"] ** 2) for q in d["branches"][0]["points"])
    if not off <= 1e-6:
        failures.append(f"tangent branches: a point {off:g} off x = p^2")
    end = d["branches"][0]["points"][-1]
    check("tangent branches: x at the end", end["state"]["x"], 1.0, 1e-9)
    check("tangent branches: p at the end", end["p"], 1.0, 1e-9)

note = subprocess.run([dynkit, "continue", f"{models}/tangent_branches.ode", "--par", "p"],
                      capture_output=True, text=True).stderr
if "detected but not located" not in note:
    failures.append(f"tangent branches: no note of the BP test's unlocated change: {note!r}")

# a figure eight (figure_eight.ode): one branch round both loops back to its start, the
# crossing at the origin a BP (within 1e-9) each of the two times the branch passes it, with
# no second branch, both folds at p = -1, 1
d = run(f"{models}/figure_eight.ode", "--par", "p")
if d:
    b = d["branches"]
    if len(b) != 1 or not b[0]["stop"].startswith("closed: back at its first point"):
        failures.append(f"figure eight: {len(b)} branches, the first stopped "
                        f"'{b[0]['stop'] if b else ''}' (expected one, closed at its start)")
    p = only(d, "BP", "figure eight")
    if len(points(d, "BP")) != 2:
        failures.append(f"figure eight: {len(points(d, 'BP'))} BP (expected the crossing twice)")
    if p:
        check("figure eight: p at BP", p["p"], 0.0, 1e-9)
        check("figure eight: x at BP", p["state"]["x"], 0.0, 1e-9)
    folds = sorted(q["p"] for _, q in points(d, "LP"))
    if len(folds) != 2:
        failures.append(f"figure eight: folds at {folds} (expected p = -1 and 1)")
    else:
        check("figure eight: fold at p = -1", folds[0], -1.0, 1e-10)
        check("figure eight: fold at p = 1", folds[1], 1.0, 1e-10)

for s, w in ((-1.0, 2.0), (1.5, 2.0), (-0.25, 0.5)):
    d = run(f"{models}/hopf.ode", "--par", "p", "--set", f"s={s}", "--set", f"w={w}")
    p = only(d, "HB", f"hopf s={s}")
    if p:
        check(f"hopf s={s}: p at HB", p["p"], 0.0, 1e-10)
        check(f"hopf s={s}: omega", p["omega"], w, 1e-10)
        check(f"hopf s={s}: l1", p["l1"], 2 * s / w, 1e-9)

# the subcritical Hopf point with a fold of cycles (bautin.ode at b2 = 1: r' = b1 r + r^3 -
# r^5, period 2 pi): LPC at b1 = -1/4 on r^2 = 1/2, and --at on the periodic branch: at
# b1 = -0.2 one orbit on each side of the fold, r^2 = (1 -+ sqrt(1 + 4 b1)) / 2, at b1 = 0.5
# the outer one
d = run(f"{models}/bautin.ode", "--par", "b1", "--set", "b2=1", "--at", "b1=-0.2,0.5")
cycles = [p for b in (d["branches"] if d else []) if b["kind"] == "periodic"
          for p in b["points"]]
lpc = [p for p in cycles if p["label"] == "LPC"]
if len(lpc) != 1:
    failures.append(f"subcritical hopf: expected one LPC, found {len(lpc)}")
for p in lpc:
    check("subcritical hopf: b1 at LPC", p["b1"], -0.25, 1e-9)
    check("subcritical hopf: radius at LPC", p["max"]["x"], 0.5 ** 0.5, 1e-6)
uz = sorted((round(p["b1"], 9), p["max"]["x"]) for p in cycles if p["label"] == "UZ")
want = sorted([(-0.2, ((1 - 0.2 ** 0.5) / 2) ** 0.5), (-0.2, ((1 + 0.2 ** 0.5) / 2) ** 0.5),
               (0.5, ((1 + 3 ** 0.5) / 2) ** 0.5)])
if len(uz) != len(want):
    failures.append(f"subcritical hopf: UZ on the periodic branch at {uz}, expected {want}")
else:
    for (b1, r), (b1_want, r_want) in zip(uz, want):
        check("subcritical hopf: b1 at UZ", b1, b1_want, 1e-12)
        check(f"subcritical hopf: radius at UZ b1 = {b1_want}", r, r_want, 1e-6)
for p in cycles:
    check(f"subcritical hopf: period at b1 = {p['b1']}", p["period"], 2 * math.pi, 1e-9)

# a family of cycles from one Hopf point to another (hopf_pair.ode: mu = p (1 - p), Hopf
# points at p = 0 and 1, cycles x^2 + y^2 = p (1 - p)): the periodic branch ends where it
# reaches the other Hopf point, the amplitude passing through zero, without a fold of
# cycles there and without coming back along itself; the other Hopf point's cycles are
# the same family, computed once
d = run(f"{models}/hopf_pair.ode", "--par", "p")
periodic = [b for b in (d["branches"] if d else []) if b["kind"] == "periodic"]
if len(periodic) != 1:
    failures.append(f"hopf_pair: {len(periodic)} periodic branches, expected 1")
for b in periodic:
    pts = b["points"]
    start, end = pts[0]["p"], pts[-1]["p"]
    other = 1.0 if start < 0.5 else 0.0
    said = re.search(r"the cycles from HB at (\S+) are those from HB at (\S+)$", b["stop"])
    if not said or abs(float(said.group(1)) - other) > 1e-9 or \
            abs(float(said.group(2)) - (1 - other)) > 1e-9 or pts[-1]["label"] != "EP":
        failures.append(f"hopf_pair: branch {b['branch']} stopped with {b['stop']!r}, "
                        f"label {pts[-1]['label']!r}, expected at the Hopf point p = {other}")
    check(f"hopf_pair: branch {b['branch']}'s end at the Hopf point", end, other, 1e-3)
    labels = [q["label"] for q in pts[1:-1] if q["label"]]
    if labels:
        failures.append(f"hopf_pair: branch {b['branch']} has labels {labels} between its ends")
    ps = [q["p"] for q in pts]
    if any((q1 - q0) * (other - start) <= 0 for q0, q1 in zip(ps, ps[1:])):
        failures.append(f"hopf_pair: branch {b['branch']} turns back in p: {ps}")
    for q in pts[1:-1]:
        check(f"hopf_pair: radius at p = {q['p']}", q["max"]["x"] ** 2, q["p"] * (1 - q["p"]),
              1e-6)
        check(f"hopf_pair: period at p = {q['p']}", q["period"], 2 * math.pi, 1e-9)

# a torus bifurcation is a complex pair of multipliers on the unit circle, a period doubling
# a multiplier -1: on Roessler's cycles in c (roessler_c.ode) two real multipliers meet at
# c = 1.48 and go on as a complex pair of modulus 0.036, which is no TR
d = run(f"{models}/roessler_c.ode", "--par", "c")
# where the equilibria meet (c = 0.4) the Jacobian has the eigenvalues 0 and +-1.4 i: the
# HB there carries omega = 1.4 and no l1 (Kuznetsov's formula solves with the singular
# Jacobian: 5e10 was given)
zh = points(d, "HB") if d else []
if len(zh) != 1:
    failures.append(f"roessler_c: {len(zh)} HB, expected the fold-Hopf point alone")
for b, p in zh:
    check("roessler_c: c at the fold-Hopf point", p["c"], 0.4, 1e-10)
    check("roessler_c: omega at the fold-Hopf point", p["omega"], 1.4, 1e-10)
    if "l1" in p:
        failures.append(f"roessler_c: l1 = {p['l1']} at the fold-Hopf point, where it is not defined")
cycles = [q for b in (d["branches"] if d else []) if b["kind"] == "periodic" and b["parent"] == 1
          for q in b["points"]]
if not any(abs(m[1]) > 1e-3 and math.hypot(*m) < 0.1 for q in cycles for m in q["multipliers"]):
    failures.append("roessler_c: no complex pair of multipliers inside the unit circle")
for q in cycles:
    ms = q["multipliers"][1:]
    if q["label"] == "TR" and not any(abs(m[1]) > 1e-6 and abs(math.hypot(*m) - 1) < 1e-4
                                      for m in ms):
        failures.append(f"roessler_c: TR at c = {q['c']} with multipliers {ms}")
    if q["label"] == "PD" and not any(abs(m[0] + 1) < 1e-6 and m[1] == 0 for m in ms):
        failures.append(f"roessler_c: PD at c = {q['c']} with multipliers {ms}")
if [q["label"] for q in cycles if q["label"] not in ("", "EP")] != ["PD"]:
    failures.append(f"roessler_c: labels {[q['label'] for q in cycles if q['label']]}, "
                    "expected one PD between the ends")

# a planar flow has no period doubling and no torus bifurcation (its one non-trivial
# multiplier is exp(int div f dt) > 0): on the CSTR's cycles (cstr.ode, NTST 15) rounding
# of the multipliers near the homoclinic orbit (~1e6 and more) made PD labels; the cycles
# from the first, subcritical Hopf point grow to a homoclinic orbit to a saddle, which in
# the plane they approach monotonically in the parameter (Andronov-Leontovich): no fold of
# cycles either, where the parameter settles to 1e-11 while the period grows
d = run(f"{models}/cstr.ode", "--par", "d")
cycles = [b for b in (d["branches"] if d else []) if b["kind"] == "periodic"]
if len(cycles) != 2:
    failures.append(f"cstr: {len(cycles)} periodic branches, expected 2 (one per Hopf point)")
for b in cycles:
    bad = [(q["label"], q["d"]) for q in b["points"] if q["label"] in ("PD", "TR")]
    if bad:
        failures.append(f"cstr: {bad} on the cycles of a planar flow")
    if b["parent_point"] == min(c["parent_point"] for c in cycles):
        folds = [q["d"] for q in b["points"] if q["label"] == "LPC"]
        if folds or max(q["period"] for q in b["points"]) < 50:
            failures.append(f"cstr: folds {folds[:5]} on the cycles towards the homoclinic "
                            f"orbit, longest period {max(q['period'] for q in b['points'])}")

# the page's orbits (continue --output FILE.html): on the normal form's periodic branch
# (s = -1, w = 2) each orbit is the circle x^2 + y^2 = p with period 2 pi / w; the page holds
# every computed orbit (the branch is short), each at its collocation nodes (5 digits) from
# s = 0 to 1, the period exact (17 digits), and the SVG a dot per orbit at its max and min
page = f"{tmp}/hopf.html"
out = subprocess.run([dynkit, "continue", f"{models}/hopf.ode", "--par", "p", "--output", page],
                     capture_output=True, text=True)
if out.returncode != 0 or out.stdout:
    failures.append(f"hopf page: exit {out.returncode}, stdout {out.stdout[:80]!r}: {out.stderr}")
else:
    html = open(page, encoding="utf-8").read()
    start = html.index('<script id="dynkit-data" type="application/json">')
    data = json.loads(html[html.index(">", start) + 1:html.index("</script>", start)])
    d = run(f"{models}/hopf.ode", "--par", "p")
    periodic = [q for b in (d["branches"] if d else []) if b["kind"] == "periodic" for q in b["points"]]
    if not periodic or len(data["orbits"]) != len(periodic) or data["orbits_computed"] != len(periodic):
        failures.append(f"hopf page: {len(data['orbits'])} orbits on the page, "
                        f"{data['orbits_computed']} computed, {len(periodic)} periodic points")
    for o, q in zip(data["orbits"], periodic):
        check(f"hopf page: period at p = {o['par']}", o["period"], math.pi, 1e-8)
        check(f"hopf page: period against --json at p = {o['par']}", o["period"], q["period"], 1e-15)
        x, y = o["u"]
        worst = max(abs(a * a + b * b - o["par"]) for a, b in zip(x, y))
        # 5 significant digits round each x^2 and y^2 by up to 1e-4 of itself
        if not worst <= 2e-4 * max(o["par"], 1e-3):
            failures.append(f"hopf page: orbit at p = {o['par']} off the circle by {worst:g}")
        if o["s"][0] != 0 or o["s"][-1] != 1 or any(b <= a for a, b in zip(o["s"], o["s"][1:])):
            failures.append(f"hopf page: the nodes of the orbit at p = {o['par']} do not rise from 0 to 1")
    dots = data["svg"].count('class="dk-orbit"')
    if dots != 2 * len(data["orbits"]):
        failures.append(f"hopf page: {dots} dots in the picture for {len(data['orbits'])} orbits")

for a in (1.0, 1.5, 0.5):
    d = run(f"{models}/brusselator.ode", "--par", "b", "--set", f"a={a}", "--init", f"x={a}",
            "--init", f"y={1 / a}", "--set", "b=1", "--opt", "parmax=5")
    p = only(d, "HB", f"brusselator a={a}")
    if p:
        check(f"brusselator a={a}: b at HB", p["b"], 1 + a * a, 1e-10)
        check(f"brusselator a={a}: omega", p["omega"], a, 1e-10)

sigma, beta = 10.0, 8.0 / 3.0
d = run(lorenz, "--par", "rho", "--init", "x=8.5", "--init", "y=8.5", "--init", "z=27",
        "--set", "rho=28", "--set", f"beta={beta!r}", "--opt", "ds=-0.5", "--opt", "dsmax=1",
        "--opt", "parmin=1", "--opt", "parmax=40")
hb = points(d, "HB") if d else []
if not hb:
    failures.append("lorenz: no HB")
for b, p in hb:
    check("lorenz: rho at HB", p["rho"], sigma * (sigma + beta + 3) / (sigma - beta - 1), 1e-10)
    if not p.get("l1", 0) > 0:
        failures.append(f"lorenz: l1 = {p.get('l1')} at the Hopf point, expected > 0 (subcritical)")

# the default window widened to contain the start (lorenz.ode gives no parmin, parmax): from
# rho = 28 with parmin = 1 given, parmax = 28 + (28 - 1) = 55, where the branch from C+
# (down to the branch point at rho = 1, up again on C-) ends on x = y = -sqrt(beta (rho - 1))
# = -12, z = rho - 1; from rho = -3 downwards (the origin,
# the only equilibrium for rho < 1), parmin = -3 - (2 - (-3)) = -8
d = run(lorenz, "--par", "rho", "--init", "x=8.5", "--init", "y=8.5", "--init", "z=27",
        "--set", "rho=28", "--opt", "ds=-0.5", "--opt", "dsmax=1", "--opt", "parmin=1")
if d:
    check("lorenz from rho = 28: parmax", d["settings"]["parmax"], 55.0, 0.0)
    ends = [p for b, p in points(d, "EP") if p["rho"] > 54.9 and p["state"]["x"] < -1]
    if not ends:
        failures.append("lorenz from rho = 28: no EP of C- at parmax = 55")
    for p in ends:
        check("lorenz: rho at parmax", p["rho"], 55.0, 1e-12)
        check("lorenz: x of C- at rho = 55", p["state"]["x"], -(8.0 / 3.0 * 54.0) ** 0.5, 1e-9)
        check("lorenz: z of C- at rho = 55", p["state"]["z"], 54.0, 1e-9)
d = run(lorenz, "--par", "rho", "--init", "x=0", "--init", "y=0", "--init", "z=0",
        "--set", "rho=-3", "--opt", "ds=-0.5", "--opt", "dsmax=1")
if d:
    check("lorenz from rho = -3: parmin", d["settings"]["parmin"], -8.0, 0.0)
    low = [p["rho"] for b, p in points(d, "EP")]
    check("lorenz from rho = -3: the lowest EP", min(low) if low else 0.0, -8.0, 1e-12)
# a window given that excludes the start is a bad command line
out = subprocess.run([dynkit, "continue", lorenz, "--par", "rho", "--set", "rho=28",
                      "--opt", "parmax=20"], capture_output=True, text=True)
if out.returncode != 2 or "parmax from --opt" not in out.stderr:
    failures.append(f"lorenz, rho = 28 outside parmax = 20: exit {out.returncode}, "
                    f"{out.stderr.strip()!r} (expected 2 and a message naming --opt)")

# a start where the equilibria form a family (w does not enter f: every w is an equilibrium
# with z = p; f_x = [[-1, 0], [1, 0]], null vector e_w): refused, the message naming w
family = os.path.join(tmp, "family.ode")
with open(family, "w") as f:
    f.write("par p=1\ninit z=1, w=0\nz'=p-z\nw'=z-1\ndone\n")
out = subprocess.run([dynkit, "continue", family, "--par", "p"], capture_output=True, text=True)
if out.returncode == 0 or "null vector along w;" not in out.stderr:
    failures.append(f"a family of equilibria along w: exit {out.returncode}, "
                    f"{out.stderr.strip()!r} (expected a failure naming w)")

# no equilibrium near the initial state (x' = -(x^3 - 3x + p) from x = 1.5: Newton's step
# lands on f' = 0 at x = 1, where |f| has a minimum 1): the branch starts from the end of a
# run over the file's span, at the real root of x^3 - 3x + 3, with a note saying so
stall = os.path.join(tmp, "stall.ode")
with open(stall, "w") as f:
    f.write("par p=3\ninit x=1.5\nx'=-(x^3-3*x+p)\n@ total=20, parmax=6\ndone\n")
out = subprocess.run([dynkit, "continue", stall, "--par", "p", "--json"], capture_output=True,
                     text=True)
lo, hi = -3.0, -2.0  # x^3 - 3x + 3: -15 at -3, 1 at -2, its one real root between
for _ in range(200):
    mid = 0.5 * (lo + hi)
    lo, hi = (mid, hi) if mid ** 3 - 3 * mid + 3 < 0 else (lo, mid)
root = 0.5 * (lo + hi)
if out.returncode != 0 or "end of a run" not in out.stderr:
    failures.append(f"start from a run: exit {out.returncode}, {out.stderr.strip()!r}")
else:
    check("start from a run: x at p = 3",
          json.loads(out.stdout)["branches"][0]["points"][0]["state"]["x"], root, 1e-10)

# no equilibrium at all (x' = x^2 + 1 + p^2 > 0) and a run that blows up at
# t = (pi/2 - atan(1.5/sqrt(10)))/sqrt(10) = 0.3567: a failure, with a note that the run
# gave no start either
blowup = os.path.join(tmp, "blowup.ode")
with open(blowup, "w") as f:
    f.write("par p=3\ninit x=1.5\nx'=x^2+1+p^2\n@ total=20, parmax=6\ndone\n")
out = subprocess.run([dynkit, "continue", blowup, "--par", "p"], capture_output=True, text=True)
if (out.returncode == 0 or "no equilibrium found near the start" not in out.stderr
        or "a run from the initial state gives no start either" not in out.stderr):
    failures.append(f"no equilibrium, a run that blows up: exit {out.returncode}, "
                    f"{out.stderr.strip()!r} (expected a failure with a note on the run)")

# neither the initial state nor the end of a run is near an equilibrium (x' = -(x^3 - 3x + p)
# from x = 1, where f' = 0 and |f| has a minimum 1, over a span of 0.001 that leaves x
# there): the branch starts from the equilibrium that the search of dynkit equilibria finds
# in the file's window x = [-4, 4], the real root of x^3 - 3x + 3, with a note; without the
# window the default box [0, 2] holds none, and the failure says so and what to give
for window, name in ((", xp=x, xlo=-4, xhi=4", "ghost_window.ode"), ("", "ghost.ode")):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(f"par p=3\ninit x=1\nx'=-(x^3-3*x+p)\n@ total=0.001, parmax=6{window}\ndone\n")
    out = subprocess.run([dynkit, "continue", path, "--par", "p", "--json"],
                         capture_output=True, text=True)
    if window and (out.returncode != 0 or "dynkit equilibria finds" not in out.stderr):
        failures.append(f"start from the equilibria in the window: exit {out.returncode}, "
                        f"{out.stderr.strip()!r}")
    elif window:
        check("start from the equilibria in the window: x at p = 3",
              json.loads(out.stdout)["branches"][0]["points"][0]["state"]["x"], root, 1e-10)
    elif out.returncode == 0 or "finds none at p = 3 either (--init NAME=VALUE" not in out.stderr:
        failures.append(f"no equilibrium in the default box: exit {out.returncode}, "
                        f"{out.stderr.strip()!r} (expected a failure naming --init)")

# x' = sin(x) - p has no equilibrium for p = 2; from x = 1.57079632679 (cos x = 2e-11)
# Newton's first step lands at x = 2e11, where its next step is below 1e-11 |x|: such a
# start, 1e8 times farther than the guess's scale, is no equilibrium and none is reported
path = os.path.join(tmp, "runaway.ode")
with open(path, "w") as f:
    f.write("par p=2\ninit x=1.57079632679\nx'=sin(x)-p\n@ total=1\ndone\n")
out = subprocess.run([dynkit, "continue", path, "--par", "p"], capture_output=True, text=True)
if out.returncode == 0 or "ran away from the guess (x to" not in out.stderr or out.stdout:
    failures.append(f"sin(x) - 2: exit {out.returncode}, {out.stdout.strip()!r} "
                    f"{out.stderr.strip()!r} (expected a failure: Newton's method ran away)")

# curves in two parameters
d = run(f"{models}/cusp.ode", "--par", "a", "--par2", "b")
cps = points(d, "CP") if d else []
if not cps:
    failures.append("cusp: no CP")
for b, p in cps:
    check("cusp: a at CP", p["a"], 0.0, 1e-10)
    check("cusp: b at CP", p["b"], 0.0, 1e-10)
for b in (d["branches"] if d else []):
    if b["kind"] == "fold":
        for p in b["points"]:
            check("cusp: 27 a^2 - 4 b^3 on the fold curve", 27 * p["a"] ** 2 - 4 * p["b"] ** 3,
                  0.0, 1e-9)

d = run(bt_model, "--par", "b1", "--par2", "b2")
for kind in ("fold", "hopf"):
    bts = [p for b in (d["branches"] if d else []) if b["kind"] == kind
           for p in b["points"] if p["label"] == "BT"]
    if not bts:
        failures.append(f"bogdanov-takens: no BT on a {kind} curve")
    for p in bts:
        check(f"bogdanov-takens: b1 at BT ({kind})", p["b1"], 0.0, 1e-10)
        check(f"bogdanov-takens: b2 at BT ({kind})", p["b2"], 0.0, 1e-10)
for b in (d["branches"] if d else []):
    for p in b["points"]:
        if b["kind"] == "fold":
            check("bogdanov-takens: b1 on the fold curve", p["b1"], 0.0, 1e-10)
        if b["kind"] == "hopf" and p["omega2"] > 0:
            check("bogdanov-takens: b1 + b2^2 on the Hopf curve", p["b1"] + p["b2"] ** 2, 0.0,
                  1e-9)

# the generalized Hopf point, at the origin and moved off it (bautin_shifted.ode: the
# equilibrium at (1, -2), GH at b2 = 0.25); l1 = 2 (b2 - b2_GH) / omega along the Hopf curve
for name, x0, b2_gh in (("bautin", (0.0, 0.0), 0.0), ("bautin_shifted", (1.0, -2.0), 0.25)):
    d = run(f"{models}/{name}.ode", "--par", "b1", "--par2", "b2")
    ghs = points(d, "GH") if d else []
    if len(ghs) != 1:
        failures.append(f"{name}: expected one GH, found {len(ghs)}")
    for b, p in ghs:
        check(f"{name}: b1 at GH", p["b1"], 0.0, 1e-10)
        check(f"{name}: b2 at GH", p["b2"], b2_gh, 1e-10)
        check(f"{name}: x at GH", p["state"]["x"], x0[0], 1e-10)
        check(f"{name}: y at GH", p["state"]["y"], x0[1], 1e-10)
    for b in (d["branches"] if d else []):
        if b["kind"] != "hopf":
            continue
        for p in b["points"]:
            if p.get("l1") is not None:
                check(f"{name}: l1 at b2 = {p['b2']}", p["l1"], 2 * (p["b2"] - b2_gh), 1e-9)

# each curve in two parameters computed once: the cusp's fold curve goes through both folds
# of the branch in a (one curve, followed both ways from the first fold); the
# Bogdanov-Takens normal form has one fold curve and one Hopf curve; hopf_circle.ode's two
# Hopf points lie on one closed curve p^2 + q^2 = 1, followed once around and ended there
def kinds(d):
    out = {}
    for b in (d["branches"] if d else []):
        out[b["kind"]] = out.get(b["kind"], 0) + 1
    return out


for path, args, want in ((f"{models}/cusp.ode", ("--par", "a", "--par2", "b"), {"fold": 2}),
                         (bt_model, ("--par", "b1", "--par2", "b2"), {"fold": 2, "hopf": 2}),
                         (f"{models}/hopf_circle.ode", ("--par", "p", "--par2", "q"),
                          {"hopf": 1})):
    d = run(path, *args)
    got = kinds(d)
    for kind, count in want.items():
        if got.get(kind, 0) != count:
            failures.append(f"{path}: {got.get(kind, 0)} {kind} curves, expected {count}")
    if path.endswith("hopf_circle.ode"):
        for b in (d["branches"] if d else []):
            if b["kind"] != "hopf":
                continue
            if not b["stop"].startswith("closed"):
                failures.append(f"hopf_circle: the Hopf curve stopped: {b['stop']}")
            qs = [p["q"] for p in b["points"]]
            if not (min(qs) < -0.99 and max(qs) > 0.99):
                failures.append(f"hopf_circle: q spans [{min(qs)}, {max(qs)}], not the circle")
            for p in b["points"]:
                check("hopf_circle: p^2 + q^2 on the Hopf curve", p["p"] ** 2 + p["q"] ** 2,
                      1.0, 1e-9)
            first, last = b["points"][0], b["points"][-1]
            check("hopf_circle: the curve closed (p)", last["p"], first["p"], 1e-12)
            check("hopf_circle: the curve closed (q)", last["q"], first["q"], 1e-12)

# van der Pol's linear centre: from the file's initial state (2, 0), not an equilibrium,
# the start is found (the origin) and the branch followed down through the Hopf point at
# mu = 0, where every circle y1^2 + y2^2 = r^2 is an orbit of period 2 pi: the periodic
# branch from it stays at mu = 0 with that period, and rounding on it makes no fold (LPC).
# The family of van der Pol's limit cycles crosses it at the circle r = 2 (averaging: the
# limit cycle tends to it as mu -> 0): one BP there, and the two branches switched to are
# those limit cycles, their period at mu = -1 van der Pol's at mu = 1 (time reversed),
# 6.6632868593231 (SciPy, docs/analysis.md "Boundary-value problems"), within 1e-6
vdp = os.path.join(os.path.dirname(lorenz), "vanderpol.ode")
d = run(vdp, "--par", "mu", "--opt", "ds=-0.02", "--opt", "parmin=-1", "--opt", "nmax=60")
p = only(d, "HB", "van der Pol")
if p:
    check("van der Pol: mu at HB", p["mu"], 0.0, 1e-10)
circles = [b for b in (d["branches"] if d else []) if b["kind"] == "periodic" and
           b["parent"] == 1]
for b in circles:
    if any(q["label"] == "LPC" for q in b["points"]):
        failures.append("van der Pol: an LPC on the linear centre's vertical branch")
    for q in b["points"]:
        check("van der Pol: mu on the periodic branch", q["mu"], 0.0, 1e-9)
        check("van der Pol: the period on the periodic branch", q["period"], 2 * math.pi, 1e-9)
    bps = [k for k, q in enumerate(b["points"]) if q["label"] == "BP"]
    if len(bps) != 1:
        failures.append(f"van der Pol: {len(bps)} BP on the circles, one expected (r = 2)")
        continue
    check("van der Pol: the BP's radius", b["points"][bps[0]]["max"]["y1"], 2.0, 1e-6)
    limit = [c for c in d["branches"] if c["parent"] == b["branch"] and
             c["parent_point"] == bps[0]]
    ends = sorted(c["points"][-1]["mu"] for c in limit)
    if len(limit) != 2 or not (abs(ends[0] + 1.0) <= 1e-12 and ends[1] > 0):
        failures.append(f"van der Pol: the branches switched to at the BP end at {ends}, "
                        "one at mu = -1 and one at mu > 0 expected")
    for c in limit:
        if abs(c["points"][-1]["mu"] + 1.0) <= 1e-12:
            check("van der Pol: the limit cycle's period at mu = -1",
                  c["points"][-1]["period"], 6.6632868593231, 1e-6)
if len(circles) != 1:
    failures.append(f"van der Pol: {len(circles)} branches of cycles from the Hopf point")

shutil.rmtree(tmp, ignore_errors=True)
for f in failures:
    print("FAIL:", f)
print(f"closed forms: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
