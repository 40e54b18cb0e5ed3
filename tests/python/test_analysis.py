# SPDX-License-Identifier: BSD-3-Clause
"""Model.equilibria and Model.lyapunov: Lorenz's three equilibria at their closed forms
(0 and (+-sqrt(beta (rho - 1)), +-sqrt(beta (rho - 1)), rho - 1)), the sum of its spectrum
-(sigma + 1 + beta), and both the same as `dynkit equilibria --json` and `dynkit lyapunov
--json` (the same library calls with the same defaults)."""
import json
import math
import os
import subprocess

import pytest

import dynkit
from conftest import CLI, SOURCE

LORENZ = os.path.join(SOURCE, "examples", "models", "lorenz.ode")


def cli_json(*args):
    return json.loads(subprocess.run([CLI, *args, "--json"], check=True, capture_output=True,
                                     text=True).stdout)


def test_lorenz_equilibria_closed_form_and_cli():
    m = dynkit.Model(LORENZ)
    got = m.equilibria()
    sigma, rho, beta = (m.parameters[k] for k in ("sigma", "rho", "beta"))
    c = math.sqrt(beta * (rho - 1))
    xs = sorted(q["state"]["x"] for q in got["equilibria"])
    assert len(xs) == 3
    assert xs[0] == pytest.approx(-c, abs=1e-10) and xs[2] == pytest.approx(c, abs=1e-10)
    assert abs(xs[1]) < 1e-10
    types = sorted(q["type"] for q in got["equilibria"])
    cli = cli_json("equilibria", LORENZ)
    assert types == sorted(q["type"] for q in cli["equilibria"])
    for ours, theirs in zip(got["equilibria"], cli["equilibria"]):
        assert ours["state"] == theirs["state"]
        assert ours["eigenvalues"] == theirs["eigenvalues"]


def test_lorenz_spectrum_sum_and_cli():
    m = dynkit.Model(LORENZ)
    got = m.lyapunov(spectrum=True, tspan=(0, 100))
    sigma, beta = m.parameters["sigma"], m.parameters["beta"]
    assert sum(got["exponents"]) == pytest.approx(-(sigma + 1 + beta), abs=1e-8)
    cli = cli_json("lyapunov", LORENZ, "--spectrum", "--tspan", "0:100")
    assert got["exponents"] == cli["exponents"]


def test_map_exponent_as_cli():
    henon = os.path.join(SOURCE, "examples", "models", "henon.ode")
    got = dynkit.Model(henon).lyapunov(tspan=(0, 5000))
    cli = cli_json("lyapunov", henon, "--tspan", "0:5000")
    assert got["map"] and got["exponents"] == cli["exponents"]
    assert got["exponents"][0] == pytest.approx(0.419, abs=0.02)  # Henon's published value
