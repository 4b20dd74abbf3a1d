"""A negative control direction (``famcc.Controller(..., direction='negative')``,
famcc-core's ``Direction``): the positive controller on the reversed input, output for
output, with limits, initial output, applied inputs, integral action and the observer;
it regulates a plant with a negative input gain that the positive direction drives
away; it survives ``config()``, pickling, ``replace`` and ``ControllerSpec``; a bad
name and an observer of the other sign are named."""

from __future__ import annotations

import pickle
from typing import Any

import famcc
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st


def ctrl(direction: str = "positive", **kw: Any) -> famcc.Controller:
    args: dict[str, Any] = {
        "constraint": "lateral",
        "eps": 0.1,
        "k_u": 4.0,
        "direction": direction,
    }
    args.update(kw)
    law = famcc.Linear(2.0) if kw.get("integral") else famcc.FiniteTime(2.0, 0.6)
    return famcc.Controller(2, 1e-3, law, **args)


def mirror(kw: dict[str, Any]) -> dict[str, Any]:
    out = dict(kw)
    if kw.get("output_limits") is not None:
        lo, hi = kw["output_limits"]
        out["output_limits"] = (-hi, -lo)
    if kw.get("initial_output") is not None:
        out["initial_output"] = -kw["initial_output"]
    if kw.get("observer") is not None:
        o = kw["observer"]
        out["observer"] = famcc.Observer(o.mu, -o.b0)
    return out


@settings(max_examples=40, deadline=None)
@given(
    limits=st.one_of(st.none(), st.tuples(st.floats(-3, -0.2), st.floats(0.2, 3))),
    rate=st.one_of(st.none(), st.floats(5, 500)),
    u0=st.one_of(st.none(), st.floats(-2, 2)),
    integral=st.booleans(),
    observed=st.booleans(),
    stream=st.lists(
        st.tuples(st.floats(-2, 2), st.one_of(st.none(), st.floats(-5, 5))),
        min_size=1,
        max_size=80,
    ),
)
def test_negative_is_the_positive_law_on_the_reversed_input(
    limits: Any, rate: Any, u0: Any, integral: bool, observed: bool, stream: Any
) -> None:
    kw: dict[str, Any] = {"output_limits": limits, "rate_limit": rate, "initial_output": u0}
    if observed:
        kw.update(observer=famcc.Observer(0.02, 1.5), cancellation_limit=2.0, integral=False)
    else:
        kw["integral"] = integral
    pos, neg = ctrl(**kw), ctrl("negative", **mirror(kw))
    for e, applied in stream:
        a = pos.step(e, applied=applied)
        b = neg.step(e, applied=None if applied is None else -applied)
        assert a == -b
        assert pos.diagnostics.xi == neg.diagnostics.xi


def regulate(direction: str) -> float:
    """``y'' = -y' - 2 u + 1`` (``G = -2``) from ``y = 0.5`` to 0 under ``|u| <= 5``:
    the largest ``|e|`` over the last second of 6 s."""
    c = ctrl(direction, output_limits=(-5.0, 5.0))
    y, v, tail = 0.5, 0.0, 0.0
    for k in range(6000):
        u = c.step(y)
        for _ in range(10):
            v += 1e-4 * (-v - 2.0 * u + 1.0)
            y += 1e-4 * v
        if k >= 5000:
            tail = max(tail, abs(y))
    return tail


def test_a_negative_gain_plant_needs_the_negative_direction() -> None:
    assert regulate("negative") < 0.1  # eps
    wrong = regulate("positive")
    assert not wrong < 0.1


def test_the_direction_survives_every_copy() -> None:
    c = ctrl("negative", output_limits=(-2.0, 1.0))
    assert c.config()["direction"] == "negative"
    assert "direction='negative'" in repr(c)
    assert "direction" not in ctrl().config()  # the paper's default stays implicit
    for copy in (
        pickle.loads(pickle.dumps(c)),
        famcc.Controller(**c.config()),
        c.replace(k_u=4.0),
        famcc._core.ControllerSpec.from_config(c.config()).build(),
        c.spec.build(),
    ):
        ref = ctrl("negative", output_limits=(-2.0, 1.0))
        for e in np.linspace(-0.5, 0.5, 7):
            assert copy.step(float(e)) == ref.step(float(e))
        assert copy.config()["direction"] == "negative"
    assert "direction" not in c.replace(direction="positive").config()


def test_bad_directions_are_named() -> None:
    with pytest.raises(famcc.ConfigError) as info:
        ctrl("down")
    assert info.value.parameter == "direction"
    assert "'positive', 'negative'" in str(info.value)
    for b0, direction in ((-1.5, "positive"), (1.5, "negative")):
        with pytest.raises(famcc.ConfigError) as info:
            ctrl(direction, observer=famcc.Observer(0.02, b0), cancellation_limit=2.0)
        assert info.value.parameter == "b0"
        assert "direction" in str(info.value)


ZERO = famcc.Constant(0.0)


class Cooler(famcc.plants.Plant):
    """``y'' = -y' - 2 tanh(u) + 0.6``: an output that falls as the input rises
    (``G`` about -2 near 0), written as an engineer writes it."""

    def __init__(self) -> None:
        super().__init__(2, [0.4, 0.0], "cooler")

    def rhs(self, t: float, x: Any, u: float) -> Any:
        return np.array([x[1], -x[1] - 2.0 * np.tanh(u) + 0.6])


def test_design_with_a_negative_gain_regulates_the_plant() -> None:
    kw: dict[str, Any] = {
        "u_limits": (-3.0, 3.0),
        "eps": 0.02,
        "settle_time": 2.0,
        "hold_input": 0.4,
    }
    d = famcc.design(2, 1e-3, gain=-2.0, **kw)
    assert d.parameters["direction"] == "negative" and "control direction: negative" in str(d)
    assert d.controller().config()["direction"] == "negative"
    res = famcc.simulate(Cooler(), d.controller(), t_end=4.0, u_limits=(-3.0, 3.0), reference=ZERO)
    late = np.asarray(res.t) >= 2.0
    assert np.max(np.abs(np.asarray(res.z1)[late])) < 0.02
    # the same design with |G| pushes the wrong way
    wrong = famcc.simulate(
        Cooler(),
        famcc.design(2, 1e-3, gain=2.0, **kw).controller(),
        4.0,
        u_limits=(-3.0, 3.0),
        reference=ZERO,
    )
    assert not np.max(np.abs(np.asarray(wrong.z1)[late])) < 0.02
    with pytest.raises(famcc.ConfigError) as info:
        famcc.design(2, 1e-3, gain=0.0, **kw)
    assert info.value.parameter == "gain" and "negative" in str(info.value)


class Lift(famcc.plants.Plant):
    """``y'' = -y' + G(y) u + 0.6``: a gain of either sign; ``gain_and_drift`` gives
    ``(G, F)``."""

    def __init__(self, gain: Any) -> None:
        super().__init__(2, [0.4, 0.0], "lift")
        self.g = gain

    def drift(self, t: float, x: Any) -> float:
        return float(-x[1] + 0.6)

    def rhs(self, t: float, x: Any, u: float) -> Any:
        return np.array([x[1], self.drift(t, x) + self.g(x) * u])

    def gain_and_drift(self, t: float, x: Any) -> tuple[float, float]:
        return self.g(x), self.drift(t, x)


def test_tune_measures_the_control_direction() -> None:
    kw: dict[str, Any] = {"dt": 1e-3, "u_limits": (-3.0, 3.0), "eps": 0.02, "settle_time": 3.0}
    d = famcc.tune(Lift(lambda x: -2.0), reference=ZERO, progress=False, **kw)
    assert d.controller().config()["direction"] == "negative"
    res = famcc.simulate(
        Lift(lambda x: -2.0), d.controller(), 5.0, u_limits=(-3.0, 3.0), reference=ZERO
    )
    late = np.asarray(res.t) >= 3.0
    assert np.max(np.abs(np.asarray(res.z1)[late])) < 0.02
    # a gain that changes sign over the run, and one that is zero at x0, are named
    for g in (lambda x: 1.0 - 5.0 * x[0], lambda x: 0.0 * x[0]):
        with pytest.raises(famcc.ConfigError) as info:
            famcc.tune(Lift(g), reference=ZERO, progress=False, **kw)
        assert info.value.parameter == "gain"


def test_a_diverged_measuring_run_is_not_trusted() -> None:
    from types import SimpleNamespace

    from famcc.tuning.measure import check_run

    for res in (None, SimpleNamespace(diverged_at=0.731)):
        with pytest.raises(famcc.ConfigError) as info:
            check_run(res, -2.0)
        assert info.value.parameter == "gain" and "diverged" in str(info.value)
    assert "0.731" in str(info.value)
