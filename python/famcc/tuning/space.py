"""famcc's design space with the extended observer: the parameter ranges a
search samples (:class:`Space`) and the controller at one of their points
(:func:`observer_controller`).

:func:`famcc.tune` and ``famcc compare`` search it alike. A point holds the
stage law (``family``: ``"finite-time"`` ``FiniteTime(k, p)`` on the lateral
constraint, ``"linear"`` ``Linear(k)`` stages on the longitudinal one,
``"variable-exponent"`` or ``"rfc"`` as the paper's examples 2 and 3, scaled by
``k``), the envelope's ``eps`` and preset time ``settle_time``, the law's
``k_u`` and the observer's ``mu`` (``obs_mu``), or, for the linear family,
the poles' ratios to ``k`` (``u_ratio``, ``obs_ratio``); ``b0`` is the
observer's nominal input gain, with its sign (docs/observer.md).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from famcc import _core

__all__ = ["Space", "latin_hypercube", "observer_controller"]


@dataclass(frozen=True)
class Space:
    """A controller's documented parameter ranges; ``params(u)`` maps the unit cube.

    ``ranges`` maps each name to ``(lo, hi, log)``; ``fixed`` holds the
    parameters that are not searched (e.g. ADRC's ``b0 = G``); ``default`` is
    the controller's documented default setting (the paper's design for famcc,
    the textbook pole placement for the peers), the first candidate the tuning
    tries.
    """

    kind: str
    ranges: dict[str, tuple[float, float, bool]]
    fixed: dict[str, Any] = field(default_factory=dict)
    default: dict[str, float] = field(default_factory=dict)
    #: ``(name, factor)``: the parameter and factor that make a candidate slower
    #: (famcc's observer: ``mu`` x 4), for the noise check (compare/tuning.py).
    slower: tuple[str, float] | None = None

    @property
    def dims(self) -> int:
        return len(self.ranges)

    def params(self, u: Sequence[float] | np.ndarray) -> dict[str, Any]:
        """The parameters at the point ``u`` of ``[0, 1]^dims``."""
        out = dict(self.fixed)
        for x, (name, (lo, hi, log)) in zip(u, self.ranges.items()):
            x = min(max(float(x), 0.0), 1.0)
            out[name] = lo * (hi / lo) ** x if log else lo + (hi - lo) * x
        return out

    def slowed(self, u: np.ndarray) -> np.ndarray | None:
        """The point ``u`` with :attr:`slower` applied (clipped to its range), or
        None when there is none or it changes nothing."""
        if self.slower is None:
            return None
        name, factor = self.slower
        p = self.params(u)
        out = self.unit({**p, name: p[name] * factor})
        return None if np.array_equal(out, u) else out

    def unit(self, params: dict[str, float]) -> np.ndarray:
        """The point of the unit cube of ``params`` (clipped to the ranges)."""
        out = []
        for name, (lo, hi, log) in self.ranges.items():
            v = float(params[name])
            x = math.log(v / lo) / math.log(hi / lo) if log else (v - lo) / (hi - lo)
            out.append(min(max(x, 0.0), 1.0))
        return np.array(out)


def latin_hypercube(rng: np.random.Generator, n: int, d: int) -> np.ndarray:
    """``n`` Latin-hypercube points in ``[0, 1]^d``."""
    out = np.empty((n, d))
    for j in range(d):
        out[:, j] = (rng.permutation(n) + rng.random(n)) / n
    return out


def observer_controller(p: dict[str, Any], dt: float, u_limits: Sequence[float]) -> Any:
    """The :class:`famcc.Controller` with the extended observer at the point ``p``.

    The observer has the nominal gain ``p["b0"]`` (a negative one gives the
    negative control direction), its measurement on the first-order hold once
    ``mu < 10 dt``; the cancellation is bounded by the actuator's range.

    Examples
    --------
    >>> p = {"family": "finite-time", "order": 2, "b0": 2.0, "k": 10.0, "p": 0.7,
    ...      "settle_time": 0.5, "eps": 0.01, "k_u": 5.0, "obs_mu": 0.01}
    >>> ctrl = observer_controller(p, 1e-3, (-5.0, 5.0))
    >>> ctrl.order, "direction" in ctrl.config()        # the default, positive
    (2, False)
    >>> observer_controller({**p, "b0": -2.0}, 1e-3, (-5.0, 5.0)).config()["direction"]
    'negative'
    """
    n = int(p["order"])
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
    common: dict[str, Any] = {
        "settle_time": p["settle_time"],
        "k_u": k_u,
        "observer": obs,
        "cancellation_limit": delta if math.isfinite(delta) else 100.0 * k_u,
        "latch": "authors",
    }
    if p["b0"] < 0:
        common["direction"] = "negative"
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
