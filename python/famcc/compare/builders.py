"""Each compared controller built from its parameters (a point of its :class:`Space`)."""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from famcc import _core
from famcc._common import DesignWarning
from famcc.compare.spaces import _KINDS
from famcc.peers import ADRCPeer, PIDPeer, lmcc


@contextmanager
def _design_warnings_silenced() -> Iterator[None]:
    """famcc's :class:`famcc.DesignWarning` ignored inside: the comparison measures its cost."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        yield


@_design_warnings_silenced()
def build(kind: str, p: dict[str, Any], dt: float, u_limits: tuple[float, float]) -> Any:
    """The controller of ``kind`` with parameters ``p`` at sample period ``dt``.

    famcc's construction-time findings (:class:`famcc.DesignWarning`, e.g. a
    differentiator too fast for a 200 Hz loop) are silenced here: the comparison
    evaluates every candidate as tuned, and the measured runs show the cost.
    """
    n = int(p["order"])
    if kind == "pid":
        w, g = p["w"], p["gain"]
        return PIDPeer(
            dt,
            n,
            kp=p["cp"] * w**n / g,
            ki=p["ci"] * w ** (n + 1) / g,
            kd=p["cd"] * w ** (n - 1) / g,
            tf=p["ctf"] / w,
            u_limits=u_limits,
        )
    if kind == "adrc":
        return ADRCPeer(dt, n, b0=p["b0"], w_cl=p["w_cl"], k_eso=p["k_eso"], u_limits=u_limits)
    if kind == "lmcc":
        eps = p["eps_factor"] * p["band"] * p["k"] ** (n - 1)
        return lmcc(
            n, dt, k=p["k"], eps=eps, settle_time=p["settle_time"], k_u=p["k_u"], mu=p["mu"]
        )
    if kind != "famcc":
        raise ValueError(f"kind must be one of {', '.join(_KINDS)}, got {kind!r}")
    # the observer with the nominal gain b0 (as ADRC's), its measurement on the
    # first-order hold once mu < 10 dt; the cancellation bounded by the actuator's range
    k, eps = p["k"], p["eps"]
    if "u_ratio" in p:  # linear stages: the poles' ratios to k (spaces.famcc_candidates)
        mu_o = 1.0 / (p["obs_ratio"] * k)
        k_u = p["u_ratio"] * k**n * eps / (2.0 * abs(p["b0"]))
    else:
        mu_o, k_u = p["obs_mu"], p["k_u"]
    obs = _core.Observer(mu_o, p["b0"], discretization="foh" if mu_o < 10.0 * dt else "exact")
    delta = max(abs(u_limits[0]), abs(u_limits[1]))
    # the envelope latch of the authors' code, as `famcc reproduce` (variant "code") uses
    common = {
        "settle_time": p["settle_time"],
        "k_u": k_u,
        "observer": obs,
        "cancellation_limit": delta if math.isfinite(delta) else 100.0 * k_u,
        "latch": "authors",
    }
    if p["family"] == "finite-time":
        return _core.Controller(
            n, dt, _core.FiniteTime(k=k, p=p.get("p", 0.5)), constraint="lateral", eps=eps, **common
        )
    if p["family"] == "linear":  # Linear(k) stages, LoMC on s ~ k^(n-1) z1, flexible boundary
        stages = [_core.Linear(k) for _ in range(n - 1)] or None  # order 1: no stages
        return _core.Controller(
            n, dt, stages, constraint="longitudinal", eps=eps * k ** (n - 1), **common
        )
    if p["family"] == "variable-exponent":  # example 2, scaled: eps_z = eps, LoMC 1.5 eps
        return _core.Controller(
            n,
            dt,
            _core.VariableExponent(1.5 * k, 0.5, 2.0, 3.0),
            skew=_core.Smooth(2.25 * eps, eps),
            constraint="longitudinal",
            eps=1.5 * eps,
            **common,
        )
    # rfc (example 3, scaled by k): stage i has FixedTime(2^i k, 0.5, 2^(i-1) k, 2) + NSMD
    laws, skews = [], []
    for i in range(n - 1):
        laws.append(_core.FixedTime(2.0**i * k, 0.5, 2.0 ** (i - 1) * k, 2.0))
        skews.append(_core.Nonsingular(eps * 30.0**i, eps * 2.0**i, 0.1 * 10.0**i))
    return _core.Controller(
        n,
        dt,
        laws,
        skew=skews,
        constraint="longitudinal",
        eps=30.0 * eps * 3.0 ** (n - 3),
        **common,
    )
