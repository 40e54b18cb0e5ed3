# SPDX-License-Identifier: BSD-3-Clause
"""The commands sweep, linearize, steady, continue and inverse from Python: the package runs
the `dynkit` tool itself (a child process, the interpreter's lock released while it waits)
with the keywords written as its options, reads the JSON it writes and returns it with
NumPy arrays. The numbers are the command line's, read back exactly (each is the shortest
decimal of its double, or 17 digits). docs/python.md, "Sweeps and analyses"."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np

from ._core import DynkitError

__all__ = ["Table", "tool", "command", "options", "with_arrays"]

_HERE = os.path.dirname(os.path.abspath(__file__))


def tool() -> str:
    """The dynkit executable the commands run: $DYNKIT_CLI, else the one built beside the
    package (<build>/dynkit for <build>/python/dynkit), else the installed one
    (<prefix>/bin/dynkit for <prefix>/lib/python3.X/site-packages/dynkit), else `dynkit` on
    the PATH."""
    candidates = [os.environ.get("DYNKIT_CLI", ""),
                  os.path.join(_HERE, os.pardir, os.pardir, "dynkit"),
                  os.path.join(_HERE, os.pardir, os.pardir, os.pardir, os.pardir, "bin",
                               "dynkit"),
                  shutil.which("dynkit") or ""]
    for path in candidates:
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return os.path.normpath(path)
    raise DynkitError("the dynkit tool was not found (looked at $DYNKIT_CLI, beside the "
                      "package, <prefix>/bin and the PATH): build it or set DYNKIT_CLI")


def _number(value: Any) -> str:
    """A value as the command line reads it: a float as its shortest decimal that reads back
    to the same double (repr), a formula or a number with a unit ("pi/4", "45deg") as is."""
    if isinstance(value, str):
        return value
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{value!r}: a number or a formula is expected, not a bool")
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return repr(float(value))


def _values(name: str, spec: Any) -> str:
    """--vary's values: (A, B, N) for N values from A to B, or a list of values."""
    if isinstance(spec, str):
        return spec
    if isinstance(spec, tuple) and len(spec) == 3 and isinstance(spec[2], (int, np.integer)):
        a, b, n = spec
        return f"{_number(a)}:{_number(b)}:{int(n)}"
    values = list(np.atleast_1d(np.asarray(spec, dtype=object)))
    if not values:
        raise ValueError(f"vary {name}: give (A, B, N) or a list of values")
    return ",".join(_number(v) for v in values)


def options(**kw: Any) -> List[str]:
    """The command line's options for keywords (None: not given): a dict (init, set, vary,
    sample, opt, prescribe, table) is one option NAME=VALUE per item, tspan (T0, T1) is
    T0:T1, a list repeats the option (events) or joins its items with commas (unknown,
    cyclic, inputs), True is a flag; a keyword's underscores are the option's dashes."""
    joined = {"unknown", "cyclic", "inputs", "reduce", "times", "rtol", "atol"}
    args: List[str] = []
    for key, value in kw.items():
        if value is None or value is False:
            continue
        flag = "--" + key.rstrip("_").replace("_", "-")
        if value is True:
            args.append(flag)
        elif key == "tspan":
            t0, t1 = value
            args += [flag, f"{_number(t0)}:{_number(t1)}"]
        elif isinstance(value, Mapping):
            for name, v in value.items():
                text = _values(name, v) if key in ("vary", "at") else _number(v)
                args += [flag, f"{name}={text}"]
        elif key in joined and not isinstance(value, str):
            args += [flag, ",".join(_number(v) for v in value)]
        elif isinstance(value, (list, tuple)):
            for v in value:
                args += [flag, str(v)]
        else:
            args += [flag, _number(value) if not isinstance(value, os.PathLike) else
                     os.fspath(value)]
    return args


def command(args: Sequence[str]) -> tuple:
    """Run `dynkit ARGS...`; its standard output and standard error (the notes and
    warnings). A non-zero exit status raises DynkitError with the tool's message."""
    proc = subprocess.run([tool(), *args], capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, check=False)
    if proc.returncode != 0:
        lines = [ln.removeprefix("dynkit: error: ") for ln in proc.stderr.splitlines()
                 if not ln.startswith("Try 'dynkit ")]
        message = "\n".join(lines).strip() or f"dynkit {args[0]} failed"
        raise DynkitError(f"dynkit {args[0]}: {message} (exit status {proc.returncode})")
    return proc.stdout, proc.stderr


def _numeric(items: list) -> bool:
    return all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool))
               for v in items)


def with_arrays(obj: Any) -> Any:
    """JSON's lists of numbers as NumPy arrays (null: nan), lists of equal rows of numbers
    as 2-D arrays; dicts and other lists element by element."""
    if isinstance(obj, dict):
        return {k: with_arrays(v) for k, v in obj.items()}
    if isinstance(obj, list):
        if obj and _numeric(obj):
            return np.array([np.nan if v is None else v for v in obj], dtype=float)
        if (obj and all(isinstance(r, list) and r and _numeric(r) for r in obj)
                and len({len(r) for r in obj}) == 1):
            return np.array([[np.nan if v is None else v for v in r] for r in obj],
                            dtype=float)
        return [with_arrays(v) for v in obj]
    return obj


class Table:
    """A table the command line writes (a sweep's rows, inverse dynamics' samples): data
    (rows x columns, float64), columns (names), units (one per column), the settings of the
    command (info: model, method, step, rtol, atol, tspan) and its notes on standard error
    (log). table["NAME"] is a column; to_dataframe() a pandas DataFrame."""

    def __init__(self, doc: Dict[str, Any], log: str = ""):
        self.columns: List[str] = list(doc["columns"])
        self.units: List[str] = list(doc["units"])
        rows = doc["rows"]
        self.data: np.ndarray = (np.array([[np.nan if v is None else v for v in r]
                                           for r in rows], dtype=float)
                                 if rows else np.zeros((0, len(self.columns))))
        self.info: Dict[str, Any] = {k: v for k, v in doc.items()
                                     if k not in ("columns", "units", "rows")}
        self.log: str = log

    def __len__(self) -> int:
        return self.data.shape[0]

    def __getitem__(self, name: str) -> np.ndarray:
        if name not in self.columns:
            raise KeyError(f"no column '{name}' (columns: {', '.join(self.columns)})")
        return self.data[:, self.columns.index(name)]

    def unit(self, name: str) -> str:
        """The unit of column NAME."""
        self[name]  # the KeyError naming the columns
        return self.units[self.columns.index(name)]

    def to_dataframe(self):
        """The table as a pandas DataFrame (pandas must be installed); the units are in
        its attrs["units"] (column -> unit)."""
        try:
            import pandas as pd  # optional
        except ImportError as e:
            raise ImportError("to_dataframe needs pandas (Debian: python3-pandas)") from e
        frame = pd.DataFrame(self.data, columns=self.columns)
        frame.attrs["units"] = dict(zip(self.columns, self.units))
        return frame

    def __repr__(self) -> str:
        return f"Table({len(self)} rows of {', '.join(self.columns)})"


def table_command(args: Sequence[str], tmpdir: Optional[str] = None) -> Table:
    """Run a command that writes a table with `--output FILE.json` into a scratch folder and
    read it back as a Table."""
    import tempfile
    with tempfile.TemporaryDirectory(prefix="dynkit-", dir=tmpdir) as scratch:
        path = os.path.join(scratch, "table.json")
        _, log = command([*args, "--output", path])
        with open(path, encoding="utf-8") as f:
            return Table(json.load(f), log)


def json_command(args: Sequence[str]) -> Dict[str, Any]:
    """Run a command with --json and return its JSON with NumPy arrays."""
    out, _ = command([*args, "--json"])
    return with_arrays(json.loads(out))
