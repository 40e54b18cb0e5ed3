# SPDX-License-Identifier: BSD-3-Clause
# Load a data file written by `dynkit run --output FILE` or `dynkit sweep --output FILE` with
# the reader people use for its format (json; numpy.load for .npy and .npz; scipy.io.loadmat
# for .mat) and print what it holds, for tests/test_formats.c to compare with the CSV of the
# same run or sweep bit for bit (a sweep's .npz and .mat hold a variable per column, named as
# the column):
#   shape ROWS COLS
#   names NAME...          (when the format carries them)
#   units UNIT...
#   meta KEY=VALUE...      (method, step, ...)
#   row VALUE...           one line per row, each value as float.hex() (exact)
# Usage: python3 load_table.py json|npy|npz|mat FILE
import json
import sys

import numpy as np


def text(v):
    """A string stored by a format: a str, a 0-d or 1-element string array."""
    if isinstance(v, str):
        return v
    a = np.asarray(v)
    return str(a.reshape(-1)[0]) if a.size else ""


def main():
    fmt, path = sys.argv[1], sys.argv[2]
    names = units = None
    meta = {}
    if fmt == "json":
        with open(path, encoding="utf-8") as f:
            d = json.load(f)
        table = np.array(d["rows"], dtype=np.float64).reshape(len(d["rows"]), len(d["columns"]))
        names, units = d["columns"], d["units"]
        meta = {k: d[k] for k in ("model", "method", "step", "rtol", "atol", "states",
                                  "varied", "reduced") if k in d}
    elif fmt == "npy":
        table = np.load(path, allow_pickle=False)
        assert table.dtype == np.float64 and table.ndim == 2, (table.dtype, table.shape)
    elif fmt == "npz":
        z = np.load(path, allow_pickle=False)
        names, units = [str(s) for s in z["names"]], [str(s) for s in z["units"]]
        if "t" in z.files:
            ykey = "y" if "y" in z.files else "forces"  # inverse cart: the force table
            parts = [z["t"].reshape(-1, 1), z[ykey]]
            if "outputs" in z.files:
                parts.append(z["outputs"])
            table = np.hstack(parts)
            meta["states"] = z[ykey].shape[1]
        else:  # a sweep's table: an array per column
            table = np.column_stack([z[n] for n in names])
        for k in ("model", "method"):
            if k in z.files:
                meta[k] = text(z[k])
        for k in ("step", "rtol", "atol"):
            if k in z.files:
                meta[k] = float(z[k])
    elif fmt == "mat":
        import scipy.io

        m = scipy.io.loadmat(path)
        names = [text(c) for c in m["names"].reshape(-1)]
        units = [text(c) for c in m["units"].reshape(-1)]
        if "t" in m:
            parts = [m["t"], m["y"]]
            if "outputs" in m:
                parts.append(m["outputs"])
            table = np.hstack(parts).astype(np.float64)
            meta["states"] = m["y"].shape[1]
        else:  # a sweep's table: a variable per column
            table = np.hstack([m[n] for n in names]).astype(np.float64)
        for k in ("model", "method"):
            if k in m:
                meta[k] = text(m[k])
        for k in ("step", "rtol", "atol"):
            if k in m:
                meta[k] = float(m[k].reshape(-1)[0])
    else:
        sys.exit("unknown format " + fmt)
    print("shape %d %d" % table.shape)
    if names is not None:
        print("names " + " ".join(names))
        print("units " + " ".join(u if u else "-" for u in units))
    print("meta " + " ".join("%s=%s" % (k, v) for k, v in meta.items()))
    for row in table:
        print("row " + " ".join(float(v).hex() for v in row))


main()
