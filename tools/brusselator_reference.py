#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""brusselator_reference.py — the reference state of the Brusselator with diffusion (Hairer &
Wanner, "Solving ODEs II", sec. IV.10, problem BRUSS; dynkit/brusselator.h) at t = 10 for N
interior points, computed independently of dynkit with SciPy: Radau IIA (order 5, the
method of Hairer & Wanner's RADAU5) with the banded sparsity of the Jacobian, and DOP853
(an explicit pair, so a different method family) at rtol = atol = 1e-13. Prints both
results' largest difference and the states as C data for src/problems/references.c.

Usage: tools/brusselator_reference.py [N]   (default 20)
"""
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.sparse import diags


def rhs_factory(N, A=1.0, B=3.0, alpha=1.0 / 50.0):
    c = alpha * (N + 1) ** 2

    def f(t, y):
        u, v = y[0::2], y[1::2]
        ue = np.concatenate(([1.0], u, [1.0]))
        ve = np.concatenate(([3.0], v, [3.0]))
        du = A + u * u * v - (B + 1.0) * u + c * (ue[:-2] - 2.0 * u + ue[2:])
        dv = B * u - u * u * v + c * (ve[:-2] - 2.0 * v + ve[2:])
        out = np.empty_like(y)
        out[0::2], out[1::2] = du, dv
        return out

    return f


def main():
    N = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    n = 2 * N
    x = np.arange(1, N + 1) / (N + 1)
    y0 = np.empty(n)
    y0[0::2] = 1.0 + np.sin(2.0 * np.pi * x)
    y0[1::2] = 3.0
    f = rhs_factory(N)
    band = diags([np.ones(n - abs(k)) for k in range(-2, 3)], list(range(-2, 3)))
    tol = 1e-13
    radau = solve_ivp(f, (0.0, 10.0), y0, method="Radau", rtol=tol, atol=tol,
                      jac_sparsity=band)
    dop = solve_ivp(f, (0.0, 10.0), y0, method="DOP853", rtol=tol, atol=tol)
    assert radau.success and dop.success
    yr, yd = radau.y[:, -1], dop.y[:, -1]
    print("/* N = %d: Radau %d steps, DOP853 %d steps, max |Radau - DOP853| = %.2e */"
          % (N, radau.t.size - 1, dop.t.size - 1, np.max(np.abs(yr - yd))))
    for i in range(0, n, 2):
        print("    %.17g, %.17g," % (yd[i], yd[i + 1]))


if __name__ == "__main__":
    main()
