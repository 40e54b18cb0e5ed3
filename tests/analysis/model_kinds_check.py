#!/usr/bin/env python3
"""Every analysis command on every model kind (docs/analysis.md, "Model kinds"): equilibria,
steady, continue, lyapunov, linearize, bvp and plot --phase-plane on a discrete map, a delay
equation, a Volterra equation, a model with Wiener noise, one with a Markov state, a DAE (0=
lines), a file with bdry lines and a C model. Each combination either gives the right answer
(checked here against the closed form of its linearization: eigenvalues of 2 x 2 matrices,
a map's fixed point 1 - 1/r and its multipliers), or refuses with exit 2 and a message that
names what is not supported, or answers with a note on standard error saying what it assumed
(noise taken as 0, Markov states held). Usage: model_kinds_check.py DYNKIT EXAMPLES_DIR"""
import cmath
import json
import os
import shutil
import subprocess
import sys
import tempfile

dynkit, examples = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
work = tempfile.mkdtemp(prefix="dynkit-kinds-")
failures = []

MODELS = {
    # the delayed logistic map: fixed point x = y = 1 - 1/r, multipliers of
    # mu^2 - mu + (r - 1) = 0
    "map.ode": "x(t+1)=r*x*(1-y)\ny(t+1)=x\npar r=1.5\ninit x=0.3, y=0.3\n@ meth=discrete\n"
               "bdry x-0.3\nbdry y-0.2\ndone\n",
    "delay.ode": "par k=0.5\nx'=y\ny'=-x-k*delay(x,1)-0.2*y\nx(0)=0.1\ny(0)=0\n@ delay=2\n"
                 "bdry x-0.1\nbdry y\ndone\n",
    "volterra.ode": "par a=1\nx'=-a*x+int{exp(-t)#y}\ny'=-y+0.5*x\ninit x=1,y=0\n"
                    "bdry x-1\nbdry y\ndone\n",
    # van der Pol with noise: the deterministic part's origin has 0.5 +- i sqrt(3)/2
    "noise.ode": "wiener w\npar mu=1, s=0.3\nx'=y\ny'=mu*(1-x^2)*y-x+s*w\ninit x=1, y=0\n"
                 "bdry x-1\nbdry y\n@ total=10, dt=0.01\ndone\n",
    "markov.ode": "par a=0.5,b=1.5\nmarkov z 2\n{0} {a}\n{b} {0}\nx'=-x+z\n"
                  "@ meth=euler,dt=0.02,total=20\nbdry x-0.3\nbdry z\ndone\n",
    # x' = y, y' = -a z - 0.3 y, 0 = z - x - z^3/10: at the origin dz/dx = 1, so the
    # eigenvalues are those of [[0, 1], [-a, -0.3]]
    "dae.ode": "par a=1\nx'=y\ny'=-a*z-0.3*y\n0=z-x-z^3/10\nsolv z=0\naux zz=z\n"
               "init x=0.5, y=0\n@ total=10\ndone\n",
}
for name, text in MODELS.items():
    with open(os.path.join(work, name), "w") as f:
        f.write(text)
shutil.copy(os.path.join(examples, "vdp_bvp.ode"), os.path.join(work, "bdry.ode"))
shutil.copy(os.path.join(examples, "spring_mass.c"), os.path.join(work, "cmodel.c"))


def run(*args):
    p = subprocess.run([dynkit, *args], cwd=work, capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


def refused(what, args, *words):
    rc, _, err = run(*args)
    if rc != 2 or not all(w in err for w in words):
        failures.append(f"{what}: expected exit 2 naming {words}, got exit {rc}: {err.strip()}")


def noted(what, args, *words):
    """exit 0, a note with the words; the output returned"""
    rc, out, err = run(*args)
    notes = [l for l in err.splitlines() if l.startswith("dynkit: note:")]
    if rc != 0 or not any(all(w in l for w in words) for l in notes):
        failures.append(f"{what}: expected exit 0 with a note naming {words}, got exit {rc}: "
                        f"{err.strip()}")
    return out if rc == 0 else None


def eig_close(what, got, want, tol=1e-8):
    key = lambda z: (round(z.real, 6), z.imag)
    got = sorted((complex(re, im) for re, im in got), key=key)
    want = sorted((complex(z) for z in want), key=key)
    if len(got) != len(want) or any(abs(a - b) > tol * max(1.0, abs(b))
                                    for a, b in zip(got, want)):
        failures.append(f"{what}: eigenvalues {got}, expected {want}")


def ok_json(what, args):
    rc, out, err = run(*args)
    if rc != 0:
        failures.append(f"{what}: exit {rc}: {err.strip()}")
        return None
    return json.loads(out)


def eig2(a, b, c, d):
    """the eigenvalues of [[a, b], [c, d]]"""
    tr, det = a + d, a * d - b * c
    s = cmath.sqrt(tr * tr / 4 - det)
    return [tr / 2 + s, tr / 2 - s]


# ---- a discrete map
r = 1.5
mus = [(1 + cmath.sqrt(1 - 4 * (r - 1))) / 2, (1 - cmath.sqrt(1 - 4 * (r - 1))) / 2]
d = ok_json("map: equilibria", ["equilibria", "map.ode", "--json"])
if d:
    fixed = [e for e in d["equilibria"] if abs(e["state"]["x"] - (1 - 1 / r)) < 1e-9]
    if len(fixed) != 1:
        failures.append(f"map: the fixed point 1 - 1/r not found: {d['equilibria']}")
    else:
        eig_close("map: multipliers", fixed[0]["eigenvalues"], mus)
d = ok_json("map: continue", ["continue", "map.ode", "--par", "r", "--json"])
if d:
    p = d["branches"][0]["points"][0]
    if d.get("map") is not True or abs(p["state"]["x"] - (1 - 1 / r)) > 1e-9:
        failures.append(f"map: continue's start {p['state']}, expected x = {1 - 1 / r}")
    else:
        eig_close("map: continue's multipliers", p["multipliers"], mus)
refused("map: steady", ["steady", "map.ode", "--unknown", "x"], "discrete map")
refused("map: linearize", ["linearize", "map.ode"], "discrete map", "equilibria")
refused("map: linearize --equilibrium", ["linearize", "map.ode", "--equilibrium"],
        "discrete map")
refused("map: bvp", ["bvp", "map.ode"], "discrete map", "not supported")
refused("map: phase plane", ["plot", "map.ode", "--phase-plane", "-o", "m.svg"], "discrete map")
rc, out, err = run("lyapunov", "map.ode", "--json")
if rc != 0 or json.loads(out).get("map") is not True:
    failures.append(f"map: lyapunov: exit {rc} {err.strip()}")

# ---- delays and Volterra integrals: refused wherever f is read away from a run
for f, word in (("delay.ode", "delay"), ("volterra.ode", "Volterra")):
    refused(f"{f}: equilibria", ["equilibria", f], word)
    refused(f"{f}: linearize", ["linearize", f], word)
    refused(f"{f}: lyapunov", ["lyapunov", f], word)
    refused(f"{f}: bvp", ["bvp", f], word, "not supported")
    refused(f"{f}: phase plane", ["plot", f, "--phase-plane", "-o", "d.svg"], word,
            "not supported")
    for args in (["steady", f, "--unknown", "x"], ["continue", f, "--par", "k" if
                                                   f == "delay.ode" else "a"]):
        rc, _, err = run(*args)
        if rc == 0 or word not in err:
            failures.append(f"{f}: {args[0]}: exit {rc}, {err.strip()!r}")

# ---- noise: the deterministic part, with a note
want = eig2(0, 1, -1, 1)
out = noted("noise: equilibria", ["equilibria", "noise.ode", "--json"], "noise", "0")
if out:
    eig_close("noise: equilibria", json.loads(out)["equilibria"][0]["eigenvalues"], want)
out = noted("noise: continue", ["continue", "noise.ode", "--par", "mu", "--json"], "noise")
if out:
    eig_close("noise: continue", json.loads(out)["branches"][0]["points"][0]["eigenvalues"],
              want)
out = noted("noise: linearize", ["linearize", "noise.ode", "--equilibrium", "--json"], "noise")
out = noted("noise: steady", ["steady", "noise.ode", "--unknown", "x,y", "--json"], "noise")
if out:
    eig_close("noise: steady", json.loads(out)["eigenvalues"], want)
noted("noise: bvp", ["bvp", "noise.ode", "-o", "n.csv"], "noise")
noted("noise: phase plane", ["plot", "noise.ode", "--phase-plane", "-o", "n.svg"], "noise",
      "trajectories carry the noise")
# the exponents of van der Pol's cycle (the deterministic part): the largest 0, along the
# flow, within its error estimate
out = noted("noise: lyapunov", ["lyapunov", "noise.ode", "--json", "--tspan", "0:400"],
            "noise")
if out:
    ly = json.loads(out)
    if not abs(ly["exponents"][0]) <= 3 * ly["errors"][0] + 1e-3:
        failures.append(f"noise: lyapunov: the cycle's largest exponent {ly['exponents'][0]} "
                        f"+- {ly['errors'][0]}, expected 0")

# ---- a Markov state: refused where it would be solved for, held with a note elsewhere
for args in (["equilibria", "markov.ode"], ["steady", "markov.ode", "--unknown", "x"],
             ["continue", "markov.ode", "--par", "a"],
             ["linearize", "markov.ode", "--equilibrium"]):
    refused(f"markov: {args[0]}", args, "Markov states", "not supported")
out = noted("markov: linearize", ["linearize", "markov.ode", "--json"], "Markov", "held")
if out:
    pt = json.loads(out)["points"][0]
    eig_close("markov: linearize", list(zip(pt["re"], pt["im"])), [-1, 0])
noted("markov: phase plane", ["plot", "markov.ode", "--phase-plane", "-o", "k.svg"], "Markov")
refused("markov: lyapunov", ["lyapunov", "markov.ode"], "Markov")

# ---- a DAE: its states' equations with the algebraic variable solved
want = eig2(0, 1, -1, -0.3)
d = ok_json("dae: equilibria", ["equilibria", "dae.ode", "--json"])
if d:
    eig_close("dae: equilibria", d["equilibria"][0]["eigenvalues"], want, 1e-7)
d = ok_json("dae: continue", ["continue", "dae.ode", "--par", "a", "--json"])
if d:
    for p in d["branches"][0]["points"]:
        eig_close(f"dae: continue at a = {p['a']}", p["eigenvalues"],
                  eig2(0, 1, -p["a"], -0.3), 1e-7)

# ---- bdry lines: the analysis of the differential equations (vdp_bvp: mu = 1, om = 6.6)
want = eig2(0, 6.6, -6.6, 6.6)
d = ok_json("bdry: equilibria", ["equilibria", "bdry.ode", "--json"])
if d:
    eig_close("bdry: equilibria", d["equilibria"][0]["eigenvalues"], want)
d = ok_json("bdry: continue", ["continue", "bdry.ode", "--par", "mu", "--json"])
if d:
    for p in d["branches"][0]["points"]:
        eig_close(f"bdry: continue at mu = {p['mu']}", p["eigenvalues"],
                  eig2(0, 6.6, -6.6, 6.6 * p["mu"]))

# ---- a C model: a damped spring m x'' = -k x - c x'
d = ok_json("C model: linearize", ["linearize", "cmodel.c", "--set", "c=0.5", "--set", "k=4",
                                   "--equilibrium", "--json"])
if d:
    pt = d["points"][0]
    eig_close("C model: linearize", list(zip(pt["re"], pt["im"])), eig2(0, 1, -4, -0.5))
d = ok_json("C model: continue", ["continue", "cmodel.c", "--par", "k", "--set", "c=0.5",
                                  "--set", "k=1", "--json"])
if d:
    for p in d["branches"][0]["points"]:
        eig_close(f"C model: continue at k = {p['k']}", p["eigenvalues"],
                  eig2(0, 1, -p["k"], -0.5))

shutil.rmtree(work, ignore_errors=True)
for f in failures:
    print("FAIL:", f)
if not failures:
    print("every analysis command answers, refuses or notes on every model kind as documented")
sys.exit(1 if failures else 0)
