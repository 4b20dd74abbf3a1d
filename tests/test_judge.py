"""One judge: the held/failed/untested type every judgement speaks (verdicts, campaigns,
the sweep, ``tune``'s assessment), its combination rule, and the guarantees a
configuration presets, taken from famcc-core."""

from __future__ import annotations

import json

import famcc
import numpy as np
import pytest
from famcc import metrics
from famcc.campaigns.controller import _corollary_time
from famcc.verdicts import STATUSES, Status, Verdict, combine, combine_codes
from hypothesis import given
from hypothesis import strategies as st

statuses = st.sampled_from(list(Status))


def test_a_status_is_its_string_in_reports_and_json():
    assert Status.HELD == "held" and f"{Status.FAILED}" == "failed"
    assert json.dumps({"s": Status.UNTESTED}) == '{"s": "untested"}'
    assert [s.value for s in STATUSES] == ["held", "failed", "untested"]
    assert [Status.from_code(s.code) for s in Status] == list(Status)
    with pytest.raises(ValueError, match="1 \\(held\\), 0 \\(failed\\) or -1"):
        Status.from_code(2)


def test_a_verdict_takes_a_string_keeps_a_status_and_rejects_others():
    v = Verdict("settling", "claim", "failed", "never settled")
    assert v.status is Status.FAILED and v.failed
    assert v.record()["status"] == "failed" and type(v.record()["status"]) is str
    with pytest.raises(ValueError, match="status must be one of"):
        Verdict("settling", "claim", "passed", "")


@given(st.lists(statuses, max_size=6))
def test_combine_fails_on_any_failure_then_is_untested_on_any_untested(found):
    out = combine(found)
    if Status.FAILED in found:
        assert out is Status.FAILED
    elif Status.UNTESTED in found:
        assert out is Status.UNTESTED
    else:
        assert out is Status.HELD
    # order does not matter, and adding a held claim changes nothing
    assert combine(reversed(found)) is out and combine([*found, Status.HELD]) is out


@given(st.lists(st.lists(statuses, min_size=3, max_size=3), min_size=1, max_size=4))
def test_the_vectorised_combination_equals_the_scalar_one(rows):
    codes = np.array([[s.code for s in row] for row in rows])  # claims x cases
    got = combine_codes(codes)
    assert got.dtype == np.int8
    want = [combine(row[j] for row in rows).code for j in range(3)]
    assert got.tolist() == want


def _hand_run(z1, u, dt=0.1, expanded=True):
    z1, u = np.asarray(z1, dtype=float), np.asarray(u, dtype=float)
    t = np.round(np.arange(z1.size) * dt, 12)
    exp = np.zeros(z1.size, dtype=bool) if expanded else None
    return famcc.SimResult(
        t=t,
        y=z1,
        y_d=0 * t,
        x=z1[:, None],
        z=z1[:, None],
        v=u,
        u=u,
        dt=dt,
        u_limits=(-1, 1),
        expanded=exp,
    )


def test_an_assessment_judges_each_requirement_with_a_verdict():
    z1 = np.where(np.arange(11) < 3, 1.0, 0.0)
    a = famcc.tuning.assess(_hand_run(z1, 0 * z1), eps=0.1, settle_time=1.0, u_limits=(-1, 1))
    assert [(v.name, v.status) for v in a.verdicts] == [
        ("settling", "held"),
        ("steady", "held"),
        ("nominal", "held"),
        ("ripple", "held"),
    ]
    assert a.ok and a.status is Status.HELD and a.failures == []
    # too slow a requirement: the settling verdict fails, and failures are its words
    b = famcc.tuning.assess(_hand_run(z1, 0 * z1), eps=0.1, settle_time=0.1, u_limits=(-1, 1))
    assert not b.ok and b.status is Status.FAILED
    assert b.failures == ["settled at 0.3 s > 0.1 s"]
    # without diagnostics the nominal requirement is untested, not held
    c = famcc.tuning.assess(
        _hand_run(z1, 0 * z1, expanded=False), eps=0.1, settle_time=1.0, u_limits=(-1, 1)
    )
    nominal = {v.name: v for v in c.verdicts}["nominal"]
    assert nominal.status is Status.UNTESTED and c.ok and c.status is Status.UNTESTED
    # a diverged run
    d = famcc.tuning.assess(None, eps=0.1, settle_time=1.0, u_limits=(-1, 1))
    assert d.failures == ["diverged"] and d.status is Status.FAILED


def _old_preset_accuracy(config):
    """The rule as the package wrote it before it moved into famcc-core (without
    integral action, where it agrees)."""
    order, kind = config.get("order"), config.get("constraint")
    if order == 1 or (order == 2 and kind == "lateral"):
        return config.get("eps")
    skews = config.get("skew")
    first = skews[0] if isinstance(skews, (list, tuple)) and skews else skews
    return getattr(first, "eps_z", None)


@pytest.mark.parametrize("name", famcc.scenarios.names())
def test_the_accuracy_and_bound_of_every_paper_scenario_come_from_the_core(name):
    sc = famcc.scenarios.paper(name)
    ctrl = sc.controller()
    cfg = ctrl.config()
    assert metrics.preset_accuracy(cfg) == sc.eps_z == _old_preset_accuracy(cfg)
    assert ctrl.spec.output_accuracy() == sc.eps_z
    z1_0 = np.array([-1.0]) if sc.example < 3 else np.array([1.0])
    assert _corollary_time(cfg, z1_0)[0] == pytest.approx(sc.t_prime, rel=1e-12)


def test_the_preset_accuracy_follows_the_constraint_and_the_first_skew():
    law = famcc.Linear(k=2.0)
    lat = famcc.Controller(2, 1e-3, feedback=law, constraint="lateral", eps=0.2, k_u=5.0)
    lon = famcc.Controller(2, 1e-3, feedback=law, constraint="longitudinal", eps=0.2, k_u=5.0)
    skewed = famcc.Controller(
        2,
        1e-3,
        feedback=law,
        skew=famcc.Smooth(eps_s=0.05, eps_z=0.02),
        constraint="longitudinal",
        eps=0.2,
        k_u=5.0,
    )
    for c, want in ((lat, 0.2), (lon, None), (skewed, 0.02)):
        assert metrics.preset_accuracy(c.config()) == want == _old_preset_accuracy(c.config())
    # not a famcc configuration: nothing preset
    assert metrics.preset_accuracy({"order": 2, "dt": 1e-3, "gain": 3.0}) is None


def test_a_design_without_a_corollary_has_no_bound_deadline():
    ctrl = famcc.Controller(
        2, 1e-3, feedback=famcc.Linear(k=2.0), constraint="lateral", eps=0.2, k_u=5.0
    )
    assert ctrl.spec.corollary_time(1.0) is None
    with pytest.raises(ValueError, match="corollary bound .*'Linear'"):
        _corollary_time(ctrl.config(), np.zeros(2))
