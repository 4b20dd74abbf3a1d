"""The compiled controller against the pure-Python reference (tests/oracle/reference.py).

The reference is an independent implementation of the same discrete-time law
(docs/design.md §3) in ``math`` only; it is the test oracle for the Rust core.
Both controllers are fed the same recorded error sequence (open-loop replay, so
no closed-loop amplification) and must agree at every sample.

Tolerances, and why:

- ``law`` tests give the reference the core's own ``Phi``/``Gamma`` (read back
  bit-exactly from the compiled controller by stepping unit states with
  ``e = 0`` and a zero state with ``e = 1``), so the differentiator is the same
  to the bit and only the law is compared: ``|dv| <= 1e-9 |v| + 1e-12`` and
  ``|dxi| <= 1e-12``. Observed: ``|dxi| <= 5e-15``, ``|dv|/|v| <= 5e-12`` (the
  order-3 manifold ``s_3 = z_3 - h_1'(z_1) z_2 - h_2(s_2)`` cancels terms of
  size ``|z_3| ~ 1e3`` down to ``~1``, and the log map's slope
  ``2/(1 - xi^2)`` reaches ~1e2 near the boundary).
- ``discretization`` tests compare the reference's ``Phi``/``Gamma`` (Taylor
  scaling-and-squaring) with the core's (Pade-13) entry by entry:
  ``<= 4e-15`` relative (observed 8.5e-16, i.e. a few ulps).
- ``end-to-end`` tests let the reference use its own ``Phi``/``Gamma``. The
  few-ulp differences feed a systematic bias: the exact DC row sum
  ``Phi_21 + Gamma_2 = 0`` holds only to ``ulp(32.7) ~ 7e-15``, the estimate
  ``z_2`` integrates it with gain ``1/(1 - 0.98) = 50``, and LaMC's
  ``h_v(z_2) = -z_2 |z_2|`` and the envelope ``x_U = 0.1`` amplify it again:
  observed ``|dxi| <= 4e-12``, ``|dv| <= 1.3e-9`` at ``|v| ~ 280``. Allowed:
  ``|dxi| <= 1e-10`` and ``|dv| <= 1e-9 |v| + 1e-10 k_u``.

The first-order hold (``"foh"``) is held to the same tolerances, none looser. Its
``Gamma_0`` and feedthrough ``D`` (the reference's from the exponential of an
augmented matrix with a ramp input, the core's from ``M0 D0 = (Gamma_zoh - tau
a)/tau`` or a series) agree like ``Gamma``: observed ``<= 1.7e-15`` of the natural
scale ``mu^-i`` (an entry that cancels, ``Gamma_0,1 = Gamma_zoh,1 - D_1 ~ 1e-13``
at ``dt = 17 mu``, is only that accurate: 1.3e-3 relative). At 200 Hz (``dt = 5 ms``, ``mu = 9 ms``,
the paper's scenarios closed by the core with the first-order hold, with and
without a prefilter) the law tests find the estimates equal bit for bit and
``|dv| <= 3.9e-11`` at ``|v| ~ 280``; end to end ``|dxi| <= 7.7e-13`` and
``|dv| <= 1.0e-10`` at ``|v| ~ 240``: at most 0.8 % of the allowed ``|dv|``.

When ``|xi|`` must be clamped (flexible boundary off, or on with
``d_sc >> rho_e`` after an outlier) both clamp to the largest float below 1
(``1 - 2^-53``, docs/design.md §3.6); ``test_clamp_value_is_largest_float_below_one``
checks the value. Elsewhere clamped samples are excluded from the comparison
(the clamp events themselves must coincide).
"""

from __future__ import annotations

import ast
import functools
import math
from pathlib import Path

import famcc
import numpy as np
import pytest
from oracle.reference import CLAMP_LIMIT, ReferenceController, discretize_hgd

#: Index of z_hat[0] in ``Controller.state()`` (after the named fields).
ZHAT = len(famcc._core.STATE_FIELDS)
#: Index of the differentiator's last (prefiltered) input in ``Controller.state()``.
FILTERED = famcc._core.STATE_FIELDS.index("filtered")
#: The input that reads the first-order hold's feedthrough ``D`` back: a power of
#: two (``0 + D_i f`` and ``/ f`` are exact) small enough for any estimate limit.
PROBE_INPUT = 2.0**-40

#: The discretizations of eq. HGD (famcc.HighGain's ``discretization``).
METHODS = ["exact", "euler", "tustin", "foh"]

# This module runs risky configurations on purpose (coarse sampling, dt ~ mu) to
# compare the core with the oracle there: their DesignWarnings are expected.
pytestmark = pytest.mark.filterwarnings("ignore::famcc.DesignWarning")

DT = 1e-3
SCENARIOS = [(n, v) for n in famcc.scenarios.names() for v in ("paper", "code")]

LAW_RTOL, LAW_ATOL, LAW_XI_ATOL = 1e-9, 1e-12, 1e-12
E2E_RTOL, E2E_ATOL_PER_KU, E2E_XI_ATOL = 1e-9, 1e-10, 1e-10


# ---------------------------------------------------------------------------
# helpers


@functools.cache
def recorded(name: str, variant: str, t_end: float = 3.0):
    """Closed loop with the compiled controller: (e, applied, v) sequences."""
    res = famcc.scenarios.paper(name, variant).run(dt=DT, t_end=t_end)
    e = np.asarray(res.y - res.y_d, dtype=float)
    applied = [None] + [float(u) for u in res.u[:-1]]
    return e, applied, np.asarray(res.v, dtype=float)


def core_discretization(ctrl: famcc.Controller):
    """The compiled controller's Phi, Gamma and first-order-hold feedthrough D (None
    without one), read back through its state. The stored ``filtered`` is set to the
    sample so that a prefilter passes it on bit for bit and the input's increment is
    0 (the step's estimate is the stored ``V``); from ``V = 0`` and ``filtered = 0`` a
    sample's estimate is ``D f`` with ``f`` the (prefiltered) input the step stores
    (exactly ``D`` times the probe without a prefilter, to an ulp with one)."""
    c = ctrl.__copy__()
    c.reset()
    c.step(0.0)
    base = np.asarray(c.state(), dtype=float)
    n = c.order
    phi = [[0.0] * n for _ in range(n)]
    for j in range(n):
        s = base.copy()
        s[ZHAT:] = 0.0
        s[ZHAT + j] = 1.0
        c.set_state(s)
        c.step(0.0)  # Phi e_j + Gamma * 0
        for i, x in enumerate(c.estimate):
            phi[i][j] = float(x)
    s = base.copy()
    s[ZHAT:] = 0.0
    s[FILTERED] = 0.0
    c.set_state(s)
    c.step(PROBE_INPUT)  # the law sees 0 + D (f - 0)
    f = float(c.state()[FILTERED])
    feed = [float(x) / f for x in c.diagnostics.z_hat]
    s = base.copy()
    s[ZHAT:] = 0.0
    s[FILTERED] = 1.0
    c.set_state(s)
    c.step(1.0)  # Phi 0 + Gamma * 1 (no increment)
    gamma = tuple(float(x) for x in c.estimate)
    return tuple(map(tuple, phi)), gamma, (tuple(feed) if any(feed) else None)


def pair(kwargs: dict, dt: float = DT, *, same_phi: bool = True, **ref_overrides):
    """A compiled controller and a reference with the same configuration."""
    kw = dict(kwargs)
    order = kw.pop("order")
    ctrl = famcc.Controller(order, dt, **kw)
    kw.update(ref_overrides)
    ref = ReferenceController(order, dt, **kw)
    if same_phi and ref.phi is not None:
        ref.phi, ref.gamma_vec, ref.feedthrough = core_discretization(ctrl)
    return ctrl, ref


def replay(ctrl, ref, e, applied=None):
    """Steps both with the same inputs; returns a dict of per-sample arrays."""
    out = {
        k: []
        for k in (
            "v_c",
            "v_r",
            "xi_c",
            "xi_r",
            "clamp_c",
            "clamp_r",
            "zh_c",
            "zh_r",
            "s_c",
            "s_r",
            "sp_c",
            "sp_r",
            "dsp_c",
            "dsp_r",
            "b_c",
            "b_r",
            "ex_c",
            "ex_r",
            "gap_c",
            "gap_r",
            "t_c",
            "t_r",
        )
    }
    for k, ek in enumerate(e):
        a = None if applied is None else applied[k]
        out["v_c"].append(ctrl.step(float(ek), a))
        out["v_r"].append(ref.step(float(ek), a))
        dc, dr = ctrl.diagnostics, ref.diagnostics
        for key, attr in (
            ("xi", "xi"),
            ("clamp", "clamp_count"),
            ("s", "s"),
            ("sp", "s_prev"),
            ("dsp", "ds_prev"),
            ("b", "bounds"),
            ("ex", "expanded"),
            ("gap", "saturation_gap"),
            ("t", "t"),
        ):
            out[key + "_c"].append(getattr(dc, attr))
            out[key + "_r"].append(getattr(dr, attr))
        out["zh_c"].append(np.asarray(dc.z_hat, dtype=float))
        out["zh_r"].append(np.asarray(dr.z_hat, dtype=float))
    return {
        k: np.asarray(
            [np.nan if x is None else x for x in v] if k.startswith("gap") else v, dtype=float
        )
        for k, v in out.items()
    }


def mismatches(r, rtol, atol, xi_atol, mask=None):
    """Indices (and a description of the worst) where v or xi disagree."""
    dv = np.abs(r["v_c"] - r["v_r"])
    bad_v = dv > rtol * np.abs(r["v_c"]) + atol
    bad_xi = np.abs(r["xi_c"] - r["xi_r"]) > xi_atol
    bad = bad_v | bad_xi
    if mask is not None:
        bad &= mask
    idx = np.flatnonzero(bad)
    if idx.size == 0:
        return idx, ""
    k = int(idx[0])
    return idx, (
        f"{idx.size} samples disagree; first k={k}: v core={r['v_c'][k]!r} "
        f"ref={r['v_r'][k]!r}, xi core={r['xi_c'][k]!r} ref={r['xi_r'][k]!r}"
    )


def assert_diagnostics_agree(r, rtol=1e-9, atol=1e-12, after_clamp=None):
    """``after_clamp``: samples whose previous output was clamped (their saturation
    gap ``v_{k-1} - applied`` inherits the known clamp mismatch)."""
    if after_clamp is not None:
        r = dict(r)
        r["gap_c"] = np.where(after_clamp, np.nan, r["gap_c"])
        r["gap_r"] = np.where(after_clamp, np.nan, r["gap_r"])
    np.testing.assert_array_equal(r["t_c"], r["t_r"])
    np.testing.assert_array_equal(r["ex_c"], r["ex_r"])
    np.testing.assert_array_equal(r["clamp_c"], r["clamp_r"])
    np.testing.assert_array_equal(np.isnan(r["gap_c"]), np.isnan(r["gap_r"]))
    for key in ("s", "sp", "dsp", "b", "gap"):
        a, b = r[key + "_c"], r[key + "_r"]
        scale = np.nanmax(np.abs(a)) if np.any(np.isfinite(a)) else 1.0
        np.testing.assert_allclose(
            b, a, rtol=rtol, atol=atol * max(scale, 1.0), equal_nan=True, err_msg=key
        )


def synthetic_error(n=3000, seed=0, dt=DT):
    """A decaying oscillation with a ripple and measurement noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt
    return 1.5 * np.exp(-t) * np.cos(3 * t) + 0.05 * np.sin(17 * t) + 1e-3 * rng.standard_normal(n)


# ---------------------------------------------------------------------------
# the paper's six scenarios, both variants


@pytest.mark.parametrize("name,variant", SCENARIOS)
def test_scenario_law_matches_core(name, variant):
    e, applied, v_closed = recorded(name, variant)
    kwargs = famcc.scenarios.paper(name, variant).controller_kwargs
    ctrl, ref = pair(kwargs)
    r = replayed_law_agrees(ctrl, ref, e, applied, v_closed)
    assert r["clamp_c"][-1] == 0


def replayed_law_agrees(ctrl, ref, e, applied, v_closed):
    """Replays a recorded closed loop through both and checks the law (returns the replay)."""
    r = replay(ctrl, ref, e, applied)
    # the replay reproduces the closed loop that recorded the inputs
    np.testing.assert_array_equal(r["v_c"], v_closed)
    # same Phi/Gamma: the estimates agree to rounding (in practice bit for bit)
    zscale = np.max(np.abs(r["zh_c"]), axis=0)
    assert np.all(np.abs(r["zh_c"] - r["zh_r"]) <= 1e-14 * zscale)
    idx, msg = mismatches(r, LAW_RTOL, LAW_ATOL, LAW_XI_ATOL)
    assert idx.size == 0, msg
    assert_diagnostics_agree(r)
    return r


@pytest.mark.parametrize("name,variant", SCENARIOS)
def test_scenario_end_to_end_matches_core(name, variant):
    e, applied, _ = recorded(name, variant)
    kwargs = famcc.scenarios.paper(name, variant).controller_kwargs
    ctrl, ref = pair(kwargs, same_phi=False)
    r = replay(ctrl, ref, e, applied)
    idx, msg = mismatches(r, E2E_RTOL, E2E_ATOL_PER_KU * kwargs["k_u"], E2E_XI_ATOL)
    assert idx.size == 0, msg


# ---------------------------------------------------------------------------
# the differentiator's discretization


@pytest.mark.parametrize("order", [2, 3])
@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize(
    "mu,dt", [(0.01, 1e-3), (0.01, 1e-4), (0.05, 2e-3), (0.01, 0.02), (0.1, 0.05), (0.003, 0.05)]
)
def test_discretization_matches_core(order, method, mu, dt):
    """Entry by entry: 4e-15 relative, or 1e-14 of the entry's natural scale
    (``mu^(j-i)`` for ``Phi_ij``, ``mu^-i`` for ``Gamma_i``). The reference is exact
    to the last bit (60 digits); the core's float64 exponential is accurate to a few
    ulps *of the O(1) balanced entries*, so an entry that is exactly 0 (order 2,
    ``dt = 5 mu``: ``Phi_11 = e^-1 (1 - 1)``) or small next to them is only accurate
    in that absolute sense: ``Gamma_3`` at ``dt = 17 mu`` (order 3) is off by 1e-8
    relative, 1.3e-15 of its scale, after 6 squarings of the augmented Pade matrix.
    The first-order hold's ``Gamma_0`` and ``D`` (zeros for the others) are held to
    the same bounds as ``Gamma``."""
    a = {2: [4.0, 4.0], 3: [4.0, 6.0, 4.0]}[order]
    law = famcc.Linear(1.0) if order == 2 else [famcc.Linear(1.0)] * 2
    if method == "euler" and dt >= mu:
        # Euler's Phi has the eigenvalue 1 - 2 dt / mu (the coefficients are
        # (s + 2)^n): unstable from dt = mu on, a ConfigError (issue 13).
        with pytest.raises(famcc.ConfigError, match="spectral radius"):
            famcc.Controller(
                order, dt, law, eps=1.0, k_u=1.0, differentiator=famcc.HighGain(mu, a, method)
            )
        return
    ctrl = famcc.Controller(
        order, dt, law, eps=1.0, k_u=1.0, differentiator=famcc.HighGain(mu, a, method)
    )
    phi_c, gam_c, feed_c = core_discretization(ctrl)
    phi_r, gam_r, feed_r = discretize_hgd(mu, a, dt, method, feedthrough=True)
    assert (feed_c is not None) == (method == "foh")
    feed_c = feed_c or (0.0,) * order
    for i in range(order):
        for j in range(order):
            tol = 4e-15 * abs(phi_r[i][j]) + 1e-14 * mu ** (j - i)
            assert abs(phi_c[i][j] - phi_r[i][j]) <= tol, (i, j, phi_c[i][j], phi_r[i][j])
        tol = 4e-15 * abs(gam_r[i]) + 1e-14 * mu ** (-i)
        assert abs(gam_c[i] - gam_r[i]) <= tol, (i, gam_c[i], gam_r[i])
        tol = 4e-15 * abs(feed_r[i]) + 1e-14 * mu ** (-i)
        assert abs(feed_c[i] - feed_r[i]) <= tol, (i, feed_c[i], feed_r[i])


def test_exact_discretization_solves_the_ode():
    """Independent of both: Phi, Gamma against RK4 of eq. HGD over one period."""
    mu, a, dt = 0.01, [4.0, 6.0, 4.0], 1e-3
    phi, gam = discretize_hgd(mu, a, dt)

    def rhs(z, e):
        innov = e - z[0]
        return [(z[i + 1] if i + 1 < 3 else 0.0) + a[i] / mu ** (i + 1) * innov for i in range(3)]

    z0, e = [0.3, -2.0, 50.0], 1.7
    z, h = list(z0), dt / 2000
    for _ in range(2000):
        k1 = rhs(z, e)
        k2 = rhs([x + h / 2 * k for x, k in zip(z, k1)], e)
        k3 = rhs([x + h / 2 * k for x, k in zip(z, k2)], e)
        k4 = rhs([x + h * k for x, k in zip(z, k3)], e)
        z = [x + h / 6 * (p + 2 * q + 2 * r + s) for x, p, q, r, s in zip(z, k1, k2, k3, k4)]
    exact = [g * e + sum(p * x for p, x in zip(row, z0)) for row, g in zip(phi, gam)]
    np.testing.assert_allclose(exact, z, rtol=1e-11)


@pytest.mark.parametrize("order", [2, 3])
@pytest.mark.parametrize("mu,dt", [(0.01, 1e-3), (9e-3, 5e-3), (0.003, 0.02)])
def test_foh_discretization_solves_the_ode(order, mu, dt):
    """Independent of both: over one period with the input the straight line from
    ``e_0`` to ``e_1``, eq. HGD (RK4) ends at ``Phi z_0 + Gamma e_0 + D (e_1 - e_0)``,
    with ``Phi`` and ``Gamma`` the exact hold's (so with ``e_1 = e_0``, a held input,
    it is the exact hold's ``Phi z_0 + Gamma e_0``)."""
    a = {2: [4.0, 4.0], 3: [4.0, 6.0, 4.0]}[order]
    phi, gam, feed = discretize_hgd(mu, a, dt, "foh", feedthrough=True)
    assert (phi, gam) == discretize_hgd(mu, a, dt, "exact")

    def rhs(z, e):
        innov = e - z[0]
        return [
            (z[i + 1] if i + 1 < order else 0.0) + a[i] / mu ** (i + 1) * innov
            for i in range(order)
        ]

    z0, e0, e1 = [0.3, -2.0, 50.0][:order], 1.7, -0.4
    steps = 4000
    z, h = list(z0), dt / steps
    for k in range(steps):
        t = k * h
        ea, em, eb = (e0 + (e1 - e0) * s / dt for s in (t, t + h / 2, t + h))
        k1 = rhs(z, ea)
        k2 = rhs([x + h / 2 * q for x, q in zip(z, k1)], em)
        k3 = rhs([x + h / 2 * q for x, q in zip(z, k2)], em)
        k4 = rhs([x + h * q for x, q in zip(z, k3)], eb)
        z = [x + h / 6 * (p + 2 * q + 2 * r + s) for x, p, q, r, s in zip(z, k1, k2, k3, k4)]
    foh = [
        g * e0 + d * (e1 - e0) + sum(p * x for p, x in zip(row, z0))
        for row, g, d in zip(phi, gam, feed)
    ]
    scale = [max(abs(x), mu**-i) for i, x in enumerate(z)]
    np.testing.assert_array_less(np.abs(np.subtract(foh, z)), 1e-10 * np.asarray(scale))


# ---------------------------------------------------------------------------
# designs beyond the paper's: every law, skew, constraint, transition, option

L = famcc


def cfg(order: int, **kw):
    """Controller keyword arguments (with ``order``)."""
    return {"order": order, **kw}


EXTRA = {
    "linear2-lateral": cfg(2, feedback=L.Linear(2.0), constraint="lateral", eps=0.1, k_u=3.0),
    "linear2-oblique": cfg(
        2, feedback=L.Linear(2.0), constraint="oblique", eps=(0.1, 0.2), k_u=3.0
    ),
    "linear3-longitudinal": cfg(3, feedback=[L.Linear(2.0), L.Linear(3.0)], eps=0.5, k_u=3.0),
    "linear3-lateral": cfg(
        3,
        feedback=[L.Linear(2.0), L.Linear(3.0)],
        constraint="lateral",
        eps=0.1,
        k_u=3.0,
        latch="authors",
    ),
    "linear3-oblique-rational": cfg(
        3,
        feedback=[L.Linear(2.0), L.Linear(3.0)],
        constraint="oblique",
        eps=(0.1, 0.3),
        k_u=3.0,
        gamma="rational",
    ),
    "finite2-lateral-ssmd": cfg(
        2,
        feedback=L.FiniteTime(1.0, 0.5),
        skew=L.Smooth(0.2, 0.1),
        constraint="lateral",
        eps=0.1,
        k_u=5.0,
    ),
    "fixed2-oblique-nsmd": cfg(
        2,
        feedback=L.FixedTime(1.0, 0.5, 0.5, 2.0),
        skew=L.Nonsingular(0.2, 0.1, 0.1),
        constraint="oblique",
        eps=(0.1, 0.15),
        k_u=5.0,
    ),
    "varexp3-nsmd-ssmd": cfg(
        3,
        feedback=[L.VariableExponent(1.5, 0.5, 2.0, 3.0), L.FiniteTime(2.0, 0.6)],
        skew=[L.Nonsingular(0.1, 0.1, 0.5), L.Smooth(0.3, 0.2)],
        eps=1.0,
        k_u=10.0,
    ),
    "transitions3": cfg(
        3,
        feedback=[L.Linear(1.0), L.FixedTime(1.0, 0.5, 1.0, 2.0)],
        skew=[L.Smooth(0.1, 0.1, "cubic"), L.Nonsingular(0.5, 0.2, 1.0, "sine")],
        eps=1.0,
        k_u=10.0,
        transition="quintic",
    ),
    "moulay2": cfg(
        2, feedback=L.MoulayDiscontinuous(1.0, 2.0, 1.0), eps=0.2, k_u=2.0, latch="authors"
    ),
    "limits-initial-derivatives": cfg(
        2,
        feedback=L.FiniteTime(1.0, 0.5),
        constraint="lateral",
        eps=0.1,
        k_u=5.0,
        initial_derivatives=[0.5],
        differentiator=L.HighGain(0.01, [4, 4], limits=[2, 3]),
    ),
    "tustin3-oblique": cfg(
        3,
        feedback=[L.FixedTime(1.0, 0.5, 0.5, 2.0), L.FixedTime(2.0, 0.5, 1.0, 2.0)],
        skew=[L.Nonsingular(0.1, 0.1, 0.1), L.Nonsingular(3.0, 0.2, 1.0)],
        constraint="oblique",
        eps=(0.5, 3.0),
        k_u=30.0,
        differentiator=L.HighGain(0.02, [4, 6, 4], "tustin"),
    ),
    "euler2-no-flexible": cfg(
        2,
        feedback=L.VariableExponent(1.5, 0.5, 2.0, 3.0),
        skew=L.Smooth(0.15, 0.1),
        eps=0.15,
        k_u=2.0,
        rho_e=None,
        differentiator=L.HighGain(0.01, [4, 4], "euler"),
    ),
    "order1": cfg(1, eps=0.1, k_u=2.0),
}

# The first-order hold in two of the designs above: with estimate limits and
# initial derivatives (order 2), and with a prefilter (order 3, oblique).
EXTRA["foh2-lateral-limits"] = {
    **EXTRA["limits-initial-derivatives"],
    "differentiator": L.HighGain(0.01, [4, 4], "foh", limits=[2, 3]),
}
EXTRA["foh3-oblique-prefilter"] = {
    **EXTRA["tustin3-oblique"],
    "differentiator": L.HighGain(0.02, [4, 6, 4], "foh", prefilter=2e-3),
}


@pytest.mark.parametrize("case", sorted(EXTRA))
@pytest.mark.parametrize("seed", [0, 1])
def test_extra_design_matches_core(case, seed):
    ctrl, ref = pair(EXTRA[case])
    e = synthetic_error(seed=seed)
    applied = [None] + [float(x) for x in np.clip(-e[:-1] * 10, -3, 3)]
    r = replay(ctrl, ref, e, applied)
    # both clamp at the same samples; the clamped value is the known mismatch
    # (test_clamp_value_is_largest_float_below_one), so compare the others here
    clamped = np.diff(np.concatenate([[0.0], r["clamp_c"]])) > 0
    idx, msg = mismatches(r, LAW_RTOL, LAW_ATOL, LAW_XI_ATOL, mask=~clamped)
    assert idx.size == 0, msg
    assert_diagnostics_agree(r, after_clamp=np.concatenate([[False], clamped[:-1]]))
    if case == "euler2-no-flexible":
        assert clamped.any()  # the case exercises the clamp


def test_extra_design_at_coarse_sampling():
    """dt = 10 ms: Phi with tau = dt/mu = 1 and the envelope sampled coarsely."""
    kw = famcc.scenarios.paper("rfc", "code").controller_kwargs
    ctrl, ref = pair(kw, dt=0.01)
    r = replay(ctrl, ref, synthetic_error(n=500, dt=0.01), None)
    idx, msg = mismatches(r, LAW_RTOL, LAW_ATOL, LAW_XI_ATOL)
    assert idx.size == 0, msg


# ---------------------------------------------------------------------------
# the first-order hold at a coarse rate

#: 200 Hz with the first-order hold: ``dt / mu = 0.56``, beyond the exact hold's
#: 0.2, where the feedthrough ``D`` is a large part of ``Gamma_zoh`` (order 3:
#: ``D_1 = 0.72``, ``D_3 = 6.4e3`` of ``Gamma_zoh = (1.13, 138, 7.8e3)``).
FOH_DT, FOH_MU = 5e-3, 9e-3
FOH_CASES = [
    ("finite-time", "code", 0.0),
    ("finite-time-saturated", "paper", 3e-3),
    ("variable-exponent", "code", 0.0),
    ("rfc", "code", 0.0),
    ("rfc", "paper", 3e-3),
]


@functools.cache
def recorded_foh(name: str, variant: str, prefilter: float):
    """The scenario closed at ``FOH_DT`` with the first-order hold (and the prefilter
    ``prefilter``, s) by the compiled controller: its keyword arguments and the (e,
    applied, v) sequences."""
    sc = famcc.scenarios.paper(name, variant)
    kw = dict(sc.controller_kwargs)
    a = [4.0, 4.0] if kw["order"] == 2 else [4.0, 6.0, 4.0]
    kw["differentiator"] = famcc.HighGain(FOH_MU, a, "foh", prefilter=prefilter)
    res = sc.run(dt=FOH_DT, differentiator=kw["differentiator"])
    e = np.asarray(res.y - res.y_d, dtype=float)
    applied = [None] + [float(u) for u in res.u[:-1]]
    return kw, e, applied, np.asarray(res.v, dtype=float)


@pytest.mark.parametrize("name,variant,prefilter", FOH_CASES)
def test_foh_law_matches_core_at_coarse_rate(name, variant, prefilter):
    kw, e, applied, v_closed = recorded_foh(name, variant, prefilter)
    ctrl, ref = pair(kw, dt=FOH_DT)
    assert ref.feedthrough is not None
    replayed_law_agrees(ctrl, ref, e, applied, v_closed)


@pytest.mark.parametrize("name,variant,prefilter", FOH_CASES)
def test_foh_end_to_end_matches_core_at_coarse_rate(name, variant, prefilter):
    """The reference with its own ``Phi``, ``Gamma_0`` and ``D`` (the module's
    end-to-end tolerances)."""
    kw, e, applied, _ = recorded_foh(name, variant, prefilter)
    ctrl, ref = pair(kw, dt=FOH_DT, same_phi=False)
    r = replay(ctrl, ref, e, applied)
    idx, msg = mismatches(r, E2E_RTOL, E2E_ATOL_PER_KU * kw["k_u"], E2E_XI_ATOL)
    assert idx.size == 0, msg


def test_foh_estimate_uses_the_current_sample():
    """The first-order hold's estimate of a sample moves with that sample (by ``D``),
    the exact hold's does not; the stored vector ``V`` does not depend on it."""
    out = {}
    for method in ("exact", "foh"):
        hg = L.HighGain(FOH_MU, [4, 4], method)
        ctrl = famcc.Controller(2, FOH_DT, L.Linear(1.0), eps=1.0, k_u=1.0, differentiator=hg)
        zs = []
        for e in (0.1, 0.2, 0.5):
            c, r = ctrl.__copy__(), ReferenceController.from_controller(ctrl)
            for x in (0.3, 0.2, e):
                c.step(x)
                r.step(x)
            np.testing.assert_allclose(r.diagnostics.z_hat, c.diagnostics.z_hat, rtol=1e-13)
            zs.append(np.asarray(c.diagnostics.z_hat))
        out[method] = zs
    np.testing.assert_array_equal(out["exact"][0], out["exact"][2])
    feed = discretize_hgd(FOH_MU, [4, 4], FOH_DT, "foh", feedthrough=True)[2]
    np.testing.assert_allclose(out["foh"][2] - out["foh"][0], 0.4 * np.asarray(feed), rtol=1e-12)


@pytest.mark.parametrize("method", METHODS)
def test_state_feedback_matches_core(method):
    """The law on the measured state; the differentiator keeps running (with the
    first-order hold's feedthrough after the first step), so the estimates agree too."""
    sc = famcc.scenarios.paper("rfc", "code")
    res = sc.run(dt=DT, t_end=1.5)
    kw = dict(sc.controller_kwargs)
    kw["differentiator"] = famcc.HighGain(0.01, [4, 6, 4], method)
    ctrl, ref = pair(kw)
    for z in res.z:
        a = ctrl.step_state([float(x) for x in z])
        b = ref.step_state(z)
        assert b == pytest.approx(a, rel=LAW_RTOL, abs=LAW_ATOL)
        assert ref.xi == pytest.approx(ctrl.diagnostics.xi, abs=LAW_XI_ATOL)
        np.testing.assert_allclose(ref.estimate, ctrl.estimate, rtol=1e-14, atol=1e-14)


def test_rejected_inputs_leave_both_unchanged():
    ctrl, ref = pair(famcc.scenarios.paper("finite-time").controller_kwargs)
    for e in (0.3, 0.2):
        ctrl.step(e)
        ref.step(e)
    for bad in (math.nan, math.inf, -math.inf):
        with pytest.raises(ValueError):
            ctrl.step(bad)
        with pytest.raises(ValueError):
            ref.step(bad)
        with pytest.raises(ValueError):
            ref.step(0.1, applied=bad)
    assert ref.step(0.1) == pytest.approx(ctrl.step(0.1), rel=LAW_RTOL, abs=LAW_ATOL)
    ctrl.reset()
    ref.reset()
    assert ref.step(-1.0) == pytest.approx(ctrl.step(-1.0), rel=LAW_RTOL, abs=LAW_ATOL)


def test_default_rho_e_is_auto_like_the_core():
    for kw in (
        cfg(2, feedback=L.Linear(1.0), constraint="lateral", eps=0.05, k_u=1.0),
        cfg(2, feedback=L.Linear(1.0), eps=0.5, k_u=1.0),
        cfg(3, feedback=[L.Linear(1.0)] * 2, constraint="oblique", eps=(0.3, 0.02), k_u=1.0),
    ):
        ctrl, ref = pair(kw)
        assert ref.rho_e == ctrl.config()["rho_e"]
        r = replay(ctrl, ref, 0.1 * synthetic_error(n=1500))
        assert mismatches(r, LAW_RTOL, LAW_ATOL, LAW_XI_ATOL)[0].size == 0


@pytest.mark.parametrize("method", ["exact", "foh"])
def test_outlier_recovery_matches_core(method):
    """A valid but huge sample cannot be used; both consume it (the recovery rule:
    the clock advances, the estimate restarts, with the first-order hold from
    ``Phi seed + Gamma_0 e`` without feedthrough), fail at the same samples and then
    agree again."""
    hg = L.HighGain(0.01, [4, 4], method)
    kw = cfg(2, feedback=L.FixedTime(1.0, 0.5, 0.5, 2.0), eps=0.5, k_u=2.0, differentiator=hg)
    ctrl, ref = pair(kw)
    e = list(synthetic_error(n=3000))
    e[100] = 1e155  # its square overflows
    failed_c, failed_r, v_c, v_r, clamped = [], [], [], [], []
    for k, ek in enumerate(e):
        outs = []
        for ctl, failed in ((ctrl, failed_c), (ref, failed_r)):
            try:
                outs.append(ctl.step(ek))
            except ValueError:
                failed.append(k)
                outs.append(math.nan)
        v_c.append(outs[0])
        v_r.append(outs[1])
        clamped.append(abs(ctrl.diagnostics.xi) >= 1.0 - 2.0**-52)
        assert ctrl.time == ref.time
    assert failed_c == failed_r and 0 < len(failed_c) < 10
    v_c, v_r, ok = np.asarray(v_c), np.asarray(v_r), ~np.asarray(clamped)
    ok[failed_c] = False
    assert ok[-500:].all()  # recovered: no clamping at the end
    np.testing.assert_allclose(v_r[ok], v_c[ok], rtol=LAW_RTOL, atol=LAW_ATOL)


# ---------------------------------------------------------------------------
# the known mismatch


def test_clamp_value_is_largest_float_below_one():
    kw = {"order": 2, "feedback": famcc.Linear(1.0), "eps": 0.1, "k_u": 1.0, "rho_e": None}
    ctrl, ref = pair(kw)
    for e in [0.0] * 1501 + [5.0, 5.0]:  # far outside the settled envelope
        v_c, v_r = ctrl.step(e), ref.step(e)
    assert ref.xi == CLAMP_LIMIT == math.nextafter(1.0, 0.0)
    assert ctrl.diagnostics.clamp_count == ref.diagnostics.clamp_count == 1
    assert ctrl.diagnostics.xi == ref.xi
    assert v_c == v_r


# ---------------------------------------------------------------------------
# the oracle can fail


@pytest.mark.parametrize(
    "scenario,change",
    [
        (("finite-time", "code"), {"k_u": lambda kw: kw["k_u"] * (1 + 1e-7)}),
        (("finite-time", "code"), {"eps": lambda kw: kw["eps"] * (1 + 1e-7)}),
        (("finite-time", "code"), {"feedback": lambda kw: famcc.FiniteTime(k=1.0, p=0.5 + 1e-7)}),
        (("finite-time", "paper"), {"settle_time": lambda kw: kw["settle_time"] * (1 + 1e-7)}),
        # the flexible boundary expands in this run
        (("variable-exponent-saturated", "code"), {"rho_e": lambda kw: kw["rho_e"] * (1 + 1e-7)}),
    ],
)
def test_oracle_detects_a_perturbed_reference(scenario, change):
    e, applied, _ = recorded(*scenario)
    kwargs = famcc.scenarios.paper(*scenario).controller_kwargs
    overrides = {k: f(kwargs) for k, f in change.items()}
    ctrl, ref = pair(kwargs, **overrides)
    r = replay(ctrl, ref, e, applied)
    idx, _ = mismatches(r, LAW_RTOL, LAW_ATOL, LAW_XI_ATOL)
    assert idx.size > 0


def test_oracle_detects_a_swapped_latch():
    # a small first sample, |s_x0| < eps_x: the two latches give different widths
    kwargs = EXTRA["linear3-lateral"]
    e = 0.02 * synthetic_error()
    ctrl, ref = pair(kwargs)
    assert mismatches(replay(ctrl, ref, e), LAW_RTOL, LAW_ATOL, LAW_XI_ATOL)[0].size == 0
    ctrl, ref = pair(kwargs, latch="paper")
    assert mismatches(replay(ctrl, ref, e), LAW_RTOL, LAW_ATOL, LAW_XI_ATOL)[0].size > 0


def test_oracle_detects_a_perturbed_nsmd_offset():
    name, variant = "rfc", "paper"
    e, applied, _ = recorded(name, variant)
    kwargs = famcc.scenarios.paper(name, variant).controller_kwargs
    sk = kwargs["skew"]
    skew = [
        famcc.Nonsingular(eps_s=sk[0].eps_s * (1 + 1e-7), eps_z=sk[0].eps_z, k_pp=sk[0].k_pp),
        sk[1],
    ]
    ctrl, ref = pair(kwargs, skew=skew)
    idx, _ = mismatches(replay(ctrl, ref, e, applied), LAW_RTOL, LAW_ATOL, LAW_XI_ATOL)
    assert idx.size > 0


# ---------------------------------------------------------------------------
# the reference is pure Python


def test_reference_step_path_is_pure_python():
    """Standard library only (math, decimal, typing): no numpy, no famcc._core."""
    import oracle.reference as mod

    tree = ast.parse(Path(mod.__file__).read_text())
    imports = [n for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom))]
    assert all(n in tree.body for n in imports)  # nothing imported lazily
    names = set()
    for node in imports:
        names |= {a.name for a in node.names} if isinstance(node, ast.Import) else {node.module}
    assert names <= {"__future__", "math", "decimal", "typing", "collections.abc"}
