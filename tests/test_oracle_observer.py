"""The core's observer against the pure-Python oracle (tests/oracle/observer.py), issue 32.

Two implementations of one concept: the closed loops of the paper's six
scenarios with the observer (``Scenario.with_observer``), held and first-order
hold, replayed through both, agree sample by sample; a perturbed oracle does not.
"""

from __future__ import annotations

import functools

import famcc
import numpy as np
import pytest
from oracle.observer import ObservedReference, binomial, discretize_extended

DT = 1e-3
CASES = [(n, d) for n in famcc.scenarios.names() for d in ("exact", "foh")]
RTOL, ATOL_PER_KU = 1e-9, 1e-10


def scenario(name: str, disc: str) -> famcc.scenarios.Scenario:
    sc = famcc.scenarios.paper(name).with_observer()
    obs = sc.controller_kwargs["observer"]
    kw = dict(sc.controller_kwargs, observer=famcc.Observer(obs.mu, obs.b0, discretization=disc))
    return famcc.scenarios.Scenario(**{**sc.__dict__, "controller_kwargs": kw})


@functools.cache
def recorded(name: str, disc: str, t_end: float = 3.0):
    res = scenario(name, disc).run(dt=DT, t_end=t_end)
    e = np.asarray(res.y - res.y_d, dtype=float)
    applied = [None] + [float(u) for u in res.u[:-1]]
    return e, applied, np.asarray(res.v, dtype=float)


def replay(name: str, disc: str, **ref_overrides):
    sc = scenario(name, disc)
    kw = dict(sc.controller_kwargs)
    order = kw.pop("order")
    ctrl = famcc.Controller(order, DT, **kw)
    ref = ObservedReference(order, DT, **{**kw, **ref_overrides})
    e, applied, v_closed = recorded(name, disc)
    out = {k: [] for k in ("v_c", "v_r", "l_c", "l_r", "xi_c", "xi_r")}
    for ek, a in zip(e, applied):
        out["v_c"].append(ctrl.step(float(ek), a))
        out["v_r"].append(ref.step(float(ek), a))
        out["l_c"].append(ctrl.lumped)
        out["l_r"].append(ref.lumped)
        out["xi_c"].append(ctrl.diagnostics.xi)
        out["xi_r"].append(ref.diagnostics.xi)
    r = {k: np.asarray(v, dtype=float) for k, v in out.items()}
    return r, v_closed, kw["k_u"]


def disagree(r, k_u):
    bad = np.abs(r["v_c"] - r["v_r"]) > RTOL * np.abs(r["v_c"]) + ATOL_PER_KU * k_u
    bad |= np.abs(r["l_c"] - r["l_r"]) > RTOL * np.abs(r["l_c"]) + 1e-9
    return np.flatnonzero(bad)


@pytest.mark.parametrize("name,disc", CASES)
def test_the_observer_matches_the_oracle(name, disc):
    r, v_closed, k_u = replay(name, disc)
    np.testing.assert_array_equal(r["v_c"], v_closed)  # the replay is the closed loop
    idx = disagree(r, k_u)
    assert idx.size == 0, (
        f"{idx.size} samples disagree; first k={idx[0]}: v {r['v_c'][idx[0]]!r} vs "
        f"{r['v_r'][idx[0]]!r}, lhat {r['l_c'][idx[0]]!r} vs {r['l_r'][idx[0]]!r}"
    )
    assert np.max(np.abs(r["l_c"])) > 0.1  # the lumped term is estimated, not 0


@pytest.mark.parametrize(
    "change",
    [{"cancellation_limit": 1e-9}, {"observer": famcc.Observer(0.021, 2.0)}],
    ids=["no cancellation", "another mu"],
)
def test_a_perturbed_oracle_disagrees(change):
    r, _, k_u = replay("finite-time", "exact", **change)
    assert disagree(r, k_u).size > 100


def test_the_sampled_observer_holds_a_constant_lumped_term():
    """Exactness of the oracle's own sampling: with e = 0 and a held input u, the true
    ``L = -b0 u`` keeps ``y = 0``; from ``(0, .., 0, -b0 u)`` the estimate stays there."""
    for order in (1, 2, 3, 4):
        a = binomial(order + 1)
        for disc in ("exact", "foh"):
            phi, g_e, g_u, _ = discretize_extended(0.02, a, 1.5, 1e-3, disc)
            x = [0.0] * order + [-1.5 * 0.7]
            nxt = [sum(p * v for p, v in zip(row, x)) + gu * 0.7 for row, gu in zip(phi, g_u)]
            assert np.allclose(nxt, x, atol=1e-12)
            # and a held measurement e is tracked: (e, 0, .., 0, 0) is a fixed point
            y = [0.4] + [0.0] * order
            nxt = [sum(p * v for p, v in zip(row, y)) + ge * 0.4 for row, ge in zip(phi, g_e)]
            assert np.allclose(nxt, y, atol=1e-12)
