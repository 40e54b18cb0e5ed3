# SPDX-License-Identifier: BSD-3-Clause
"""Model.sweep, linearize, steady, continue_ and Mechanism.inverse against the commands'
own output (bit for bit: the CSV's shortest decimals and the JSON read back), and each
against a physical fact: the pendulum's highest point from its energy, the saddle at the
top (eigenvalues +-sqrt(g/l)), the Lorenz system's Hopf point at rho = s(s+b+3)/(s-b-1),
and the cart's inverse dynamics from its mechanism file beside the homework's own
derivation (dynkit inverse cart). The DataFrames of Run and Table, when pandas is
installed."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import dynkit
from conftest import CLI, SOURCE

LORENZ = os.path.join(SOURCE, "examples", "models", "lorenz.ode")
TOP = os.path.join(SOURCE, "examples", "mechanisms", "top.mech")
CART = os.path.join(SOURCE, "examples", "mechanisms", "cart.mech")
# the status words of dynkit sweep's CSV and the library's numbers of its other formats
STATUS = {"ok": 0, "nonfinite": 3, "step-size": 7, "max-steps": 8}


def cli(*args):
    return subprocess.run([CLI, *args], check=True, capture_output=True, text=True).stdout


def csv_rows(text):
    lines = text.strip().splitlines()
    return lines[0].split(","), [line.split(",") for line in lines[1:]]


def same_bits(a, b):
    """a (our arrays, dicts, lists) equals b (the command's JSON) exactly, nan as null."""
    if isinstance(b, dict):
        return isinstance(a, dict) and a.keys() == b.keys() and all(
            same_bits(a[k], b[k]) for k in b)
    if isinstance(a, np.ndarray):
        ref = np.array(b, dtype=float) if b else np.zeros(0)
        ref[ref != ref] = np.nan
        return a.shape == ref.shape and a.tobytes() == ref.tobytes()
    if isinstance(b, list):
        return len(a) == len(b) and all(same_bits(x, y) for x, y in zip(a, b))
    return a == b and type(a) is type(b)


def test_sweep_is_dynkit_sweep_bit_for_bit():
    names, rows = csv_rows(cli("sweep", "pendulum", "--tspan", "0:5", "--vary",
                               "dphi=0.1:1.9:7", "--vary", "l=1,2", "--reduce",
                               "event:turn,max:height,final"))
    table = dynkit.Model("pendulum").sweep(vary={"dphi": (0.1, 1.9, 7), "l": [1, 2]},
                                           reduce=["event:turn", "max:height", "final"],
                                           tspan=(0, 5))
    assert table.columns == names
    assert table.data.shape == (len(rows), len(names))
    ref = np.array([[float(v) for v in r] for r in rows])
    assert table.data.tobytes() == ref.tobytes()
    assert table.unit("max_height") == "m" and table.unit("event_turn") == "s"
    assert table.unit("dphi") == "rad/s" and table.info["method"] == "dp45"
    # the energy, m l^2 dphi0^2 / 2 = m g h: the highest point h = l^2 dphi0^2 / (2 g) (the
    # samples every 0.01 s miss the top by less than 1e-3 of it)
    g = dynkit.Model("pendulum").parameters["g"]
    top = table["l"] ** 2 * table["dphi"] ** 2 / (2 * g)
    assert np.all(np.abs(table["max_height"] - top) <= 1e-3 * top)


def test_sweep_failed_runs_and_options():
    names, rows = csv_rows(cli("sweep", "vanderpol", "--tspan", "0:1", "--vary",
                               "mu=-1,1e300", "--method", "rk4", "--step", "0.01"))
    table = dynkit.Model("vanderpol").sweep(vary={"mu": [-1, 1e300]}, tspan=(0, 1),
                                            method="rk4", step=0.01, threads=2)
    assert table.columns == names and names[-1] == "status"
    for row, ref in zip(table.data, rows):
        assert [float(v) for v in ref[:-1]] == pytest.approx(list(row[:-1]), rel=0,
                                                             abs=0, nan_ok=True)
        assert row[-1] == STATUS[ref[-1]]
    assert table["status"][0] == 0 and math.isnan(table["final_y1"][1])


def test_sweep_bad_input():
    vdp = dynkit.Model("vanderpol")
    with pytest.raises(dynkit.DynkitError, match="'nope' is neither a parameter nor a state"):
        vdp.sweep(vary={"nope": [1, 2]})
    with pytest.raises(dynkit.DynkitError, match="--reduce"):
        vdp.sweep(vary={"mu": [1, 2]}, reduce="max:nothing")
    with pytest.raises(TypeError):
        vdp.sweep(vary={"mu": [1, 2]}, tolerance=1e-3)
    with pytest.raises(KeyError, match="columns: run, mu"):
        vdp.sweep(vary={"mu": [1]}, tspan=(0, 0.1))["y9"]


def test_linearize_is_dynkit_linearize():
    ref = json.loads(cli("linearize", "pendulum", "--init", "phi=pi", "--init", "dphi=0",
                         "--json"))
    got = dynkit.Model("pendulum").linearize(init={"phi": "pi", "dphi": 0})
    assert same_bits(got, ref)
    p = got["points"][0]
    assert p["A"].shape == (2, 2) and p["stability"] == "unstable"
    g, l = 9.81, dynkit.Model("pendulum").parameters["l"]
    assert np.allclose(np.sort(p["re"]), [-math.sqrt(g / l), math.sqrt(g / l)], rtol=1e-9)
    # one point per value of --vary, as the command
    ref = json.loads(cli("linearize", "vanderpol", "--init", "y1=0", "--vary", "mu=0:3:4",
                         "--json"))
    got = dynkit.Model("vanderpol").linearize(init={"y1": 0}, vary={"mu": (0, 3, 4)})
    assert same_bits(got, ref) and len(got["points"]) == 4


def test_steady_is_dynkit_steady():
    ref = json.loads(cli("steady", TOP, "--unknown", "dpsi", "--init", "dpsi=1", "--json"))
    got = dynkit.Model(TOP).steady("dpsi", init={"dpsi": 1})
    assert same_bits(got, ref)
    assert got["eigenvalues"].shape[1] == 2 and got["residual"] < 1e-10
    assert got["unknowns"] == ["dpsi"]


def test_continue_is_dynkit_continue():
    args = ["--par", "rho", "--init", "x=8.5", "--init", "y=8.5", "--init", "z=27", "--set",
            "rho=28", "--opt", "ds=-0.5", "--opt", "parmin=1", "--opt", "parmax=30",
            "--opt", "dsmax=1"]
    ref = json.loads(cli("continue", LORENZ, *args, "--json"))
    got = dynkit.Model(LORENZ).continue_("rho", init={"x": 8.5, "y": 8.5, "z": 27},
                                         set={"rho": 28},
                                         opt={"ds": -0.5, "parmin": 1, "parmax": 30,
                                              "dsmax": 1})
    assert same_bits(got, ref)
    # the Hopf point of the Lorenz system: rho = s (s + b + 3) / (s - b - 1)
    s, b = 10.0, 8.0 / 3.0
    hopf = [p["rho"] for br in got["branches"] for p in br["points"] if p["label"] == "HB"]
    assert hopf and abs(hopf[0] - s * (s + b + 3) / (s - b - 1)) < 1e-8


def test_inverse_is_dynkit_inverse_and_the_homework():
    opts = ["--prescribe", "sX=-20*t", "--prescribe", "theta=pi/8*sin(4*pi*t)",
            "--inputs", "Fx,Fy", "--tspan", "0:0.5", "--step", "0.01"]
    names, rows = csv_rows(cli("inverse", CART, *opts))
    cart = dynkit.Mechanism(CART)
    table = cart.inverse(prescribe={"sX": "-20*t", "theta": "pi/8*sin(4*pi*t)"},
                         inputs=["Fx", "Fy"], tspan=(0, 0.5), step=0.01)
    assert table.columns == names
    assert table.data.tobytes() == np.array([[float(v) for v in r] for r in rows]).tobytes()
    assert table.unit("Fx") == "N" and "project-init" in table.log
    # the homework's own derivation of the same motion (problem 4a: v0 = 20, f = 2)
    hn, hrows = csv_rows(cli("inverse", "cart", "--set", "N=51"))
    hw = np.array([[float(v) for v in r] for r in hrows])
    assert hn[:3] == ["t", "Fx", "Fy"] and np.array_equal(hw[:, 0], table["t"])
    scale = np.max(np.abs(hw[:, 1:3]))
    assert np.max(np.abs(hw[:, 1:3] - table.data[:, 1:3])) < 1e-6 * scale


def test_dataframes():
    pd = pytest.importorskip("pandas")
    run = dynkit.Model("vanderpol").run(method="rk4", step=0.01, tspan=(0, 1))
    frame = run.to_dataframe()
    assert isinstance(frame, pd.DataFrame) and list(frame.columns) == run.names
    assert frame["y1"].to_numpy().tobytes() == run["y1"].tobytes()
    table = dynkit.Model("pendulum").sweep(vary={"dphi": (0.1, 1.0, 4)}, tspan=(0, 1))
    frame = table.to_dataframe()
    assert list(frame.columns) == table.columns and len(frame) == 4
    assert frame.to_numpy().tobytes() == table.data.tobytes()
    assert frame.attrs["units"]["final_phi"] == "rad"


def test_analyses_bad_input():
    pendulum = dynkit.Model("pendulum")
    with pytest.raises(dynkit.DynkitError, match="--par 'nope': not a parameter of pendulum"):
        pendulum.continue_("nope")
    with pytest.raises(dynkit.DynkitError, match="no state or parameter 'nope'"):
        pendulum.steady("nope")
    with pytest.raises(dynkit.DynkitError, match="--jacobian"):
        pendulum.linearize(jacobian="magic")
    with pytest.raises(TypeError):
        pendulum.linearize(step=0.1)
    with pytest.raises(dynkit.DynkitError, match="'zz' is not a coordinate"):
        dynkit.Mechanism(CART).inverse(prescribe={"zz": "t"})
