"""What a figure needs to know about a run: accuracy, ``T_s``, constraint, laws, window."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from famcc import _core
from famcc._common import Signal
from famcc.verdicts import STARTUP


@dataclass
class _View:
    """A run and what its panels need: accuracy, ``T_s``, constraint, laws, window."""

    r: Any
    eps: float | None
    settle_time: float | None
    constraint: str | None
    laws: list[Any] = field(default_factory=list)
    show_limits: bool = False
    window: tuple[float, float] | None = None

    @property
    def t(self) -> np.ndarray:
        return np.asarray(self.r.t, dtype=float)

    @property
    def order(self) -> int:
        return int(self.r.z.shape[1])

    @property
    def out(self) -> Signal:
        return getattr(self.r, "output", None) or Signal("y")

    @property
    def inp(self) -> Signal:
        return getattr(self.r, "input", None) or Signal("u")

    @property
    def axis(self) -> int:
        """0 when the constraint acts in the x direction (LaMC, OMC), 1 for LoMC."""
        if self.constraint in ("lateral", "oblique"):
            return 0
        if self.constraint == "longitudinal" or self.r.nominal_bounds is None:
            return 1
        # a controller without a configuration: the direction whose bound is used
        nb = np.abs(np.nan_to_num(np.asarray(self.r.nominal_bounds, dtype=float)))
        return 0 if nb[:, 0].max() > 0 and nb[:, 1].max() == 0 else 1

    def mask(self, after: float | None = None) -> np.ndarray:
        """Samples inside the window; without a window, those from ``after`` on."""
        t = self.t
        if self.window is not None:
            m = (t >= self.window[0]) & (t <= self.window[1])
        elif after is not None:
            m = t >= after
        else:
            return np.ones_like(t, dtype=bool)
        return m if m.sum() >= 2 else np.ones_like(t, dtype=bool)

    def zoom_start(self) -> float | None:
        """``T_s`` when the accuracy panels start there (no window, ``T_s`` in the run)."""
        ts = self.settle_time
        if self.window is None and ts is not None and ts < float(self.t[-1]):
            return ts
        return None

    def episodes(self) -> list[tuple[float, float]]:
        return list(self.r.saturation_episodes())


def _laws_from(feedback: Any, skew: Any, order: int) -> list[Any]:
    """The callables ``h_m`` of the stages (None where the binding cannot build one)."""
    n = max(order - 1, 0)
    fbs = list(feedback) if isinstance(feedback, (list, tuple)) else [feedback] * n
    sks = list(skew) if isinstance(skew, (list, tuple)) else [skew] * n
    laws: list[Any] = []
    for fb, sk in zip(fbs, sks):
        try:
            laws.append(_core.skewed(fb, sk))
        except (TypeError, ValueError):  # a law the binding does not know: draw no curve
            laws.append(None)
    return laws


def _view(
    result: Any, eps: float | None = None, window: tuple[float, float] | None = None
) -> _View:
    """What the general figure knows of a run: from its recorded controller configuration."""
    cfg = getattr(result, "controller_config", None) or {}
    accuracy = eps if eps is not None else getattr(result, "accuracy", None)
    laws = _laws_from(cfg.get("feedback"), cfg.get("skew"), result.z.shape[1]) if cfg else []
    show = False
    if result.u_limits is not None:  # limits in view when saturated or near the input
        late = np.asarray(result.t) >= STARTUP
        late = late if late.sum() >= 2 else np.ones_like(late)
        u_late = float(np.max(np.abs(np.asarray(result.u)[late])))
        near = max(abs(x) for x in result.u_limits) <= 3.0 * u_late
        show = near or bool(np.any(np.asarray(result.saturated)[late]))
    if window is not None:
        t0, t1 = (float(w) for w in window)
        if not (math.isfinite(t0) and math.isfinite(t1) and t0 < t1):
            raise ValueError(f"window must be (t0, t1) with t0 < t1, got {window!r}")
        window = (t0, t1)
    return _View(
        result,
        accuracy,
        getattr(result, "settle_time", None),
        getattr(result, "constraint", None),
        laws,
        show,
        window,
    )


def _scenario_view(scenario: Any, result: Any) -> _View:
    kw = scenario.controller_kwargs
    return _View(
        result,
        float(scenario.eps_z),
        float(scenario.settle_time),
        kw.get("constraint", "longitudinal"),
        _laws_from(kw.get("feedback"), kw.get("skew"), result.z.shape[1]),
        bool(scenario.saturated),
    )


def constrained_offset(
    result: Any, constraint: str | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(offset, flexible bound, nominal bound)`` in the constraint's direction.

    The offset is what the constraint bounds: the horizontal offset (``s_fn`` at
    order 2) from the zero manifold for LaMC and OMC, the manifold value ``s`` for
    LoMC. The LaMC/OMC offset is recovered as ``xi~ * x~_U``, which equals the
    controller's offset exactly unless ``xi~`` was clamped; the bounds are the
    upper ones (the lower ones are their negatives).

    Parameters
    ----------
    result : famcc.SimResult
        A recorded run (``record=True``).
    constraint : str, optional
        ``"lateral"``, ``"longitudinal"`` or ``"oblique"``; default: the
        controller's, as recorded in ``result``.
    """
    if result.bounds is None or result.nominal_bounds is None:
        raise ValueError("result has no diagnostics; simulate with record=True")
    view = _view(result)
    if constraint is not None:
        view.constraint = constraint
    return _offset(view)


def _offset(v: _View) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    ax = v.axis
    flex = np.asarray(v.r.bounds, dtype=float)[:, ax]
    nom = np.asarray(v.r.nominal_bounds, dtype=float)[:, ax]
    if ax == 1:
        offset = np.asarray(v.r.s, dtype=float)
    else:
        offset = np.asarray(v.r.xi, dtype=float) * flex
    return offset, flex, nom
