"""Tests of famcc.simulate (module famcc.simulation): sample-and-hold loop, integrator accuracy, metrics, validation."""

from __future__ import annotations

import math
import sys
from types import SimpleNamespace

import famcc
import numpy as np
import pytest
from famcc import plants
from famcc.simulation import SimResult, Sine, simulate

# -- a mock controller with the duck-typed interface -----------------------------------------


class MockPD:
    """PD on the sampled error (backward difference), with fake but traceable diagnostics.

    ``diagnostics`` describes the last output: ``xi = v / 1000``, ``s = call index``,
    ``z_hat = (e, de)``; the "bounds" expand by ``1 + |v| / 10`` while ``|v| > expand_above``.
    """

    def __init__(self, dt=1e-3, order=2, kp=100.0, kd=20.0, expand_above=math.inf):
        self.dt, self.order = dt, order
        self.kp, self.kd = kp, kd
        self.expand_above = expand_above
        self.calls: list[tuple[float, float | None]] = []
        self._prev: float | None = None
        self.diagnostics = self._diag(0.0, 0.0, 0.0, False)

    def _diag(self, v, e, de, expanded):
        factor = 1.0 + abs(v) / 10.0 if expanded else 1.0
        k = len(self.calls)
        return SimpleNamespace(
            t=(k - 1) * self.dt,
            xi=v / 1000.0,
            s=float(k),
            s_prev=e,
            ds_prev=de,
            bounds=(0.0, 0.5 * factor),
            nominal_bounds=(0.0, 0.5),
            z_hat=np.array([e, de] + [0.0] * (self.order - 2)),
            expanded=expanded,
            clamp_count=3 * k,
        )

    def step(self, e, applied=None):
        self.calls.append((e, applied))
        de = 0.0 if self._prev is None else (e - self._prev) / self.dt
        self._prev = e
        v = -self.kp * e - self.kd * de
        self.diagnostics = self._diag(v, e, de, abs(v) > self.expand_above)
        return v


class RecordingPlant:
    """Wraps a plant (without ``rhs_fast``) and records every right-hand-side call."""

    def __init__(self, plant):
        self.plant, self.order, self.calls = plant, plant.order, []

    @property
    def x0(self):
        return self.plant.x0

    def rhs(self, t, x, u):
        self.calls.append((t, u))
        return self.plant.rhs(t, x, u)

    def output_derivatives(self, t, x):
        return self.plant.output_derivatives(t, x)

    def gain_and_drift(self, t, x):
        return self.plant.gain_and_drift(t, x)


# -- closed loop ---------------------------------------------------------------------------


@pytest.mark.parametrize("variant", ["paper", "code"])
def test_pd_mock_stabilises_the_second_order_plant(variant):
    res = simulate(plants.second_order(variant), MockPD(), t_end=6.0, reference=Sine())
    tail = res.t >= 4.0
    # measured: max |z1| 0.015 (paper) / 0.034 (code), max |z2| 0.023 / 0.050
    assert np.max(np.abs(res.z[tail, 0])) < 0.05
    assert np.max(np.abs(res.z[tail, 1])) < 0.1
    assert res.settling_time(0.05) is not None and res.settling_time(0.05) < 1.0
    assert np.all(np.isfinite(res.x))


def test_shapes_and_sample_grid():
    res = simulate(plants.second_order(), MockPD(dt=2e-3), t_end=1.0, reference=Sine())
    K = 501  # round(t_end / dt) + 1 samples, t = 0 and t = t_end included
    assert res.t.shape == res.y.shape == res.v.shape == res.u.shape == (K,)
    assert res.x.shape == res.z.shape == res.z_hat.shape == (K, 2)
    assert res.bounds.shape == res.nominal_bounds.shape == (K, 2)
    assert res.expanded.dtype == bool and res.neg_f_over_g.shape == (K,)
    np.testing.assert_allclose(res.t, np.arange(K) * 2e-3, rtol=0, atol=1e-15)
    assert res.dt == 2e-3 and res.u_limits is None


def test_horizon_is_rounded_to_whole_samples():
    res = simulate(
        plants.second_order(), MockPD(dt=0.01), t_end=0.1049, record=False, reference=Sine()
    )
    assert len(res.t) == 11 and res.t[-1] == pytest.approx(0.1)


def test_sample_and_hold_and_controller_calls():
    plant = RecordingPlant(plants.second_order())
    ctrl = MockPD(dt=5e-3)
    substeps = 4
    res = simulate(
        plant, ctrl, t_end=0.5, u_limits=(-2.5, 3.0), substeps=substeps, reference=Sine()
    )
    K = len(res.t)
    # the controller is called exactly once per sample, with e_k = y(t_k) - y_d(t_k)
    assert len(ctrl.calls) == K == 101
    e = np.array([c[0] for c in ctrl.calls])
    np.testing.assert_array_equal(e, res.y - res.y_d)
    np.testing.assert_array_equal(res.y, res.x[:, 0])
    np.testing.assert_allclose(res.y_d, np.sin(res.t), rtol=0, atol=1e-15)
    # `applied` is the input really held over the previous period
    assert ctrl.calls[0][1] is None
    assert [c[1] for c in ctrl.calls[1:]] == res.u[:-1].tolist()
    # every RHS call inside [t_k, t_k + dt] sees u_k; the plant is not integrated past t_end
    calls = plant.calls
    assert len(calls) == (K - 1) * substeps * 4
    for k in range(K - 1):
        chunk = calls[k * substeps * 4 : (k + 1) * substeps * 4]
        assert all(u == res.u[k] for _, u in chunk)
        times = [t for t, _ in chunk]
        assert min(times) == pytest.approx(res.t[k]) and max(times) == pytest.approx(res.t[k + 1])
    # the loop really saturated, so holding and clipping were both exercised
    assert res.saturated_fraction > 0


def test_diagnostics_are_recorded_after_each_step():
    ctrl = MockPD(dt=1e-2, expand_above=5.0)
    res = simulate(plants.second_order(), ctrl, t_end=1.0, reference=Sine())
    np.testing.assert_array_equal(res.s, np.arange(1, len(res.t) + 1))
    np.testing.assert_allclose(res.xi, res.v / 1000.0)
    np.testing.assert_array_equal(res.z_hat[:, 0], res.y - res.y_d)
    np.testing.assert_array_equal(res.expanded, np.abs(res.v) > 5.0)
    assert res.clamp_count == 3 * len(res.t)
    assert res.max_abs_xi == pytest.approx(np.max(np.abs(res.v)) / 1000.0)


def test_input_respects_limits_and_saturation_is_reported():
    lo, hi = -2.5, 3.0
    ctrl = MockPD(dt=1e-3, expand_above=3.0)
    res = simulate(
        plants.second_order("code"), ctrl, t_end=3.0, u_limits=(lo, hi), reference=Sine()
    )
    assert np.all(res.u >= lo) and np.all(res.u <= hi)
    assert res.u_min == lo and res.u_max == hi
    np.testing.assert_array_equal(res.u, np.clip(res.v, lo, hi))
    sat = (res.v < lo) | (res.v > hi)
    assert res.saturated_fraction == pytest.approx(np.mean(sat))
    episodes = res.saturation_episodes()
    assert episodes and episodes[0][0] == 0.0  # the initial error saturates at once
    assert res.last_saturation_end == episodes[-1][1]
    assert res.largest_expansion > 1.0


def test_true_error_vector_and_minus_f_over_g():
    plant = plants.second_order("code")
    res = simulate(plant, MockPD(dt=1e-2), t_end=1.0, reference=Sine())
    for k in (0, 37, len(res.t) - 1):
        t, x = res.t[k], res.x[k]
        np.testing.assert_allclose(
            res.z[k], plant.output_derivatives(t, x) - [np.sin(t), np.cos(t)]
        )
        gain, drift = plant.gain_and_drift(t, x)
        # dz_n/dt = G u + F with F = F_a - y_d^(n); -F/G makes it vanish
        assert gain * res.neg_f_over_g[k] + (drift + np.sin(t)) == pytest.approx(0.0, abs=1e-12)


def test_minus_f_over_g_is_consistent_with_the_simulated_motion():
    plant = plants.second_order("paper")
    res = simulate(plant, MockPD(dt=1e-3), t_end=1.0, reference=Sine())
    # d z2/dt over one hold period (central difference of the exact z2) = G (u - (-F/G))
    dz2 = (res.z[2:, 1] - res.z[:-2, 1]) / (2 * res.dt)
    gains = np.array([plant.gain_and_drift(t, x)[0] for t, x in zip(res.t, res.x)])
    predicted = gains[1:-1] * (0.5 * (res.u[:-2] + res.u[1:-1]) - res.neg_f_over_g[1:-1])
    # measured 3e-4 (second-difference error) against values up to 17
    assert np.max(np.abs(dz2 - predicted)[50:]) < 3e-3


# -- integrator ----------------------------------------------------------------------------


class Zero:
    order = 2

    def __init__(self, dt, order=2):
        self.dt, self.order = dt, order

    def step(self, e, applied=None):
        return 0.0


def test_rk4_substeps_converge_at_fourth_order():
    plant = plants.second_order()
    runs = {
        s: simulate(plant, Zero(1e-2), 2.0, substeps=s, record=False, reference=Sine())
        for s in (1, 2, 100)
    }
    err1 = np.max(np.abs(runs[1].x - runs[100].x))
    err2 = np.max(np.abs(runs[2].x - runs[100].x))
    assert 12.0 < err1 / err2 < 20.0  # 2^4 = 16 (measured 16.2)


def test_ten_substeps_agree_with_a_hundred():
    # Measured max |x| (max |v|) difference, 10 vs 100 substeps, closed loop with the PD
    # mock (|x| <= 4, first input 100): dt = 1e-3: 2.2e-12 (3.3e-10); dt = 1e-2: 1.2e-7
    # (2.1e-6). Open-loop third-order plant, dt = 1e-3: 1.2e-11 over 5 s (|x| up to 100).
    plant = plants.second_order()
    for dt, tol_x, tol_v in ((1e-3, 2e-11, 3e-9), (1e-2, 1e-6, 2e-5)):
        a = simulate(plant, MockPD(dt=dt), 1.0, substeps=10, record=False, reference=Sine())
        b = simulate(plant, MockPD(dt=dt), 1.0, substeps=100, record=False, reference=Sine())
        assert np.max(np.abs(a.x - b.x)) < tol_x
        assert np.max(np.abs(a.v - b.v)) < tol_v
    third = plants.third_order()
    a = simulate(third, Zero(1e-3, 3), 1.0, substeps=10, record=False, reference=Sine())
    b = simulate(third, Zero(1e-3, 3), 1.0, substeps=100, record=False, reference=Sine())
    assert np.max(np.abs(a.x - b.x)) < 1e-10


def test_fast_path_equals_numpy_path():
    plant = plants.third_order("paper")
    a = simulate(plant, MockPD(dt=1e-2, order=3, kp=5.0, kd=1.0), 1.0, reference=Sine())
    b = simulate(
        RecordingPlant(plant), MockPD(dt=1e-2, order=3, kp=5.0, kd=1.0), 1.0, reference=Sine()
    )
    np.testing.assert_allclose(a.x, b.x, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(a.neg_f_over_g, b.neg_f_over_g, rtol=1e-12)


# -- references ----------------------------------------------------------------------------


def test_sine_derivatives():
    ref = Sine(amplitude=2.0, omega=3.0, phase=0.5)
    t = 0.8
    expected = [
        2 * np.sin(2.9),
        6 * np.cos(2.9),
        -18 * np.sin(2.9),
        -54 * np.cos(2.9),
        162 * np.sin(2.9),
    ]
    np.testing.assert_allclose([ref(t, k) for k in range(5)], expected, rtol=1e-14)
    with pytest.raises(ValueError, match="amplitude"):
        Sine(amplitude=math.nan)


def test_reference_forms_are_equivalent():
    plant = plants.second_order()
    base = simulate(plant, MockPD(dt=1e-2), 1.0, reference=Sine())
    as_callable = simulate(plant, MockPD(dt=1e-2), 1.0, reference=lambda t, k: Sine()(t, k))
    as_tuple = simulate(
        plant, MockPD(dt=1e-2), 1.0, reference=(np.sin, np.cos, lambda t: -np.sin(t))
    )
    for other in (as_callable, as_tuple):
        np.testing.assert_allclose(other.x, base.x, rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(other.neg_f_over_g, base.neg_f_over_g, rtol=1e-12)
    short = simulate(plant, MockPD(dt=1e-2), 1.0, reference=(np.sin, np.cos))
    assert short.neg_f_over_g is None
    np.testing.assert_allclose(short.z, base.z, rtol=1e-13, atol=1e-13)


def test_other_reference_is_tracked():
    ref = Sine(amplitude=0.5, omega=2.0)
    res = simulate(plants.second_order(), MockPD(), 5.0, reference=ref)
    np.testing.assert_allclose(res.y_d, 0.5 * np.sin(2 * res.t), atol=1e-15)
    assert np.max(np.abs(res.z[res.t > 3, 0])) < 0.05


def test_the_function_does_not_shadow_its_module():
    import famcc

    assert famcc.simulate is simulate and famcc.Sine is Sine and famcc.SimResult is SimResult
    assert sys.modules["famcc.simulation"].simulate is simulate


# -- plants without derivatives, record=False ------------------------------------------------


def test_record_false_needs_no_diagnostics():
    res = simulate(plants.second_order(), Zero(1e-2), 0.5, record=False, reference=Sine())
    for name in (
        "z_hat",
        "xi",
        "s",
        "s_prev",
        "ds_prev",
        "bounds",
        "nominal_bounds",
        "expanded",
        "neg_f_over_g",
    ):
        assert getattr(res, name) is None
    assert res.max_abs_xi is None and res.largest_expansion is None
    assert res.summary()["clamp_count"] == 0


def test_plant_without_derivatives_reports_z1_only():
    g = [lambda x, t: 1.0, lambda x, t: 1.0, lambda x, t: 2.0 + math.cos(t)]
    f = [lambda x, t: -x[0], lambda x, t: math.sin(x[0]), lambda x, t: -x[2]]
    plant = plants.StrictFeedback(g, f, [0.1, 0.0, 0.0])
    res = simulate(plant, MockPD(dt=1e-2, order=3, kp=1.0, kd=0.0), 0.3, reference=Sine())
    np.testing.assert_array_equal(res.z[:, 0], res.y - res.y_d)
    assert np.all(np.isnan(res.z[:, 1:]))
    assert res.neg_f_over_g is None


# -- failures ------------------------------------------------------------------------------


class Blowup(plants.Plant):
    """x' = x^2 + u from x(0) = 1: finite escape at t = 1."""

    def __init__(self):
        super().__init__(1, [1.0], name="blowup")

    def rhs(self, t, x, u):
        return np.array([x[0] ** 2 + u])


def test_non_finite_state_stops_with_the_time():
    # x = 1 / (1 - t): RK4 with h = 0.01 steps past the escape time within (1.0, 1.1)
    with pytest.raises(FloatingPointError, match=r"non-finite between t = 1 s and t = 1\.1 s"):
        simulate(Blowup(), Zero(0.1, order=1), t_end=3.0, record=False, reference=Sine())


def test_non_finite_controller_output_stops_with_the_time():
    class NaNAfterTwo(Zero):
        n = 0

        def step(self, e, applied=None):
            self.n += 1
            return math.nan if self.n > 2 else 0.0

    with pytest.raises(FloatingPointError, match=r"t = 0\.02"):
        simulate(plants.second_order(), NaNAfterTwo(0.01), 1.0, record=False, reference=Sine())


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"t_end": 0.0}, "t_end"),
        ({"t_end": -1.0}, "t_end"),
        ({"t_end": math.nan}, "t_end"),
        ({"t_end": math.inf}, "t_end"),
        ({"t_end": "1"}, "t_end"),
        ({"t_end": 0.004}, "t_end"),
        ({"substeps": 0}, "substeps"),
        ({"substeps": 2.5}, "substeps"),
        ({"substeps": True}, "substeps"),
        ({"u_limits": (2.0, 2.0)}, "u_limits"),
        ({"u_limits": (3.0, -3.0)}, "u_limits"),
        ({"u_limits": (-1.0,)}, "u_limits"),
        ({"u_limits": "ab"}, "u_limits"),
        ({"u_limits": (math.nan, 1.0)}, "u_limits"),
        ({"reference": 3.0}, "reference"),
        ({"reference": (np.sin,)}, "reference"),
        ({"reference": lambda t, k: math.inf}, "reference"),
        ({"reference": lambda t: 0.0}, "reference"),
    ],
)
def test_bad_arguments_raise_value_error_naming_them(kwargs, match):
    args = {"t_end": 1.0, "reference": Sine(), **kwargs}
    with pytest.raises(ValueError, match=match):
        simulate(plants.second_order(), MockPD(dt=0.01), **args)


@pytest.mark.parametrize(
    ("ctrl", "match"),
    [
        (SimpleNamespace(dt=0.01, order=3, step=lambda e, applied=None: 0.0), "order"),
        (SimpleNamespace(dt=0.0, order=2, step=lambda e, applied=None: 0.0), "dt"),
        (SimpleNamespace(dt=-1e-3, order=2, step=lambda e, applied=None: 0.0), "dt"),
        (SimpleNamespace(order=2, step=lambda e, applied=None: 0.0), "dt"),
        (SimpleNamespace(dt=0.01, order=2), "step"),
    ],
)
def test_bad_controller_raises_value_error(ctrl, match):
    with pytest.raises(ValueError, match=match):
        simulate(plants.second_order(), ctrl, 1.0, reference=Sine())


def test_missing_diagnostics_need_record_false():
    with pytest.raises(ValueError, match="record=False"):
        simulate(plants.second_order(), Zero(0.01), 1.0, reference=Sine())


def test_bad_plant_raises_value_error():
    with pytest.raises(ValueError, match="plant"):
        simulate(
            SimpleNamespace(order=0, x0=[], rhs=None),
            Zero(0.01),
            1.0,
            record=False,
            reference=Sine(),
        )


# -- metrics on hand-made arrays -----------------------------------------------------------


def make_result(z1, v=None, u_limits=None, bounds=None, nominal=None, expanded=None, dt=0.1):
    z1 = np.asarray(z1, dtype=float)
    t = np.round(np.arange(len(z1)) * dt, 12)
    v = np.zeros_like(z1) if v is None else np.asarray(v, dtype=float)
    u = v if u_limits is None else np.clip(v, *u_limits)
    return SimResult(
        t=t,
        y=z1,
        y_d=np.zeros_like(z1),
        x=z1[:, None],
        z=z1[:, None],
        v=v,
        u=u,
        dt=dt,
        u_limits=u_limits,
        bounds=None if bounds is None else np.asarray(bounds, dtype=float),
        nominal_bounds=None if nominal is None else np.asarray(nominal, dtype=float),
        expanded=None if expanded is None else np.asarray(expanded, dtype=bool),
    )


def test_settling_time_and_first_entry():
    r = make_result([1.0, 0.05, 0.2, 0.09, 0.0, -0.05])
    assert r.first_entry(0.1) == 0.1
    assert r.settling_time(0.1) == 0.3  # last outside at 0.2, then inside to the end
    assert r.settling_time(0.3) == 0.1
    assert r.settling_time(2.0) == 0.0  # always inside
    assert r.first_entry(0.01) == 0.4
    assert r.settling_time(0.01) is None  # the last sample is outside
    assert make_result([1.0, 2.0]).first_entry(0.5) is None
    # the band is open: |z1| == eps counts as outside
    assert make_result([0.1, 0.0]).settling_time(0.1) == 0.1
    # NaN counts as outside
    assert make_result([0.0, math.nan, 0.0]).settling_time(0.1) == 0.2
    with pytest.raises(ValueError, match="eps"):
        r.settling_time(0.0)
    with pytest.raises(ValueError, match="eps"):
        r.first_entry(-1.0)


def test_saturation_metrics():
    v = [5.0, 4.0, 1.0, 0.0, -3.0, 2.0, 9.0, 9.0]
    r = make_result(np.zeros(8), v=v, u_limits=(-2.0, 3.0))
    assert r.saturated_fraction == pytest.approx(5 / 8)
    # an episode covers its hold intervals: it ends at the first unsaturated sample,
    # clipped to the horizon when it lasts to the end
    assert r.saturation_episodes() == [(0.0, 0.2), (0.4, 0.5), (0.6, 0.7)]
    assert r.last_saturation_end == 0.7
    assert (r.u_min, r.u_max) == (-2.0, 3.0)
    # v equal to a limit is not saturated
    edge = make_result(np.zeros(3), v=[3.0, -2.0, 0.0], u_limits=(-2.0, 3.0))
    assert edge.saturated_fraction == 0.0 and edge.last_saturation_end is None
    free = make_result(np.zeros(3), v=[50.0, -50.0, 0.0])
    assert free.saturated_fraction == 0.0 and free.saturation_episodes() == []
    assert (free.u_min, free.u_max) == (-50.0, 50.0)


def test_expansion_metrics():
    nominal = [[0.0, 1.0], [0.0, 1.0], [0.0, 0.9], [0.0, 0.8], [0.0, 0.7], [0.0, 0.6]]
    bounds = [[0.0, 1.0], [0.0, 2.5], [0.0, 1.8], [0.0, 0.9], [0.0, 0.7], [0.0, 0.6]]
    expanded = [False, True, True, False, False, False]
    r = make_result(np.zeros(6), bounds=bounds, nominal=nominal, expanded=expanded)
    assert r.largest_expansion == pytest.approx(2.5)
    # the last expanded sample is at 0.2; bounds still relax at 0.3 and equal nominal at 0.4
    assert r.nominal_return_time == 0.4
    never = make_result(np.zeros(6), bounds=nominal, nominal=nominal, expanded=[False] * 6)
    assert never.largest_expansion == 1.0 and never.nominal_return_time is None
    stuck = make_result(
        np.zeros(6), bounds=bounds, nominal=nominal, expanded=[False, True, True, True, True, True]
    )
    assert stuck.nominal_return_time is None


def test_summary_collects_the_metrics():
    r = make_result(
        [1.0, 0.05, 0.0],
        v=[9.0, 0.0, 0.0],
        u_limits=(-1.0, 1.0),
        bounds=[[1.0, 0.0], [1.0, 0.0], [1.0, 0.0]],
        nominal=[[1.0, 0.0], [1.0, 0.0], [1.0, 0.0]],
        expanded=[False] * 3,
    )
    s = r.summary(eps=0.1)
    assert s["settling_time"] == 0.1 and s["first_entry"] == 0.1
    assert s["saturated_fraction"] == pytest.approx(1 / 3)
    assert s["saturation_episodes"] == 1 and s["last_saturation_end"] == 0.1
    assert s["largest_expansion"] == 1.0 and s["nominal_return_time"] is None
    assert {"max_abs_xi", "u_min", "u_max", "clamp_count"} <= set(s)


def test_a_controller_without_famcc_configuration_is_named_by_its_class():
    plant = plants.second_order()
    res = simulate(plant, MockPD(), 0.01, reference=Sine())
    assert res.controller_description == "MockPD (no famcc configuration)"
    # a class whose default repr has no module ("<Bare object at 0x...>")
    bare = type("Bare", (MockPD,), {"__module__": "builtins"})()
    assert repr(bare).startswith("<Bare object at ")
    res = simulate(plant, bare, 0.01, reference=Sine())
    assert res.controller_description == "Bare (no famcc configuration)"


def test_iae_is_the_trapezoid_of_the_absolute_error():
    # trapezoids of |z1| = 2, 1, 0, 1, 4: 1.5 + 0.5 + 0.5 + 2.5 = 5, times dt
    assert make_result([2.0, -1.0, 0.0, 1.0, -4.0]).iae == pytest.approx(0.5, rel=1e-12)
    assert make_result([3.0]).iae == 0.0


def test_repr_names_samples_horizon_and_step():
    head = repr(make_result(np.zeros(6))).splitlines()[0]
    assert head.startswith("<famcc.SimResult: 6 samples, 0-0.5 s at dt = 0.1 s;"), head


def test_total_variation_of_u_per_second():
    r = make_result(np.zeros(5), v=[0.0, 1.0, -1.0, -1.0, 2.0])  # 0.4 s; 1 + 2 + 0 + 3 = 6
    assert r.tv_u_per_s == pytest.approx(15.0, rel=1e-12)
    assert make_result([0.0], v=[3.0]).tv_u_per_s == 0.0  # no duration, no variation
    empty = make_result([])
    assert (empty.tv_u_per_s, empty.iae, empty.rms_u) == (0.0, 0.0, 0.0)


def test_z1_ripple_counts_the_sample_at_the_settling_time():
    r = make_result([1.0, 0.05, -0.02, 0.01])  # settled (eps 0.1) at 0.1 s, on its peak
    assert r.settling_time(0.1) == 0.1
    assert r.z1_ripple(0.1) == pytest.approx(0.07, rel=1e-12)
    assert make_result([1.0, 1.0]).z1_ripple(0.1) is None


def test_summary_of_a_run_that_never_settled_names_its_horizon():
    text = make_result(np.ones(6)).summary(eps=0.1).text
    assert "NOT settled to |z1| < 0.1 by the end (0.5 s; first entry never" in text, text


def test_controller_description_names_constraint_laws_and_parameters():
    ctrl = famcc.Controller(
        2, 1e-3, famcc.FiniteTime(k=2.0, p=0.5), constraint="lateral", eps=0.02, k_u=2.0
    )
    res = simulate(plants.second_order(), ctrl, 0.01, reference=Sine())
    assert res.controller_description == (
        "LaMC (lateral constraint), h_p FiniteTime(k=2.0, p=0.5), eps = 0.02, T_s = 1 s, k_u = 2"
    )
    rfc = famcc.scenarios.paper("rfc").run(t_end=0.01).controller_description
    assert rfc == (
        "LoMC (longitudinal constraint), h_p FixedTime(alpha=1.0, p=0.5, beta=0.5, q=2.0) + NSMD, "
        "FixedTime(alpha=2.0, p=0.5, beta=1.0, q=2.0) + NSMD, eps = 3, T_s = 1 s, k_u = 30"
    )
