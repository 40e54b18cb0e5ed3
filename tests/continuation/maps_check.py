#!/usr/bin/env python3
"""dynkit continue on discrete maps against closed forms (docs/analysis.md, "Discrete
maps"): the fixed points of F(y) - y = 0 and their multipliers, the eigenvalues of dF/dy.
The logistic map x -> r x (1 - x): every point on x = 1 - 1/r with multiplier 2 - r, stable
for 1 < r < 3, the period doubling PD at r = 3 (x = 2/3, multiplier -1); the branch point BP
at r = 1, x = 0 and the branch x = 0 switched to, with multiplier r, stable for r < 1. Henon's
map (1 - a x^2 + y, b x): the fold LP at a = -(1 - b)^2/4 and PD at a = 3 (1 - b)^2/4 for two
values of b, its 2-cycle's PD at a = 73/80 for b = 0.3. The delayed logistic map (r x (1 - y), x): the Neimark-Sacker point, labelled
TR, at r = 2 with the multipliers exp(+-i pi/3) there; with @ njmp=7 (XPPAUT's period of a
map for AUTO) its points of period 7, each fold a fold of F^7 computed here. The logistic map's cycles born at
each PD (period 2 on its closed form, doubling at 1 + sqrt(6); periods 4, 8, 16 doubling at
the cascade's known values). In two parameters Henon's curves of folds and of flips of its
fixed points and of its 2-cycles (the cycle checked by iterating the map here); the
Neimark-Sacker curves of the delayed logistic map with a second parameter (r + a = 2,
cos(theta) = (1 + a)/2) and of Henon's map (b = -1, cos(theta) = -a x). Usage:
maps_check.py DYNKIT MODELS_DIR"""
import cmath
import json
import math
import os
import subprocess
import sys
import tempfile

dynkit, models = sys.argv[1:3]
failures = []


def run(name, *args):
    cmd = [dynkit, "continue", f"{models}/{name}", "--json", *args]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        failures.append(f"{' '.join(cmd)}: exit {out.returncode}: {out.stderr.strip()}")
        return None
    d = json.loads(out.stdout)
    if d.get("map") is not True:
        failures.append(f"{' '.join(cmd)}: the JSON does not say \"map\": true")
    return d


def check(what, got, want, tol):
    if not abs(got - want) <= tol * max(1.0, abs(want)):
        failures.append(f"{what}: {got!r}, expected {want!r} (tolerance {tol:g} relative)")


def labelled(d, label):
    """the points labelled so among the fixed points (period 1)"""
    return [(b, p) for b in d["branches"] for p in b["points"]
            if p["label"] == label and p["period"] == 1]


def one(d, label, what):
    pts = labelled(d, label) if d else []
    if len({round(p["state"][next(iter(p["state"]))], 8) for _, p in pts}) != 1:
        failures.append(f"{what}: expected one {label}, found {len(pts)}")
        return None
    return pts[0][1]


def multipliers(p):
    return [complex(re, im) for re, im in p["multipliers"]]


# ---- the logistic map: x = 1 - 1/r from r = 2.5 up (a flow's x' = F(x) would give x = 1)
d = run("logistic_map.ode", "--par", "r", "--opt", "parmin=0.5", "--opt", "parmax=4")
if d:
    first = d["branches"][0]["points"]
    check("logistic: the start", first[0]["state"]["x"], 0.6, 1e-12)
    for p in first:
        r, x = p["r"], p["state"]["x"]
        check(f"logistic: x at r = {r}", x, 1.0 - 1.0 / r, 1e-9)
        check(f"logistic: multiplier at r = {r}", multipliers(p)[0].real, 2.0 - r, 1e-7)
        if p["label"] not in ("PD",) and p["stable"] != (1.0 < r < 3.0):
            failures.append(f"logistic: stable = {p['stable']} at r = {r}")
    p = one(d, "PD", "logistic PD")
    if p:
        check("logistic: r at PD", p["r"], 3.0, 1e-10)
        check("logistic: x at PD", p["state"]["x"], 2.0 / 3.0, 1e-9)
        check("logistic: multiplier at PD", multipliers(p)[0].real, -1.0, 1e-8)

d = run("logistic_map.ode", "--par", "r", "--opt", "ds=-0.02", "--opt", "parmin=0.5",
        "--opt", "parmax=4")
p = one(d, "BP", "logistic BP")
if p:
    check("logistic: r at BP", p["r"], 1.0, 1e-10)
    check("logistic: x at BP", p["state"]["x"], 0.0, 1e-8)
    switched = [b for b in d["branches"] if b["parent"] is not None]
    if len(switched) != 2:
        failures.append(f"logistic: expected two branches from the BP, found {len(switched)}")
    for b in switched:
        for q in b["points"]:
            r, x = q["r"], q["state"]["x"]
            check(f"logistic: x on the switched branch at r = {r}", x, 0.0, 1e-9)
            check(f"logistic: multiplier of x = 0 at r = {r}", multipliers(q)[0].real, r, 1e-7)
            if q["label"] != "BP" and q["stable"] != (r < 1.0):
                failures.append(f"logistic: x = 0 stable = {q['stable']} at r = {r}")

# ---- the logistic map's cascade: the points of period 2 born at r = 3, on
# x = ((r + 1) +- sqrt((r + 1)(r - 3))) / (2 r) with multiplier 4 + 2 r - r^2 (of F o F),
# doubling again at 1 + sqrt(6); then the periods 4, 8, 16 doubling at Feigenbaum's values
# of the cascade (r3 = 3.5440903595519..., r4 = 3.5644072660954..., r5 = 3.5687594195...)
d = run("logistic_map.ode", "--par", "r", "--opt", "parmin=0.5", "--opt", "parmax=3.6")
if d:
    by_period = {}
    for b in d["branches"]:
        by_period.setdefault(b["points"][0]["period"], []).append(b)
    if sorted(by_period) != [1, 2, 4, 8, 16] or any(len(v) != 1 for v in by_period.values()):
        failures.append(f"logistic cascade: branches of periods "
                        f"{[(k, len(v)) for k, v in sorted(by_period.items())]}, expected one "
                        "each of 1, 2, 4, 8, 16")
    for q in by_period.get(2, [{}])[0].get("points", []):
        r, x = q["r"], q["state"]["x"]
        root = math.sqrt(max((r + 1) * (r - 3), 0.0))
        want = min(((r + 1) + root) / (2 * r), ((r + 1) - root) / (2 * r),
                   key=lambda w: abs(w - x))
        check(f"logistic period 2: x at r = {r}", x, want, 1e-8)
        if q["label"] == "":
            check(f"logistic period 2: multiplier at r = {r}", multipliers(q)[0].real,
                  4 + 2 * r - r * r, 1e-6)
            if q["stable"] != (3 < r < 1 + math.sqrt(6)):
                failures.append(f"logistic period 2: stable = {q['stable']} at r = {r}")
    for period, want in ((2, 1 + math.sqrt(6)), (4, 3.5440903595519), (8, 3.5644072660954),
                         (16, 3.5687594195)):
        pds = [p["r"] for b in by_period.get(period, []) for k, p in enumerate(b["points"])
               if p["label"] == "PD" and k > 0]
        if len(pds) != 1:
            failures.append(f"logistic period {period}: PDs {pds}, expected one")
        else:
            check(f"logistic period {period}: r at PD", pds[0], want,
                  1e-10 if period < 16 else 1e-9)

# ---- the cascade's cycles followed on into the chaotic range (the default window, r up to
# 5): there the cycles of period 16 lie close together with multipliers of order 1e5 and a
# step of the continuation can land on another one; a test function that jumps there is no
# special point: every PD has a multiplier -1 (1e-6), every BP one +1 (and the PD where a
# doubled cycle's branch starts, as a cycle of twice the period, +1)
d = run("logistic_map.ode", "--par", "r")
if d:
    for b in d["branches"]:
        for k, p in enumerate(b["points"]):
            want = {"PD": 1.0 if k == 0 else -1.0, "BP": 1.0}.get(p["label"])
            if want is not None and not any(abs(m - want) <= 1e-6 for m in multipliers(p)):
                failures.append(f"logistic to r = 5: {p['label']} at r = {p['r']} (period "
                                f"{p['period']}) has the multipliers {multipliers(p)}")

# ---- Henon's map: the fold and the period doubling of its fixed points
for b in (0.3, -0.4):
    sets = ["--set", f"b={b}"]
    d = run("henon_map.ode", "--par", "a", *sets, "--opt", "ds=-0.02", "--opt", "parmin=-1",
            "--opt", "parmax=2", "--opt", "nmax=60")
    p = one(d, "LP", f"Henon b = {b}: LP")
    if p:
        check(f"Henon b = {b}: a at LP", p["a"], -(1 - b) ** 2 / 4, 1e-10)
        check(f"Henon b = {b}: x at LP", p["state"]["x"], 2.0 / (1 - b), 1e-7)
        check(f"Henon b = {b}: largest multiplier at LP", max(m.real for m in multipliers(p)),
              1.0, 1e-7)
    d = run("henon_map.ode", "--par", "a", *sets, "--opt", "parmin=-1", "--opt", "parmax=2")
    if d and b == 0.3:
        # the 2-cycle's PD: 1 + tr(dF(x2) dF(x1)) + b^2 = 0 on the cycle, a = 73/80 (SymPy)
        pds = [p["a"] for br in d["branches"] for k, p in enumerate(br["points"])
               if p["label"] == "PD" and p["period"] == 2 and k > 0]
        if len(pds) != 1:
            failures.append(f"Henon b = 0.3: the 2-cycle's PDs {pds}, expected one")
        else:
            check("Henon b = 0.3: a at the 2-cycle's PD", pds[0], 73 / 80, 1e-10)
    p = one(d, "PD", f"Henon b = {b}: PD")
    if p:
        check(f"Henon b = {b}: a at PD", p["a"], 3 * (1 - b) ** 2 / 4, 1e-10)
        check(f"Henon b = {b}: smallest multiplier at PD", min(m.real for m in multipliers(p)),
              -1.0, 1e-7)

# ---- the delayed logistic map: a Neimark-Sacker point at r = 2
d = run("delayed_logistic.ode", "--par", "r", "--opt", "parmin=1.1", "--opt", "parmax=2.5")
p = one(d, "TR", "delayed logistic TR")
if p:
    check("delayed logistic: r at TR", p["r"], 2.0, 1e-10)
    check("delayed logistic: x at TR", p["state"]["x"], 0.5, 1e-9)
    check("delayed logistic: the angle at TR", p.get("angle", math.nan), math.pi / 3, 1e-8)
    for m in multipliers(p):
        check("delayed logistic: |mu| at TR", abs(m), 1.0, 1e-8)
if d:
    for q in d["branches"][0]["points"]:
        if q["label"] != "TR" and q["stable"] != (q["r"] < 2.0):
            failures.append(f"delayed logistic: stable = {q['stable']} at r = {q['r']}")
        want = (1 + cmath.sqrt(1 - 4 * (q["r"] - 1))) / 2
        check(f"delayed logistic: |mu| at r = {q['r']}", max(abs(m) for m in multipliers(q)),
              abs(want), 1e-8)

# ---- Henon's curves in (a, b): folds on a = -(1 - b)^2/4, flips of the fixed points on
# a = 3 (1 - b)^2/4, and the 2-cycles' flips where the cycle (x1, x2 = F(x1)) has
# 1 + tr(dF(x2) dF(x1)) + b^2 = 0 (its multipliers' product is b^2): checked on the stored
# point of the cycle by iterating F here
def henon(a, b, x, y):
    return 1 - a * x * x + y, b * x


d = run("henon_map.ode", "--par", "a", "--par2", "b", "--opt", "ds=-0.02", "--opt",
        "parmin=-1", "--opt", "parmax=0.5", "--opt", "par2min=-0.9", "--opt", "par2max=0.9",
        "--opt", "nmax=60")
folds = [b for b in d["branches"] if b["kind"] == "fold"] if d else []
if len(folds) != 2:
    failures.append(f"Henon: {len(folds)} fold curves, expected 2 (both ways from the LP)")
for b in folds:
    for q in b["points"]:
        check(f"Henon fold curve at b = {q['b']}", q["a"], -(1 - q["b"]) ** 2 / 4, 1e-9)
d = run("henon_map.ode", "--par", "a", "--par2", "b", "--opt", "parmin=-1", "--opt",
        "parmax=1", "--opt", "par2min=-0.9", "--opt", "par2max=0.9", "--opt", "nmax=60")
flips = {}
for b in (d["branches"] if d else []):
    if b["kind"] == "flip":
        parent = next(p for p in d["branches"] if p["branch"] == b["parent"])
        flips.setdefault(parent["points"][0]["period"], []).append(b)
if sorted(flips) != [1, 2] or any(len(v) != 2 for v in flips.values()):
    failures.append(f"Henon: flip curves of periods "
                    f"{[(k, len(v)) for k, v in sorted(flips.items())]}, expected two each "
                    "of 1 and 2")
for b in flips.get(1, []):
    for q in b["points"]:
        check(f"Henon flip curve at b = {q['b']}", q["a"], 3 * (1 - q["b"]) ** 2 / 4, 1e-9)
for b in flips.get(2, []):
    for q in b["points"]:
        a_, b_, x1 = q["a"], q["b"], (q["state"]["x"], q["state"]["y"])
        x2 = henon(a_, b_, *x1)
        back = henon(a_, b_, *x2)
        tr = 4 * a_ * a_ * x1[0] * x2[0] + 2 * b_  # tr of [[-2a x2, 1], [b, 0]] [[-2a x1, 1], [b, 0]]
        if not (abs(back[0] - x1[0]) + abs(back[1] - x1[1]) <= 1e-9 and
                abs(1 + tr + b_ * b_) <= 1e-8):
            failures.append(f"Henon 2-cycle flip curve at (a, b) = ({a_}, {b_}): F(F(x)) - x = "
                            f"{back[0] - x1[0]:.3g}, 1 + tr + b^2 = {1 + tr + b_ * b_:.3g}")
            break

# ---- Neimark-Sacker curves: the delayed logistic map with a second parameter a,
# (x, y) -> (r x (1 - y) + a (x - y), x), has its fixed point's multipliers on the unit circle
# on the line r + a = 2 with cos(theta) = (1 + a)/2; Henon's map (multipliers' product -b) on
# the line b = -1 with cos(theta) = -a x. Both ways from the TR point, every point on them
d = run("delayed_logistic_ns.ode", "--par", "r", "--par2", "a", "--opt", "parmin=1.1",
        "--opt", "parmax=4", "--opt", "par2min=-2.5", "--opt", "par2max=0.8")
curves = [b for b in d["branches"] if b["kind"] == "neimark-sacker"] if d else []
if len(curves) != 2 or any(b["points"][0]["label"] != "TR" for b in curves):
    failures.append(f"delayed logistic: {len(curves)} Neimark-Sacker curves, expected 2 from "
                    "the TR point")
for b in curves:
    for q in b["points"]:
        r, a = q["r"], q["a"]
        check(f"delayed logistic NS curve at a = {a}: r", r, 2 - a, 1e-9)
        check(f"delayed logistic NS curve at a = {a}: angle", q["angle"],
              math.acos((1 + a) / 2), 1e-9)
        check(f"delayed logistic NS curve at a = {a}: x", q["state"]["x"], 1 - 1 / r, 1e-9)
        check(f"delayed logistic NS curve at a = {a}: |mu|",
              max(abs(m) for m in multipliers(q)), 1.0, 1e-9)
    if len(b["points"]) < 5:
        failures.append(f"delayed logistic: a Neimark-Sacker curve of {len(b['points'])} points")
d = run("henon_map.ode", "--par", "b", "--par2", "a", "--set", "a=0.2", "--set", "b=-0.5",
        "--init", "x=1", "--opt", "ds=-0.02", "--opt", "parmin=-1.5", "--opt", "parmax=0",
        "--opt", "par2min=0.1", "--opt", "par2max=2")
curves = [b for b in d["branches"] if b["kind"] == "neimark-sacker"] if d else []
if len(curves) != 2:
    failures.append(f"Henon: {len(curves)} Neimark-Sacker curves, expected 2")
for b in curves:
    for q in b["points"]:
        a, x = q["a"], q["state"]["x"]
        check(f"Henon NS curve at a = {a}: b", q["b"], -1.0, 1e-9)
        check(f"Henon NS curve at a = {a}: x", 1 - a * x * x + q["b"] * x - x, 0.0, 1e-9)
        check(f"Henon NS curve at a = {a}: angle", math.cos(q["angle"]), -a * x, 1e-9)

# a start on the logistic map's BP (r = 1, x = 0: dF/dx - 1 = r - 1 = 0) is refused with the
# map's words: dF/dy - I singular along x, fixed points
cmd = [dynkit, "continue", f"{models}/logistic_map.ode", "--par", "r", "--set", "r=1",
       "--init", "x=0"]
out = subprocess.run(cmd, capture_output=True, text=True)
if (out.returncode == 0 or "dF/dy - I is singular (null vector along x;" not in out.stderr
        or "a family of fixed points" not in out.stderr):
    failures.append(f"a singular start of a map: exit {out.returncode}, {out.stderr.strip()!r}")

# XPPAUT's NJMP is the period of a map's points for AUTO: the delayed logistic map with
# @ njmp=7 from r = 2.177 (Debian's XPPAUT example del_log.ode) follows its points of period
# 7, the 1:7 resonance on the invariant circle born at r = 2; each LP is a fold of F^7
# (F^7(y) = y, det(dF^7/dy - I) = 0, both computed here along the orbit), the cycle is no
# fixed point of F, and the two edges of the resonance lie in (2.17, 2.21)
njmp = os.path.join(tempfile.mkdtemp(), "delayed_logistic_7.ode")
with open(njmp, "w") as f:
    f.write("x(t+1)=r*x*(1-y)\ny(t+1)=x\npar r=2.177\ninit x=.11, y=.21\n"
            "@ meth=discrete, total=100, njmp=7\n@ parmin=2, parmax=2.5, dsmax=.025\ndone\n")
d = run(os.path.relpath(njmp, models), "--par", "r")
edges = set()
for b in (d["branches"] if d else []):
    for q in b["points"]:
        if q["period"] != 7:
            failures.append(f"njmp=7: a point of period {q['period']}")
            break
        if q["label"] != "LP":
            continue
        r, x, y = q["r"], q["state"]["x"], q["state"]["y"]
        J = [[1.0, 0.0], [0.0, 1.0]]  # d(x, y) of F^7, the product along the orbit
        x1, y1 = x, y
        for _ in range(7):
            A = [[r * (1 - y1), -r * x1], [1.0, 0.0]]
            J = [[A[i][0] * J[0][j] + A[i][1] * J[1][j] for j in range(2)] for i in range(2)]
            x1, y1 = r * x1 * (1 - y1), x1
        det = (J[0][0] - 1) * (J[1][1] - 1) - J[0][1] * J[1][0]
        if not (abs(x1 - x) + abs(y1 - y) <= 1e-12 and abs(det) <= 1e-9
                and abs(r * x * (1 - y) - x) + abs(x - y) > 1e-2 and 2.17 < r < 2.21):
            failures.append(f"njmp=7: LP at r = {r}: F^7 - y = {x1 - x:.3g}, {y1 - y:.3g}, "
                            f"det(dF^7 - I) = {det:.3g}")
        edges.add(round(r, 9))
if len(edges) != 2:
    failures.append(f"njmp=7: the 1:7 resonance's edges at r = {sorted(edges)}, expected two")

for f in failures:
    print("FAIL:", f)
if not failures:
    print("maps: logistic (BP r = 1, PD r = 3), Henon (LP, PD), delayed logistic (TR r = 2) "
          "agree with their closed forms")
sys.exit(1 if failures else 0)
