"""A campaign's controller settings: the controller, its preset accuracy and its deadline."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from famcc.simulation import _as_float


def _controller(config: Mapping[str, Any], overrides: Mapping[str, float]) -> Any:
    import famcc

    kw = dict(config)
    order, dt = kw.pop("order"), kw.pop("dt")
    kw.update(overrides)
    return famcc.Controller(order, dt, **kw)


def _preset_accuracy(cfg: Mapping[str, Any]) -> float | None:
    order, kind = cfg.get("order"), cfg.get("constraint")
    if order == 1 or (order == 2 and kind == "lateral"):
        return _as_float(cfg.get("eps"))
    skews = cfg.get("skew")
    first = skews[0] if isinstance(skews, (list, tuple)) and skews else skews
    eps_z = getattr(first, "eps_z", None)
    return _as_float(eps_z)


def _corollary_time(cfg: Mapping[str, Any], z1_0: np.ndarray) -> np.ndarray:
    """``T'`` of the paper's corollaries for the design (per case for the finite-time law)."""
    from famcc import bounds

    laws = cfg.get("feedback") or []
    laws = list(laws) if isinstance(laws, (list, tuple)) else [laws]
    names = {type(law).__name__ for law in laws}
    if laws and names == {"FixedTime"}:
        stages = [(law.alpha, law.p, law.beta, law.q) for law in laws]
        return np.full(len(z1_0), bounds.fixed_time(stages))
    if len(laws) == 1 and names == {"VariableExponent"}:
        law = laws[0]
        return np.full(len(z1_0), bounds.variable_exponent(law.k, law.r_b, law.r_1, law.r_t))
    if len(laws) == 1 and names == {"FiniteTime"}:
        law = laws[0]
        return np.array([bounds.finite_time(law.k, law.p, float(z)) for z in z1_0])
    raise ValueError(
        "settle_by='bound' needs a design with a corollary bound (FixedTime stages, one "
        f"VariableExponent or one FiniteTime stage), got {sorted(names) or 'no laws'}: "
        "give settle_by in seconds"
    )
