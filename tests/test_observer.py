"""famcc.Observer in the Python API (docs/observer.md): on a plant written the way
an engineer writes one (tanh friction, a load switched on by an ``if``, a 20 % error
in the nominal gain), the observer removes the steady error that the plain
controller's holding input leaves, keeps the barrier and the output limits; its
rules are named; it survives config(), pickling, state() and banks."""

from __future__ import annotations

import pickle
from typing import Any

import famcc
import numpy as np
import pytest

GAIN = 3.0  # the plant's true input gain; b0 below is 20 % low
LOAD = -4.0


class Motor:
    """y'' = -2 tanh(5 y') - 0.5 y' + 3 u + load(t), the load switched on at 3 s."""

    order = 2
    x0 = np.array([0.0, 0.0])

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        load = LOAD if t > 3.0 else 0.0
        return np.array([x[1], -2.0 * np.tanh(5.0 * x[1]) - 0.5 * x[1] + GAIN * u + load])


def controller(limits: tuple[float, float] = (-6.0, 6.0), **kw: Any) -> famcc.Controller:
    return famcc.Controller(
        2,
        1e-3,
        famcc.FiniteTime(k=2.0, p=0.7),
        constraint="lateral",
        eps=0.05,
        k_u=4.0,
        output_limits=limits,
        **kw,
    )


def tail_error(ctrl: famcc.Controller) -> tuple[float, famcc.SimResult]:
    r = famcc.simulate(Motor(), ctrl, 6.0, reference=famcc.Constant(1.0))
    t, z1 = np.asarray(r.t), np.asarray(r.z1)
    return float(np.abs(z1[t > 5.0]).max()), r


@pytest.mark.parametrize("hold", ["exact", "foh"])
def test_the_observer_removes_the_holding_input_floor(hold: str) -> None:
    floor, plain = tail_error(controller())
    obs = famcc.Observer(0.02, 0.8 * GAIN, discretization=hold)
    ctrl = controller(observer=obs)
    tail, r = tail_error(ctrl)
    # The plain loop holds u = 4/3 through xi: |e| ~ eps tanh(1.33 / 8) ~ 8e-3.
    assert floor > 5e-3, floor
    assert tail < 1e-3 * floor, (tail, floor)
    assert r.max_abs_xi < 1.0 and plain.max_abs_xi < 1.0
    assert -6.0 <= r.u_min and r.u_max <= 6.0
    # At rest Lhat lumps the load and the gain error: L = LOAD + (G - b0) u, u = -LOAD / G.
    u_hold = -LOAD / GAIN
    assert ctrl.lumped == pytest.approx(LOAD + 0.2 * GAIN * u_hold, abs=1e-3)
    assert ctrl.diagnostics.cancellation == pytest.approx(-u_hold, abs=1e-3)
    assert ctrl.diagnostics.v == pytest.approx(u_hold, abs=1e-3)
    # Without the observer nothing is cancelled.
    assert controller().lumped == 0.0


def test_a_bounded_cancellation_leaves_the_rest_to_the_law() -> None:
    ctrl = controller(observer=famcc.Observer(0.02, GAIN), cancellation_limit=0.5)
    tail, r = tail_error(ctrl)
    assert ctrl.diagnostics.cancellation == pytest.approx(-0.5)
    assert r.max_abs_xi < 1.0 and tail < 0.05


def test_the_default_bound_is_half_the_output_range() -> None:
    ctrl = controller(observer=famcc.Observer(0.02, GAIN))
    assert ctrl.spec.build().config()["observer"] == famcc.Observer(0.02, GAIN)
    big = controller((-1.0, 3.0), observer=famcc.Observer(0.02, GAIN))
    # (3 - -1) / 2 = 2: a load needing 3 is cancelled only up to 2.
    for _ in range(3000):
        big.step(0.2)
    assert abs(big.diagnostics.cancellation) <= 2.0


def bad(**kw: Any) -> str:
    with pytest.raises(famcc.ConfigError) as info:
        controller(**kw)
    return str(info.value.parameter)


def test_bad_observers_are_named() -> None:
    with pytest.raises(famcc.ConfigError) as info:
        famcc.Observer(0.0, 1.0)
    assert info.value.parameter == "observer_mu"
    with pytest.raises(famcc.ConfigError) as info:
        famcc.Observer(0.02, 0.0)
    assert info.value.parameter == "b0"
    with pytest.raises(famcc.ConfigError) as info:
        famcc.Observer(0.02, 1.0, discretization="tustin")
    assert info.value.parameter == "observer_discretization"
    with pytest.raises(famcc.ConfigError) as info:
        famcc.Observer(0.02, 1.0, a=[1.0, -2.0, 1.0])  # not Hurwitz
    assert info.value.parameter == "observer_a"
    obs = famcc.Observer(0.02, 1.0)
    assert bad(observer=famcc.Observer(0.02, 1.0, a=[3.0, 3.0, 3.0, 1.0])) == "observer_a"
    assert bad(observer=obs, differentiator=famcc.HighGain.default(2)) == "differentiator"
    assert bad(observer=obs, cancellation_limit=0.0) == "cancellation_limit"
    assert bad(cancellation_limit=1.0) == "cancellation_limit"
    with pytest.raises(famcc.ConfigError) as info:
        famcc.Controller(
            2, 1e-3, famcc.Linear(1.0), eps=0.1, k_u=1.0, observer=obs
        )  # no output limits: the bound must be given
    assert info.value.parameter == "cancellation_limit"
    with pytest.raises(famcc.ConfigError) as info:
        famcc.Controller(
            1, 1e-3, [famcc.Linear(1.0)], eps=0.1, k_u=1.0, integral=True, observer=obs,
            cancellation_limit=1.0,
        )  # fmt: skip
    assert info.value.parameter == "integral"


def stepped(ctrl: famcc.Controller, n: int = 800) -> famcc.Controller:
    for k in range(n):
        ctrl.step(0.3 + 0.2 * np.sin(3e-3 * k))
    return ctrl


def test_config_pickle_and_state_carry_the_observer() -> None:
    obs = famcc.Observer(0.02, 2.0, discretization="foh")
    ctrl = stepped(controller(observer=obs, cancellation_limit=3.0))
    cfg = ctrl.config()
    assert cfg["observer"] == obs and cfg["cancellation_limit"] == 3.0
    assert cfg["differentiator"] is None
    assert "observer=Observer(mu=0.02, b0=2.0, discretization='foh')" in repr(ctrl)
    assert (
        pickle.loads(pickle.dumps(obs)) == obs
        and repr(obs) == "Observer(mu=0.02, b0=2.0, discretization='foh')"
    )
    twin = pickle.loads(pickle.dumps(ctrl))
    state = ctrl.state()
    lhat = famcc._core.STATE_FIELDS.index("lhat")
    assert state[lhat] == ctrl.lumped != 0.0
    for k in range(200):
        assert twin.step(0.1 * k * 1e-3) == ctrl.step(0.1 * k * 1e-3)
    # A plain controller refuses a state with an estimate of the lumped term.
    plain = controller()
    with pytest.raises(famcc.ConfigError) as info:
        plain.set_state(state)
    assert info.value.parameter in {"state.config", "state.lhat"}
    # replace() keeps or changes it.
    faster = ctrl.replace(observer=famcc.Observer(0.01, 2.0))
    assert faster.config()["observer"].mu == 0.01


def test_a_bank_steps_as_the_controllers_do() -> None:
    one = controller(observer=famcc.Observer(0.02, 2.0))
    bank = famcc.ControllerBank(one, 3)
    singles = [controller(observer=famcc.Observer(0.02, 2.0)) for _ in range(3)]
    rng = np.random.default_rng(7)
    for _ in range(300):
        e = rng.uniform(-1.0, 1.0, 3)
        out = bank.step(e)
        assert list(out) == [c.step(float(x)) for c, x in zip(singles, e, strict=True)]
