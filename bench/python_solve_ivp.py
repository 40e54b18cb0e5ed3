#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""dynkit.solve_ivp against scipy.integrate.solve_ivp, measured in the same run.

- the same Python fun in both (van der Pol, mu = 1, over [0, 20]; a chain of six masses,
  12 states, over [0, 20]), at rtol 1e-6 and 1e-9: the time of each, their ratio;
- a dynkit.Model (vanderpol, bench/chain12.ode) as fun: native right-hand side, against
  SciPy with the Python fun;
- the overhead of a call: a solve of one step of x' = -x.
Each time is the best of several repetitions. Usage: python_solve_ivp.py [PYTHONPATH_DIR]
"""
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "build",
                                                                         "python"))
import numpy as np  # noqa: E402
import scipy.integrate  # noqa: E402

import dynkit  # noqa: E402


def vdp(t, y):
    return [y[1], (1 - y[0] * y[0]) * y[1] - y[0]]


K, C = 1.0, 0.05


def chain(t, y):
    """plain Python on the 12 floats: for a system this small NumPy's slicing costs more
    than the arithmetic"""
    x1, v1, x2, v2, x3, v3, x4, v4, x5, v5, x6, v6 = y.tolist()
    return [v1, -K * (2 * x1 - x2) - C * v1,
            v2, -K * (2 * x2 - x1 - x3) - C * v2,
            v3, -K * (2 * x3 - x2 - x4) - C * v3,
            v4, -K * (2 * x4 - x3 - x5) - C * v4,
            v5, -K * (2 * x5 - x4 - x6) - C * v5,
            v6, -K * (2 * x6 - x5) - C * v6]


def best(f, reps):
    times = []
    for _ in range(reps):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def main():
    y_chain = np.zeros(12)
    y_chain[0] = 1.0
    vdp_model = dynkit.Model("vanderpol")
    chain_model = dynkit.Model(os.path.join(HERE, "chain12.ode"))
    print("| system | rtol | SciPy RK45, Python fun [ms] | dynkit, Python fun [ms] | ratio | "
          "dynkit, Model [ms] | ratio |")
    print("|---|---|---|---|---|---|---|")
    for name, fun, model, y0 in [("van der Pol", vdp, vdp_model, [2.0, 0.0]),
                                 ("chain of 6 masses (12 states)", chain, chain_model, y_chain)]:
        for rtol in (1e-6, 1e-9):
            atol = rtol * 1e-3
            ts = best(lambda: scipy.integrate.solve_ivp(fun, (0, 20), y0, rtol=rtol,
                                                        atol=atol), 3)
            td = best(lambda: dynkit.solve_ivp(fun, (0, 20), y0, rtol=rtol, atol=atol), 3)
            tm = best(lambda: dynkit.solve_ivp(model, (0, 20), y0, rtol=rtol, atol=atol), 20)
            print(f"| {name} | {rtol:g} | {ts * 1e3:.1f} | {td * 1e3:.2f} | {ts / td:.1f}x | "
                  f"{tm * 1e3:.3f} | {ts / tm:.0f}x |")
    one = lambda: dynkit.solve_ivp(lambda t, y: -y, (0, 1e-3), [1.0], method="rk4",
                                   step=1e-3)
    one_model = lambda: dynkit.solve_ivp(vdp_model, (0, 1e-3), [2.0, 0.0], method="rk4",
                                         step=1e-3)
    n = 2000
    t1 = best(lambda: [one() for _ in range(n)], 3) / n
    t2 = best(lambda: [one_model() for _ in range(n)], 3) / n
    ts1 = best(lambda: [scipy.integrate.solve_ivp(lambda t, y: -y, (0, 1e-3), [1.0])
                        for _ in range(200)], 3) / 200
    print()
    print(f"call overhead, one rk4 step: {t1 * 1e6:.1f} us with a Python fun, "
          f"{t2 * 1e6:.1f} us with a Model; SciPy's shortest solve_ivp: {ts1 * 1e6:.0f} us")


if __name__ == "__main__":
    main()
