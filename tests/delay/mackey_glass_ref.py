#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""An independent solve of the Mackey-Glass equation
    x'(t) = beta x(t - tau) / (1 + x(t - tau)^n) - gamma x(t),  x = x0 for t <= 0,
by the method of steps with the classical Runge-Kutta method at a step h = tau / N: the
delayed values at the grid points are the solution's own samples, those at the half steps
come from the cubic Hermite interpolant of the samples and their derivatives (error
O(h^4), the method's order). Prints "t x" at every `every` time units up to t1.

usage: mackey_glass_ref.py N T1 EVERY [beta gamma n tau x0]
"""
import sys


def solve(N, t1, every, beta=0.2, gamma=0.1, n=10.0, tau=17.0, x0=0.5):
    h = tau / N
    steps = int(round(t1 / h))
    xs = [x0]  # x at k h, k = 0 .. steps
    fs = []    # f at k h (filled as we go)

    def past(k, half):
        """x at (k + half/2) h for k < 0: the history x0; else from the samples."""
        if k < 0:
            return x0
        if not half:
            return xs[k]
        # cubic Hermite at the midpoint of [k h, (k+1) h]
        return 0.5 * (xs[k] + xs[k + 1]) + h / 8.0 * (fs[k] - fs[k + 1])

    def g(xd, x):
        return beta * xd / (1.0 + xd ** n) - gamma * x

    dpast = [None]
    # derivative at the grid points: f(t_k, x_k) with the delayed x at k - N
    for k in range(steps):
        x = xs[k]
        if len(fs) == k:
            fs.append(g(past(k - N, 0), x))
        xd0 = past(k - N, 0)
        xdm = past(k - N, 1)
        xd1 = past(k - N + 1, 0)
        k1 = g(xd0, x)
        k2 = g(xdm, x + 0.5 * h * k1)
        k3 = g(xdm, x + 0.5 * h * k2)
        k4 = g(xd1, x + h * k3)
        xs.append(x + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4))
    del dpast
    out = []
    stride = int(round(every / h))
    for k in range(0, steps + 1, stride):
        out.append((k * h, xs[k]))
    return out


if __name__ == "__main__":
    args = [float(a) for a in sys.argv[1:]]
    if len(args) < 3:
        sys.exit(__doc__)
    N, t1, every = int(args[0]), args[1], args[2]
    for t, x in solve(N, t1, every, *args[3:]):
        print("%.17g %.17g" % (t, x))
