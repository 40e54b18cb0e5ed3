#!/usr/bin/env python3
"""dynkit steady, linearize and continue on six mechanisms written from docs/mechanisms.md
alone (tests/continuation/models), each against the closed form of its steady motions and
of where they lose stability (Routh's reduced system for an ignorable coordinate: the
effective potential V + p^2 / (2 I(q)) at a fixed momentum p; Greenwood, Advanced Dynamics,
sec. 4.6).

- spun_rod.mech: a uniform rod (mass m, length L) hinged at its upper end on a vertical axis
  turned at the prescribed rate W (`rot z:W*t y:pi-a`): (m L^2/3) a'' = (m L^2/3) W^2 sin a
  cos a - m g L/2 sin a, so cos a = 3 g / (2 L W^2), swinging about it at W sin a; the
  hanging rod loses stability in a pitchfork at W^2 = 3 g / (2 L). The file writes pi - a:
  the hanging rod is an equilibrium exactly (not within sin(fl(pi)) = 1.2e-16), so the
  pitchfork is a BP, located, with its two branches, and no LP beside it.
- hoop_free.mech: a bead (m) on a hoop (radius R, moment J = M R^2/2 about its vertical
  diameter) free to turn about that diameter (phi ignorable): at the hoop's rate W the bead
  stays at cos th = g / (R W^2), where it swings at W sin th sqrt(1 + 4 m R^2 cos^2 th / I),
  I = J + m R^2 sin^2 th (Routh); the bottom, th = 0, loses stability at W^2 = g / R (BP).
- cone_body.mech: a heavy symmetric body (mass m, moments A, C about its mass centre, which
  is l below a spherical joint) on a cone of angle theta: psi'^2 = m g l / ((A' - C) cos
  theta), A' = A + m l^2, nutating at psi' sqrt(((A' - C) sin^2 th + (A' - C)^2 sin^2(2 th)
  / I) / A'), I = A' sin^2 th + C cos^2 th; continued down in the rate W the cone closes at
  W^2 = m g l / (A' - C), a BP where the hanging body's branch crosses (not a fold).
- rotating_double.mech: a double pendulum (equal masses and rods) in a plane turned at W:
  about hanging, M q'' + (K - W^2 M) q = 0, so the eigenvalues are +-sqrt(W^2 - w_i^2) with
  w_i^2 = (2 -+ sqrt 2) g / l, and the hanging state has BPs at W = w_1 and W = w_2.
- governor.mech: Watt's governor, two balls m on arms L from the top of a spindle turned at
  W and a sleeve ms held by links L at the depth s = 2 L cos al (a holonomic constraint):
  cos al = (m + ms) g / (m L W^2), swinging at W sin al sqrt(m / (m + 2 ms sin^2 al)); the
  arms leave the spindle at W^2 = (m + ms) g / (m L) (BP). `continue` takes --init values
  that do not hold the constraint (the sleeve follows from it, as for `steady`).
- spun_tube.mech: a bead (m) on a spring (k, l0) in a horizontal tube turning freely (J):
  r = k l0 / (k - m W^2) at the rate W, swinging at sqrt((k - m W^2 + 4 m^2 r^2 W^2 /
  (J + m r^2)) / m).
- A steady branch that runs where the model fails (arm_pendulum.mech with amax = 0.06, its
  right-hand side not finite beyond a = amax) stops saying where and why.

Usage: steady_mechanisms.py DYNKIT SOURCE_DIR ARTIFACTS_DIR."""
import json
import math
import os
import subprocess
import sys

DYNKIT, SOURCE, ARTIFACTS = sys.argv[1], sys.argv[2], sys.argv[3]
MODELS = os.path.join(SOURCE, "tests", "continuation", "models")
FAILED = []
G = 9.81


def check(cond, what):
    print(("ok    " if cond else "FAILED ") + what)
    if not cond:
        FAILED.append(what)


def dynkit(args, name):
    p = subprocess.run([DYNKIT] + args, capture_output=True, text=True)
    if p.returncode != 0:
        os.makedirs(ARTIFACTS, exist_ok=True)
        with open(os.path.join(ARTIFACTS, "steady_mech_" + name + ".txt"), "w") as f:
            f.write(" ".join(args) + "\n" + p.stdout + p.stderr)
    return p


def model(name):
    return os.path.join(MODELS, name + ".mech")


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def steady(name, args):
    p = dynkit(["steady", model(name)] + args + ["--json"], name + "_steady")
    check(p.returncode == 0, "%s: steady runs (status %d)" % (name, p.returncode))
    return json.loads(p.stdout) if p.returncode == 0 else None


def imag_parts(eigs):
    """the positive imaginary parts of the eigenvalues on the imaginary axis"""
    return sorted(im for re, im in eigs if im > 1e-6 and abs(re) <= 1e-7 * abs(im))


def linearize_imag(name, state, params):
    args = ["linearize", model(name)]
    for k, v in state.items():
        args += ["--init", "%s=%r" % (k, v)]
    for k, v in params.items():
        args += ["--set", "%s=%r" % (k, v)]
    p = dynkit(args + ["--output", "-.json"], name + "_linearize")
    if p.returncode != 0:
        return None
    pt = json.loads(p.stdout)["points"][0]
    return imag_parts(list(zip(pt["re"], pt["im"])))


def cont(name, args):
    p = dynkit(["continue", model(name)] + args + ["--json"], name + "_continue")
    check(p.returncode == 0, "%s: continue %s runs (status %d)" % (name, " ".join(args),
                                                                    p.returncode))
    return json.loads(p.stdout) if p.returncode == 0 else {"branches": []}


def labelled(d, label, par):
    return [pt[par] for b in d["branches"] for pt in b["points"] if pt["label"] == label]


def first_bp(d, par):
    bps = [pt[par] for pt in d["branches"][0]["points"] if pt["label"] == "BP"] \
        if d["branches"] else []
    return bps


def steady_and_linearize(name, args, state_name, closed_state, omega, params):
    d = steady(name, args)
    if not d:
        return
    x = d["state"][state_name]
    check(rel(x, closed_state) < 1e-11, "%s: steady %s = %.15g, closed form %.15g (%.1e)"
          % (name, state_name, x, closed_state, rel(x, closed_state)))
    im = imag_parts(d["eigenvalues"])
    check(len(im) == 1 and rel(im[0], omega) < 1e-9,
          "%s: steady's swing %s against %.15g" % (name, im, omega))
    lin = linearize_imag(name, d["state"], params)
    check(lin is not None and len(lin) == 1 and rel(lin[0], omega) < 1e-9,
          "%s: linearize there gives %s against %.15g" % (name, lin, omega))


def spun_rod():
    L, W = 1.0, 5.0
    a = math.acos(3 * G / (2 * L * W * W))
    steady_and_linearize("spun_rod", ["--unknown", "a", "--init", "a=0.9"], "a", a,
                         W * math.sin(a), {})
    p = dynkit(["steady", model("spun_rod"), "--unknown", "a", "--init", "a=0.9"], "rod_text")
    check("cyclic (moving at constant rates): none\n" in p.stdout,
          "spun_rod: the text says no state is cyclic")
    d = cont("spun_rod", ["--par", "W", "--init", "a=0", "--set", "W=2", "--opt", "parmax=6"])
    wc = math.sqrt(3 * G / (2 * L))
    bp = first_bp(d, "W")
    check(len(bp) == 1 and rel(bp[0], wc) < 1e-11,
          "spun_rod: BP of the hanging rod at %s, closed form W = %.15g" % (bp, wc))
    trivial = d["branches"][0]["points"] if d["branches"] else []
    check(trivial and all(pt["state"]["a"] == 0 for pt in trivial),
          "spun_rod: the hanging rod is an equilibrium exactly (a = 0 at every point)")
    check(not labelled(d, "LP", "W"), "spun_rod: no LP (the pitchfork is one BP)")
    turned = [b for b in d["branches"] if b["parent"] == 1]
    worst = max((abs(math.cos(pt["state"]["a"]) - 3 * G / (2 * L * pt["W"] ** 2))
                 for b in turned for pt in b["points"][1:]), default=1.0)
    check(len(turned) == 2 and worst < 1e-10,
          "spun_rod: %d branches from the BP, on cos a = 3 g / (2 L W^2) within %.1e"
          % (len(turned), worst))


def hoop_free():
    m, M, R, W = 0.1, 1.0, 0.5, 6.0
    th = math.acos(G / (R * W * W))
    inertia = M * R * R / 2 + m * R * R * math.sin(th) ** 2
    omega = W * math.sin(th) * math.sqrt(1 + 4 * m * R * R * math.cos(th) ** 2 / inertia)
    steady_and_linearize("hoop_free", ["--unknown", "th"], "th", th, omega, {})
    d = cont("hoop_free", ["--par", "W", "--set", "W=3", "--init", "th=0", "--opt", "parmax=8",
                           "--at", "W=6"])
    wc = math.sqrt(G / R)
    bp = first_bp(d, "W")
    check(len(bp) == 1 and rel(bp[0], wc) < 1e-11,
          "hoop_free: BP at the bottom at %s, closed form W^2 = g/R: %.15g" % (bp, wc))
    uz = [pt for b in d["branches"] if b["parent"] == 1 for pt in b["points"]
          if pt["label"] == "UZ"]
    ok = len(uz) == 2
    for pt in uz:
        w = pt["W"]
        t = math.acos(G / (R * w * w))
        inertia = M * R * R / 2 + m * R * R * math.sin(t) ** 2
        om = w * math.sin(t) * math.sqrt(1 + 4 * m * R * R * math.cos(t) ** 2 / inertia)
        im = imag_parts(pt["eigenvalues"])
        ok = ok and abs(abs(pt["state"]["th"]) - t) < 1e-10 and len(im) == 1 and \
            rel(im[0], om) < 1e-9
    check(ok, "hoop_free: the turned branches at W = 6 on the closed form (angle and swing)")


def cone_body():
    m, l, A, C, th = 2.0, 0.4, 0.05, 0.02, 0.6
    Ap = A + m * l * l
    rate = math.sqrt(m * G * l / ((Ap - C) * math.cos(th)))
    inertia = Ap * math.sin(th) ** 2 + C * math.cos(th) ** 2
    omega = math.sqrt(((Ap - C) * rate ** 2 * math.sin(th) ** 2 +
                       rate ** 2 * (Ap - C) ** 2 * math.sin(2 * th) ** 2 / inertia) / Ap)
    steady_and_linearize("cone_body", ["--unknown", "dpsi"], "dpsi", rate, omega, {})
    d = cont("cone_body", ["--par", "W", "--set", "W=6", "--opt", "ds=-0.02", "--opt",
                           "parmin=3", "--opt", "parmax=10"])
    wc = math.sqrt(m * G * l / (Ap - C))
    bp = first_bp(d, "W")
    check(len(bp) == 1 and rel(bp[0], wc) < 1e-11,
          "cone_body: the cone closes at a BP %s, closed form %.15g" % (bp, wc))
    check(not labelled(d, "LP", "W"), "cone_body: no LP where the cone closes")
    cone = d["branches"][0]["points"] if d["branches"] else []
    worst = max((rel(pt["W"] ** 2 * math.cos(pt["state"]["theta"]), m * G * l / (Ap - C))
                 for pt in cone), default=1.0)
    check(worst < 1e-10, "cone_body: every point on W^2 cos(theta) = m g l / (A' - C) within "
          "%.1e" % worst)
    hanging = [b for b in d["branches"] if b["parent"] == 1]
    check(len(hanging) == 2 and all(abs(pt["state"]["theta"]) < 1e-12
                                    for b in hanging for pt in b["points"]),
          "cone_body: the hanging body's branch both ways from the BP")


def rotating_double():
    l = 1.0
    w1 = math.sqrt((2 - math.sqrt(2)) * G / l)
    w2 = math.sqrt((2 + math.sqrt(2)) * G / l)
    d = cont("rotating_double", ["--par", "W", "--set", "W=1", "--opt", "parmax=6.5", "--at",
                                 "W=1.5,4"])
    bp = first_bp(d, "W")
    check(len(bp) == 2 and rel(bp[0], w1) < 1e-11 and rel(bp[1], w2) < 1e-11,
          "rotating_double: BPs at %s, closed forms %.15g, %.15g" % (bp, w1, w2))
    uz = [pt for pt in d["branches"][0]["points"] if pt["label"] == "UZ"] \
        if d["branches"] else []
    ok = len(uz) == 2
    for pt in uz:
        w = pt["W"]
        want = [complex(w * w - wi * wi) ** 0.5 for wi in (w1, w2)]
        got = [complex(re, im) for re, im in pt["eigenvalues"]]
        for z in want:
            for s in (1, -1):
                ok = ok and min(abs(s * z - g) for g in got) < 1e-8 * abs(z)
    check(ok, "rotating_double: eigenvalues +-sqrt(W^2 - w_i^2) at W = 1.5 and 4")


def governor():
    m, ms, L, W = 1.0, 0.5, 0.5, 6.0
    al = math.acos((m + ms) * G / (m * L * W * W))
    omega = W * math.sin(al) * math.sqrt(m / (m + 2 * ms * math.sin(al) ** 2))
    d = steady("governor", ["--unknown", "al"])
    if d:
        check(rel(d["state"]["al"], al) < 1e-11 and
              rel(d["state"]["s"], 2 * L * math.cos(al)) < 1e-11,
              "governor: steady al = %.15g, s = %.15g against %.15g, %.15g"
              % (d["state"]["al"], d["state"]["s"], al, 2 * L * math.cos(al)))
        im = imag_parts(d["eigenvalues"])
        check(len(im) == 1 and rel(im[0], omega) < 1e-9,
              "governor: the arms swing at %s against %.15g" % (im, omega))
        lin = linearize_imag("governor", d["state"], {})
        check(lin is not None and len(lin) == 1 and rel(lin[0], omega) < 1e-9,
              "governor: linearize there (minimal coordinates) gives %s" % lin)
    d = cont("governor", ["--par", "W", "--set", "W=6", "--init", "al=%r" % al, "--opt",
                          "ds=-0.02", "--opt", "parmin=4", "--opt", "parmax=8"])
    wc = math.sqrt((m + ms) * G / (m * L))
    bp = first_bp(d, "W")
    check(len(bp) == 1 and rel(bp[0], wc) < 1e-11,
          "governor: the arms leave the spindle at BP %s, closed form %.15g" % (bp, wc))
    pts = [pt for pt in d["branches"][0]["points"]] if d["branches"] else []
    worst = max((abs(math.cos(pt["state"]["al"]) - min(1.0, (m + ms) * G / (m * L * pt["W"] ** 2)))
                 + abs(pt["state"]["s"] - 2 * L * math.cos(pt["state"]["al"])) for pt in pts),
                default=1.0)
    check(pts and worst < 1e-10, "governor: every point on the closed form and the links "
          "within %.1e" % worst)


def spun_tube():
    m, J, k, l0, W = 0.2, 0.05, 20.0, 0.4, 5.0

    def closed(w):
        r = k * l0 / (k - m * w * w)
        return r, math.sqrt((k - m * w * w + 4 * m * m * r * r * w * w / (J + m * r * r)) / m)

    r, omega = closed(W)
    steady_and_linearize("spun_tube", ["--unknown", "r"], "r", r, omega, {})
    d = cont("spun_tube", ["--par", "W", "--set", "W=5", "--opt", "parmax=9", "--at", "W=7,8"])
    pts = d["branches"][0]["points"] if d["branches"] else []
    worst = max((rel(pt["state"]["r"], closed(pt["W"])[0]) for pt in pts), default=1.0)
    check(pts and worst < 1e-10, "spun_tube: every point on r = k l0 / (k - m W^2) within %.1e"
          % worst)
    uz = [pt for pt in pts if pt["label"] == "UZ"]
    check(len(uz) == 2 and all(len(imag_parts(pt["eigenvalues"])) == 1 and
                               rel(imag_parts(pt["eigenvalues"])[0], closed(pt["W"])[1]) < 1e-9
                               for pt in uz),
          "spun_tube: the swing at W = 7 and 8 on the closed form")


def failing_branch():
    p = dynkit(["continue", os.path.join(MODELS, "arm_pendulum.mech"), "--par", "a", "--set",
                "amax=0.06", "--opt", "parmax=0.1", "--unknown", "theta,dtheta", "--json"],
               "arm_failing")
    stop = json.loads(p.stdout)["branches"][0]["stop"] if p.returncode == 0 else ""
    check(stop.startswith("failed at a = 0.06") and "not finite" in stop,
          "a branch that runs where the model fails says where and why: '%s'" % stop)


for case in (spun_rod, hoop_free, cone_body, rotating_double, governor, spun_tube,
             failing_branch):
    case()
if FAILED:
    print("%d checks failed" % len(FAILED))
    sys.exit(1)
print("all checks passed")
