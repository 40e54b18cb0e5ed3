#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The complex Ginzburg-Landau lattice as an .ode file (bench/cgl.ode is its output for
ring 128): A_t = A + (1 + i a) A_xx - (1 + i b) |A|^2 A, A = u + i v, on N sites with the
second difference d (A_{j+1} - 2 A_j + A_{j-1}), d = 1/dx^2.

  gen_cgl.py ring N    periodic: sites 0 and N-1 are neighbours (sparse, not banded)
  gen_cgl.py chain N   fixed ends A_{-1} = A_N = 0 (banded: 3 below and 3 above)

States interleaved u0, v0, u1, v1, ...; the initial state is a plane wave of wavenumber 2
with a perturbation of wavenumber 5, written as numbers (XPPAUT reads only a number there).
The file goes to stdout."""
import math
import sys


def lines(kind, n):
    yield ("# The complex Ginzburg-Landau equation A_t = A + (1 + i a) A_xx - (1 + i b) |A|^2 A"
           " on %s of %d sites" % ("a ring" if kind == "ring" else "a chain", n))
    yield ("# (A = u + i v, d = 1/dx^2), %d states. Written by bench/gen_cgl.py %s %d; "
           "docs/stiff.md, \"Sparse Jacobians\"." % (2 * n, kind, n))
    yield "#: title complex Ginzburg-Landau %s, %d sites" % (kind, n)
    yield "#: a [1] linear dispersion"
    yield "#: b [1] nonlinear dispersion"
    yield "#: d [1] 1/dx^2 of the second difference"
    yield "par a=1, b=-0.5, d=64"

    def nb(j):
        if kind == "ring":
            return "%d" % ((j + 1) % n), "%d" % ((j - 1) % n)
        return ("%d" % (j + 1) if j + 1 < n else None), ("%d" % (j - 1) if j > 0 else None)

    for j in range(n):
        up, lo = nb(j)

        def lap(x):
            terms = ["-2*%s%d" % (x, j)]
            if up is not None:
                terms.insert(0, "%s%s" % (x, up))
            if lo is not None:
                terms.append("+%s%s" % (x, lo))
            return "".join(terms)

        r = "(u%d^2+v%d^2)" % (j, j)
        yield "u%d'=u%d+d*(%s)-a*d*(%s)-%s*(u%d-b*v%d)" % (j, j, lap("u"), lap("v"), r, j, j)
        yield "v%d'=v%d+d*(%s)+a*d*(%s)-%s*(v%d+b*u%d)" % (j, j, lap("v"), lap("u"), r, j, j)
    for j in range(n):
        x = 2 * math.pi * j / n
        u = 0.9 * math.cos(2 * x) + 0.1 * math.cos(5 * x)
        v = 0.9 * math.sin(2 * x)
        yield "init u%d=%.17g, v%d=%.17g" % (j, u, j, v)
    yield "@ total=10, dt=0.1"
    yield "done"


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("ring", "chain") or not sys.argv[2].isdigit():
        sys.exit("usage: gen_cgl.py ring|chain N")
    n = int(sys.argv[2])
    if n < 3:
        sys.exit("gen_cgl.py: N must be at least 3")
    for line in lines(sys.argv[1], n):
        print(line)


if __name__ == "__main__":
    main()
