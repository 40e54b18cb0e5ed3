# SPDX-License-Identifier: BSD-3-Clause
"""dynkit.solve_ivp: scipy.integrate.solve_ivp's signature and result on dynkit's solvers.

Methods: SciPy's names map to dynkit's (RK45 -> dp45, RK23 -> bs23, DOP853 -> dop853,
Radau, BDF and LSODA -> rodas4, a stiffly accurate Rosenbrock method of order 4); dynkit's
own names (rk4, heun, euler, ... with step=) and MATLAB's (ode45, ode15s) are accepted too.
"""
from __future__ import annotations

from typing import Any, Callable, Optional, Sequence, Union

import numpy as np

from . import _core

__all__ = ["solve_ivp", "OdeResult", "OdeSolution"]


class OdeResult(dict):
    """The result of solve_ivp, as SciPy's: t, y, sol, t_events, y_events, nfev, njev, nlu,
    status (-1 failed, 0 reached the end, 1 a terminal event), message, success. Items are
    also attributes."""

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError as e:
            raise AttributeError(name) from e

    def __repr__(self) -> str:
        keys = ", ".join(sorted(self))
        return f"OdeResult({keys})"


class OdeSolution:
    """The dense output of a solve: sol(t) for a time or an array of times in [t0, t1]."""

    def __init__(self, capsule: Any, t_min: float, t_max: float):
        self._capsule = capsule
        self.t_min = t_min
        self.t_max = t_max

    def __call__(self, t: Union[float, Sequence[float], np.ndarray]) -> np.ndarray:
        arr = np.asarray(t, dtype=float)
        y = _core.ivp_eval(self._capsule, arr.ravel())
        return y[:, 0] if arr.ndim == 0 else y


def solve_ivp(fun: Union[Callable[..., Any], "Model"], t_span: Sequence[float],
              y0: Sequence[float], method: str = "RK45",
              t_eval: Optional[Sequence[float]] = None, dense_output: bool = False,
              events: Union[None, Callable[..., float], Sequence[Callable[..., float]]] = None,
              vectorized: bool = False, args: Optional[tuple] = None, *,
              rtol: float = 1e-3, atol: float = 1e-6, max_step: float = np.inf,
              first_step: Optional[float] = None, jac: Optional[Callable[..., Any]] = None,
              step: Optional[float] = None, params: Optional[dict] = None) -> OdeResult:
    """Solve y' = fun(t, y, *args), y(t_span[0]) = y0, as scipy.integrate.solve_ivp does.

    fun is a Python callable (called with the interpreter's lock held), or a dynkit.Model,
    whose right-hand side then runs natively with the lock released (params: its parameters
    by name). events: callables g(t, y, *args) with optional attributes terminal and
    direction, as SciPy's (at most 16). step: the step of a fixed-step method (rk4, heun,
    euler, ...). vectorized is accepted and not used (fun is called with one state).
    Raises ValueError for bad arguments and what fun, jac or an event raises.
    """
    del vectorized  # one state at a time
    if len(t_span) != 2:
        raise ValueError("t_span must be (t0, t1)")
    t0, t1 = float(t_span[0]), float(t_span[1])
    if not t1 > t0:
        raise ValueError(f"t_span = ({t0}, {t1}): dynkit integrates forward, t1 > t0")
    if rtol <= 0 or atol < 0:
        raise ValueError(f"rtol must be > 0 and atol >= 0 (got {rtol}, {atol})")
    if events is not None and callable(events):
        events = [events]
    if args is not None and not isinstance(args, tuple):
        args = (args,)
    inner = getattr(fun, "_core", fun)
    res = _core.solve_ivp(
        inner, t0, t1, np.asarray(y0, dtype=float), method=method,
        t_eval=None if t_eval is None else np.asarray(t_eval, dtype=float),
        dense_output=bool(dense_output), events=events, rtol=float(rtol), atol=float(atol),
        max_step=0.0 if not np.isfinite(max_step) else float(max_step),
        first_step=0.0 if first_step is None else float(first_step),
        step=0.0 if step is None else float(step), jac=jac, args=args, params=params)
    out = OdeResult(res)
    out["success"] = out["status"] >= 0
    if events is None:
        out["t_events"] = None
        out["y_events"] = None
    cap = out.pop("sol", None)
    out["sol"] = OdeSolution(cap, t0, out["t_reached"]) if cap is not None else None
    return out
