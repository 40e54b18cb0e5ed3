#!/usr/bin/env python3
"""The time of an equilibrium diagram in dynkit continue and in AUTO-07p, measured in the
same run (docs/performance.md, "Continuation against AUTO-07p"): the problems of
tests/continuation/auto_check.py (the same formulas, steps and range in both), each program
run REPEAT times, the best wall time kept; AUTO-07p's own "Total Time" (its computation,
without compiling the equations file and starting Python) beside it. dynkit's model is
compiled on the first run and cached, so its best time is the diagram's and the tool's start;
the same command with nmax=2 (the start and one step) measures the start alone.
Usage: continuation_auto.py DYNKIT [REPEAT]"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "tests", "continuation"))
import auto_check  # noqa: E402

dynkit = os.path.abspath(sys.argv[1])
repeat = int(sys.argv[2]) if len(sys.argv) > 2 else 3
if not shutil.which("auto-07p") or not shutil.which("gfortran"):
    print("skipped: auto-07p or gfortran is not installed")
    sys.exit(77)


def best(cmd, cwd):
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, check=True)
        times.append(time.perf_counter() - t)
    return min(times), out.stdout


print(f"{'problem':12} {'points':>6} {'dynkit [s]':>11} {'nmax=2 [s]':>11} "
      f"{'AUTO wall [s]':>14} {'AUTO Total Time [s]':>20}")
for name, pb in auto_check.PROBLEMS.items():
    work = tempfile.mkdtemp(prefix=f"bench-auto-{name}-")
    for fname, text in (("pb.f90", auto_check.fortran(pb)), ("c.pb", auto_check.constants(pb)),
                        ("run.auto", auto_check.RUN_AUTO % pb["icp"]),
                        (f"{name}.ode", auto_check.ode(pb))):
        with open(os.path.join(work, fname), "w") as f:
            f.write(text)
    t_dyn, out = best([dynkit, "continue", f"{name}.ode", "--par", pb["icp"], "--output",
                       "d.csv"], work)
    with open(os.path.join(work, "d.csv")) as f:
        points = sum(1 for line in f if line.startswith("1,"))
    t_start, _ = best([dynkit, "continue", f"{name}.ode", "--par", pb["icp"], "--opt", "nmax=2",
                       "--output", "s.csv"], work)
    t_auto, aout = best(["auto-07p", "run.auto"], work)
    total = re.findall(r"Total Time\s+([0-9.Ee+-]+)", aout)
    print(f"{name:12} {points:6d} {t_dyn:11.4f} {t_start:11.4f} {t_auto:14.3f} "
          f"{(float(total[-1]) if total else float('nan')):20.4f}")
    shutil.rmtree(work, ignore_errors=True)
