# SPDX-License-Identifier: BSD-3-Clause
"""Model.sweep, Model.linearize, Model.steady and Model.continue_: the commands `dynkit sweep`,
`linearize --json`, `steady --json` and `continue --json` on the model, their options as
keywords (dynkit._cli runs the tool), their results as a Table or as the commands' JSON
contracts with NumPy arrays (docs/sweeps.md, docs/analysis.md, docs/continuation.md)."""
from __future__ import annotations

from typing import Any, Dict, Optional, Sequence, Union

from ._cli import Table, json_command, options, table_command

__all__ = ["Commands"]

Values = Union[Dict[str, float], None]


class Commands:
    """The commands of the command line as methods of a Model (its spec: a built-in name or
    the path it was opened with)."""

    spec: str

    def sweep(self, vary: Optional[Dict[str, Any]] = None,
              sample: Optional[Dict[str, str]] = None, runs: Optional[int] = None,
              seed: Optional[int] = None, from_: Optional[str] = None,
              reduce: Union[str, Sequence[str]] = "final", threads: Optional[int] = None,
              method: Optional[str] = None, tspan: Optional[Sequence[float]] = None,
              step: Optional[float] = None, end: Optional[str] = None, init: Values = None,
              set: Values = None, rtol: Any = None, atol: Any = None,
              max_step: Optional[float] = None, first_step: Optional[float] = None,
              max_steps: Optional[int] = None, events: Optional[Sequence[str]] = None,
              jac_pattern: Optional[str] = None, project_init: bool = False,
              forces: Optional[str] = None, interp: Optional[str] = None) -> Table:
        """Many runs, one row each, as `dynkit sweep MODEL` (docs/sweeps.md). The runs (one
        of): vary={NAME: (A, B, N) or [V1, V2, ...]} (several: the full grid, the last
        fastest), sample={NAME: "uniform(A,B)" | "normal(M,S)" | "lognormal(M,S)"} with runs=N
        and seed=S, from_="FILE.csv" (a table of values), or runs=N alone for a model with
        noise. reduce: "final", "max:NAME", "event:NAME", ... (a string with commas or a
        list). The run options are dynkit run's: method, tspan=(T0, T1), step, end
        ("exact"/"grid"), init, set, rtol, atol (a number or one per state), max_step,
        first_step, max_steps, events=["NAME", "NAME:stop"], jac_pattern, project_init,
        forces, interp; threads: the threads of the sweep (the table is the same for any).
        Returns a Table: columns run, the varied names, the reductions (and status, the
        library's number, when a run failed: 0 ok, 3 nonfinite, 7 step-size, 8 max-steps),
        their units, the rows as a float64 array; raises DynkitError with the command's
        message for a bad option."""
        red = reduce if isinstance(reduce, str) else ",".join(reduce)
        args = ["sweep", self.spec, "--quiet"] + options(
            vary=vary, sample=sample, runs=runs, seed=seed, from_=from_, reduce=red,
            threads=threads, method=method, tspan=tspan, step=step, end=end, init=init,
            set=set, rtol=rtol, atol=atol, max_step=max_step, initial_step=first_step,
            max_steps=max_steps, event=events, jac_pattern=jac_pattern,
            project_init=project_init, forces=forces, interp=interp)
        return table_command(args)

    def linearize(self, init: Values = None, set: Values = None, t: Optional[float] = None,
                  equilibrium: bool = False, vary: Optional[Dict[str, Any]] = None,
                  jacobian: Optional[str] = None, project_init: bool = False,
                  forces: Optional[str] = None) -> Dict[str, Any]:
        """A = df/dy about a state, its eigenvalues and stability, as `dynkit linearize
        --json`: {"model", "t", "states", "points": [{"y", "f", "A", "re", "im",
        "stability", "jacobian", ...}]} with y, f, re, im as 1-D and A as 2-D NumPy arrays
        (a mechanism with constraints: also its minimal coordinates). init, set: the state
        and parameters (dynkit run's --init, --set); t: the time; equilibrium: find an
        equilibrium from the state first; vary={NAME: (A, B, N) or [values]}: one point
        per value; jacobian: "auto", "analytic", "central" or "richardson"."""
        return json_command(["linearize", self.spec] + options(
            init=init, set=set, t=t, equilibrium=equilibrium, vary=vary, jacobian=jacobian,
            project_init=project_init, forces=forces))

    def steady(self, unknown: Union[str, Sequence[str]], cyclic: Optional[Sequence[str]] = None,
               init: Values = None, set: Values = None,
               t: Optional[float] = None) -> Dict[str, Any]:
        """A steady motion (a relative equilibrium), as `dynkit steady --json`: the unknowns
        (states or parameters) solved so that the non-cyclic states' derivatives vanish,
        then the eigenvalues there: {"state": {NAME: value}, "parameters": {...},
        "unknowns", "cyclic", "kept", "eigenvalues" (k x 2 array: re, im), "stability",
        "residual", "iterations"}. cyclic: the cyclic states (default: found); init: the
        known states and the unknowns' first guesses."""
        unknowns = [unknown] if isinstance(unknown, str) else list(unknown)
        return json_command(["steady", self.spec] + options(
            unknown=unknowns, cyclic=cyclic, init=init, set=set, t=t))

    def continue_(self, par: str, par2: Optional[str] = None, init: Values = None,
                  set: Values = None, at: Optional[Dict[str, Any]] = None,
                  opt: Optional[Dict[str, float]] = None,
                  jacobian: Optional[str] = None) -> Dict[str, Any]:
        """The branch of equilibria in parameter par by pseudo-arclength continuation, with
        its folds (LP), Hopf (HB) and branch points (BP), as `dynkit continue --json`
        (docs/continuation.md); par2: the curves of folds and Hopf points in two
        parameters. init, set: the starting guess and parameters; at={par: (A, B, N) or
        [values]}: points at these values (UZ); opt={NAME: value}: AUTO's settings (ds,
        dsmax, nmax, parmin, parmax, ...). The numbers of the points are NumPy arrays."""
        return json_command(["continue", self.spec] + options(
            par=par, par2=par2, init=init, set=set, at=at, opt=opt, jacobian=jacobian))
