#!/usr/bin/env python3
"""examples/mechanisms/bicycle.mech against the benchmark bicycle of Meijaard, Papadopoulos,
Ruina and Schwab (2007), Proc. R. Soc. A 463, 1955-1982.

`dynkit linearize bicycle.mech --vary v=0:10:11` linearizes the whole multibody model (16
states, five constraints) about upright straight running in its minimal coordinates and
speeds; its four eigenvalues that are not zero must be those of the paper's linearized
equations M q'' + v C1 q' + (g K0 + v^2 K2) q = 0 (q = roll, steer; the matrices of its
eq. 5.4 to 14 digits), and the other six zero (x, y, yaw, both wheels' angles, the forward
speed). The weave and capsize speeds, where the real part of the weave pair and of the
capsize eigenvalue cross zero, are found from dynkit's eigenvalues alone (a grid, then
quadratic interpolation on two finer triples) and compared with the paper's 4.292382536341
and 6.024262015388 m/s. Usage: bicycle_check.py DYNKIT SOURCE_DIR. Exit 77 without NumPy."""
import csv
import io
import subprocess
import sys

try:
    import numpy as np
except ImportError:
    sys.exit(77)

DYNKIT, SOURCE = sys.argv[1], sys.argv[2]
MECH = SOURCE + "/examples/mechanisms/bicycle.mech"
FAILED = []

M = np.array([[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]])
C1 = np.array([[0.0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]])
K0 = np.array([[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]])
K2 = np.array([[0.0, 76.59734589573222], [0.0, 2.65431523794604]])
WEAVE, CAPSIZE = 4.292382536341, 6.024262015388  # the paper's table 2 (to 1e-12)


def check(cond, what):
    print(("ok    " if cond else "FAILED ") + what)
    if not cond:
        FAILED.append(what)


def benchmark(v):
    Mi = np.linalg.inv(M)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-Mi @ (9.81 * K0 + v * v * K2), -Mi @ (v * C1)]])
    return np.linalg.eigvals(A)


def linearize(values):
    """dynkit's eigenvalues at each speed: {v: [complex, ...]}"""
    vary = "v=" + values if isinstance(values, str) else "v=" + ",".join(repr(v) for v in values)
    p = subprocess.run([DYNKIT, "linearize", MECH, "--vary", vary, "--output", "-"],
                       capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stderr)
        sys.exit(1)
    out = {}
    for r in csv.DictReader(io.StringIO(p.stdout)):
        out.setdefault(float(r["v"]), []).append(complex(float(r["re"]), float(r["im"])))
    return out


def weave_re(eig):  # None where the weave pair is not complex (v = 0)
    return max((z.real for z in eig if abs(z.imag) > 1e-6), default=None)


def capsize_re(eig):
    """The capsize eigenvalue: the real parts of all but the weave pair and the castor mode
    (below -5 1/s) summed. Near its root it pairs with the forward speed's eigenvalue (about
    1e-13) into -8e-12 +- 2e-8 i; the sum of their real parts stays the capsize one within
    about 1e-13."""
    return sum(z.real for z in eig if abs(z.imag) < 1e-3 and z.real > -5)


def main():
    grid = linearize("0:10:11")
    worst = 0.0
    for v, eig in sorted(grid.items()):
        big = [z for z in eig if abs(z) > 1e-6]
        zeros = [z for z in eig if abs(z) <= 1e-6]
        want = benchmark(v)
        err = max(min(abs(z - w) for z in big) for w in want) / max(abs(want))
        worst = max(worst, err)
        check(len(big) == 4 and len(zeros) == 6 and max(abs(z) for z in zeros) < 1e-9
              and err < 1e-9, f"v = {v:g}: eigenvalues of M, C1, K0, K2 within {err:.1e}, six zeros")
    print(f"worst relative difference from the paper's matrices: {worst:.2e}")
    roots = []
    for f, sign in ((weave_re, -1), (capsize_re, 1)):  # weave stabilizes, capsize not
        vs = [v for v in sorted(grid) if f(grid[v]) is not None]
        k = next(i for i in range(len(vs) - 1)
                 if f(grid[vs[i]]) * sign < 0 < f(grid[vs[i + 1]]) * sign)
        a, b = vs[k], vs[k + 1]
        fa, fb = f(grid[a]), f(grid[b])
        roots.append(a - fa * (b - a) / (fb - fa))
    for h in (1e-2, 1e-4):  # quadratic through three speeds around each estimate
        pts = [r + d for r in roots for d in (-h, 0.0, h)]
        got = linearize(pts)
        new = []
        for r, f in zip(roots, (weave_re, capsize_re)):
            xs = [r - h, r, r + h]
            ys = [f(got[x]) for x in xs]
            c2, c1, c0 = np.polyfit(np.array(xs) - r, ys, 2)
            disc = np.sqrt(c1 * c1 - 4 * c2 * c0)
            d = min(((-c1 + disc) / (2 * c2), (-c1 - disc) / (2 * c2)), key=abs) if c2 else -c0 / c1
            new.append(r + d)
        roots = new
    check(abs(roots[0] - WEAVE) < 1e-9, f"weave speed {roots[0]:.12f} (paper {WEAVE}), "
          f"difference {abs(roots[0] - WEAVE):.1e}")
    check(abs(roots[1] - CAPSIZE) < 1e-9, f"capsize speed {roots[1]:.12f} (paper {CAPSIZE}), "
          f"difference {abs(roots[1] - CAPSIZE):.1e}")
    for f in FAILED:
        print("FAILED:", f)
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
