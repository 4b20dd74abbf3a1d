"""Measuring a plant by experiments (famcc.tuning.probe, famcc.tuning.measure):
the pulse gain against the exact one, the holding input at the reference, and
tune on plants without derivatives (an `if` load, a black box)."""

from __future__ import annotations

import math
import warnings

import famcc
import numpy as np
import pytest
from famcc.plants import BlackBox, Plant
from famcc.tuning import measure, probe
from hypothesis import given, settings
from hypothesis import strategies as st


class Chain(Plant):
    """x_i' = x_{i+1}, x_n' = g(x) u + f(x): G = g(x), exactly."""

    def __init__(self, order: int, a: float, b: float, c: float, x0: list[float]) -> None:
        super().__init__(order, x0)
        self.a, self.b, self.c = a, b, c

    def _g(self, x: np.ndarray) -> float:
        return self.a * (1.5 + math.sin(x[0]))

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        f = self.b * x[0] + self.c * math.tanh(x[-1]) + (0.3 if t >= 1.0 else 0.0)
        return np.concatenate((x[1:], [self._g(x) * u + f]))

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        return self._g(x), math.nan


class Loaded(Plant):
    """y'' = -3 y' + 2.5 u - load, the load switching on at t = 1 s (no jets)."""

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        return np.array([x[1], -3.0 * x[1] + 2.5 * u - (0.6 if t >= 1.0 else 0.0)])


@settings(max_examples=40, deadline=None)
@given(
    order=st.integers(1, 3),
    a=st.floats(0.2, 50.0) | st.floats(-50.0, -0.2),
    b=st.floats(-5.0, 5.0),
    c=st.floats(-5.0, 5.0),
    x=st.lists(st.floats(-2.0, 2.0), min_size=3, max_size=3),
    t=st.floats(0.0, 2.0),
)
def test_the_pulse_gain_equals_the_exact_gain(
    order: int, a: float, b: float, c: float, x: list[float], t: float
) -> None:
    plant = Chain(order, a, b, c, x[:order])
    state = np.array(x[:order])
    g, note = probe.pulse_gain(plant, 1e-3, (-5.0, 5.0), x=state, t0=t)
    exact = plant.gain_and_drift(t, state)[0]
    assert note == ""
    # the state moves during the 16-sample pulse, so G(x) drifts: 1 % (tune adds 20 %)
    assert g == pytest.approx(exact, rel=1e-2)  # the sign as well as the size


def test_a_wrong_order_is_named() -> None:
    plant = Chain(2, 1.0, -1.0, 0.5, [0.3, 0.0])
    plant.order = 3  # declared too high: y responds like t^2, not t^3
    assert "lower than 3" in probe.pulse_gain(plant, 1e-3, (-1.0, 1.0))[1]
    plant.order = 1  # declared too low: no t^1 term
    assert "higher than 1" in probe.pulse_gain(plant, 1e-3, (-1.0, 1.0))[1]
    # a plant the input does not reach
    deaf = Chain(2, 0.0, -1.0, 0.5, [0.3, 0.0])
    g, note = probe.pulse_gain(deaf, 1e-3, (-1.0, 1.0))
    assert g == 0.0 and "higher than 2" in note


def test_the_holding_input_is_the_equilibrium_at_the_reference() -> None:
    # before the load the plant holds with u = 0; after it, u = 0.6 / 2.5
    plant = Loaded(2, [1.0, 0.0])
    u, x = probe.equilibrium_input(plant, 0.5, [0.0], 1e-3) or (math.nan, None)
    assert u == pytest.approx(0.0, abs=1e-9)
    u, x = probe.equilibrium_input(plant, 0.5, [0.0, 3.0], 1e-3) or (math.nan, None)
    assert u == pytest.approx(0.24, rel=1e-9)
    np.testing.assert_allclose(x, [0.5, 0.0], atol=1e-9)

    class VanDerPol(Plant):  # the transient needs |u| near 9; the set point 0 needs 0
        def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
            return np.array([x[1], 1.5 * (1 - x[0] ** 2) * x[1] - x[0] + u])

    u, _ = probe.equilibrium_input(VanDerPol(2, [2.0, 0.0]), 0.0, [0.0], 1e-3) or (math.nan, 0)
    assert u == pytest.approx(0.0, abs=1e-9)

    class Drifting(Plant):  # y' = 1: no input holds it
        def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
            return np.array([1.0 + 0.0 * u])

    assert probe.equilibrium_input(Drifting(1, [0.0]), 0.0, [0.0], 1e-3) is None


class Cart:
    """A black box: p'' = 2 u - 0.5 (a constant load), integrated exactly."""

    def reset(self) -> float:
        self.p, self.v = 1.0, 0.0
        return self.p

    def step(self, u: float, dt: float) -> float:
        a = 2.0 * u - 0.5
        self.p += self.v * dt + 0.5 * a * dt * dt
        self.v += a * dt
        return self.p


def test_a_black_box_is_measured_by_its_own_runs() -> None:
    box = BlackBox(Cart(), order=2)
    assert probe.equilibrium_input(box, 0.0, [0.0], 1e-3) is None  # its state is hidden
    g, note = probe.pulse_gain(box, 1e-3, (-2.0, 2.0))
    assert note == "" and g == pytest.approx(2.0, rel=1e-6)


def test_settled_input_needs_a_settled_run() -> None:
    from types import SimpleNamespace

    t = np.linspace(0.0, 2.0, 201)
    u = 0.25 + 0.0 * t
    settled = SimpleNamespace(t=t, z=np.c_[np.exp(-10 * t)], u=u, neg_f_over_g=None)
    assert probe.settled_input(settled, 0.01) == pytest.approx(0.25)
    cycling = SimpleNamespace(t=t, z=np.c_[np.sin(5 * t)], u=3.0 * np.sign(np.sin(5 * t)))
    cycling.neg_f_over_g = None
    assert probe.settled_input(cycling, 0.01) is None
    value, warning = measure.hold_from_run(cycling, 0.005, (-3.0, 3.0))
    assert value == pytest.approx(3.0) and warning is not None
    assert "never settled" in warning and "hold_input=" in warning


def _tune(plant: object, **kw: object) -> famcc.Design:
    args: dict[str, object] = {"dt": 1e-3, "u_limits": (-2.0, 2.0), "eps": 0.02}
    args.update({"settle_time": 2.0, "t_end": 4.0, "progress": False})
    args.update(kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", famcc.DesignWarning)
        return famcc.tune(plant, **args)  # type: ignore[arg-type]


def test_tune_measures_a_plant_with_an_if_load_without_jets() -> None:
    plant, ref = Loaded(2, [1.0, 0.0]), famcc.Constant(0.0)
    d = _tune(plant, reference=ref)
    assert d.requirements["measured_gain"] == pytest.approx(measure.MARGIN * 2.5, rel=1e-3)
    # the holding input at the reference after the load, not along the transient
    assert d.requirements["measured_hold_input"] == pytest.approx(measure.MARGIN * 0.24, rel=1e-6)
    # the controller designed from these regulates through the load (how fast is
    # the search's business, not the measurement's)
    res = famcc.simulate(plant, d.controller(), 4.0, reference=ref, u_limits=(-2.0, 2.0))
    assert np.max(np.abs(res.z1[res.t >= 3.5])) < 0.02


def test_tune_measures_a_black_box_without_gain_or_hold_input() -> None:
    box, ref = BlackBox(Cart(), order=2), famcc.Constant(0.0)
    d = _tune(box, reference=ref)
    assert d.requirements["measured_gain"] == pytest.approx(measure.MARGIN * 2.0, rel=1e-3)
    # read from the settled stretch of the measuring run: the load 0.5 / G
    assert d.requirements["measured_hold_input"] == pytest.approx(measure.MARGIN * 0.25, rel=0.05)


def test_tunes_verdict_is_the_judge_of_the_returned_controllers_own_run() -> None:
    # one judge: famcc.tuning.assess on the run the user gets from the Design
    for settle in (1.0, 3.0):  # one the search cannot meet, one it can
        plant, ref = Loaded(2, [1.0, 0.0]), famcc.Constant(0.0)
        d = _tune(plant, reference=ref, settle_time=settle, t_end=2.0 * settle + 1.0)
        res = famcc.simulate(
            plant, d.controller(), 2.0 * settle + 1.0, reference=ref, u_limits=(-2.0, 2.0)
        )
        a = famcc.tuning.assess(res, eps=0.02, settle_time=settle, u_limits=(-2.0, 2.0))
        found = next(f for f in d.checks if f.name == "tune")
        assert (found.level == "ok") == a.ok, (settle, found.message, a)


def test_the_objective_orders_the_choice() -> None:
    plant, ref = Loaded(2, [1.0, 0.0]), famcc.Constant(0.0)
    runs = {}
    for objective in ("accuracy", "smooth"):
        d = _tune(plant, reference=ref, settle_time=3.0, t_end=7.0, objective=objective)
        res = famcc.simulate(plant, d.controller(), 7.0, reference=ref, u_limits=(-2.0, 2.0))
        a = famcc.tuning.assess(res, eps=0.02, settle_time=3.0, u_limits=(-2.0, 2.0))
        assert a.ok, (objective, a)
        runs[objective] = (float(np.sum(np.abs(res.z1))) * res.dt, a.effort, d)
    # each objective's choice is at least as good as the other's by its own measure
    assert runs["accuracy"][0] <= runs["smooth"][0] * 1.001
    assert runs["smooth"][1] <= runs["accuracy"][1] * 1.001
    d = runs["accuracy"][2]
    if "observer_candidate" in d.parameters:  # the text says what was chosen
        assert "extended observer" in str(d)
        kw = d.controller_kwargs()
        again = famcc.Controller(kw.pop("order"), kw.pop("dt"), **kw)
        assert again.config() == d.controller().config()
    with pytest.raises(ValueError, match="objective"):
        _tune(plant, reference=ref, objective="fastest")
