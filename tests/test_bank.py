"""famcc.ControllerBank: n copies stepped together equal n copies stepped alone."""

from __future__ import annotations

import copy
import threading

import famcc
import numpy as np
import pytest


def _designs():
    return {
        "finite-time": famcc.scenarios.paper("finite-time").controller(),
        "variable-exponent": famcc.scenarios.paper("variable-exponent").controller(),
        "rfc": famcc.scenarios.paper("rfc").controller(),
        "rfc-f32": famcc.scenarios.paper("rfc").controller(dtype="float32"),
    }


def _errors(steps: int, n: int, order: int, seed: int = 0) -> np.ndarray:
    """Error samples of n different runs: smooth decays with noise."""
    rng = np.random.default_rng(seed + order)
    t = np.arange(steps)[:, None] * 1e-3
    amp = rng.uniform(-2.0, 2.0, size=n)
    return amp * np.exp(-2.0 * t) * np.cos(5.0 * t) + 1e-3 * rng.standard_normal((steps, n))


def _states(ctrls) -> np.ndarray:
    return np.array([c.state() for c in ctrls])


@pytest.mark.parametrize("name", list(_designs()))
def test_bank_equals_copies_stepped_one_by_one(name):
    ctrl = _designs()[name]
    n, steps = 25, 200
    bank = famcc.ControllerBank(ctrl, n)
    copies = [copy.copy(ctrl) for _ in range(n)]
    assert len(bank) == n
    for e in _errors(steps, n, ctrl.order):
        out = bank.step(e)
        ref = np.array([c.step(float(x)) for c, x in zip(copies, e)])
        assert out.dtype == np.float64 and out.shape == (n,)
        assert np.array_equal(out, ref)  # exact, sample by sample
        assert np.array_equal(bank.xi, [c.diagnostics.xi for c in copies])
    for i in (0, n // 2, n - 1):
        assert np.array_equal(bank.controller(i).state(), copies[i].state())
    # The template controller was copied, not shared.
    assert ctrl.time == 0.0


@pytest.mark.parametrize("name", ["finite-time", "rfc", "rfc-f32"])
def test_bank_nominal_xi_and_expansion_equal_the_copies_diagnostics(name):
    ctrl = _designs()[name]
    n = 12
    bank = famcc.ControllerBank(ctrl, n)
    copies = [copy.copy(ctrl) for _ in range(n)]
    expanded_seen = False
    # Errors large enough to push some controllers out of their nominal set.
    for e in 40.0 * _errors(150, n, ctrl.order, seed=3):
        bank.step(e)
        for c, x in zip(copies, e):
            c.step(float(x))
        xi_nom, fac = bank.xi_nominal, bank.expansion
        assert xi_nom.dtype == np.float64 and xi_nom.shape == (n,) and fac.shape == (n,)
        assert np.array_equal(xi_nom, [c.diagnostics.xi_nominal for c in copies])
        assert np.array_equal(fac, [c.diagnostics.expansion for c in copies])
        assert np.array_equal(fac > 1.0, [c.diagnostics.expanded for c in copies])
        expanded_seen |= bool(np.any(fac > 1.0))
    assert expanded_seen  # the factor was really exercised above 1


def test_bank_copies_a_stepped_controller_and_continues_it():
    ctrl = famcc.scenarios.paper("rfc").controller()
    for e in (0.9, 0.8, 0.7):
        ctrl.step(e)
    bank = famcc.ControllerBank(ctrl, 3)
    out = bank.step(np.full(3, 0.6))
    assert np.array_equal(out, np.full(3, copy.copy(ctrl).step(0.6)))


def test_bank_controller_is_a_working_independent_copy():
    ctrl = famcc.scenarios.paper("finite-time").controller()
    bank = famcc.ControllerBank(ctrl, 4)
    bank.step(np.array([-1.0, -0.5, 0.5, 1.0]))
    c2 = bank.controller(2)
    assert isinstance(c2, famcc.Controller)
    twin = copy.copy(ctrl)
    twin.step(0.5)
    assert np.array_equal(c2.state(), twin.state())
    assert c2.step(0.4) == twin.step(0.4)
    # Stepping the extracted copy does not move the bank.
    assert bank.controller(2).time == pytest.approx(1e-3)
    with pytest.raises(IndexError, match="out of range"):
        bank.controller(4)


def test_reset_restores_every_controller():
    ctrl = famcc.scenarios.paper("finite-time").controller()
    bank = famcc.ControllerBank(ctrl, 5)
    first = bank.step(np.linspace(-1.0, 1.0, 5))
    bank.step(np.zeros(5))
    bank.reset()
    assert np.array_equal(bank.step(np.linspace(-1.0, 1.0, 5)), first)


@pytest.mark.parametrize(
    "bad",
    [
        np.array([0.1, np.nan, 0.2, 0.3]),
        np.array([0.1, 0.2, 0.3, np.inf]),
        np.array([-np.inf, 0.2, 0.3, 0.4]),
    ],
)
def test_non_finite_entry_raises_and_moves_no_controller(bad):
    ctrl = famcc.scenarios.paper("rfc").controller()
    bank = famcc.ControllerBank(ctrl, 4)
    bank.step(np.full(4, 0.5))
    before = _states(bank.controller(i) for i in range(4))
    with pytest.raises(famcc.StepError, match="not finite; no controller was stepped"):
        bank.step(bad)
    assert np.array_equal(_states(bank.controller(i) for i in range(4)), before)
    # Still usable, and still equal to the copies.
    twin = copy.copy(ctrl)
    twin.step(0.5)
    assert np.array_equal(bank.step(np.full(4, 0.25)), np.full(4, twin.step(0.25)))


@pytest.mark.parametrize("length", [0, 3, 5])
def test_wrong_length_raises_and_moves_no_controller(length):
    ctrl = famcc.scenarios.paper("finite-time").controller()
    bank = famcc.ControllerBank(ctrl, 4)
    bank.step(np.full(4, -0.5))
    before = _states(bank.controller(i) for i in range(4))
    with pytest.raises(famcc.StepError, match=f"length 4 .*got {length}"):
        bank.step(np.zeros(length))
    assert np.array_equal(_states(bank.controller(i) for i in range(4)), before)
    twin = copy.copy(ctrl)
    twin.step(-0.5)
    assert np.array_equal(bank.step(np.full(4, -0.4)), np.full(4, twin.step(-0.4)))


@pytest.mark.parametrize(
    "bad",
    [
        np.zeros(4, dtype=np.int64),  # rejected, not converted: the message names float64
        np.zeros(4, dtype=np.float32),
        np.zeros((2, 2)),
        [0.0, 0.0, 0.0, 0.0],
    ],
)
def test_wrong_type_raises_type_error_and_moves_no_controller(bad):
    ctrl = famcc.scenarios.paper("finite-time").controller()
    bank = famcc.ControllerBank(ctrl, 4)
    bank.step(np.full(4, 0.3))
    before = _states(bank.controller(i) for i in range(4))
    with pytest.raises(TypeError, match="float64|ndarray|dimensionality"):
        bank.step(bad)
    assert np.array_equal(_states(bank.controller(i) for i in range(4)), before)


def test_non_contiguous_array_is_rejected_clearly():
    bank = famcc.ControllerBank(famcc.scenarios.paper("finite-time").controller(), 4)
    with pytest.raises(famcc.StepError, match="contiguous float64"):
        bank.step(np.zeros(8)[::2])
    assert bank.controller(0).time == 0.0
    # The documented fix works.
    bank.step(np.ascontiguousarray(np.zeros(8)[::2]))
    assert bank.controller(0).time == pytest.approx(1e-3)


def test_bad_bank_size():
    ctrl = famcc.scenarios.paper("finite-time").controller()
    with pytest.raises(famcc.ConfigError, match="n must be >= 1"):
        famcc.ControllerBank(ctrl, 0)
    with pytest.raises((OverflowError, ValueError)):
        famcc.ControllerBank(ctrl, -1)
    with pytest.raises(TypeError):
        famcc.ControllerBank("not a controller", 3)  # type: ignore[arg-type]
    assert "n=3" in repr(famcc.ControllerBank(ctrl, 3))


@pytest.mark.parametrize("order", [2, 3])
def test_large_bank_gil_released_path(order):
    """n = 10^5 (above the size that releases the GIL): exact, and fast enough."""
    name = "finite-time" if order == 2 else "rfc"
    ctrl = famcc.scenarios.paper(name).controller()
    n, steps = 100_000, 3
    bank = famcc.ControllerBank(ctrl, n)
    copies = [copy.copy(ctrl) for _ in range(n)]
    for e in _errors(steps, n, order, seed=7):
        out = bank.step(e)
        ref = np.fromiter((c.step(x) for c, x in zip(copies, e.tolist())), float, count=n)
        assert np.array_equal(out, ref)
    assert np.all(np.abs(bank.xi) < 1.0)


def test_banks_step_concurrently_from_threads():
    """Two large banks stepped from two threads (GIL released) give the serial result."""
    ctrl = famcc.scenarios.paper("rfc").controller()
    n, steps = 20_000, 5
    errs = [_errors(steps, n, 3, seed=s) for s in (1, 2)]
    serial = []
    for ev in errs:
        b = famcc.ControllerBank(ctrl, n)
        serial.append([b.step(e) for e in ev])
    results: dict[int, list[np.ndarray]] = {}

    def work(i: int) -> None:
        b = famcc.ControllerBank(ctrl, n)
        results[i] = [b.step(e) for e in errs[i]]

    threads = [threading.Thread(target=work, args=(i,)) for i in (0, 1)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for i in (0, 1):
        for a, b in zip(results[i], serial[i]):
            assert np.array_equal(a, b)


def test_overflow_consumes_the_sample_and_holds_the_previous_output():
    ctrl = famcc.scenarios.paper("rfc").controller()
    bank = famcc.ControllerBank(ctrl, 2)
    bank.step(np.array([0.1, 0.1]))
    held = bank.step(np.array([1e80, 0.1]))  # a finite outlier: accepted
    assert bank.overflows == 0
    out = bank.step(np.array([0.1, 0.1]))  # the law overflows on the huge estimate
    assert bank.overflows == 1
    assert np.isfinite(out).all()
    assert out[0] == held[0]  # controller 0 repeats its previous output
    # it recovers as the estimate decays
    for _ in range(3000):
        bank.step(np.array([0.1, 0.1]))
    assert bank.overflows == 0
