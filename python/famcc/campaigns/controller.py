"""A campaign's controller settings: the controller, its preset accuracy and its deadline."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from famcc import _core
from famcc.metrics import preset_accuracy


def _spec(config: _core.ControllerSpec | Mapping[str, Any]) -> _core.ControllerSpec:
    """The spec of a configuration (a spec is itself)."""
    if isinstance(config, _core.ControllerSpec):
        return config
    return _core.ControllerSpec.from_config(dict(config))


def _controller(
    config: _core.ControllerSpec | Mapping[str, Any], overrides: Mapping[str, float]
) -> Any:
    """A fresh controller of the configuration with a case's settings (``k_u``, ``eps``, ...):
    a copy of the spec, changed where the case says."""
    kw: dict[str, Any] = dict(overrides)
    return _spec(config).replace(**kw).build()


_preset_accuracy = preset_accuracy


def _corollary_time(cfg: _core.ControllerSpec | Mapping[str, Any], z1_0: np.ndarray) -> np.ndarray:
    """``T'`` of the paper's corollaries for the design (per case for the finite-time law):
    famcc-core's rule (``Config::corollary_time``)."""
    t_prime = _spec(cfg).corollary_time(np.asarray(z1_0, dtype=np.float64))
    if t_prime is None:
        conf = cfg.config() if isinstance(cfg, _core.ControllerSpec) else cfg
        laws = conf.get("feedback") or []
        laws = list(laws) if isinstance(laws, (list, tuple)) else [laws]
        names = sorted({type(law).__name__ for law in laws})
        raise ValueError(
            "settle_by='bound' needs a design with a corollary bound (FixedTime stages, one "
            f"VariableExponent or one FiniteTime stage), got {names or 'no laws'}: "
            "give settle_by in seconds"
        )
    return np.asarray(t_prime, dtype=np.float64)
