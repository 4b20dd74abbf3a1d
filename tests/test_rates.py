"""The paper's scenarios at 200 and 500 Hz with the differentiator the core's
rules pick for the sample period (issue 14, item 5; docs/tuning.md, "Sample
rate")."""

from __future__ import annotations

import famcc
import pytest
from famcc import scenarios


def test_the_rules_give_the_papers_differentiator_at_1_khz():
    for name in scenarios.names():
        sc = scenarios.paper(name)
        n = sc.controller_kwargs["order"]
        assert famcc.HighGain.for_rate(n, 1e-3) == sc.controller_kwargs["differentiator"]
        assert (
            sc.controller(1e-3).config()
            == famcc.Controller(
                n, 1e-3, **{k: v for k, v in sc.controller_kwargs.items() if k != "order"}
            ).config()
        )


def test_slower_rates_get_the_first_order_hold_unless_a_differentiator_is_given():
    h2, h3 = famcc.HighGain.for_rate(2, 5e-3), famcc.HighGain.for_rate(3, 5e-3)
    # 0.5 dt + n mu / 2 = 1.5 ms + n 5 ms: the paper's loop delay at 1 kHz
    assert h2.mu == pytest.approx(9e-3) and h2.discretization == "foh"
    assert h3.mu == pytest.approx(0.01 - 2e-3 / 3) and h3.discretization == "foh"
    h500 = famcc.HighGain.for_rate(3, 2e-3)
    assert (h500.mu, h500.discretization) == (0.01, "foh")
    sc = scenarios.paper("rfc")
    assert sc.controller(5e-3).config()["differentiator"] == h3
    mine = famcc.HighGain.default(3, mu=0.01)  # exact at dt / mu = 0.5: the lint warns
    with pytest.warns(famcc.DesignWarning, match=r"dt / mu <= 0.2"):
        assert sc.controller(5e-3, differentiator=mine).config()["differentiator"] == mine
    with pytest.raises(famcc.ConfigError):
        famcc.HighGain.for_rate(3, 0.0)


@pytest.mark.parametrize("dt", [5e-3, 2e-3])
@pytest.mark.parametrize("name", scenarios.names())
def test_every_scenario_keeps_its_guarantees_at_200_and_500_hz(name, dt):
    sc = scenarios.paper(name)
    res = sc.run(dt=dt)
    assert sc.check(res) == []
    assert not any(v.status == "untested" for v in sc.verdicts(res) if not sc.saturated)


# Risky on purpose (exact at dt / mu = 0.56; a law that chatters): the lints warn.
@pytest.mark.filterwarnings("ignore::famcc.DesignWarning")
@pytest.mark.parametrize("held", ["exact", "tustin"])
def test_a_held_input_at_the_same_mu_loses_the_nominal_bounds_at_200_hz(held):
    # The same differentiator with the sample held over the period instead of
    # the first-order hold: variable-exponent's s jumps when z1 crosses zero
    # (its law has an infinite slope there), and one more period of delay
    # lets it through the boundary (docs/tuning.md, "Sample rate").
    sc = scenarios.paper("variable-exponent")
    h = famcc.HighGain.for_rate(2, 5e-3)
    res = sc.run(dt=5e-3, differentiator=famcc.HighGain(h.mu, list(h.a), held))
    failed = sc.check(res)
    assert len(failed) == 1 and failed[0].startswith("nominal: failed")
