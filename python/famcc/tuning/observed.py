"""The second half of :func:`famcc.tune`'s search: famcc with the extended
observer (:mod:`famcc.tuning.space`), its ranges in the units of the
requirement.

The rules' grid (:func:`famcc.design` with its knobs) is the start; this
search adds the controllers the rules do not reach: the stage law's gain and
exponent, the envelope, ``k_u`` and an observer with the nominal gain
``b0`` (the measured gain, or the one given) that estimates and cancels the
lumped term. It samples the default, a Latin hypercube and rounds around the
best, as ``famcc compare`` does for every controller.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from famcc.tuning.rules import Design
from famcc.tuning.space import Space, latin_hypercube, observer_controller

__all__ = ["BUDGET", "candidate", "requirement_space", "search"]

#: Runs of the observer search: the default, a Latin hypercube of
#: ``BUDGET // 2 - 1`` and two rounds around the best.
BUDGET = 18


def requirement_space(
    order: int,
    dt: float,
    eps: float,
    settle_time: float,
    b0: float,
    hold: float,
    limits: tuple[float, float],
) -> Space:
    """The observer space for a requirement ``(eps, settle_time)``.

    With ``T`` the required settling time: the law's ``k`` in ``[1, 100] / T``;
    the envelope's preset time in ``[0.1, 0.9] T``; its ``eps`` in
    ``[0.05, 1]`` of the required one. At order 2 ``FiniteTime(k, p)``, ``p``
    in ``[0.5, 0.95]``, ``k_u`` in ``[0.3, 100] H`` (``H`` the hold input, at
    least 5 % of the range) and the observer's ``mu`` in ``[2 dt, T / 5]``;
    elsewhere ``Linear(k)`` stages with the pole ratios of
    :func:`famcc.compare.famcc_candidates`. All log-uniform but ``p``.

    Examples
    --------
    >>> sp = requirement_space(2, 1e-3, 0.01, 1.0, 2.0, 0.5, (-5.0, 5.0))
    >>> round(sp.params(sp.unit(sp.default))["k"], 9), sp.fixed["b0"]
    (5.0, 2.0)
    """
    t_req, lo, hi = float(settle_time), float(limits[0]), float(limits[1])
    h = max(float(hold), 0.05 * (hi - lo))
    fixed = {"order": int(order), "band": float(eps), "b0": float(b0)}
    common = {
        "k": (1.0 / t_req, 100.0 / t_req, True),
        "settle_time": (0.1 * t_req, 0.9 * t_req, True),
        "eps": (0.05 * eps, float(eps), True),
    }
    start = {"k": 5.0 / t_req, "settle_time": 0.5 * t_req, "eps": 0.5 * eps}
    if order == 2:
        return Space(
            "famcc",
            {
                **common,
                "p": (0.5, 0.95, False),
                "k_u": (0.3 * h, 100.0 * h, True),
                "obs_mu": (2.0 * dt, max(t_req / 5.0, 4.0 * dt), True),
            },
            {**fixed, "family": "finite-time"},
            {**start, "p": 0.7, "k_u": 10.0 * h, "obs_mu": max(t_req / 50.0, 2.0 * dt)},
        )
    return Space(
        "famcc",
        {**common, "u_ratio": (1.0, 30.0, True), "obs_ratio": (2.0, 10.0, True)},
        {**fixed, "family": "linear"},
        {**start, "u_ratio": 10.0, "obs_ratio": 5.0},
    )


def candidate(start: Design, params: dict[str, Any], dt: float, limits: Any) -> Design:
    """The :class:`Design` of one observer point: ``start``'s requirements, its
    parameters with ``observer_candidate`` (the point), and the point's
    controller as its spec (:meth:`Design.controller` builds it)."""
    ctrl = observer_controller(params, dt, limits)
    return Design(
        start.requirements,
        {**start.parameters, "observer_candidate": dict(params)},
        (),
        spec=ctrl.spec,
    )


def search(
    space: Space,
    evaluate: Callable[[dict[str, Any]], tuple[float, float]],
    seed: int,
    budget: int = BUDGET,
) -> None:
    """Sample ``space``: ``evaluate(params) -> (rank, objective)`` for each
    point (lower is better, rank first: 0 for a feasible run), the default
    first, then a Latin hypercube, then two rounds of Gaussian steps around the
    best so far."""
    rng = np.random.default_rng(seed)
    first = budget // 2
    points = np.vstack([space.unit(space.default), latin_hypercube(rng, first - 1, space.dims)])
    seen: list[tuple[tuple[float, float], np.ndarray]] = []
    for u in points:
        seen.append((evaluate(space.params(u)), u))
    left = budget - first
    for r in range(2):
        m = left // (2 - r)
        left -= m
        best = min(seen, key=lambda s: s[0])[1]
        for u in np.clip(best + rng.normal(0.0, 0.2 * 0.5**r, (m, space.dims)), 0.0, 1.0):
            seen.append((evaluate(space.params(u)), u))
