"""Every verdict famcc prints can fail: a bad run per claim, and the metrics behind them.

The claims are those of :mod:`famcc.verdicts` (docs/design.md §8). Each test
builds a run that breaks one claim -- on the paper's own scenarios with one
setting made bad (a too slow or unstable differentiator, a too weak gain, a
too loose accuracy) -- and asserts that the claim fails; synthetic runs pin
the boundaries between held, failed and untested exactly.
"""

from __future__ import annotations

import famcc
import numpy as np
import pytest
from famcc import scenarios, verdicts

# This module runs bad configurations on purpose, to see the verdicts fail:
# their DesignWarnings (lint, health) are expected.
pytestmark = pytest.mark.filterwarnings("ignore::famcc.DesignWarning")

H = famcc.HighGain


def _by_name(found: list[verdicts.Verdict]) -> dict[str, verdicts.Verdict]:
    return {v.name: v for v in found}


def _run(name: str, **kw):
    sc = scenarios.paper(name)
    res = sc.run(**kw)
    return sc, res, _by_name(sc.verdicts(res))


# -- synthetic runs: exact boundaries -----------------------------------------------


def _result(z1, v=None, limits=None, expanded=None, dt=0.01):
    z1 = np.asarray(z1, dtype=float)
    t = np.arange(z1.size) * dt
    v = np.zeros_like(z1) if v is None else np.asarray(v, dtype=float)
    r = famcc.SimResult(
        t=t,
        y=z1,
        y_d=0 * t,
        x=z1[:, None],
        z=z1[:, None],
        v=v,
        u=v if limits is None else np.clip(v, *limits),
        dt=dt,
        u_limits=limits,
    )
    if expanded is not None:
        r.expanded = np.asarray(expanded, dtype=bool)
        r.expansion = np.where(r.expanded, 2.0, 1.0)
        r.xi_nominal = np.where(r.expanded, 1.5, 0.5)
    return r


def test_settling_held_failed_untested_at_the_bound():
    z1 = np.where(np.arange(501) * 0.01 < 2.0, 1.0, 0.0)  # settles at 2.00 s
    r = _result(z1)
    held = verdicts.settling(r, 0.1, 1.0, 1.0)
    assert held.status == "held"  # bound 2.0 s
    # never saturated: T_e = 0 in the stated bound
    assert "max(T_e, T_s) + T' = max(0, 1) + 1 = 2 s" in held.claim
    assert verdicts.settling(r, 0.1, 1.0, 0.99).status == "failed"  # bound 1.99 s
    assert verdicts.settling(r, 0.1, 1.0, 4.01).status == "untested"  # bound 5.01 s > 5 s
    never = _result(np.ones(501))
    v = verdicts.settling(never, 0.1, 1.0, 1.0)
    assert v.status == "failed" and "never" in v.detail


def test_settling_bound_counts_saturation_that_ends_after_the_preset_time():
    t = np.arange(501) * 0.01
    z1 = np.where(t < 2.5, 1.0, 0.0)
    v = np.where((t >= 1.5) & (t < 2.0), 10.0, 0.0)  # saturated until T_e = 2 s
    r = _result(z1, v=v, limits=(-1.0, 1.0))
    assert verdicts.settling(r, 0.1, 1.0, 0.5).status == "held"  # bound max(2, 1) + 0.5
    assert verdicts.settling(r, 0.1, 1.0, 0.4).status == "failed"


def test_unsaturated_and_nominal_ignore_the_startup_only():
    n = 101
    v = np.zeros(n)
    v[:10] = 50.0  # 0-0.09 s: start-up
    exp = np.zeros(n, dtype=bool)
    exp[:10] = True
    r = _result(np.zeros(n), v=v, limits=(-1.0, 1.0), expanded=exp)
    assert verdicts.unsaturated(r, 0.1).status == "held"
    assert verdicts.nominal(r, 0.1).status == "held"
    v[60] = 50.0
    exp[60] = True
    r = _result(np.zeros(n), v=v, limits=(-1.0, 1.0), expanded=exp)
    assert verdicts.unsaturated(r, 0.1).status == "failed"
    assert verdicts.nominal(r, 0.1).status == "failed"
    assert "0.600 s" in verdicts.nominal(r, 0.1).detail


def test_recovery_windows_due_and_not_due():
    t = np.arange(1001) * 0.01  # 10 s
    v = np.where(((t >= 1.0) & (t < 2.0)) | ((t >= 3.0) & (t < 3.5)), 9.0, 0.0)
    z1 = np.where(t < 2.2, 1.0, 0.0)
    r = _result(z1, v=v, limits=(-1.0, 1.0))
    # T' = 0.5: episode 1 ends 2.0, due 2.5 < next start 3.0 (due); episode 2 ends 3.5, due 4.0.
    w = verdicts.recovery_windows(r, 1.0, 0.5)
    assert [round(x, 6) for x in w[0]] == [2.0, 2.5, 3.0]
    assert verdicts.recovery(r, 0.1, 1.0, 0.5).status == "held"
    # T' = 1.5: episode 1 due 3.5 > 3.0 (pre-empted); episode 2 due 5.0: still due, and held.
    v2 = verdicts.recovery(r, 0.1, 1.0, 1.5)
    assert v2.status == "held" and "1 not due" in v2.detail
    # T' = 7: no window falls due in 10 s.
    assert verdicts.recovery(r, 0.1, 1.0, 7.0).status == "untested"
    # The error leaves the band in a due window: fails.
    z1b = z1.copy()
    z1b[(t > 4.2) & (t < 4.3)] = 0.5
    assert verdicts.recovery(_result(z1b, v=v, limits=(-1.0, 1.0)), 0.1, 1.0, 0.5).failed


def test_nominal_again_fails_when_bounds_stay_expanded_with_headroom():
    t = np.arange(1001) * 0.01
    v = np.where(t < 1.0, 9.0, 0.0)
    exp = t < 1.0
    r = _result(np.zeros(t.size), v=v, limits=(-1.0, 1.0), expanded=exp)
    assert verdicts.nominal_again(r, 1.0, 1.0).status == "held"
    r = _result(np.zeros(t.size), v=v, limits=(-1.0, 1.0), expanded=t < 6.0)
    assert verdicts.nominal_again(r, 1.0, 1.0).failed


def test_a_run_saturated_to_the_end_has_no_due_window():
    r = _result(np.ones(301), v=np.full(301, 5.0), limits=(-1.0, 1.0))
    assert verdicts.recovery(r, 0.1, 1.0, 0.5).status == "untested"
    v = verdicts.settles(r, 0.1, within=10.0)
    assert v.failed and "saturated 100 %" in v.detail


def test_verdict_rejects_unknown_status_and_counts():
    with pytest.raises(ValueError, match="status"):
        verdicts.Verdict("x", "claim", "ok", "")
    found = [
        verdicts.Verdict("a", "", "held", ""),
        verdicts.Verdict("b", "", "failed", ""),
        verdicts.Verdict("c", "", "untested", ""),
    ]
    assert verdicts.count(found) == {"held": 1, "failed": 1, "untested": 1, "tested": 2, "total": 3}


# -- the paper's scenarios with one thing made bad: each claim fails --------------


def test_issue_example_euler_100hz_saturated_run_fails_its_check():
    # Issue 13: Euler at dt = mu (eigenvalue -1 of Phi, a double one) is unstable
    # and now rejected at construction instead of running to a failed check.
    with pytest.raises(famcc.ConfigError, match="spectral radius"):
        _run(
            "finite-time-saturated",
            dt=1e-2,
            substeps=40,
            differentiator=H(0.01, [4.0, 4.0], discretization="euler"),
        )


def test_settling_fails_with_an_unstable_euler_differentiator_at_100hz():
    with pytest.raises(famcc.ConfigError, match="spectral radius"):
        _run(
            "finite-time",
            dt=1e-2,
            substeps=40,
            differentiator=H(0.01, [4.0, 4.0], discretization="euler"),
        )


def test_settling_fails_with_a_differentiator_too_slow_for_the_plant():
    _, _, v = _run("finite-time", differentiator=H(0.3, [4.0, 4.0]))
    assert v["settling"].failed and "never" in v["settling"].detail


def test_nominal_fails_although_settling_holds_tustin_100hz():
    _, res, v = _run(
        "finite-time",
        dt=1e-2,
        substeps=40,
        differentiator=H(0.01, [4.0, 4.0], discretization="tustin"),
    )
    assert v["settling"].status == "held"
    assert v["nominal"].failed
    # The evidence: |xi~| stayed below 1 (by construction), the nominal xi did not.
    assert res.max_abs_xi < 1.0 < res.max_abs_xi_nominal
    assert res.expanded_unsaturated_fraction > 0.1


def test_unsaturated_fails_when_rfc_sits_on_its_limits_at_100hz():
    _, _, v = _run(
        "rfc",
        dt=1e-2,
        substeps=40,
        differentiator=H(0.01, [4.0, 6.0, 4.0], discretization="tustin"),
    )
    assert v["unsaturated"].failed


def test_recovery_fails_with_a_gain_too_weak_for_the_load():
    _, res, v = _run("finite-time-saturated", k_u=0.5)
    assert v["recovery"].failed
    assert v["nominal-again"].failed
    assert res.expanded_unsaturated_fraction > 0.3


def test_recovery_fails_when_the_controller_is_built_for_a_looser_accuracy():
    _, _, v = _run("finite-time-saturated", eps=0.5)
    assert v["recovery"].failed


def test_nominal_again_fails_when_bounds_stay_expanded_after_saturation():
    _, _, v = _run("finite-time-saturated", k_u=1.0)
    assert v["nominal-again"].failed


def test_bound_beyond_a_short_horizon_is_untested_not_held():
    sc, res, v = _run("finite-time", t_end=2.0)
    assert res.settling_time(0.1) is not None  # it did settle ...
    assert v["settling"].status == "untested"  # ... but the claim is about t >= 3 s
    assert sc.check(res) == []


def test_saturated_scenario_runs_until_a_recovery_claim_falls_due():
    sc = scenarios.paper("variable-exponent-saturated", "code")
    res = sc.run()
    assert float(res.t[-1]) > sc.t_end  # extended past the paper's 10 s
    v = _by_name(sc.verdicts(res))
    assert v["recovery"].status == "held" and "due windows hold" in v["recovery"].detail
    assert sc.run(t_end=10.0).t[-1] == pytest.approx(10.0)  # an explicit horizon is kept


def test_paper_numbers_rfc_saturated_fail_settling_as_a_known_failure():
    sc = scenarios.paper("rfc-saturated", "paper")
    res = sc.run(t_end=10.0)
    v = _by_name(sc.verdicts(res))
    assert v["settles"].failed and v["settles"].known
    assert sc.check(res) and "known" in sc.check(res)[0]


# -- SimResult's new per-sample records and metrics -------------------------------


def test_simresult_records_nominal_xi_expansion_and_saturation():
    sc = scenarios.paper("finite-time-saturated")
    res = sc.run(t_end=6.0)
    assert res.xi_nominal is not None and res.expansion is not None
    assert np.all(res.expansion >= 1.0)
    # xi~ = xi / factor, the factor is > 1 exactly where the bounds are expanded
    np.testing.assert_allclose(res.xi, res.xi_nominal / res.expansion, rtol=1e-12)
    assert np.array_equal(res.expansion > 1.0, res.expanded)
    lo, hi = sc.u_limits
    assert np.array_equal(res.saturated, (res.v < lo) | (res.v > hi))
    assert res.max_abs_xi_nominal > 1.0 > res.max_abs_xi
    assert res.expanded_fraction == pytest.approx(float(np.mean(res.expanded)))
    assert 0.0 <= res.expanded_unsaturated_fraction <= res.expanded_fraction


def test_steady_rms_is_the_rms_after_settling():
    t = np.arange(11) * 0.1
    z1 = np.array([1.0, 0.5, 0.2, 0.05, -0.05, 0.05, -0.05, 0.03, -0.03, 0.03, -0.03])
    r = _result(z1, dt=0.1)
    assert r.settling_time(0.1) == pytest.approx(0.3)
    expected = float(np.sqrt(np.mean(z1[3:] ** 2)))
    assert r.steady_rms(0.1) == pytest.approx(expected)
    assert _result(np.ones(5)).steady_rms(0.1) is None
    assert t.size == z1.size


def test_requirements_name_a_bad_accuracy_or_time():
    r = _result(np.where(np.arange(301) * 0.01 < 1.5, 1.0, 0.01))
    for eps in (0.0, -0.1, float("inf"), float("nan"), "0.1"):
        with pytest.raises(ValueError, match="eps must be a finite number > 0"):
            verdicts.requirements(r, eps=eps)
    for settle_time in (-1.0, -1e-9, float("inf"), float("nan"), "2"):
        with pytest.raises(ValueError, match="settle_time must be a finite number >= 0"):
            verdicts.requirements(r, eps=0.1, settle_time=settle_time)
    with pytest.raises(ValueError, match="give eps too"):
        verdicts.requirements(r, settle_time=2.0)
    # 0 s is a (demanding) requirement, not an error: the run settles at 1.5 s
    assert [(v.name, v.status) for v in verdicts.requirements(r, eps=0.1, settle_time=0)] == [
        ("settled-by", "failed")
    ]


def test_failed_unsaturated_and_nominal_say_how_often_and_from_when():
    k = np.arange(400)
    v = np.where((k >= 100) & (k < 200), 5.0, 0.0)  # outside the limits for 1 s of 4
    r = _result(np.zeros(400), v=v, limits=(-1.0, 1.0), expanded=(k >= 300) & (k < 310))
    u = verdicts.unsaturated(r, startup=0.0)
    assert u.status == "failed"
    assert u.detail == (
        "outside the limits at 25.0 % of the samples after the start-up, first at 1.000 s"
    )
    n = verdicts.nominal(r, startup=0.0)
    assert n.status == "failed"
    assert n.detail == (
        "expanded at 2.5 % of the samples after the start-up, first at 3.000 s, up to 2x"
    )


def test_an_untested_claim_still_says_when_the_run_settled():
    settled = _result(np.where(np.arange(301) * 0.01 < 2.0, 1.0, 0.0))  # 2 s of a 3 s run
    never = _result(np.ones(301))
    for r, when in ((settled, "2.000 s"), (never, "never")):
        v = verdicts.settling(r, eps=0.1, settle_time=1.0, t_prime=5.0)
        assert v.status == "untested" and v.detail.endswith(f"(settled at {when})"), v
        v = verdicts.settled_by(r, eps=0.1, by=4.0)
        assert v.status == "untested" and v.detail.endswith(f"(settled at {when})"), v


def test_settles_when_only_the_last_sample_is_inside_the_band():
    z1 = np.ones(101)
    z1[-1] = 0.0
    v = verdicts.settles(_result(z1), eps=0.1, within=10.0)
    assert (v.status, v.detail) == ("held", "settled at 1.000 s")
    z1[-1] = 1.0
    assert verdicts.settles(_result(z1), eps=0.1, within=10.0).status == "failed"


def test_only_an_episode_that_lasts_to_the_end_is_never_due():
    t = np.arange(1001) * 0.01  # 10 s
    v = np.where(((t >= 1.0) & (t < 2.0)) | (t >= 8.0), 9.0, 0.0)
    z1 = np.where((t < 2.2) | (t >= 8.5), 1.0, 0.0)  # out of the band again while saturated
    r = _result(z1, v=v, limits=(-1.0, 1.0))
    # T' = 2: episode 1 ends at 2 s, due at 4 s, before the next (8 s): held; the last
    # never ended, so it is not due however long T' is.
    rec = verdicts.recovery(r, 0.1, 1.0, 2.0)
    assert (rec.status, rec.detail) == ("held", "all 1 due windows hold; 1 not due")


def test_a_failed_recovery_counts_every_window_and_details_the_first_two():
    t = np.arange(1001) * 0.01
    v = np.where(
        ((t >= 1.0) & (t < 1.5)) | ((t >= 4.0) & (t < 4.5)) | ((t >= 7.0) & (t < 7.5)), 9.0, 0.0
    )
    r = _result(np.ones(t.size), v=v, limits=(-1.0, 1.0))  # never inside the band
    rec = verdicts.recovery(r, 0.1, 1.0, 0.5)
    assert rec.failed and rec.detail.startswith("3 of 3 due windows fail; after the episode ")
    assert rec.detail.count("after the episode ending at") == 2
    assert "1.500 s: max |z1| = 1 in [2.000, 4.000] s" in rec.detail


def test_check_lists_the_failed_claims_only():
    sc = scenarios.paper("finite-time")  # eps 0.1, bound T_s + T' = 3 s
    k = np.arange(501)  # 5 s
    z1 = np.where(k < 400, 1.0, 0.0)  # settles at 4 s, after the bound
    v = np.where((k >= 100) & (k < 110), 500.0, 0.0)  # beyond the limits after the start-up
    bad = _result(z1, v=v, limits=sc.u_limits, expanded=np.zeros(501, dtype=bool))
    assert sc.check(bad) == [
        "settling: failed: settled only at 4.000 s",  # bound max(1.1, 1) + 2 = 3.1 s
        (
            "unsaturated: failed: outside the limits at 2.1 % of the samples after the "
            "start-up, first at 1.000 s"
        ),
    ]
    good = _result(np.where(k < 100, 1.0, 0.0), limits=sc.u_limits, expanded=np.zeros(501, bool))
    assert sc.check(good) == []


def test_a_diverged_run_fails_its_settling_claims_instead_of_raising():
    # The exact ZOH at dt = mu (200 Hz, mu = 5 ms) destabilises rfc: the plant
    # state goes non-finite at about 0.5 s. Scenario.run stops the run there
    # (flagged diverged) and every settling claim fails, none is "untested".
    sc, res, found = _run("rfc", dt=5e-3, differentiator=H(5e-3, [4.0, 6.0, 4.0], "exact"))
    assert res.diverged and res.diverged_at is not None and res.diverged_at < 1.0
    assert found["settling"].status == "failed"
    assert "diverged at" in found["settling"].detail
    assert any(c.startswith("settling: failed") for c in sc.check(res))


def test_diverged_synthetic_runs_fail_settles_and_settled_by():
    r = _result(np.full(100, 0.01))  # inside the band throughout ...
    assert verdicts.settles(r, 0.1, 10.0).status == "held"
    assert verdicts.settled_by(r, 0.1, 0.5).status == "held"
    r.diverged_at = 0.99  # ... but stopped as diverged
    for v in (
        verdicts.settles(r, 0.1, 10.0),
        verdicts.settled_by(r, 0.1, 0.5),
        verdicts.settling(r, 0.1, 0.2, 0.3),
    ):
        assert v.status == "failed" and "diverged at 0.99 s" in v.detail, v
