# SPDX-License-Identifier: BSD-3-Clause
"""dynkit.Model: a built-in model or a model file (.ode, .mech, .c), its description and
its runs through the library's one entry (dyn_run), as `dynkit run` makes them."""
from __future__ import annotations

import json
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from . import _core
from ._cli import Table, options, table_command
from ._commands import Commands

__all__ = ["Model", "Mechanism", "Run", "models", "report"]


def models() -> List[str]:
    """The names of the built-in models (`dynkit models`)."""
    return _core.models()


def report() -> Dict[str, Any]:
    """The homework's answers as `dynkit report --json` gives them, as a dict."""
    return json.loads(_core.report_json())


class Run:
    """The samples of one run: t (n,), y (n, states), outputs (n, outputs) or None, names and
    units of the columns, status, message, stats (steps, rhs_calls, ...), events (name, t).
    run["NAME"] is a column by name; run.to_dataframe() a pandas DataFrame."""

    def __init__(self, raw: Dict[str, Any], model: "Model"):
        self.t: np.ndarray = raw["t"].ravel()
        self.y: np.ndarray = raw["y"]
        self.outputs: Optional[np.ndarray] = raw["outputs"]
        self.status: int = raw["status"]
        self.message: str = raw["message"]
        self.stats: Dict[str, int] = raw["stats"]
        self.events: List[tuple] = raw["events"]
        self.names: List[str] = ["t"] + model.states
        self.units: List[str] = [model.time_unit] + [u for _, u, _ in model.info["states"]]
        if self.outputs is not None:
            self.names += model.outputs
            self.units += [u for _, u, _ in model.info["outputs"]]

    @property
    def success(self) -> bool:
        return self.status == 0

    def column(self, name: str) -> np.ndarray:
        if name == "t":
            return self.t
        if name not in self.names:
            raise KeyError(f"no column '{name}' (columns: {', '.join(self.names)})")
        i = self.names.index(name) - 1
        n = self.y.shape[1]
        return self.y[:, i] if i < n else self.outputs[:, i - n]

    __getitem__ = column

    def table(self) -> np.ndarray:
        """All columns side by side, in `dynkit run`'s order (t, states, outputs)."""
        parts = [self.t[:, None], self.y] + ([self.outputs] if self.outputs is not None else [])
        return np.hstack(parts)

    def to_dataframe(self):
        """A pandas DataFrame of the columns (pandas must be installed; Debian:
        python3-pandas); its attrs["units"] maps each column to its unit."""
        import pandas as pd  # optional
        frame = pd.DataFrame(self.table(), columns=self.names)
        frame.attrs["units"] = dict(zip(self.names, self.units))
        return frame

    def __repr__(self) -> str:
        return (f"Run({len(self.t)} samples of {', '.join(self.names)}; "
                f"status {self.status}{': ' + self.message if self.message else ''})")


class Model(Commands):
    """A model by name (`dynkit models`: pendulum, vanderpol, plane, cart, ...) or path (an
    XPPAUT .ode file, a mechanism .mech, a C file defining dynkit_model()), compiled to
    native code as `dynkit run` compiles it. sweep, linearize, steady and continue_ run the
    commands of the same names on it (dynkit._commands)."""

    def __init__(self, name_or_path: str):
        self.spec: str = str(name_or_path)
        self._core = _core.Model(self.spec)
        self.info: Dict[str, Any] = self._core.info()
        self.name: str = self.info["name"]
        self.states: List[str] = [n for n, _, _ in self.info["states"]]
        self.parameters: Dict[str, float] = {n: v for n, _, _, v in self.info["parameters"]}
        self.units: Dict[str, str] = {n: u for n, u, _ in self.info["states"]}
        self.units.update({n: u for n, u, _, _ in self.info["parameters"]})
        self.units.update({n: u for n, u, _ in self.info["outputs"]})
        self.outputs: List[str] = [n for n, _, _ in self.info["outputs"]]
        self.initial: Dict[str, float] = dict(zip(self.states, self.info["initial"]))
        self.time_unit: str = self.info["time_unit"]

    def __repr__(self) -> str:
        return f"Model({self.name!r}: states {self.states}, parameters {list(self.parameters)})"

    def run(self, method: Optional[str] = None, tspan: Optional[Sequence[float]] = None,
            step: Optional[float] = None, init: Optional[Dict[str, float]] = None,
            set: Optional[Dict[str, float]] = None, y0: Optional[Sequence[float]] = None,
            rtol: float = 0.0, atol: float = 0.0, times: Optional[Sequence[float]] = None,
            max_step: float = 0.0, first_step: float = 0.0, max_steps: Optional[int] = None,
            every: int = 0, seed: int = 0, outputs: bool = False,
            events: Optional[Sequence[str]] = None) -> Run:
        """One run, with `dynkit run`'s options as keywords: method (default the model's),
        tspan=(t0, t1), step, init={state: value} (over the model's initial state, which
        may follow the parameters), set={parameter: value}, or y0 (every state), rtol, atol
        (default the model's), times (output times), max_step, first_step, max_steps, every,
        seed (noise), outputs (the model's extra outputs), events (names of the model's
        events to report). Raises ValueError or KeyError naming a bad option."""
        t0, t1 = (self.info["t0"], self.info["t1"]) if tspan is None else map(float, tspan)
        params = dict(set or {})
        for k in params:
            if k not in self.parameters:
                raise KeyError(f"model {self.name} has no parameter '{k}' "
                               f"(parameters: {', '.join(self.parameters)})")
        start = None
        if y0 is not None:
            start = np.asarray(y0, dtype=float)
        elif init:
            base = self._initial_for(params)
            for k, v in init.items():
                if k not in self.states:
                    raise KeyError(f"model {self.name} has no state '{k}' "
                                   f"(states: {', '.join(self.states)})")
                base[self.states.index(k)] = float(v)
            start = base
        kw: Dict[str, Any] = dict(method=method, t0=float(t0), t1=float(t1), y0=start,
                                  params=params, rtol=float(rtol), atol=float(atol),
                                  times=None if times is None else np.asarray(times, float),
                                  max_step=float(max_step), first_step=float(first_step),
                                  max_steps=-1 if max_steps is None else int(max_steps),
                                  every=int(every), seed=int(seed), outputs=bool(outputs),
                                  events=list(events) if events else None)
        if step is not None:
            kw["step"] = float(step)
        return Run(self._core.run(**kw), self)

    def default_box(self, set: Optional[Dict[str, float]] = None,
                    init: Optional[Dict[str, float]] = None) -> Dict[str, tuple]:
        """`dynkit equilibria`'s default box: the range of each state over the model's default
        run widened by half its width (at least 1) on each side; the file's @ xlo..yhi win
        for the states of its phase plane."""
        run = self.run(set=set, init=init)
        lo, hi = run.y.min(axis=0), run.y.max(axis=0)
        margin = np.maximum(0.5 * (hi - lo), 1.0)
        box = {name: (float(lo[i] - margin[i]), float(hi[i] + margin[i]))
               for i, name in enumerate(self.states)}
        window = self.info["phase_window"]
        for axis, name in enumerate((self.info["phase_x"], self.info["phase_y"])):
            if name in box and window[2 * axis] < window[2 * axis + 1]:
                box[name] = (window[2 * axis], window[2 * axis + 1])
        return box

    def equilibria(self, box: Optional[Dict[str, Sequence[float]]] = None,
                   set: Optional[Dict[str, float]] = None,
                   init: Optional[Dict[str, float]] = None, starts: int = 0) -> Dict[str, Any]:
        """Every equilibrium in a box, as `dynkit equilibria --json`: {"equilibria":
        [{"state": {NAME: value}, "eigenvalues": [[re, im], ...], "type": "...",
        "residual": r, "manifolds": [stable, unstable, centre]}], ...}. box: {state: (lo,
        hi)} for the states it names, the default box (default_box) for the others; the
        initial state (with init) is a start too. A discrete map's fixed points and
        multipliers. Eigenvalues need the LAPACK backend (else the types are
        "unclassified")."""
        full = self.default_box(set, init)
        for k, v in (box or {}).items():
            if k not in full:
                raise KeyError(f"model {self.name} has no state '{k}'")
            if len(v) != 2 or not v[0] <= v[1]:
                raise ValueError(f"box of {k}: give (lo, hi) with lo <= hi")
            full[k] = (float(v[0]), float(v[1]))
        guess = self._initial_for(dict(set or {}))
        for k, v in (init or {}).items():
            guess[self.states.index(k)] = float(v)
        return self._core.equilibria([full[s][0] for s in self.states],
                                     [full[s][1] for s in self.states], params=set,
                                     guess=guess, starts=int(starts))

    def lyapunov(self, spectrum: bool = False, exponents: int = 1,
                 tspan: Optional[Sequence[float]] = None, transient: Optional[float] = None,
                 tau: Optional[float] = None, rtol: float = 0.0, atol: float = 0.0,
                 set: Optional[Dict[str, float]] = None,
                 init: Optional[Dict[str, float]] = None) -> Dict[str, Any]:
        """The Lyapunov exponents along the trajectory from the initial state, as `dynkit
        lyapunov --json`: {"exponents": [...] largest first, "errors": [...]} (Benettin's
        method on the variational equations). spectrum: all of them; exponents: the k
        largest. tspan (default the model's span; a map: iterations), transient (default a
        tenth of it), tau (default min(10 step, the averaging time / 10); a map: 1)."""
        t0, t1 = (self.info["t0"], self.info["t1"]) if tspan is None else map(float, tspan)
        span = t1 - t0
        trans = 0.1 * span if transient is None else float(transient)
        if not 0 <= trans < span:
            raise ValueError(f"transient {trans}: from 0 to below the span {span}")
        avg = span - trans
        if self.info["map"]:
            tau_ = 1.0  # a map: every iteration, and its time steps by 1
        else:
            tau_ = min(10.0 * self.info["step"], avg / 10) if tau is None else float(tau)
        y0 = self._initial_for(dict(set or {}))
        for k, v in (init or {}).items():
            if k not in self.states:
                raise KeyError(f"model {self.name} has no state '{k}'")
            y0[self.states.index(k)] = float(v)
        k = len(self.states) if spectrum else int(exponents)
        return self._core.lyapunov(k, float(t0), y0, trans, avg, tau_, float(rtol),
                                   float(atol), params=set)

    def _initial_for(self, params: Dict[str, float]) -> np.ndarray:
        """The model's initial state for these parameters (a run of no length asks it)."""
        if not params:
            return np.array(self.info["initial"], dtype=float)
        probe = self._core.run(method="euler", t0=0.0, t1=1.0, step=1.0, params=params,
                               max_steps=-1)
        return probe["y"][0].copy()


class Mechanism(Model):
    """A mechanism file (.mech, docs/mechanisms.md): a Model (run, equilibria, lyapunov, ...)
    with the equations dynkit derives by TMT and its constraint forces named with units."""

    def __init__(self, path: str):
        if not str(path).endswith(".mech"):
            raise ValueError(f"'{path}' is not a mechanism file NAME.mech")
        super().__init__(path)
        self.path = str(path)
        # the constraints, as derive names them ("constraint NAME (of the positions)")
        names = [line.split()[1] for line in self.derive().splitlines()
                 if line.startswith("constraint ")]
        units = {n: u for n, u, _ in self.info["outputs"]}
        #: each constraint's force (its multiplier, an output of the runs), name -> unit
        self.constraint_forces: Dict[str, str] = {n: units[n] for n in names if n in units}

    def derive(self, c: bool = False) -> str:
        """The equations of motion as `dynkit derive FILE.mech` prints them: M q'' = F + D' lambda
        with the constraints, each term a formula SymPy parses; c=True: the generated C."""
        return _core.mech_text(self.path, bool(c))

    def inverse(self, prescribe: Optional[Dict[str, str]] = None,
                inputs: Optional[Sequence[str]] = None, method: Optional[str] = None,
                tspan: Optional[Sequence[float]] = None, step: Optional[float] = None,
                rtol: Optional[float] = None, atol: Optional[float] = None,
                set: Optional[Dict[str, float]] = None,
                init: Optional[Dict[str, float]] = None) -> Table:
        """Inverse dynamics, as `dynkit inverse FILE.mech`: the forces of the prescribed
        motions (the file's `prescribe` lines and prescribe={COORD: "formula of t"}), the
        mechanism run from its initial state moved onto the constraints. Returns a Table:
        t, the generalized forces that drive the prescribed coordinates (or, with
        inputs=[A, B, ...], the values of these parameters that drive them, a table
        `dynkit run FILE.mech --forces` reads), then the other constraints' forces, with
        their units; its log has the command's notes (the initial state's changes, the
        residual of the inputs)."""
        return table_command(["inverse", self.path] + options(
            prescribe=prescribe, inputs=inputs, method=method, tspan=tspan, step=step,
            rtol=rtol, atol=atol, set=set, init=init))
