#!/usr/bin/env python3
"""dynkit continue on a mechanism's steady motions against published values and closed forms.

- The benchmark bicycle (examples/mechanisms/bicycle.mech; Meijaard, Papadopoulos, Ruina and
  Schwab 2007, Proc. R. Soc. A 463, 1955-1982): upright straight running continued in v from
  3 to 10 m/s must give HB at the weave speed and BP at the capsize speed, within 1e-8 of the
  paper's table 2 (4.292382536341, 6.024262015388 m/s) and of the same speeds computed here
  from the paper's linearized matrices M, C1, K0, K2 (eq. 5.4) alone: the capsize speed from
  det(g K0 + v^2 K2) = 0 (a quadratic in v^2), the weave speed by bisection on the real part
  of the eigenvalues of the first-order form. `stable` must be 1 exactly between them (the
  self-stable range), and the eigenvalues at --at v=2.5,5,8 those of the matrices (1e-9).
- The rolling disk (examples/mechanisms/rolling_disk.mech, a thin uniform disk): upright
  rolling continued in its spin W changes stability where W^2 = g/(3r) (docs/mechanisms.md:
  (A + m r^2) theta'' = (m g r - W^2 C (C + m r^2)/A) theta with A = m r^2/4, C = m r^2/2):
  BP there within 1e-8 for two radii and both choices of the unknowns, the lean's eigenvalues
  +-sqrt((4 g - 12 W^2 r)/(5 r)) (real below, imaginary above) at --at values within 1e-8.
- The bicycle's steady turns, switched from the capsize BP: two mirror-image branches
  leaving along the null vector of the paper's g K0 + v^2 K2, with its yaw kinematics.
- The sleeping top (examples/mechanisms/sleeping_top.mech) continued upright in g, C and L:
  HH (two imaginary pairs collide and leave the axis) at C^2 W^2 = 4 (A + m L^2) m g L
  within 1e-10, its frequency and the eigenvalues either side the closed form's.
- Bad input: an unknown that is not a steady equation's state, default unknowns that the
  equations do not determine, --par2 the same as --par: refused with the reason and a
  non-zero status.
- --par2: the heavy top's fold of steady precessions (top.mech, theta = 30 deg held) in
  (g, L) on the closed form C^2 phi'^2 = 4 (A + m L^2 - C) cos(theta) m g L; the bicycle's
  weave speed as its trail c changes, at the curve's points the HB of one-parameter runs.
- Every example that dynkit continue --help shows runs.

Usage: steady_check.py DYNKIT SOURCE_DIR ARTIFACTS_DIR. Exit 77 without NumPy."""
import csv
import io
import json
import math
import os
import subprocess
import sys

try:
    import numpy as np
except ImportError:
    sys.exit(77)

DYNKIT, SOURCE, ARTIFACTS = sys.argv[1], sys.argv[2], sys.argv[3]
BICYCLE = os.path.join(SOURCE, "examples", "mechanisms", "bicycle.mech")
DISK = os.path.join(SOURCE, "examples", "mechanisms", "rolling_disk.mech")
FAILED = []

M = np.array([[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]])
C1 = np.array([[0.0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]])
K0 = np.array([[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]])
K2 = np.array([[0.0, 76.59734589573222], [0.0, 2.65431523794604]])
G = 9.81
WEAVE_PAPER, CAPSIZE_PAPER = 4.292382536341, 6.024262015388


def check(cond, what):
    print(("ok    " if cond else "FAILED ") + what)
    if not cond:
        FAILED.append(what)


def keep(name, text):
    os.makedirs(ARTIFACTS, exist_ok=True)
    with open(os.path.join(ARTIFACTS, name), "w") as f:
        f.write(text)


def run(args, name):
    p = subprocess.run([DYNKIT, "continue"] + args, capture_output=True, text=True)
    if p.returncode != 0:
        keep("steady_continue_" + name + ".txt", " ".join(args) + "\n" + p.stdout + p.stderr)
    return p


def benchmark_eig(v):
    Mi = np.linalg.inv(M)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-Mi @ (G * K0 + v * v * K2), -Mi @ (v * C1)]])
    return np.linalg.eigvals(A)


def benchmark_speeds():
    """capsize: det(g K0 + v^2 K2) = a + b v^2 + c v^4 = 0 (K2's first column is zero, so
    c = 0: one root); weave: the largest real part of a complex pair crosses zero"""
    # det(g K0 + s K2) is linear in s = v^2 here: evaluate at two values of s
    d0 = np.linalg.det(G * K0)
    d1 = np.linalg.det(G * K0 + K2)
    d2 = np.linalg.det(G * K0 + 2 * K2)
    check(abs(d2 - 2 * d1 + d0) < 1e-9 * abs(d0), "det(g K0 + v^2 K2) is linear in v^2")
    capsize = math.sqrt(-d0 / (d1 - d0))

    def weave_re(v):
        return max(z.real for z in benchmark_eig(v) if abs(z.imag) > 1e-9)

    lo, hi = 3.0, 5.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if weave_re(mid) > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi), capsize


def points(p, first_only=True):
    """the points of the first branch (of every branch with first_only False)"""
    d = json.loads(p.stdout)
    return [pt for b in d["branches"] if not first_only or b["parent"] is None
            for pt in b["points"]]


def steady_turns(d, capsize):
    """the two branches switched from at the capsize BP: the bicycle's steady turns. At the
    pitchfork the lean phi and steer delta leave along the null vector of g K0 + v^2 K2
    (the paper's delta is the file's -delta: its z axis points down), v - v_c = O(phi^2),
    the yaw rate obeys the benchmark's kinematics psi' = v delta cos(lam) / w (eq. 5.2)
    to O(phi^2), and the two branches are mirror images (phi, delta, psi' -> -phi, -delta,
    -psi' at the same v)."""
    turns = [b for b in d["branches"] if b["parent"] == 1]
    check(len(turns) == 2 and all(b["points"][0]["label"] == "BP" for b in turns),
          "bicycle: two steady-turn branches switched from the capsize BP (%d)" % len(turns))
    if len(turns) != 2:
        return
    Kc = G * K0 + capsize * capsize * K2
    ratio = Kc[0, 0] / Kc[0, 1]  # the file's delta/phi: minus the paper's -Kc00/Kc01
    kin = math.cos(math.pi / 10) / 1.02
    a, b = turns[0]["points"][1:4], turns[1]["points"][1:4]
    mirror = max(max(abs(p["v"] - q["v"]), abs(p["state"]["phi"] + q["state"]["phi"]),
                     abs(p["state"]["delta"] + q["state"]["delta"]),
                     abs(p["state"]["dpsi"] + q["state"]["dpsi"])) for p, q in zip(a, b))
    check(len(a) == 3 and len(b) == 3 and mirror < 1e-9,
          "bicycle: the two steady-turn branches are mirror images (%.2g)" % mirror)
    # Richardson in phi^2 on the two points nearest the BP: the limits at phi = 0
    p1, p2 = a[0]["state"], a[1]["state"]
    f1, f2 = p1["phi"] ** 2, p2["phi"] ** 2

    def limit(g1, g2):
        return (g1 * f2 - g2 * f1) / (f2 - f1)

    r = limit(p1["delta"] / p1["phi"], p2["delta"] / p2["phi"])
    k = limit(p1["dpsi"] / (a[0]["v"] * p1["delta"]), p2["dpsi"] / (a[1]["v"] * p2["delta"]))
    c1, c2 = ((pt["v"] - capsize) / pt["state"]["phi"] ** 2 for pt in a[:2])
    check(abs(p1["phi"]) < 0.05 and abs(r - ratio) < 1e-5 * abs(ratio),
          "bicycle: the steady turns leave along g K0 + v^2 K2's null vector: delta/phi -> "
          "%.9f (matrices: %.9f)" % (r, ratio))
    check(abs(k - kin) < 1e-5 * kin,
          "bicycle: their yaw rate psi'/(v delta) -> %.9f = cos(lam)/w %.9f" % (k, kin))
    check(abs(c1 - c2) < 0.02 * abs(c1), "bicycle: a pitchfork, v - v_c = c phi^2 (c = %.4g "
          "and %.4g at the first two points)" % (c1, c2))


def slow_turns(d):
    """the steady turns go on below 2.5 m/s, where the constraints' pivoting would keep the
    front wheel's rate instead of the rear's (the start's choice is kept), down to v = 0:
    a turn at about 1.6 m/s integrated by dynkit run for 1 s keeps its lean, steer and yaw
    rate; at v = 0 (at rest, a conservative spectrum) the weave pair crosses the axis: HB"""
    turns = [b for b in d["branches"] if b["parent"] == 1]
    for b in turns:
        check(b["stop"] == "reached parmin = 0" and min(pt["v"] for pt in b["points"]) < 1e-9,
              "bicycle: a steady-turn branch goes down to v = 0 (%s)" % b["stop"])
    if not turns:
        return
    pt = min(turns[0]["points"], key=lambda q: abs(q["v"] - 1.6))
    args = [DYNKIT, "run", BICYCLE, "--set", "v=%r" % pt["v"], "--tspan", "0:1", "-o", "-"]
    for name, value in pt["state"].items():
        args += ["--init", "%s=%r" % (name, value)]
    p = subprocess.run(args, capture_output=True, text=True)
    rows = list(csv.DictReader(io.StringIO(p.stdout))) if p.returncode == 0 else []
    drift = max((abs(float(r[k]) - pt["state"][k]) for r in rows for k in ("phi", "delta", "dpsi")),
                default=math.inf)
    if drift > 1e-9:
        keep("steady_turn_run.txt", " ".join(args) + "\n" + p.stdout[-2000:] + p.stderr)
    check(len(rows) > 10 and drift < 1e-9 and pt["v"] < 2.0,
          "bicycle: the steady turn at v = %.4g, integrated for 1 s, keeps its lean, steer and "
          "yaw rate within %.2g" % (pt["v"], drift))
    hb = [q for q in turns[0]["points"] if q["label"] == "HB"]
    eig = [complex(a, b) for a, b in hb[0]["eigenvalues"]] if hb else []
    sym = max((min(abs(z + w) for w in eig) for z in eig), default=math.inf)
    check(len(hb) == 1 and abs(hb[0]["v"]) < 1e-12 and sym < 1e-9 * max(abs(z) for z in eig),
          "bicycle: on the turns HB at v = %s, where the spectrum is symmetric (%.2g)"
          % ([q["v"] for q in hb], sym))


def bicycle():
    weave, capsize = benchmark_speeds()
    check(abs(weave - WEAVE_PAPER) < 2e-12 and abs(capsize - CAPSIZE_PAPER) < 2e-12,
          "the paper's matrices give its weave %.13f and capsize %.13f m/s" % (weave, capsize))
    p = run([BICYCLE, "--par", "v", "--set", "v=3", "--opt", "parmax=10", "--at", "v=2.5,5,8",
             "--json"], "bicycle")
    check(p.returncode == 0, "bicycle: continue in v runs (status %d)" % p.returncode)
    if p.returncode != 0:
        return
    pts = points(p)
    steady_turns(json.loads(p.stdout), capsize)
    slow_turns(json.loads(p.stdout))
    hb = [pt["v"] for pt in pts if pt["label"] == "HB"]
    bp = [pt["v"] for pt in pts if pt["label"] == "BP"]
    check(len(hb) == 1 and abs(hb[0] - WEAVE_PAPER) < 1e-8 and abs(hb[0] - weave) < 1e-8,
          "bicycle: HB at the weave speed %s (paper %.12f)" % (hb, WEAVE_PAPER))
    check(len(bp) == 1 and abs(bp[0] - CAPSIZE_PAPER) < 1e-8 and abs(bp[0] - capsize) < 1e-8,
          "bicycle: BP at the capsize speed %s (paper %.12f)" % (bp, CAPSIZE_PAPER))
    hbp = [pt for pt in pts if pt["label"] == "HB"]
    if hbp:
        want = max(abs(z.imag) for z in benchmark_eig(hb[0]) if abs(z.real) < 1e-6)
        check(abs(hbp[0]["omega"] - want) < 1e-8 * want,
              "bicycle: the weave's frequency at HB %.12g rad/s (matrices: %.12g)"
              % (hbp[0]["omega"], want))
    wrong = [pt["v"] for pt in pts if pt["label"] in ("", "EP", "UZ")
             and pt["stable"] != (weave < pt["v"] < capsize)]
    check(not wrong, "bicycle: stable exactly between the weave and capsize speeds %s" % wrong)
    uz = [pt for pt in pts if pt["label"] == "UZ"]
    check(sorted(pt["v"] for pt in uz) == [5.0, 8.0], "bicycle: UZ at v = 5 and 8 (2.5 is "
          "below the start's branch)")
    worst = 0.0
    for pt in uz:
        got = sorted((complex(re, im) for re, im in pt["eigenvalues"]), key=lambda z: (z.real, z.imag))
        want = sorted(benchmark_eig(pt["v"]), key=lambda z: (z.real, z.imag))
        worst = max(worst, max(abs(a - b) for a, b in zip(got, want)) / max(abs(w) for w in want))
    check(len(uz) == 2 and worst < 1e-9,
          "bicycle: the four eigenvalues at UZ points are the matrices' (%.2g relative)" % worst)
    # downwards from 5 m/s: the same weave speed
    p = run([BICYCLE, "--par", "v", "--opt", "ds=-0.02", "--opt", "parmax=10",
             "--opt", "parmin=3", "--output", "-"], "bicycle_down")
    rows = list(csv.DictReader(io.StringIO(p.stdout))) if p.returncode == 0 else []
    hb2 = [float(r["v"]) for r in rows if r["label"] == "HB"]
    check(len(hb2) == 1 and abs(hb2[0] - WEAVE_PAPER) < 1e-8,
          "bicycle: downwards from v = 5, HB at %s (CSV)" % hb2)
    check(rows and rows[0]["kind"] == "steady" and "stable" in rows[0] and "dthR" in rows[0],
          "bicycle: CSV columns branch, kind steady, label, v, the states, stable")


def disk():
    for r in (0.3, 0.5):
        wc = math.sqrt(G / (3 * r))
        for unknown in ("dpsi,dtheta", "theta,dtheta"):
            at = "W=%r,%r" % (0.8 * wc, 1.5 * wc)
            p = run([DISK, "--par", "W", "--set", "W=%r" % (0.5 * wc), "--set", "r=%r" % r,
                     "--opt", "parmax=%r" % (2 * wc), "--unknown", unknown, "--at", at,
                     "--json"], "disk_%g_%s" % (r, unknown.replace(",", "_")))
            check(p.returncode == 0, "disk r=%g --unknown %s runs" % (r, unknown))
            if p.returncode != 0:
                continue
            pts = points(p)
            check(len(json.loads(p.stdout)["branches"]) == 1 and "no other branch" in p.stderr,
                  "disk r=%g --unknown %s: its BP has no other branch of steady motions "
                  "(the equations are regular there), and a note says so" % (r, unknown))
            bp = [pt["W"] for pt in pts if pt["label"] == "BP"]
            check(len(bp) == 1 and abs(bp[0] - wc) < 1e-8,
                  "disk r=%g --unknown %s: BP at W = %s, sqrt(g/(3r)) = %.15g"
                  % (r, unknown, bp, wc))
            for pt in pts:
                if pt["label"] != "UZ":
                    continue
                W = pt["W"]
                lam2 = (4 * G - 12 * W * W * r) / (5 * r)
                lean = [complex(a, b) for a, b in pt["eigenvalues"] if abs(complex(a, b)) > 1e-6]
                want = math.sqrt(abs(lam2))
                ok = len(lean) == 2 and all(
                    abs(abs(z) - want) < 1e-8 * want and
                    (abs(z.imag) < 1e-8 * want if lam2 > 0 else abs(z.real) < 1e-8 * want)
                    for z in lean)
                check(ok and pt["stable"] is False,
                      "disk r=%g W=%.6g: the lean's eigenvalues %s, %s sqrt(|%.6g|), not "
                      "asymptotically stable" % (r, W, lean, "+-" if lam2 > 0 else "+-i", lam2))


def sleeping_top():
    """The sleeping top (examples/mechanisms/sleeping_top.mech: upright, spin W = dphi, mass m,
    mass centre at L from the tip, inertias A about the mass centre and C about the axis):
    linearized, A' lambda^2 - i C W lambda - m g L = 0 in alpha + i beta, A' = A + m L^2, so
    its two imaginary pairs i (C W +- sqrt(C^2 W^2 - 4 A' m g L)) / (2 A') meet at
    C^2 W^2 = 4 A' m g L (Maievski's limit) with frequency C W / (2 A') and leave the axis
    as +-sqrt(4 A' m g L - C^2 W^2) / (2 A') + i C W / (2 A'): HH there, in g for two spins,
    in C, and in L (a cubic), within 1e-10; at --at values the eigenvalues are these."""
    top = os.path.join(SOURCE, "examples", "mechanisms", "sleeping_top.mech")
    m, A, C, L, g = 1.0, 0.002, 0.004, 0.1, G
    cubic = [r.real for r in np.roots([4 * m * m * g, 0, 4 * A * m * g, -(C * 60) ** 2])
             if abs(r.imag) < 1e-12 and r.real > 0]
    cases = [("g", 60, C * C * 3600 / (4 * (A + m * L * L) * m * L), ["--set", "g=5",
                                                                     "--opt", "parmax=20"]),
             ("g", 80, C * C * 6400 / (4 * (A + m * L * L) * m * L), ["--set", "g=5",
                                                                     "--opt", "parmax=30"]),
             ("C", 60, math.sqrt(4 * (A + m * L * L) * m * g * L) / 60,
              ["--opt", "ds=-0.0001", "--opt", "dsmin=1e-6", "--opt", "dsmax=0.0002",
               "--opt", "parmin=0.002"]),
             ("L", 60, cubic[0], ["--opt", "ds=0.002", "--opt", "dsmax=0.01",
                                  "--opt", "parmax=0.2"])]
    for par, W, crit, extra in cases:
        at = "%s=%r,%r" % (par, 0.95 * crit, 1.1 * crit)
        p = run([top, "--par", par, "--init", "dphi=%d" % W, "--unknown",
                 "alpha,beta,dalpha,dbeta", "--at", at, "--json"] + extra,
                "top_%s_%d" % (par, W))
        what = "sleeping top in %s, W = %d" % (par, W)
        check(p.returncode == 0, what + ": runs (status %d)" % p.returncode)
        if p.returncode != 0:
            continue
        pts = points(p)
        hh = [pt for pt in pts if pt["label"] == "HH"]
        other = [pt["label"] for pt in pts if pt["label"] in ("HB", "BP", "LP")]
        check(len(hh) == 1 and abs(hh[0][par] - crit) < 1e-10 * crit and not other,
              what + ": HH at %s (closed form %.15g), no HB, BP, LP %s"
              % ([pt[par] for pt in hh], crit, other))
        if len(hh) != 1:
            continue

        def parts(pt):
            q = dict(m=m, A=A, C=C, L=L, g=g)
            q[par] = pt[par]
            Ap = q["A"] + q["m"] * q["L"] ** 2
            return Ap, q["C"] * W, 4 * Ap * q["m"] * q["g"] * q["L"]

        Ap, CW, _ = parts(hh[0])
        check(abs(hh[0]["omega"] - CW / (2 * Ap)) < 1e-8 * CW / (2 * Ap),
              what + ": omega at HH %.12g, C W / (2 A') = %.12g" % (hh[0]["omega"], CW / (2 * Ap)))
        worst, count = 0.0, 0
        for pt in pts:
            if pt["label"] != "UZ":
                continue
            Ap, CW, D = parts(pt)
            s = complex(CW * CW - D) ** 0.5
            roots = [1j * (CW + s) / (2 * Ap), 1j * (CW - s) / (2 * Ap)]
            want = sorted(roots + [z.conjugate() for z in roots], key=lambda z: (z.real, z.imag))
            got = sorted((complex(a, b) for a, b in pt["eigenvalues"]),
                         key=lambda z: (z.real, z.imag))
            worst = max(worst, max(abs(a - b) for a, b in zip(got, want)) / abs(want[0]))
            count += 1
        check(count == 2 and worst < 1e-8,
              what + ": the eigenvalues at 0.95 and 1.1 times the limit are the closed form's "
              "(%.2g relative)" % worst)


def par2_fold():
    """the top's two steady precession rates at a fixed lean, the roots of
    (I1 - C) cos(theta) psi'^2 - C phi' psi' + m g L = 0 (I1 = A + m L^2 about the tip), meet
    where C^2 phi'^2 = 4 (I1 - C) cos(theta) m g L: the fold curve in (g, L)"""
    top = os.path.join(SOURCE, "examples", "mechanisms", "top.mech")
    p = run([top, "--par", "g", "--par2", "L", "--unknown", "dpsi,dtheta", "--init",
             "dpsi=2.5", "--opt", "parmax=200", "--opt", "par2min=0.05", "--opt",
             "par2max=0.3", "--opt", "ds=0.5", "--opt", "dsmax=5", "--json"], "top_par2")
    check(p.returncode == 0, "top --par g --par2 L runs (status %d)" % p.returncode)
    if p.returncode != 0:
        return
    d = json.loads(p.stdout)
    folds = [b for b in d["branches"] if b["kind"] == "fold"]
    m, A, C, W, th = 1.0, 0.002, 0.004, 100.0, math.radians(30)
    worst, n, Ls = 0.0, 0, []
    for b in folds:
        for pt in b["points"]:
            g, L = pt["g"], pt["L"]
            want = C * C * W * W / (4 * (A + m * L * L - C) * math.cos(th) * m * L)
            worst = max(worst, abs(g - want) / want)
            n += 1
            Ls.append(L)
    lp = [pt["g"] for pt in points(p) if pt["label"] == "LP"]
    want = C * C * W * W / (4 * (A + m * 0.01 - C) * math.cos(th) * m * 0.1)
    check(len(lp) == 1 and abs(lp[0] - want) < 1e-10 * want,
          "top: the fold of the precessions at g = %s, LP (closed form %.15g)" % (lp, want))
    check(len(folds) == 2 and n > 20 and min(Ls) < 0.097 and max(Ls) > 0.16 and worst < 1e-8,
          "top: the fold curve in (g, L), %d points on L from %.3g to %.3g, on the closed "
          "form within %.2g relative" % (n, min(Ls or [0]), max(Ls or [0]), worst))


def par2_weave():
    """the bicycle's weave speed as its trail c changes: the Hopf curve in (v, c) (3.75 to
    4.70 m/s), and at three of its points a one-parameter run at that trail finds HB at
    that speed; up to 5.5 m/s, below the capsize speed"""
    p = run([BICYCLE, "--par", "v", "--par2", "c", "--set", "v=3", "--opt", "parmax=5.5",
             "--opt", "par2min=0.04", "--opt", "par2max=0.12", "--opt", "dsmax=0.2",
             "--json"], "bicycle_par2")
    check(p.returncode == 0, "bicycle --par v --par2 c runs (status %d)" % p.returncode)
    if p.returncode != 0:
        return
    d = json.loads(p.stdout)
    hopf = [pt for b in d["branches"] if b["kind"] == "hopf" and b["parent"] == 1
            for pt in b["points"]]
    cs = sorted(pt["c"] for pt in hopf)
    check(len(hopf) > 5 and cs[0] < 0.041 and cs[-1] > 0.119,
          "bicycle: the weave's Hopf curve spans c from %.3g to %.3g (%d points)"
          % (cs[0] if cs else 0, cs[-1] if cs else 0, len(hopf)))
    if len(hopf) <= 5:
        return
    picks = [min(hopf, key=lambda pt: pt["c"]), max(hopf, key=lambda pt: pt["c"]),
             hopf[len(hopf) // 3]]
    worst = 0.0
    for pt in picks:
        q = run([BICYCLE, "--par", "v", "--set", "v=3", "--set", "c=%r" % pt["c"], "--opt",
                 "parmax=5.5", "--json"], "bicycle_c")
        hb = [x["v"] for x in points(q) if x["label"] == "HB"] if q.returncode == 0 else []
        worst = max(worst, abs(hb[0] - pt["v"]) if len(hb) == 1 else math.inf)
    check(worst < 1e-8, "bicycle: at c = %s the one-parameter runs' HB within %.2g m/s of "
          "the curve's speeds" % (", ".join("%.4g" % pt["c"] for pt in picks), worst))


def par2_failure():
    """a pendulum hinged at a from the axis of a freely turning arm
    (tests/continuation/models/arm_pendulum.mech): its folds of steady motions,
    g sin(theta) = W^2 (a + L sin(theta)) cos(theta) and that expression's theta-derivative
    zero, followed in (W, a) through the cusp at a = 0; with amax = 0.06 the model fails
    beyond a = 0.06: that curve ends there with its points kept, a note and its reason"""
    arm = os.path.join(SOURCE, "tests", "continuation", "models", "arm_pendulum.mech")
    g, L = G, 1.0
    for amax in (1.0, 0.06):
        p = run([arm, "--par", "W", "--par2", "a", "--init", "theta=-0.3", "--set", "W=3.5",
                 "--set", "amax=%r" % amax, "--opt", "parmin=2", "--opt", "parmax=5", "--opt",
                 "par2min=-0.1", "--opt", "par2max=0.1", "--opt", "ds=-0.01", "--opt",
                 "dsmax=0.05", "--json"], "arm_%g" % amax)
        check(p.returncode == 0, "arm pendulum amax=%g: --par2 runs (status %d)"
              % (amax, p.returncode))
        if p.returncode != 0:
            continue
        folds = [b for b in json.loads(p.stdout)["branches"] if b["kind"] == "fold"]
        worst, n = 0.0, 0
        for b in folds:
            for pt in b["points"]:
                W, a, th = pt["W"], pt["a"], pt["state"]["theta"]
                f = g * math.sin(th) - W * W * (a + L * math.sin(th)) * math.cos(th)
                fth = g * math.cos(th) - W * W * (L * math.cos(2 * th) - a * math.sin(th))
                worst = max(worst, abs(f) / g, abs(fth) / g)
                n += 1
        a_all = [pt["a"] for b in folds for pt in b["points"]]
        up = [b for b in folds if b["points"][-1]["a"] > 0.02]
        if amax == 1.0:
            check(len(folds) == 2 and n > 20 and worst < 1e-9 and min(a_all) < -0.099
                  and max(a_all) > 0.099,
                  "arm pendulum: the fold curve in (W, a) from a = %.3g to %.3g through the "
                  "cusp, on the closed form within %.2g" % (min(a_all), max(a_all), worst))
            continue
        ok = (len(up) == 1 and up[0]["stop"].startswith("failed at W = ")
              and "not finite" in up[0]["stop"] and 0.05 < up[0]["points"][-1]["a"] < 0.06
              and up[0]["points"][-1]["label"] == "EP" and len(up[0]["points"]) > 5)
        check(ok and worst < 1e-9 and "ends where the model or the reduction fails" in p.stderr,
              "arm pendulum amax=0.06: the fold curve ends at a = %s, its %d points kept "
              "(on the closed form within %.2g), stop '%s', a note"
              % ([b["points"][-1]["a"] for b in up], len(up[0]["points"]) if up else 0, worst,
                 up[0]["stop"] if up else ""))


def refusals():
    p = run([DISK, "--par", "W", "--set", "W=2", "--opt", "parmax=6"], "disk_default")
    check(p.returncode == 1 and "--unknown" in p.stderr and "determine" in p.stderr,
          "disk with the default unknowns: refused, naming --unknown (status %d)" % p.returncode)
    p = subprocess.run([DYNKIT, "continue", DISK, "--par", "W", "--set", "W=2", "--unknown", "x"],
                       capture_output=True, text=True)
    check(p.returncode == 2 and "accepted: theta, dpsi, dtheta, dphi" in p.stderr,
          "--unknown x: refused with the accepted states (status %d)" % p.returncode)
    p = subprocess.run([DYNKIT, "continue", BICYCLE, "--par", "v", "--par2", "v"],
                       capture_output=True, text=True)
    check(p.returncode == 2 and "--par2" in p.stderr, "--par2 the same as --par: refused")
    p = subprocess.run([DYNKIT, "continue",
                        os.path.join(SOURCE, "examples", "models", "brusselator.ode"),
                        "--par", "b", "--unknown", "x"], capture_output=True, text=True)
    check(p.returncode == 2 and ".mech" in p.stderr, "--unknown on an .ode file: refused")


def help_examples():
    """every example of dynkit continue --help runs (tests/analysis/analysis_common.py)"""
    sys.path.insert(0, os.path.join(SOURCE, "tests", "analysis"))
    from analysis_common import Checks
    c = Checks(DYNKIT, "continue")
    c.help_examples(SOURCE)
    FAILED.extend(c.failed)


def main():
    bicycle()
    disk()
    sleeping_top()
    par2_fold()
    par2_weave()
    par2_failure()
    refusals()
    help_examples()
    if FAILED:
        print("%d failed" % len(FAILED))
        sys.exit(1)
    print("all passed")


main()
