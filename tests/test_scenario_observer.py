"""The paper's six scenarios with the extended observer: every claim still holds (issue 32).

The scenario's design, plant, limits and claims are the paper's; only the
differentiator is replaced by the observer (``Scenario.with_observer``). The
same claims without the observer are checked by tests/test_reproduce.py.
"""

from __future__ import annotations

import famcc
import numpy as np
import pytest
from famcc import scenarios


@pytest.fixture(scope="module")
def observed_runs() -> dict[str, tuple[scenarios.Scenario, famcc.SimResult]]:
    out = {}
    for name in scenarios.names():
        sc = scenarios.paper(name).with_observer()
        out[name] = (sc, sc.run())
    return out


@pytest.mark.parametrize("name", scenarios.names())
def test_every_claim_holds_with_the_observer(observed_runs, name):
    sc, res = observed_runs[name]
    assert not res.diverged
    assert sc.check(res) == []
    # the settling claim is tested, not left untested
    first = sc.verdicts(res)[0]
    assert first.status == "held", first.text()


@pytest.mark.parametrize("name", ["finite-time", "rfc-saturated"])
def test_the_observer_is_what_runs(observed_runs, name):
    sc, res = observed_runs[name]
    ctrl = sc.controller()
    assert ctrl.config()["observer"] is not None
    assert ctrl.config()["differentiator"] is None
    assert ctrl.config()["cancellation_limit"] == max(abs(v) for v in sc.u_limits)
    # the run differs from the differentiator's
    plain = scenarios.paper(name).run(t_end=float(res.t[-1]))
    n = min(len(plain.u), len(res.u))
    assert not np.allclose(plain.u[:n], res.u[:n])


def test_with_observer_leaves_the_scenario_unchanged():
    sc = scenarios.paper("rfc")
    before = dict(sc.controller_kwargs)
    obs = sc.with_observer(mu=0.03, b0=1.5)
    assert sc.controller_kwargs == before
    assert "differentiator" not in obs.controller_kwargs
    assert obs.controller_kwargs["observer"].mu == pytest.approx(0.03)
    assert obs.controller_kwargs["observer"].b0 == pytest.approx(1.5)
    assert (obs.u_limits, obs.eps_z, obs.t_prime) == (sc.u_limits, sc.eps_z, sc.t_prime)


def test_a_too_fast_observer_fails_the_claims():
    """The check can fail: mu = 5 ms on the third-order example peaks out of the limits."""
    sc = scenarios.paper("rfc").with_observer(mu=0.005)
    fails = sc.check(sc.run())
    assert fails, "a 5 ms observer on example 3 was measured to diverge"


def test_nominal_gain_is_the_constant_term_of_the_paper_gain():
    for example in (1, 2, 3):
        sc = scenarios.paper({1: "finite-time", 2: "variable-exponent", 3: "rfc"}[example])
        g0 = famcc._core.paper_nominal_gain(example)
        assert g0 == 2.0
        # the true gain along the plain run stays within 50 % of it
        res = sc.run(t_end=3.0)
        x, t = np.asarray(res.x), np.asarray(res.t)
        g = [sc.plant.gain_and_drift(float(t[i]), x[i])[0] for i in range(0, len(t), 100)]
        assert 0.5 * g0 < min(g) and max(g) < 1.5 * g0
    with pytest.raises(ValueError):
        famcc._core.paper_nominal_gain(4)


def test_reproduce_with_the_observer(tmp_path):
    import json

    from famcc import cli

    assert (
        cli.main(["reproduce", "--observer", "--no-figures", "--quiet", "--out", str(tmp_path)])
        == 0
    )
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["observer_mu"] == scenarios.OBSERVER_MU and summary["no_guarantee_failed"]
    md = (tmp_path / "report.md").read_text()
    assert "With the extended observer (mu = 0.02 s" in md
    assert "--observer 0.02" in md
    # the same claims are tested as without it: 16 of 18, none failed
    assert "16 of 18 guarantees tested: 16 hold, 0 fail" in md
    with pytest.raises(SystemExit):
        cli.main(["reproduce", "--observer", "-1", "--out", str(tmp_path)])
    with pytest.raises(ValueError, match="observer"):
        famcc.reporting.reproduce(tmp_path, observer=float("nan"), figures=False, progress=None)
