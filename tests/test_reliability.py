"""Issue 15 in Python: set_state checks every slot and the configuration,
every pickle protocol, numbers that are not bools, argument names in type
errors, Python's negative bank indices, and banks that hold non-finite lanes."""

from __future__ import annotations

import copy
import pickle

import famcc
import numpy as np
import pytest

FIELDS = famcc._core.STATE_FIELDS


def example1(**kw: object) -> famcc.Controller:
    args: dict[str, object] = {"constraint": "lateral", "eps": 0.1, "k_u": 5.0}
    args.update(kw)
    return famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5), **args)  # type: ignore[arg-type]


def test_state_layout_names_period_and_config() -> None:
    assert FIELDS == (
        "started",
        "t_base",
        "k",
        "rho0_x",
        "rho0_y",
        "clamp_count",
        "last_v",
        "period",
        "config",
        "filtered",
        "lhat",
    )
    ctrl = example1()
    ctrl.step(0.1)
    s = ctrl.state()
    assert s[FIELDS.index("period")] == 1e-3
    # without a prefilter the differentiator's last input is the sample itself
    assert s[FIELDS.index("filtered")] == 0.1
    assert s.shape == (len(FIELDS) + 2,)


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("started", np.nan),
        ("started", np.inf),
        ("started", -1.0),
        ("started", 2.0**60),
        ("k", -1.0),
        ("k", 0.5),
        ("k", 2.0**60),
        ("t_base", np.nan),
        ("clamp_count", -1.0),
        ("rho0_x", 0.0),
        ("last_v", np.inf),
        ("period", 0.0),
        ("config", 1.0),
        ("filtered", np.inf),
        ("filtered", np.nan),
        ("lhat", 0.5),  # a plain controller has no observer: Lhat must be 0
        ("lhat", np.nan),
    ],
)
def test_set_state_checks_every_slot(field: str, value: float) -> None:
    ctrl = example1()
    ctrl.step(0.1)
    before = ctrl.state()
    bad = before.copy()
    bad[FIELDS.index(field)] = value
    with pytest.raises(famcc.ConfigError, match="state"):
        ctrl.set_state(bad)
    assert np.array_equal(ctrl.state(), before)


def test_set_state_rejects_another_configuration() -> None:
    a, b = example1(), example1(k_u=6.0)
    a.step(0.1)
    with pytest.raises(famcc.ConfigError, match="another configuration"):
        b.set_state(a.state())
    twin = example1()
    twin.set_state(a.state())
    assert twin.step(0.2) == a.step(0.2)


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_every_pickle_protocol(protocol: int) -> None:
    ctrl = famcc.Controller(
        3,
        1e-3,
        famcc.FixedTime(alpha=1.0, p=0.5, beta=0.5, q=2.0),
        skew=famcc.Nonsingular(eps_s=0.1, eps_z=0.1, k_pp=0.1),
        eps=3.0,
        k_u=30.0,
        differentiator=famcc.HighGain(0.01, [4.0, 6.0, 4.0]),
    )
    for e in (0.3, 0.2, 0.1):
        ctrl.step(e)
    other = pickle.loads(pickle.dumps(ctrl, protocol=protocol))
    assert np.array_equal(other.state(), ctrl.state())
    assert other.step(0.05) == ctrl.step(0.05)
    for obj in (
        famcc.FiniteTime(k=1.0, p=0.5),
        famcc.Smooth(eps_s=0.1, eps_z=0.1),
        famcc.HighGain(0.01, [4.0, 4.0]),
    ):
        assert pickle.loads(pickle.dumps(obj, protocol=protocol)) == obj


@pytest.mark.parametrize(
    ("make", "name"),
    [
        (lambda: famcc.Controller(True, 1e-3, eps=0.1, k_u=5.0), "order"),
        (lambda: famcc.Controller(1, True, eps=0.1, k_u=5.0), "dt"),
        (lambda: famcc.Controller(1, 1e-3, eps=0.1, k_u=False), "k_u"),
        (lambda: famcc.Controller(1, 1e-3, eps=0.1, k_u=5.0, settle_time=True), "settle_time"),
        (lambda: famcc.Controller(1, "fast", eps=0.1, k_u=5.0), "dt"),
        (lambda: famcc.Controller(1, 1e-3, eps=0.1, k_u=5.0, constraint=3), "constraint"),
        (lambda: famcc.FiniteTime(k=True, p=0.5), "k"),
        (lambda: famcc.FiniteTime(k="1", p=0.5), "k"),
        (lambda: famcc.Smooth(eps_s=0.1, eps_z=True), "eps_z"),
        (lambda: famcc.HighGain(True, [4.0, 4.0]), "mu"),
        (lambda: famcc.ControllerBank(example1(), True), "n"),
    ],
)
def test_type_errors_name_the_argument_and_bools_are_no_numbers(make, name: str) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(TypeError) as info:
        make()
    assert str(info.value).startswith(f"argument '{name}': must be"), str(info.value)


def test_bank_indices_like_pythons() -> None:
    ctrl = example1()
    bank = famcc.ControllerBank(ctrl, 3)
    bank.step(np.array([0.1, 0.2, 0.3]))
    last = bank.controller(-1)
    assert np.array_equal(last.state(), bank.controller(2).state())
    assert np.array_equal(bank.controller(-3).state(), bank.controller(0).state())
    for i in (3, -4):
        with pytest.raises(IndexError, match=f"index {i} out of range for 3"):
            bank.controller(i)


def test_bank_holds_non_finite_lanes() -> None:
    ctrl = example1()
    bank = famcc.ControllerBank(ctrl, 4)
    twins = [copy.copy(ctrl) for _ in range(4)]
    e0 = np.array([0.1, 0.2, 0.3, 0.4])
    v0 = bank.step(e0)
    for t, e in zip(twins, e0, strict=True):
        t.step(float(e))
    with pytest.raises(famcc.StepError, match="hold"):
        bank.step(np.array([0.1, np.nan, 0.1, 0.1]))
    held_state = [bank.controller(i).state() for i in range(4)]
    e1 = np.array([0.15, np.nan, 0.25, np.inf])
    v1 = bank.step(e1, on_nonfinite="hold")
    assert bank.held == (1, 3)
    assert v1[1] == v0[1] and v1[3] == v0[3]
    assert np.array_equal(bank.controller(1).state(), held_state[1])
    assert v1[0] == twins[0].step(0.15) and v1[2] == twins[2].step(0.25)
    bank.step(e0)
    assert bank.held == ()
    with pytest.raises(famcc.ConfigError, match="on_nonfinite"):
        bank.step(e0, on_nonfinite="skip")


def test_one_outlier_costs_one_sample() -> None:
    for dtype, outlier in (("float64", 1e300), ("float32", 3.4e38)):
        ctrl = example1(dtype=dtype)
        errors = 0
        for k in range(2000):
            try:
                ctrl.step(
                    1e300 if dtype == "float64" and k == 1000 else (outlier if k == 1000 else 0.01)
                )
            except famcc.StepError:
                errors += 1
        assert errors == 1, dtype


def test_the_clock_is_exact_in_float32() -> None:
    ctrl = example1(dtype="float32")
    ctrl.step(0.1)
    s = ctrl.state()
    s[FIELDS.index("k")] = 10**8  # t = 1e5 s
    ctrl.set_state(s)
    dt = float(np.float32(1e-3))
    for j in range(100):
        assert ctrl.time == (10**8 + j) * dt
        ctrl.step(0.01)
        assert ctrl.diagnostics.t == (10**8 + j) * dt
