# SPDX-License-Identifier: BSD-3-Clause
"""Bad input to the Python package: a wrong shape, a non-finite y0, a fun that raises or
returns the wrong length, an unknown method, option or model give a Python exception naming
it, and many failing calls leak no memory."""
import math
import resource

import numpy as np
import pytest

import dynkit


def f(t, y):
    return [y[1], -y[0]]


def test_fun_raises_its_own_exception():
    class Boom(Exception):
        pass

    def bad(t, y):
        if t > 0.5:
            raise Boom("at t > 0.5")
        return [y[1], -y[0]]
    with pytest.raises(Boom, match="at t > 0.5"):
        dynkit.solve_ivp(bad, (0, 1), [1, 0])


def test_wrong_length_and_shape():
    with pytest.raises(ValueError, match="has 3 values, 2 expected"):
        dynkit.solve_ivp(lambda t, y: [1, 2, 3], (0, 1), [1, 0])
    with pytest.raises(TypeError, match="real numbers"):
        dynkit.solve_ivp(f, (0, 1), [[1, 0], [0, 1]])
    with pytest.raises(ValueError, match="t_span"):
        dynkit.solve_ivp(f, (0, 1, 2), [1, 0])
    with pytest.raises(ValueError, match="jac"):
        dynkit.solve_ivp(f, (0, 1), [1, 0], method="BDF", jac=lambda t, y: np.eye(3))


def test_nonfinite_y0_and_unknown_names():
    with pytest.raises(ValueError, match="y0"):
        dynkit.solve_ivp(f, (0, 1), [math.nan, 0])
    with pytest.raises(ValueError, match="unknown method 'RK99'"):
        dynkit.solve_ivp(f, (0, 1), [1, 0], method="RK99")
    with pytest.raises(TypeError):
        dynkit.solve_ivp(f, (0, 1), [1, 0], rtoll=1e-3)
    with pytest.raises(dynkit.DynkitError, match="unknown model 'pendulm'"):
        dynkit.Model("pendulm")
    with pytest.raises(ValueError, match="y0"):
        dynkit.Model("pendulum").run(y0=[math.inf, 0])
    with pytest.raises(ValueError, match="no event 'nope'"):
        dynkit.Model("pendulum").run(events=["nope"])


def test_model_file_errors_name_the_place(tmp_path):
    bad = tmp_path / "bad.ode"
    bad.write_text("x'=-k*x\ndone\n")
    with pytest.raises(dynkit.DynkitError, match=r"bad.ode:1:\d+: .*'k'"):
        dynkit.Model(str(bad))


def test_failing_calls_leak_nothing():
    def bad(t, y):
        raise RuntimeError("no")

    def many():
        for _ in range(2000):
            with pytest.raises(RuntimeError):
                dynkit.solve_ivp(bad, (0, 1), np.ones(50))
            with pytest.raises(ValueError):
                dynkit.solve_ivp(lambda t, y: np.ones(3), (0, 1), np.ones(50))
    many()  # warm up allocators
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    many()
    many()
    after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    assert after - before < 2048, (before, after)  # kB: no growth with the calls
