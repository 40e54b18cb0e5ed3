#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""A periodic branch: dynkit's collocation against AUTO-07p and against a sweep of runs, in
the same run (docs/performance.md, "Periodic orbits").

The problem: the Roessler system x' = -y - z, y' = x + a y, z' = 0.2 + z (x - 5.7) in a,
the branch of periodic orbits from its Hopf point (a = 0.0059784) to a = 0.25, its period
doubling, and the period-doubled branch from it to a = 0.25. Both programs use the same
discretization (NTST 50 intervals of NCOL 4 Gauss points, mesh adapted every 3 points),
the same steps (DS 0.01, DSMIN 1e-5, DSMAX 0.05) and stop at a = 0.25; AUTO-07p runs with
one thread (OMP_NUM_THREADS=1) and its own timer ("Total Time", wall time by
omp_get_wtime) is read, which leaves out its compilation of the problem; dynkit's wall and
CPU times are bench_colloc's (the library called directly, no file written). The sweep is what a user without continuation would run
for the same picture: `dynkit sweep` of the branch's number of values of a, each run long
enough (2000 time units, dp45 at rtol 1e-8) for the maxima of x on the attractor, and
gives only the stable orbits' maxima.

With --check (a test: tests run it, never timed): one repeat, no sweep; the period
doublings of both branches must be AUTO-07p's, as many and at the same a, period and L2 norm
to AUTO's printed 6 digits (relative 1e-5); what failed is kept under ARTIFACTS/colloc_auto.

Usage: colloc_auto.py BUILD_DIR [REPEATS] [--check ARTIFACTS]
(exit 77 when auto-07p or gfortran is not installed)
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ARGS = [a for a in sys.argv[1:]]
CHECK = None
if "--check" in ARGS:
    k = ARGS.index("--check")
    CHECK = ARGS[k + 1] if k + 1 < len(ARGS) else "."
    del ARGS[k:k + 2]
BUILD = ARGS[0] if ARGS else "build"
REPEATS = 1 if CHECK else (int(ARGS[1]) if len(ARGS) > 1 else 3)

FORTRAN = """\
SUBROUTINE FUNC(NDIM,U,ICP,PAR,IJAC,F,DFDU,DFDP)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM, ICP(*), IJAC
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM), PAR(*)
  DOUBLE PRECISION, INTENT(OUT) :: F(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: DFDU(NDIM,NDIM), DFDP(NDIM,*)
  F(1) = -U(2) - U(3)
  F(2) = U(1) + PAR(1)*U(2)
  F(3) = PAR(2) + U(3)*(U(1) - PAR(3))
END SUBROUTINE FUNC
SUBROUTINE STPNT(NDIM,U,PAR,T)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(INOUT) :: U(NDIM),PAR(*)
  DOUBLE PRECISION, INTENT(IN) :: T
  DOUBLE PRECISION A, B, C, Y
  A = 0.001d0; B = 0.2d0; C = 5.7d0
  PAR(1) = A; PAR(2) = B; PAR(3) = C
  Y = (-C + SQRT(C*C - 4*A*B))/(2*A)
  U(1) = -A*Y; U(2) = Y; U(3) = -Y
END SUBROUTINE STPNT
SUBROUTINE BCND
END SUBROUTINE BCND
SUBROUTINE ICND
END SUBROUTINE ICND
SUBROUTINE FOPT
END SUBROUTINE FOPT
SUBROUTINE PVLS
END SUBROUTINE PVLS
"""
CONSTANTS = """\
NDIM=3, IPS=1, IRS=0, ILP=1
ICP=[1]
NTST=50, NCOL=4, IAD=3, ISP=2, ISW=1, IPLT=0, NBC=0, NINT=0
NMX=400, NPR=1000, DS=0.01, DSMIN=1e-5, DSMAX=0.05
EPSL=1e-7, EPSU=1e-7, EPSS=1e-5, ITMX=8, NWTN=3, ITNW=7, JAC=1
UZSTOP={1: 0.25}
"""
SCRIPT = """\
eq = run(e='ros', c='ros', DS=0.001)
po = run(eq('HB1'), IPS=2, ICP=[1, 11])
po2 = run(po('PD1'), ISW=-1, ICP=[1, 11])
"""
ODE = """\
# Roessler's system for the sweep of bench/colloc_auto.py
par a=0.05, b=0.2, c=5.7
x' = -y - z
y' = x + a*y
z' = b + z*(x - c)
init x=1, y=0, z=0
@ total=2000, dt=0.5
done
"""


def auto_jacobian(text):
    """FUNC with the analytic Jacobian (JAC=1), as dynkit uses the model's."""
    return text.replace("  F(3) = PAR(2) + U(3)*(U(1) - PAR(3))\n",
                        "  F(3) = PAR(2) + U(3)*(U(1) - PAR(3))\n"
                        "  IF (IJAC == 0) RETURN\n"
                        "  DFDU(1,1) = 0; DFDU(1,2) = -1; DFDU(1,3) = -1\n"
                        "  DFDU(2,1) = 1; DFDU(2,2) = PAR(1); DFDU(2,3) = 0\n"
                        "  DFDU(3,1) = U(3); DFDU(3,2) = 0; DFDU(3,3) = U(1) - PAR(3)\n"
                        "  IF (IJAC == 1) RETURN\n"
                        "  DFDP(1,1) = 0; DFDP(2,1) = U(2); DFDP(3,1) = 0\n")


def run_auto(tmp):
    with open(os.path.join(tmp, "ros.f90"), "w") as f:
        f.write(auto_jacobian(FORTRAN))
    with open(os.path.join(tmp, "c.ros"), "w") as f:
        f.write(CONSTANTS)
    with open(os.path.join(tmp, "run.auto"), "w") as f:
        f.write(SCRIPT)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    best = None
    for _ in range(REPEATS):
        p = subprocess.run(["auto-07p", "run.auto"], cwd=tmp, capture_output=True, text=True,
                           env=env)
        if p.returncode:
            raise SystemExit("auto-07p failed:\n" + p.stdout[-2000:] + p.stderr[-2000:])
        times = [float(t) for t in re.findall(r"Total Time\s+(\S+)", p.stdout)]
        pds = re.findall(r"^\s*\d+\s+\d+\s+PD\s+\d+\s+(\S+)\s+(\S+)(?:\s+\S+){3}\s+(\S+)",
                         p.stdout, re.M)
        if len(times) < 3:
            raise SystemExit("auto-07p printed no timings:\n" + p.stdout[-2000:])
        ends = re.findall(r"^\s*\d+\s+(\d+)\s+UZ", p.stdout, re.M)
        RAW["auto"] = p.stdout
        if best is None or times[1] < best["branch"]:
            best = {"branch": times[1], "doubled": times[2],
                    "points": [int(e) for e in ends],
                    "pd": [{"a": float(a), "l2": float(l2), "period": float(T)}
                           for a, l2, T in pds]}
    return best


RAW = {}


def run_dynkit():
    exe = os.path.join(BUILD, "bench", "bench_colloc")
    p = subprocess.run([exe, str(REPEATS)], capture_output=True, text=True, check=True)
    RAW["dynkit"] = p.stdout
    return json.loads(p.stdout)


def check(auto, ours):
    """0 when the period doublings agree with AUTO-07p's, else 1 (kept under CHECK)."""
    mine = ours["branch"]["pd"] + ours["doubled"]["pd"]
    bad = []
    if len(mine) != len(auto["pd"]):
        bad.append(f"{len(mine)} PD points, AUTO-07p {len(auto['pd'])}")
    for k, (a, b) in enumerate(zip(mine, auto["pd"])):
        for key in ("a", "period", "l2"):
            ok = abs(a[key] - b[key]) <= 1e-5 * abs(b[key])
            print(("ok    " if ok else "FAIL  ") +
                  f"PD {k + 1} {key}: dynkit {a[key]:.10g}, AUTO-07p {b[key]:.6g}")
            if not ok:
                bad.append(f"PD {k + 1} {key}")
    if bad:
        d = os.path.join(CHECK, "colloc_auto")
        os.makedirs(d, exist_ok=True)
        for name, text in RAW.items():
            with open(os.path.join(d, name + ".txt"), "w") as f:
                f.write(text)
        print("FAILED: " + "; ".join(bad) + f" (kept in {d})")
        return 1
    return 0


def run_sweep(tmp, points):
    path = os.path.join(tmp, "roessler.ode")
    with open(path, "w") as f:
        f.write(ODE)
    dynkit = os.path.join(BUILD, "dynkit")
    args = [dynkit, "sweep", path, "--vary", f"a=0.006:0.25:{points}", "--method", "dp45",
            "--rtol", "1e-8", "--atol", "1e-10", "--reduce", "max:x", "--threads", "1",
            "--quiet", "-o", os.path.join(tmp, "sweep.csv")]
    subprocess.run(args, check=True, capture_output=True)  # compiles the model once
    best = float("inf")
    for _ in range(REPEATS):
        t0 = time.monotonic()
        subprocess.run(args, check=True, capture_output=True)
        best = min(best, time.monotonic() - t0)
    return best


def main():
    if not shutil.which("auto-07p") or not shutil.which("gfortran"):
        print("SKIP: auto-07p or gfortran is not installed (scripts/install-deps.sh)")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        auto = run_auto(tmp)
        ours = run_dynkit()
        if CHECK:
            return check(auto, ours)
        sweep = run_sweep(tmp, ours["branch"]["points"])
    print("Roessler in a, NTST 50, NCOL 4, from the Hopf point to a = 0.25 (best of %d)"
          % REPEATS)
    print(f"{'':24} {'dynkit wall':>12} {'dynkit CPU':>12} {'AUTO-07p wall':>14} "
          f"{'points':>12}")
    for k, name in enumerate(("branch", "doubled")):
        pts = auto["points"][k] if len(auto["points"]) > k else "?"
        print(f"{'periodic' if k == 0 else 'period-doubled':24} {ours[name]['wall']:12.3f} "
              f"{ours[name]['cpu']:12.3f} {auto[name]:14.3f} {ours[name]['points']:>5} / "
              f"{pts:<5}")
    for k, (a, b) in enumerate(zip(ours["branch"]["pd"] + ours["doubled"]["pd"], auto["pd"])):
        print(f"PD {k + 1}: a = {a['a']:.10f} / {b['a']:.5E}, period {a['period']:.8f} / "
              f"{b['period']:.5E}, L2 {a['l2']:.6f} / {b['l2']:.5E}")
    print(f"sweep of {ours['branch']['points']} runs of 2000 time units (dp45, rtol 1e-8, "
          f"one thread): {sweep:.3f} s wall")
    return 0


if __name__ == "__main__":
    sys.exit(main())
