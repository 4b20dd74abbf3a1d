"""The physical plant suite: exact derivatives and -F/G against finite differences."""

from __future__ import annotations

import math

import famcc
import numpy as np
import pytest
from famcc import plants

SUITE = {
    "dc-motor": plants.dc_motor,
    "pendulum": plants.pendulum,
    "quadrotor-altitude": plants.quadrotor_altitude,
    "flexible-joint": plants.flexible_joint,
}


def _trajectory(plant, u, t0, x0, h, steps):
    """Fine RK4 of the plant under constant u: the output at t0 + k h."""
    x = np.array(x0, dtype=float)
    ys = [x[0]]
    for k in range(steps):
        t = t0 + k * h
        k1 = plant.rhs(t, x, u)
        k2 = plant.rhs(t + h / 2, x + h / 2 * k1, u)
        k3 = plant.rhs(t + h / 2, x + h / 2 * k2, u)
        k4 = plant.rhs(t + h, x + h * k3, u)
        x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        ys.append(x[0])
    return np.array(ys)


@pytest.mark.parametrize("name", sorted(SUITE))
def test_output_derivatives_and_gain_match_finite_differences(name):
    plant = SUITE[name]()
    n = plant.order
    rng = np.random.default_rng(3)
    x0 = np.asarray(plant.x0) + rng.uniform(-0.3, 0.3, size=n)
    t0, u = 1.3, 0.7
    d = plant.output_derivatives(t0, x0)
    gain, drift = plant.gain_and_drift(t0, x0)
    # central differences of the simulated output, order by order
    h = 1e-3
    ys = _trajectory(plant, u, t0 - 8 * h, _back(plant, u, t0, x0, 8 * h), h, 16)
    stencil = {
        1: [-1 / 2, 0, 1 / 2],
        2: [1, -2, 1],
        3: [-1 / 2, 1, 0, -1, 1 / 2],
        4: [1, -4, 6, -4, 1],
    }
    mid = 8
    for k in range(1, n + 1):
        w = stencil[k]
        half = len(w) // 2
        fd = sum(c * ys[mid - half + j] for j, c in enumerate(w)) / h**k
        want = d[k] if k < n else gain * u + drift
        assert fd == pytest.approx(want, rel=2e-3, abs=2e-3 * (1 + abs(want))), (name, k)
    assert gain == pytest.approx(plant.gain, rel=0.2)


def _back(plant, u, t0, x0, span):
    """The state at t0 - span that reaches x0 at t0 (integrate backwards)."""
    x = np.array(x0, dtype=float)
    steps = 400
    h = -span / steps
    for k in range(steps):
        t = t0 + k * h
        k1 = plant.rhs(t, x, u)
        k2 = plant.rhs(t + h / 2, x + h / 2 * k1, u)
        k3 = plant.rhs(t + h / 2, x + h / 2 * k2, u)
        k4 = plant.rhs(t + h, x + h * k3, u)
        x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return x


@pytest.mark.parametrize("name", sorted(SUITE))
def test_fast_path_equals_the_array_path(name):
    plant = SUITE[name]()
    x = np.asarray(plant.x0) + 0.2
    np.testing.assert_allclose(
        plant.rhs_fast(0.7, list(x), -0.4), plant.rhs(0.7, x, -0.4), rtol=1e-14, atol=1e-14
    )


def test_the_motor_load_needs_the_hold_input():
    m = plants.dc_motor()
    # at rest after the load step, -F/G is the holding voltage R T / K
    gain, drift = m.gain_and_drift(5.0, np.array([0.0, 0.0]))
    assert -drift / gain == pytest.approx(m.hold_input(), rel=1e-9)
    assert m.hold_input() == pytest.approx(4.0)


def test_quadrotor_thrust_limits_are_asymmetric_and_accepted():
    q = plants.quadrotor_altitude()
    ctrl = famcc.Controller(2, 1e-3, famcc.Linear(2.0), eps=0.5, k_u=10.0)
    res = famcc.simulate(
        q, ctrl, 0.5, reference=lambda t, k=0: 1.0 if k == 0 else 0.0, u_limits=(0.0, 30.0)
    )
    assert res.u_min >= 0.0 and res.u_max <= 30.0


@pytest.mark.parametrize("bad", [{"J": 0.0}, {"K": -1.0}, {"R": math.nan}])
def test_bad_parameters_are_rejected_by_name(bad):
    (name,) = bad
    with pytest.raises(ValueError, match=name):
        plants.dc_motor(**bad)
