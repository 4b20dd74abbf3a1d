"""The options of issue 13 in the Python API: integral action, output and rate
limits, bumpless start, step_output, lint warnings, the health warning, the
unstable differentiator's ConfigError and the auto differentiator at high order."""

from __future__ import annotations

import copy
import math
import pickle
import warnings

import famcc
import numpy as np
import pytest

DT = 1e-3


def _loaded_double_integrator(ctrl: famcc.Controller, load: float, t_end: float) -> float:
    """Regulates x'' = u - load to 0 from x = 0.5; returns the last second's max |e|."""
    x, v, tail, u = 0.5, 0.0, 0.0, None
    steps = int(t_end / DT)
    for k in range(steps):
        u = ctrl.step_output(x, 0.0, applied=u)
        if k > steps - 1000:
            tail = max(tail, abs(x))
        v += DT * (u - load)
        x += DT * v
    return tail


def _pd(order: int = 2, **kw: object) -> famcc.Controller:
    n_laws = order if kw.get("integral") else order - 1
    return famcc.Controller(
        order, DT, [famcc.Linear(2.0)] * n_laws, eps=2.0, k_u=4.0, **kw  # type: ignore[arg-type]
    )


def test_integral_action_removes_the_steady_error():
    without = _loaded_double_integrator(_pd(), 1.0, 20.0)
    ctrl = _pd(integral=True)
    with_i = _loaded_double_integrator(ctrl, 1.0, 20.0)
    assert without > 1e-2 and with_i < 1e-4
    d = ctrl.diagnostics
    assert ctrl.integral and d.integral is not None and abs(d.v - 1.0) < 1e-2


def test_integral_kwargs_and_round_trips():
    ctrl = _pd(integral=True, output_limits=(-3.0, 3.0), rate_limit=100.0, initial_output=0.5)
    kw = ctrl.config()
    assert kw["integral"] is True and kw["output_limits"] == (-3.0, 3.0)
    assert kw["rate_limit"] == 100.0 and kw["initial_output"] == 0.5
    assert len(kw["feedback"]) == 2 and kw["differentiator"].a == (4.0, 4.0)
    again = famcc.Controller(kw.pop("order"), kw.pop("dt"), **kw)
    assert repr(again) == repr(ctrl)
    for k in range(200):
        ctrl.step(0.3 * math.sin(0.02 * k) - 0.2)
    assert ctrl.diagnostics.integral != 0.0
    fresh = _pd(integral=True, output_limits=(-3.0, 3.0), rate_limit=100.0, initial_output=0.5)
    fresh.set_state(ctrl.state())
    copies = [pickle.loads(pickle.dumps(ctrl)), copy.deepcopy(ctrl), fresh]
    for other in copies:
        assert np.array_equal(other.state(), ctrl.state())
    inputs = [0.1 * math.cos(0.3 * k) for k in range(50)]
    expected = [ctrl.step(e) for e in inputs]
    for other in copies:
        assert [other.step(e) for e in inputs] == expected  # bit for bit, I included
    # The paper's configurations keep their keyword arguments.
    assert "integral" not in _pd().config()


def test_integral_rules():
    with pytest.raises(famcc.ConfigError, match="feedback must have order"):
        famcc.Controller(2, DT, [famcc.Linear(1.0)], eps=1.0, k_u=1.0, integral=True)
    with pytest.raises(famcc.ConfigError, match="integral=True needs order <= 7"):
        famcc.Controller(8, DT, famcc.Linear(1.0), eps=1.0, k_u=1.0, integral=True)
    # Order 1 with integral action needs no differentiator: Z = (I, e).
    c = famcc.Controller(1, DT, famcc.Linear(1.0), eps=1.0, k_u=1.0, integral=True)
    assert c.config()["differentiator"] is None and math.isfinite(c.step(0.5))
    # step_state takes the plant's vector; the integral is the controller's.
    c = _pd(integral=True)
    assert math.isfinite(c.step_state([0.1, 0.0]))
    with pytest.raises(famcc.StepError, match="2 entries"):
        c.step_state([0.0, 0.1, 0.0])


def test_output_and_rate_limits():
    ctrl = _pd(output_limits=(-1.0, 2.0), rate_limit=50.0, initial_output=0.0)
    prev = 0.0
    for k in range(1000):
        u = ctrl.step(3.0 * math.sin(0.01 * k))
        assert -1.0 <= u <= 2.0 and abs(u - prev) <= 50.0 * DT * (1 + 1e-12)
        assert ctrl.diagnostics.v == u
        prev = u
    # Saturated at the end: the law asks for more than the limit.
    d = ctrl.diagnostics
    assert d.v in (-1.0, 2.0) or abs(d.v_unlimited - d.v) < 1e-12


def test_bumpless_start():
    for u0 in (-2.0, 0.3, 1.7):
        c = _pd(integral=True, initial_output=u0)
        assert c.step(0.05) == pytest.approx(u0, abs=1e-6)


def test_step_output_is_step_of_y_minus_y_d():
    a, b = _pd(), _pd()
    for k in range(100):
        y = math.cos(0.03 * k)
        assert a.step_output(y, 0.2) == b.step(y - 0.2)
    bank = famcc.ControllerBank(_pd(), 3)
    twin = famcc.ControllerBank(_pd(), 3)
    y, yd = np.array([0.1, 0.2, 0.3]), np.array([0.0, 0.5, -0.5])
    assert np.array_equal(bank.step_output(y, yd), twin.step(y - yd))
    with pytest.raises(famcc.StepError, match="same length"):
        bank.step_output(y, yd[:2])


def test_lint_findings_warn_at_construction():
    with pytest.warns(famcc.DesignWarning, match=r"rho_e: .*rule: rho_e <= 0.1 eps.*suggested rho_e"):
        c = famcc.Controller(2, DT, famcc.Linear(1.0), eps=1.0, k_u=1.0, rho_e=0.5)
    assert len(c.lint()) == 1
    with pytest.warns(famcc.DesignWarning, match=r"dt / mu <= 0.2"):
        famcc.Controller(2, 5e-3, famcc.Linear(1.0), eps=1.0, k_u=1.0)
    with pytest.warns(famcc.DesignWarning, match="discretization: .*suggested discretization = tustin"):
        famcc.Controller(
            4,
            DT,
            famcc.Linear(1.0),
            eps=1.0,
            k_u=1.0,
            differentiator=famcc.HighGain(0.01, [8, 24, 32, 16], limits=[10, 1e2, 1e3, 1e4]),
        )
    with pytest.warns(famcc.DesignWarning, match="stage 2: k: .*chatters"):
        famcc.Controller(
            3, DT, [famcc.Linear(1.0), famcc.FiniteTime(20.0, 0.5)], eps=0.01, k_u=5.0
        )


def test_the_papers_scenarios_construct_without_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for name in ("finite-time", "variable-exponent", "rfc"):
            assert famcc.scenarios.paper(name).controller(dt=DT).lint() == []


def test_unstable_differentiator_is_a_config_error():
    with pytest.raises(famcc.ConfigError, match="spectral radius"):
        famcc.Controller(
            2,
            0.05,
            famcc.Linear(1.0),
            eps=0.1,
            k_u=5.0,
            differentiator=famcc.HighGain(0.01, [4.0, 4.0], "euler"),
        )


def test_health_warning_once_with_the_cure():
    ctrl = famcc.Controller(
        2,
        DT,
        famcc.Linear(2.0),
        eps=2.0,
        k_u=0.3,
        rho_e=0.1,
        settle_time=0.2,
        output_limits=(-100.0, 100.0),
    )
    with pytest.warns(famcc.DesignWarning, match=r"k_u too small for this plant: .*raise k_u to"):
        _loaded_double_integrator(ctrl, 2.0, 3.0)
    n = ctrl.diagnostics.unsaturated_expansions
    assert n > 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # once per controller
        _loaded_double_integrator(ctrl, 2.0, 1.0)
    assert ctrl.diagnostics.unsaturated_expansions > n


def test_simresult_reports_the_health_count():
    # x'' = u - 2: a load the small k_u cannot hold with the bounds nominal.
    plant = famcc.plants.StrictFeedback(
        g=[lambda x, t: 1.0, lambda x, t: 1.0],
        f=[lambda x, t: 0.0, lambda x, t: -2.0],
        x0=[0.5, 0.0],
    )
    ctrl = famcc.Controller(
        2, DT, famcc.Linear(2.0), eps=2.0, k_u=0.3, rho_e=0.1, settle_time=0.2
    )
    with pytest.warns(famcc.DesignWarning, match="k_u too small"):
        res = famcc.simulate(plant, ctrl, 3.0, reference=famcc.Constant(0.0))
    assert res.unsaturated_expansions >= 100
    assert res.unsaturated_expansions is not None and res.unsaturated_expansions > 0


@pytest.mark.parametrize("order", [4, 5, 6])
def test_auto_differentiator_at_high_order(order):
    with pytest.warns(famcc.DesignWarning, match="estimate_limits"):
        c = famcc.Controller(order, DT, famcc.Linear(1.0), eps=1.0, k_u=2.0)
    h = c.config()["differentiator"]
    assert (h.mu, h.discretization) == (0.01, "tustin")
