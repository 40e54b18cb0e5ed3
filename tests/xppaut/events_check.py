#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Globals as XPPAUT fires them (docs/model-files.md, "Globals and events").

1. examples/models/iaf_pair.ode, two coupled integrate-and-fire neurons, against an
   independent event simulation: between events the solution is exact
   (v = i + (v0 - i) exp(-(t - t0))), the next threshold crossing comes in closed form, and at
   each instant the globals fire under the documented rules (those crossing at that time in
   file order, each reset seeing the ones before, then in cycles every global whose condition
   the resets carried onto or across zero, each at most once). dynkit (rtol 1e-10) must be
   within 1e-7 of it at every sample and fire at the same times; XPPAUT (`xppaut -silent`,
   RK4 at dt with events placed by linear interpolation), when installed, within 10 dt^2.
2. tests/xppaut/events/gap_pair.ode, two integrate-and-fire neurons with a gap junction, each
   spike resetting itself and kicking the other, `global 0` lines resetting a neuron a kick
   carries across, started so close that both cross threshold within one step: against an
   event simulation of XPPAUT's instants (the exact linear flow between events, each
   crossing found to rounding; at an instant the crossing neuron's condition just past zero,
   the globals fired in rounds: each round's assignments in file order, each seeing the ones
   before; then every global not yet fired whose condition moved by more than 1e-10 from its
   value at the instant before any assignment, onto or across zero for sign 1 and -1, to the
   other sign or from or to zero for sign 0, fires in the next round; each at most once).
   dynkit (rtol 1e-10) within 1e-7 at every sample, spike times within 1e-8, v1 = v2 exactly
   after the first instant (with RK4 at the file's dt too); XPPAUT, when installed, within
   10 dt^2 of the simulation and v1 = v2 exactly after the first instant.
3. The small files in tests/xppaut/events/ (one rule each: a cascade, declaration order, a
   chain back to a global that already fired, sign -1, sign 0), run with RK4 at their dt
   (exact for their linear states), against the final row each file derives in its
   `# expect:` line (to 1e-6) and against XPPAUT at every sample both write, within
   10 dt^2 max(1, |value|) (XPPAUT interpolates every state linearly inside the step of an
   event).

Exit status 0 when all agree, 1 when not.
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compat  # noqa: E402  (same directory: keep_artifacts)

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
IAF = os.path.join(ROOT, "examples", "models", "iaf_pair.ode")


def iaf_reference(t_samples, i=(1.2, 1.1), eps=0.2, v0=(0.0, 0.3)):
    """States at t_samples and the event times (time, neuron) of the pair under the rules."""
    i = np.array(i)
    v = np.array(v0, dtype=float)
    t = 0.0
    events = []
    out = np.empty((len(t_samples), 2))
    k = 0

    def flow(v, dt):
        return i + (v - i) * math.exp(-dt)

    def crossing(v):
        """Time to each neuron's threshold (inf when it does not reach it)."""
        return [math.log((i[j] - v[j]) / (i[j] - 1.0)) if i[j] > 1.0 and v[j] < 1.0
                else math.inf for j in range(2)]

    def reset(j, v):
        v = v.copy()
        v[j] = 0.0
        v[1 - j] += eps
        return v

    t_end = t_samples[-1]
    while True:
        dts = crossing(v)
        dt = min(dts)
        while k < len(t_samples) and t_samples[k] < t + dt:
            out[k] = flow(v, t_samples[k] - t)
            k += 1
        if t + dt > t_end:
            break
        t += dt
        v = flow(v, dt)
        first = [j for j in range(2) if dts[j] <= dt * (1 + 1e-14)]
        g0 = v - 1.0
        for j in first:  # the globals crossing now, in file order, each seeing the one before
            v[j] = 1.0  # exactly at its threshold
            g0[j] = 0.0
        fired = set()
        cycle = first
        while cycle:
            for j in cycle:
                events.append((t, j))
                v = reset(j, v)
                fired.add(j)
            g1 = v - 1.0
            cycle = [j for j in range(2) if j not in fired and g0[j] <= 0.0 <= g1[j]
                     and g1[j] != g0[j]]
    return out, events


GAP = os.path.join(HERE, "events", "gap_pair.ode")
# gap_pair.ode's globals in file order: (sign, the neuron whose v - 1 is the condition,
# the assignments (neuron, value from the state v and the kick k) in order)
GAP_GLOBALS = [
    (1, 0, [(0, lambda v, k: 0.0), (1, lambda v, k: v[1] + k)]),
    (1, 1, [(1, lambda v, k: 0.0), (0, lambda v, k: v[0] + k)]),
    (0, 0, [(0, lambda v, k: 0.0)]),
    (0, 1, [(1, lambda v, k: 0.0)]),
]


def xppaut_rounds(v, crossing, globals_, k):
    """XPPAUT's instant on the state v (a list, changed in place): the globals of crossing
    fire first; returns the globals fired, in order."""
    # the conditions at the instant before any assignment; a crossing neuron's just past zero
    g0 = [math.ulp(0.0) if j in crossing else v[j] - 1.0 for (_, j, _) in globals_]
    fired, order = set(), []
    now = [q for q, (sign, j, _) in enumerate(globals_) if sign == 1 and j in crossing]
    while now:
        for q in now:  # file order, each assignment seeing those before
            for (target, value) in globals_[q][2]:
                v[target] = value(v, k)
            fired.add(q)
            order.append(q)
        now = []
        for q, (sign, j, _) in enumerate(globals_):
            if q in fired:
                continue
            a, b = g0[q], v[j] - 1.0
            if not abs(b - a) > 1e-10:
                continue
            if ((sign == 1 and a <= 0.0 <= b) or (sign == -1 and a >= 0.0 >= b)
                    or (sign == 0 and a * b <= 0.0)):
                now.append(q)
    return order


def gap_reference(t_samples, i=1.2, g=0.1, k=0.05, v0=(0.5, 0.4995)):
    """States of gap_pair.ode at t_samples and its spikes (time, neuron) under the rules."""
    from scipy.optimize import brentq

    def flow(v, dt):
        s = 2 * i + (v[0] + v[1] - 2 * i) * math.exp(-dt)
        d = (v[0] - v[1]) * math.exp(-(1 + 2 * g) * dt)
        return [(s + d) / 2, (s - d) / 2]

    def crossing(v, j):
        f = lambda dt: flow(v, dt)[j] - 1.0
        return brentq(f, 0.0, 50.0, xtol=1e-15, rtol=4 * np.finfo(float).eps) \
            if f(50.0) > 0 else math.inf

    v, t, k_out, spikes = list(v0), 0.0, 0, []
    out = np.empty((len(t_samples), 2))
    while True:
        dts = [crossing(v, j) for j in range(2)]
        dt = min(dts)
        while k_out < len(t_samples) and t_samples[k_out] < t + dt:
            out[k_out] = flow(v, t_samples[k_out] - t)
            k_out += 1
        if t + dt > t_samples[-1]:
            break
        t += dt
        v = flow(v, dt)
        crossed = {j for j in range(2) if dts[j] <= dt * (1 + 1e-10)}
        for j in crossed:
            v[j] = 1.0
        for q in xppaut_rounds(v, crossed, GAP_GLOBALS, k):
            if GAP_GLOBALS[q][0] == 1:
                spikes.append((t, GAP_GLOBALS[q][1]))
    return out, spikes


def equal_after(rows, t_first):
    """v1 == v2 (to the last digit written) in every row after t_first."""
    after = rows[rows[:, 0] > t_first + 1e-9]
    return len(after) > 0 and bool(np.all(after[:, 1] == after[:, 2]))


def check_gap(dynkit, tmp):
    ok = True
    dyn, err = run_dynkit(dynkit, GAP, "--rtol", "1e-10", "--atol", "1e-12", "--event",
                          "global1", "--event", "global2")
    ref, spikes = gap_reference(dyn[:, 0])
    e = float(np.max(np.abs(dyn[:, 1:] - ref)))
    times = [float(line.split(" at t = ")[1].split(":")[0]) for line in err.splitlines()
             if " at t = " in line]
    et = max(abs(a - b[0]) for a, b in zip(times, spikes)) if times else math.inf
    first = spikes[0][0] if spikes else math.inf
    rk4, _ = run_dynkit(dynkit, GAP, "--method", "rk4")
    sync = equal_after(dyn, first) and equal_after(rk4, first)
    print("gap_pair.ode: %d spikes, the first instant at t = %.10g (neuron %d's kick carries "
          "neuron %d across); dynkit: states within %.1e of the event simulation, spike times "
          "within %.1e, v1 = v2 exactly after it: %s"
          % (len(spikes), first, spikes[0][1] + 1 if spikes else 0,
             spikes[1][1] + 1 if len(spikes) > 1 else 0, e, et, "yes" if sync else "no"))
    if e > 1e-7 or len(times) != len(spikes) or et > 1e-8 or not sync:
        print("  dynkit differs from the event simulation (%d spikes against %d)"
              % (len(times), len(spikes)))
        ok = False
    if len(spikes) < 8 or spikes[0][0] != spikes[1][0] or spikes[0][1] == spikes[1][1]:
        print("  the reference does not fire both neurons at the first instant: the test "
              "lost its point")
        ok = False
    xpp = run_xppaut(GAP, tmp)
    if xpp is not None:
        r = gap_reference(xpp[:, 0])[0]
        ex = float(np.max(np.abs(xpp[:, 1:] - r)))
        dt = float(xpp[1, 0] - xpp[0, 0])
        xsync = equal_after(xpp, first)
        print("  XPPAUT: within %.1e of the event simulation (10 dt^2 = %.1e allowed), "
              "v1 = v2 exactly after the first instant: %s" % (ex, 10 * dt * dt,
                                                                "yes" if xsync else "no"))
        if ex > 10 * dt * dt or not xsync:
            ok = False
    return ok


KEEP = {}  # the work directory, where dynkit's outputs are written too


def run_dynkit(dynkit, path, *args):
    p = subprocess.run([dynkit, "run", path] + list(args), capture_output=True, text=True)
    if KEEP.get("dir"):
        stem = os.path.join(KEEP["dir"], "dynkit-%s-%d" % (os.path.basename(path),
                                                            len(os.listdir(KEEP["dir"]))))
        with open(stem + ".csv", "w") as f:
            f.write(p.stdout)
        with open(stem + ".stderr", "w") as f:
            f.write(" ".join([dynkit, "run", path] + list(args)) + "\n" + p.stderr)
    if p.returncode != 0:
        raise RuntimeError("dynkit run %s failed: %s" % (path, p.stderr))
    return np.loadtxt(p.stdout.splitlines()[1:], delimiter=",", ndmin=2), p.stderr


def run_xppaut(path, tmp):
    if not shutil.which("xppaut"):
        return None
    out = os.path.join(tmp, os.path.basename(path) + ".dat")
    try:
        subprocess.run(["xppaut", path, "-silent", "-outfile", out], cwd=tmp,
                       capture_output=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return np.loadtxt(out, ndmin=2) if os.path.exists(out) else None


def common(a, b):
    """Rows of a and b at the same times (within 1e-6: XPPAUT writes 8 digits)."""
    ia, ib = [], []
    for r, t in enumerate(a[:, 0]):
        j = int(np.argmin(np.abs(b[:, 0] - t)))
        if abs(b[j, 0] - t) <= 1e-6 * max(1.0, abs(t)):
            ia.append(r)
            ib.append(j)
    return a[ia], b[ib]


def check_iaf(dynkit, tmp):
    ok = True
    dyn, err = run_dynkit(dynkit, IAF, "--rtol", "1e-10", "--atol", "1e-12", "--event",
                          "spike1", "--event", "spike2")
    ref, events = iaf_reference(dyn[:, 0])
    e = float(np.max(np.abs(dyn[:, 1:] - ref)))
    times = [float(line.split(" at t = ")[1].split(":")[0]) for line in err.splitlines()
             if " at t = " in line]
    et = max(abs(a - b[0]) for a, b in zip(times, events)) if times else math.inf
    together = sum(1 for a, b in zip(events, events[1:]) if a[0] == b[0])
    print("iaf_pair.ode: %d spikes, %d of them in pairs at one instant (the neurons fire "
          "together); dynkit: states within %.1e of the event simulation, spike times within "
          "%.1e" % (len(events), 2 * together, e, et))
    if e > 1e-7 or len(times) != len(events) or et > 1e-8:
        print("  dynkit differs from the event simulation (%d spikes against %d)"
              % (len(times), len(events)))
        ok = False
    if together < 10:
        print("  the reference does not synchronise: the test lost its point")
        ok = False
    xpp = run_xppaut(IAF, tmp)
    if xpp is not None:
        x, r = xpp, iaf_reference(xpp[:, 0])[0]
        ex = float(np.max(np.abs(x[:, 1:] - r)))
        print("  XPPAUT: within %.1e of the event simulation (10 dt^2 = 1e-3 allowed)" % ex)
        if ex > 1e-3:
            ok = False
    return ok


def check_rules(dynkit, tmp):
    ok = True
    folder = os.path.join(HERE, "events")
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".ode"):
            continue
        path = os.path.join(folder, name)
        with open(path) as f:
            text = f.read()
        what = text.splitlines()[0].lstrip("# ")
        expect = [float(v) for line in text.splitlines() if line.startswith("# expect:")
                  for v in line.split(":", 1)[1].split()]
        dyn, _ = run_dynkit(dynkit, path, "--method", "rk4")
        xpp = run_xppaut(path, tmp)
        line = "%-22s %s" % (name, what)
        bad = False
        if expect:
            e = float(np.max(np.abs(dyn[-1] - np.array(expect))))
            line += "; final row within %.1e of the expected" % e
            bad = e > 1e-6
        if xpp is not None:
            a, b = common(dyn, xpp)
            d = float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b))))
            line += "; XPPAUT: %d samples within %.1e" % (len(a), d)
            dt = float(dyn[1, 0] - dyn[0, 0])
            bad = bad or d > 10 * dt * dt or len(a) < len(xpp) // 2
        print(line)
        ok = ok and not bad
    return ok


def main():
    dynkit = sys.argv[1] if len(sys.argv) > 1 else "dynkit"
    with tempfile.TemporaryDirectory() as tmp:
        KEEP["dir"] = tmp
        ok = check_iaf(dynkit, tmp)
        ok = check_gap(dynkit, tmp) and ok
        ok = check_rules(dynkit, tmp) and ok
        if not ok:
            print("inputs and outputs kept in %s" % compat.keep_artifacts(
                dynkit, "xppaut-events", [tmp, IAF, os.path.join(HERE, "events")]))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
