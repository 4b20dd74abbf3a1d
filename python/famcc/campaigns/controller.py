"""A campaign's controller settings: the controller, its preset accuracy and its deadline."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from famcc import _core, bounds
from famcc.metrics import preset_accuracy


def _controller(config: Mapping[str, Any], overrides: Mapping[str, float]) -> Any:
    kw = dict(config)
    order, dt = kw.pop("order"), kw.pop("dt")
    kw.update(overrides)
    return _core.Controller(order, dt, **kw)


_preset_accuracy = preset_accuracy


def _corollary_time(cfg: Mapping[str, Any], z1_0: np.ndarray) -> np.ndarray:
    """``T'`` of the paper's corollaries for the design (per case for the finite-time law)."""
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
