"""famcc.design, famcc.tune and famcc.tuning.assess (docs/tuning.md): the rules give
controllers that close the loop, every finding and every requirement can fail."""

from __future__ import annotations

import dataclasses
import math
import warnings

import famcc
import numpy as np
import pytest

MOTOR = {"u_limits": (-12.0, 12.0), "eps": 0.01, "settle_time": 1.5}


def _quiet_design(*args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", famcc.DesignWarning)
        return famcc.design(*args, **kwargs)


def _finding(d, name):
    return next(f for f in d.checks if f.name == name)


@pytest.mark.parametrize("order", range(1, 8))
def test_design_builds_a_controller_of_the_plant_order_at_every_order(order):
    d = _quiet_design(
        order,
        1e-3,
        u_limits=(-10, 10),
        eps=0.01,
        settle_time=10.0,
        hold_input=1.0,
        gain=2.0,
        max_error=1.0,
    )
    assert d.integral and d.law_order == order + 1
    ctrl = d.controller()
    assert ctrl.order == order
    assert math.isfinite(ctrl.step(0.1))
    # the phase-budget ratio: differentiator / loop = loop / manifold
    p = d.parameters
    if order > 1:
        assert 2.0 / p["mu"] / p["loop_rate"] == pytest.approx(p["loop_rate"] / p["lambda"])
    assert p["mu"] >= 10 * 1e-3 - 1e-15


def test_design_alone_closes_the_loop_on_a_loaded_motor_without_expansion():
    plant = famcc.plants.dc_motor(load=1.0, t_load=0.0)
    d = _quiet_design(2, 1e-3, hold_input=plant.hold_input(), gain=plant.gain, **MOTOR)
    res = famcc.simulate(
        plant,
        d.controller(),
        4.0,
        reference=famcc.Constant(1.0),
        u_limits=MOTOR["u_limits"],
        substeps=4,
    )
    a = famcc.tuning.assess(res, **MOTOR)
    assert a.ok, a.failures
    assert res.unsaturated_expansions == 0


@pytest.mark.parametrize(
    ("name", "kwargs"),
    [
        ("hold-input", {"hold_input": 20.0, "gain": 25.0}),
        ("settle-time", {"hold_input": 1.0, "gain": 25.0, "settle_time": 0.05}),
        ("accuracy", {"hold_input": 4.0, "gain": 25.0, "integral": False}),
        ("noise", {"hold_input": 1.0, "gain": 25.0, "noise_std": 10.0}),
    ],
)
def test_every_design_finding_can_fail_and_warns(name, kwargs):
    req = {**MOTOR, "settle_time": 3.0, **kwargs}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        d = famcc.design(2, 1e-3, **req)
    assert any(
        issubclass(w.category, famcc.DesignWarning) and f": {name}: " in str(w.message)
        for w in caught
    )
    f = _finding(d, name)
    assert f.level == "fail" and not d.ok
    assert str(f).startswith("[fail]")


def test_unknown_gain_warns_and_high_order_asks_for_max_error():
    with pytest.warns(famcc.DesignWarning, match="gain-unknown"):
        d = famcc.design(2, 1e-3, hold_input=1.0, **MOTOR)
    assert _finding(d, "gain-unknown").level == "warn" and not d.integral
    with pytest.warns(famcc.DesignWarning, match="estimate-limits"):
        d4 = famcc.design(
            4, 1e-3, hold_input=1.0, gain=1e3, u_limits=(-5, 5), eps=0.01, settle_time=10.0
        )
    assert _finding(d4, "estimate-limits").level == "warn"
    d4 = _quiet_design(
        4,
        1e-3,
        hold_input=1.0,
        gain=1e3,
        u_limits=(-5, 5),
        eps=0.01,
        settle_time=10.0,
        max_error=0.5,
    )
    assert _finding(d4, "estimate-limits").level == "ok"
    assert d4.controller_kwargs()["differentiator"].limits is not None


@pytest.mark.parametrize("bad", ["order", "dt", "eps", "settle_time", "u_limits", "hold_input"])
def test_design_rejects_bad_requirements_by_name(bad):
    req = {"order": 2, "dt": 1e-3, "hold_input": 1.0, **MOTOR}
    req[bad] = (1.0, -1.0) if bad == "u_limits" else (0 if bad == "order" else -1.0)
    with pytest.raises(famcc.ConfigError, match=bad):
        famcc.design(req.pop("order"), req.pop("dt"), **req)


def _motor_run(ctrl, t_end=3.0, load=0.0):
    plant = famcc.plants.dc_motor(load=load, t_load=0.0)
    return famcc.simulate(
        plant, ctrl, t_end, reference=famcc.Constant(1.0), u_limits=(-12.0, 12.0), substeps=4
    )


def test_assess_fails_a_run_that_settles_late_or_never():
    d = _quiet_design(
        2,
        1e-3,
        hold_input=0.5,
        gain=25.0,
        integral=False,
        u_limits=(-12, 12),
        eps=0.02,
        settle_time=2.0,
    )
    res = _motor_run(d.controller())
    assert famcc.tuning.assess(res, eps=0.02, settle_time=2.0, u_limits=(-12, 12)).ok
    late = famcc.tuning.assess(res, eps=0.02, settle_time=0.2, u_limits=(-12, 12))
    assert not late.ok and late.failures[0].startswith("settled at")
    assert famcc.tuning.assess(None, eps=0.02, settle_time=2.0, u_limits=(-12, 12)).failures == [
        "diverged"
    ]


def test_assess_fails_a_chattering_run_and_one_that_expands_with_headroom():
    # A hand-made stiff loop: the s-loop rate 2 k_u G / eps = 800 1/s at 1 kHz chatters.
    with warnings.catch_warnings():  # its health warning is expected
        warnings.simplefilter("ignore", famcc.DesignWarning)
        stiff = famcc.Controller(
            2, 1e-3, famcc.Linear(3.0), eps=0.5, k_u=8.0, settle_time=0.5, rho_e=1e-4
        )
        res_stiff = _motor_run(stiff)
    a = famcc.tuning.assess(res_stiff, eps=0.05, settle_time=2.9, u_limits=(-12, 12))
    assert any(f.startswith("u ripple") for f in a.failures), a
    never = famcc.tuning.assess(res_stiff, eps=1e-4, settle_time=2.9, u_limits=(-12, 12))
    assert "never settled" in never.failures and never.settling_time is None, never
    # k_u far below the 4 V hold input: the bounds open although 12 V are available.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", famcc.DesignWarning)
        weak = famcc.Controller(
            2, 1e-3, famcc.Linear(5.0), eps=0.5, k_u=0.5, settle_time=0.5, rho_e=0.05
        )
        res = _motor_run(weak, t_end=3.0, load=1.0)
        assert res.unsaturated_expansions > 0
    b = famcc.tuning.assess(res, eps=0.5, settle_time=2.9, u_limits=(-12, 12))
    assert b.expanded_unsaturated > 0 and any("headroom" in f for f in b.failures), b


def test_tune_reports_failure_when_no_candidate_can_meet_the_requirement():
    plant = famcc.plants.dc_motor(load=0.0)
    with pytest.warns(famcc.DesignWarning, match="no candidate"):
        d = famcc.tune(
            plant,
            dt=1e-3,
            u_limits=(-12, 12),
            eps=1e-3,
            settle_time=0.05,
            reference=famcc.Constant(1.0),
            progress=False,
            t_end=0.5,
        )
    f = _finding(d, "tune")
    assert f.level == "fail" and not d.ok
    assert len(d.trials) >= 15 and all(not t.feasible for t in d.trials)
    assert all(t.reason for t in d.trials)


def _hand_run(z1, u, dt=0.1):
    """A run of hand-made samples, the input inside the limits (-1, 1)."""
    z1, u = np.asarray(z1, dtype=float), np.asarray(u, dtype=float)
    t = np.round(np.arange(z1.size) * dt, 12)
    return famcc.SimResult(
        t=t, y=z1, y_d=0 * t, x=z1[:, None], z=z1[:, None], v=u, u=u, dt=dt, u_limits=(-1, 1)
    )


def test_assess_measures_a_hand_made_run():
    # |e| < 0.1 from 0.15 s on; after it u moves by 0.05 (2.5 % of the range 2)
    z1 = [1.0, 0.5, 0.2, 0.0, 0.01, -0.01, 0.0, 0.0, 0.0, 0.02, 0.0]
    u = [1.0, -1.0, 0.5, 0.05, 0.0, 0.05, 0.0, 0.05, 0.0, 0.05, 0.0]
    res = _hand_run(z1, u, dt=0.05)  # 0.5 s
    a = famcc.tuning.assess(res, eps=0.1, settle_time=0.15, u_limits=(-1, 1))
    # settled exactly at the required time: the requirement is met
    assert a.settling_time == 0.15 and a.ok, a
    assert a.steady_error == 0.02  # the largest |e| over the last fifth (t >= 0.4 s)
    assert a.ripple == pytest.approx(0.025, rel=1e-12)
    # total variation 2 + 1.5 + 0.45 + 7 * 0.05 = 4.3 in 0.5 s
    assert a.effort == pytest.approx(8.6, rel=1e-12)
    tight = famcc.tuning.assess(res, eps=0.1, settle_time=0.15, u_limits=(-1, 1), ripple_limit=0.01)
    assert tight.failures == ["u ripple 2.5 % > 1 % of the range"]
    late = famcc.tuning.assess(res, eps=0.1, settle_time=0.14, u_limits=(-1, 1))
    assert late.failures == ["settled at 0.15 s > 0.14 s"]


def test_assess_takes_the_ripple_of_a_run_that_never_settled_over_its_last_tenth():
    u = np.where(np.arange(21) < 18, 1.0, 0.0) * np.resize([1.0, -1.0], 21)  # +-1 until 1.8 s
    u[18:] = [0.1, -0.1, 0.1]  # the last 10 % (t >= 1.8 s of 2 s): peak-to-peak 0.2
    a = famcc.tuning.assess(_hand_run(np.ones(21), u), eps=0.1, settle_time=1.0, u_limits=(-1, 1))
    assert a.settling_time is None and "never settled" in a.failures
    assert a.ripple == pytest.approx(0.1, rel=1e-12)  # 0.2 of the range 2


def test_assessment_text_gives_the_percentages():
    a = famcc.tuning.Assessment(
        settling_time=0.5,
        steady_error=0.012,
        expanded_unsaturated=0.25,
        ripple=0.02,
        effort=3.0,
        saturated=0.1,
    )
    assert str(a) == (
        "settling time 0.500 s, steady max |e| 0.012, expanded with headroom 25 %, u ripple "
        "2 % of the range, saturated 10 %: requirement met"
    )
    b = famcc.tuning.Assessment(None, 0.5, 0.0, 0.0, 0.0, 0.0, ["never settled", "x"])
    assert str(b).startswith("settling time never,")
    assert str(b).endswith("saturated 0 %: requirement NOT met: never settled; x")


def test_ripple_is_steady_oscillation_not_convergence() -> None:
    # settled from 1 s of 10 s; u converges smoothly by 60 % of the range after settling,
    # and answers a load step at 5 s: neither is ripple
    t = np.round(np.arange(1001) * 0.01, 12)
    z1 = np.where(t < 1.0, 1.0, 0.01)
    smooth = 0.6 * np.exp(-(t - 1.0) / 3.0) * (t >= 1.0) + 0.3 * (t >= 5.0)
    a = famcc.tuning.assess(
        _hand_run(z1, smooth, dt=0.01), eps=0.1, settle_time=2.0, u_limits=(-1, 1)
    )
    assert a.ok and a.ripple < 0.01, a
    # a limit cycle of 0.1 in the last fifth is ripple: peak-to-peak 0.2 of the range 2
    cycle = 0.3 + 0.1 * np.sign(np.sin(2 * np.pi * 7.3 * t))
    b = famcc.tuning.assess(
        _hand_run(z1, cycle, dt=0.01), eps=0.1, settle_time=2.0, u_limits=(-1, 1)
    )
    assert b.ripple == pytest.approx(0.1, rel=0.05)
    assert b.failures == [f"u ripple {100 * b.ripple:.3g} % > 5 % of the range"]
    # the trend is removed, the oscillation about it is not: a ramp plus the cycle
    ramp = cycle + 0.05 * t
    c = famcc.tuning.assess(
        _hand_run(z1, ramp, dt=0.01), eps=0.1, settle_time=2.0, u_limits=(-1, 1)
    )
    assert c.ripple == pytest.approx(b.ripple, rel=0.05)


def test_assess_counts_expansions_with_headroom_after_settling_or_over_the_last_tenth() -> None:
    def run(z1: list[float], expanded: list[bool]) -> famcc.SimResult:
        res = _hand_run(z1, np.zeros(len(z1)))
        return dataclasses.replace(res, expanded=np.array(expanded))

    # settled from 1.0 s of 1.9 s: 10 samples after, 3 of them expanded with headroom
    z1 = [1.0] * 10 + [0.0] * 10
    a = famcc.tuning.assess(
        run(z1, [True] * 10 + [False, True] * 3 + [False] * 4),
        eps=0.1,
        settle_time=1.5,
        u_limits=(-1, 1),
    )
    assert a.expanded_unsaturated == pytest.approx(0.3)
    assert a.failures == ["bounds expanded with headroom 30 % of the time"]
    # never settled (2 s): only the last tenth counts, where it never expanded
    never = famcc.tuning.assess(
        run([1.0] * 21, [True] * 18 + [False] * 3), eps=0.1, settle_time=1.5, u_limits=(-1, 1)
    )
    assert never.expanded_unsaturated == 0.0
    assert not any("headroom" in f for f in never.failures)
