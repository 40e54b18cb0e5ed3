# SPDX-License-Identifier: BSD-3-Clause
"""dynkit: simulation of mechanical and dynamical systems, from Python.

    import dynkit
    sol = dynkit.solve_ivp(lambda t, y: [y[1], -y[0]], (0, 10), [1, 0], rtol=1e-8)
    vdp = dynkit.Model("vanderpol")           # a built-in model, .ode, .mech or .c file
    run = vdp.run(method="rk4", step=0.01, t1=15)
    print(run.t[-1], run["y1"][-1])

solve_ivp follows scipy.integrate.solve_ivp (signature and result); Model runs any model
through the library's one entry (dyn_run) as `dynkit run` does; Model.sweep, linearize,
steady, continue_ and Mechanism.inverse run the dynkit tool's commands of those names. docs/python.md has the whole
reference.
"""
from ._core import DynkitError
from ._cli import Table
from ._ivp import OdeResult, OdeSolution, solve_ivp
from ._model import Mechanism, Model, Run, models, report

__all__ = ["solve_ivp", "OdeResult", "OdeSolution", "Model", "Mechanism", "Run", "Table",
           "models",
           "report",
           "DynkitError"]
