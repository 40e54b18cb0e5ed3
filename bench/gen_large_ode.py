#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Large generated model files, for the bounds on compiling them (docs/model-files.md,
"Large models"; tests/jit_large.sh).

  gen_large_ode.py chain N   x' = -q_N with q_1 = x, q_k = (q_{k-1} + x)/2: N chained fixed
                             quantities, each equal to x, so x(t) = exp(-t)
  gen_large_ode.py states N  x_1' = -x_1, x_k' = x_{k-1} - x_k, x_1(0) = 1, the others 0:
                             x_k(t) = t^(k-1) exp(-t)/(k-1)!, so x_2(1) = exp(-1)

The file goes to stdout."""
import sys


def chain(n):
    yield "# %d chained fixed quantities, each equal to x: x' = -x" % n
    yield "init x=1"
    yield "q1=x"
    for k in range(2, n + 1):
        yield "q%d=(q%d+x)/2" % (k, k - 1)
    yield "x'=-q%d" % n
    yield "@ total=1, dt=0.01"


def states(n):
    yield "# %d states in a linear chain: x_k(t) = t^(k-1) exp(-t)/(k-1)!" % n
    yield "init x1=1"
    yield "x1'=-x1"
    for k in range(2, n + 1):
        yield "x%d'=x%d-x%d" % (k, k - 1, k)
    yield "@ total=1, dt=0.01"


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("chain", "states") or not sys.argv[2].isdigit():
        sys.exit("usage: gen_large_ode.py chain|states N")
    n = int(sys.argv[2])
    if n < 2:
        sys.exit("gen_large_ode.py: N must be at least 2")
    gen = chain if sys.argv[1] == "chain" else states
    sys.stdout.write("\n".join(gen(n)) + "\n")


main()
