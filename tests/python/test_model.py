# SPDX-License-Identifier: BSD-3-Clause
"""dynkit.Model: built-in models, a model file and a mechanism run through the library's one
entry, with the same bits as `dynkit run`; the seed's van der Pol run; a Model as the fun of
solve_ivp (native right-hand side); threads; the homework's report as a dict."""
import os
import subprocess
import threading

import numpy as np
import pytest

import dynkit
from conftest import CLI, SOURCE


def cli_final(*args):
    out = subprocess.run([CLI, "run", *args, "--final"], check=True, capture_output=True,
                         text=True).stdout.strip().splitlines()
    return out[0].split(","), [float(v) for v in out[1].split(",")]


@pytest.mark.parametrize("model,method,extra", [
    ("vanderpol", "rk4", ["--step", "0.01", "--tspan", "0:15"]),
    ("pendulum", "dp45", []),
    ("plane", "ode45", ["--rtol", "1e-8", "--atol", "1e-10"]),
])
def test_run_is_dynkit_run(model, method, extra):
    names, values = cli_final(model, "--method", method, *extra)
    m = dynkit.Model(model)
    kw = {}
    if "--step" in extra:
        kw["step"] = float(extra[extra.index("--step") + 1])
        kw["tspan"] = tuple(map(float, extra[extra.index("--tspan") + 1].split(":")))
    if "--rtol" in extra:
        kw["rtol"] = float(extra[extra.index("--rtol") + 1])
        kw["atol"] = float(extra[extra.index("--atol") + 1])
    run = m.run(method=method, **kw)
    assert run.names == names
    assert run.success
    assert list(run.table()[-1]) == values  # bit for bit


def test_model_file_and_mechanism():
    lorenz = dynkit.Model(os.path.join(SOURCE, "examples", "models", "lorenz.ode"))
    run = lorenz.run(tspan=(0, 1))
    names, values = cli_final(os.path.join(SOURCE, "examples", "models", "lorenz.ode"),
                              "--tspan", "0:1")
    assert run.names == names and list(run.table()[-1]) == values
    mech = dynkit.Model(os.path.join(SOURCE, "examples", "mechanisms", "double_pendulum.mech"))
    run = mech.run(tspan=(0, 2), outputs=True, rtol=1e-10, atol=1e-12)
    # a conservative mechanism: its energy output stays put
    energy = [n for n in mech.outputs if n in ("energy", "total")]
    if energy:
        e = run[energy[0]]
        assert np.max(np.abs(e - e[0])) < 1e-6 * max(1.0, abs(e[0]))


def test_units_parameters_and_initial_state():
    p = dynkit.Model("pendulum")
    assert p.units["phi"] == "rad" and p.time_unit == "s"
    assert "l" in p.parameters
    run = p.run(set={"l": 2.0}, init={"phi": 0.1}, tspan=(0, 1), step=0.5)
    assert run.y[0, 0] == 0.1
    with pytest.raises(KeyError, match="no parameter 'nope'"):
        p.run(set={"nope": 1})
    with pytest.raises(KeyError, match="no state 'nope'"):
        p.run(init={"nope": 1})


def test_seed_vanderpol_numbers():
    """the seed's vanderpoldemo: rk4, h = 0.01 over [0, 15], mu = 1, from (2, 0)"""
    run = dynkit.Model("vanderpol").run(method="rk4", step=0.01, tspan=(0, 15), y0=[2, 0])
    names, values = cli_final("vanderpol", "--method", "rk4", "--step", "0.01", "--tspan",
                              "0:15", "--init", "y1=2", "--init", "y2=0")
    assert list(run.table()[-1]) == values


def test_model_as_fun_of_solve_ivp_runs_native():
    vdp = dynkit.Model("vanderpol")
    a = dynkit.solve_ivp(vdp, (0, 15), [2, 0], method="DOP853", rtol=1e-10, atol=1e-12)
    b = dynkit.solve_ivp(lambda t, y: [y[1], (1 - y[0] ** 2) * y[1] - y[0]], (0, 15), [2, 0],
                         method="DOP853", rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(a.y[:, -1], b.y[:, -1], rtol=1e-9, atol=1e-12)
    # threads: the lock is released in native runs; each thread's answer is the same
    results = [None] * 4

    def work(i):
        results[i] = dynkit.solve_ivp(vdp, (0, 50), [2, 0], rtol=1e-9, atol=1e-12).y[:, -1]
    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results[1:]:
        np.testing.assert_array_equal(r, results[0])


def test_report_is_the_homeworks():
    rep = dynkit.report()
    text = subprocess.run([CLI, "report", "--json", "--no-studies"], capture_output=True,
                          text=True).stdout
    assert isinstance(rep, dict) and rep
    import json
    cli = json.loads(text)
    common = set(rep) & set(cli)
    assert common
    for key in common:
        if key not in ("compute_seconds", "studies", "timing"):
            assert rep[key] == cli[key], key


def test_mechanism_derive_and_forces():
    path = os.path.join(SOURCE, "examples", "mechanisms", "fourbar.mech")
    mech = dynkit.Mechanism(path)
    cli = subprocess.run([CLI, "derive", path], check=True, capture_output=True,
                         text=True).stdout
    assert mech.derive() == cli
    assert mech.constraint_forces == {"loop_x": "N", "loop_y": "N"}
    run = mech.run(outputs=True, tspan=(0, 0.5))
    names, values = cli_final(path, "--tspan", "0:0.5", "--outputs")
    assert run.names == names and list(run.table()[-1]) == values
    with pytest.raises(ValueError, match="not a mechanism file"):
        dynkit.Mechanism(os.path.join(SOURCE, "examples", "models", "lorenz.ode"))
