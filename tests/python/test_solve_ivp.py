# SPDX-License-Identifier: BSD-3-Clause
"""dynkit.solve_ivp against exact solutions and against SciPy's solve_ivp on the same
problems: the harmonic oscillator (exact cos t), events with terminal and direction (the
first zero at pi/2), dense output, args, the Jacobian of a stiff problem (Robertson, against
SciPy's Radau at tight tolerances), and errors at equal tolerance within a factor of SciPy's."""
import math

import numpy as np
import pytest
import scipy.integrate

import dynkit


def oscillator(t, y):
    return [y[1], -y[0]]


def test_oscillator_is_cos():
    sol = dynkit.solve_ivp(oscillator, (0, 10), [1, 0], rtol=1e-10, atol=1e-12)
    assert sol.success and sol.status == 0
    assert sol.t[0] == 0 and sol.t[-1] == 10
    assert sol.y.shape == (2, len(sol.t))
    assert np.max(np.abs(sol.y[0] - np.cos(sol.t))) < 1e-8
    assert sol.nfev > 0 and sol.t_events is None


@pytest.mark.parametrize("method,scipy_method", [("RK45", "RK45"), ("RK23", "RK23"),
                                                 ("DOP853", "DOP853")])
@pytest.mark.parametrize("rtol", [1e-6, 1e-9])
def test_error_at_equal_tolerance_as_scipy(method, scipy_method, rtol):
    """the same tolerance gives an error no larger than ten times SciPy's"""
    t_eval = np.linspace(0, 20, 41)
    ours = dynkit.solve_ivp(oscillator, (0, 20), [1, 0], method=method, t_eval=t_eval,
                            rtol=rtol, atol=rtol * 1e-3)
    ref = scipy.integrate.solve_ivp(oscillator, (0, 20), [1, 0], method=scipy_method,
                                    t_eval=t_eval, rtol=rtol, atol=rtol * 1e-3)
    np.testing.assert_array_equal(ours.t, t_eval)
    err = np.max(np.abs(ours.y[0] - np.cos(t_eval)))
    err_ref = np.max(np.abs(ref.y[0] - np.cos(t_eval)))
    assert err < 10 * err_ref + 1e-14, (err, err_ref)


def test_terminal_event_with_direction():
    def down(t, y):
        return y[0]
    down.terminal = True
    down.direction = -1

    def up(t, y):
        return y[0]
    up.direction = 1
    sol = dynkit.solve_ivp(oscillator, (0, 10), [1, 0], events=[up, down], rtol=1e-10,
                           atol=1e-12)
    assert sol.status == 1 and sol.message == "A termination event occurred."
    assert len(sol.t_events[0]) == 0
    assert sol.t_events[1][0] == pytest.approx(math.pi / 2, abs=1e-9)
    assert sol.t[-1] == pytest.approx(math.pi / 2, abs=1e-9)
    assert sol.y_events[1].shape == (1, 2)
    assert sol.y_events[1][0, 1] == pytest.approx(-1.0, abs=1e-9)
    # every crossing of a non-terminal event, both ways
    both = dynkit.solve_ivp(oscillator, (0, 10), [1, 0], events=lambda t, y: y[0],
                            rtol=1e-10, atol=1e-12)
    expected = [math.pi / 2 + k * math.pi for k in range(3)]
    np.testing.assert_allclose(both.t_events[0], expected, atol=1e-9)


def test_dense_output_and_args():
    def decay(t, y, k):
        return [-k * y[0]]
    sol = dynkit.solve_ivp(decay, (0, 2), [3.0], args=(0.7,), dense_output=True, rtol=1e-10,
                           atol=1e-12)
    t = np.linspace(0, 2, 17)
    np.testing.assert_allclose(sol.sol(t)[0], 3.0 * np.exp(-0.7 * t), rtol=1e-8)
    assert sol.sol(1.0)[0] == pytest.approx(3.0 * math.exp(-0.7), rel=1e-8)
    with pytest.raises(ValueError, match="outside"):
        sol.sol(3.0)


def robertson(t, y):
    return [-0.04 * y[0] + 1e4 * y[1] * y[2],
            0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] ** 2,
            3e7 * y[1] ** 2]


def robertson_jac(t, y):
    return [[-0.04, 1e4 * y[2], 1e4 * y[1]],
            [0.04, -1e4 * y[2] - 6e7 * y[1], -1e4 * y[1]],
            [0.0, 6e7 * y[1], 0.0]]


def test_stiff_with_jacobian_as_scipy_radau():
    ours = dynkit.solve_ivp(robertson, (0, 40), [1, 0, 0], method="Radau", rtol=1e-8,
                            atol=1e-12, jac=robertson_jac)
    ref = scipy.integrate.solve_ivp(robertson, (0, 40), [1, 0, 0], method="Radau", rtol=1e-11,
                                    atol=1e-14, jac=robertson_jac)
    assert ours.success and ours.njev > 0 and ours.nlu > 0
    np.testing.assert_allclose(ours.y[:, -1], ref.y[:, -1], rtol=1e-5, atol=1e-12)
    # the conserved total
    assert abs(np.sum(ours.y[:, -1]) - 1.0) < 1e-9


def test_fixed_step_methods_take_a_step():
    sol = dynkit.solve_ivp(oscillator, (0, 1), [1, 0], method="rk4", step=0.1)
    assert len(sol.t) == 11
    assert sol.y[0, -1] == pytest.approx(math.cos(1.0), abs=1e-5)
