"""The checks of a simulation's arguments, and what :func:`famcc.simulate` runs with.

:func:`check_run` validates every argument of :func:`famcc.simulate` (each error
names its argument) and returns a :class:`Setup`: the sample grid, the
reference's table, the sampled noise and disturbance, the limits, the initial
state and the names of the signals. :func:`famcc.joints.simulate_joints` shares
the per-argument checks.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from famcc._common import Signal
from famcc.plants.base import is_real
from famcc.signals import reference_table, sampled, source

__all__ = ["Setup", "check_limits", "check_run", "check_substeps", "describe_controller_of"]


def check_limits(u_limits: Any, label: str = "u_limits") -> tuple[float, float] | None:
    """``u_limits`` as ``(lo, hi)`` with ``lo < hi``, or None; ValueError otherwise."""
    if u_limits is None:
        return None
    try:
        lo, hi = (float(v) for v in u_limits)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{label} must be None or a pair (lo, hi), got {u_limits!r}") from exc
    if not (lo < hi) or math.isnan(lo) or math.isnan(hi):
        raise ValueError(f"{label} must satisfy lo < hi, got {u_limits!r}")
    return (lo, hi)


def check_substeps(substeps: Any) -> int:
    """``substeps`` when it is an integer >= 1, else ValueError."""
    if not isinstance(substeps, (int, np.integer)) or isinstance(substeps, bool) or substeps < 1:
        raise ValueError(f"substeps must be an integer >= 1, got {substeps!r}")
    return int(substeps)


def describe_controller_of(controller: Any) -> tuple[str, dict[str, Any] | None]:
    """``(repr, config)`` of the controller at the start of the run (config may be None)."""
    text = repr(controller)
    config = getattr(controller, "config", None)
    cfg = None
    if callable(config):
        try:
            value = config()
        except (TypeError, ValueError, AttributeError, RuntimeError):
            value = None  # a duck-typed controller's config(): then no configuration
        cfg = dict(value) if isinstance(value, dict) else None
    return text, cfg


@dataclass(frozen=True)
class Setup:
    """A checked simulation: what the loop and the result are built from.

    ``t`` holds the ``samples = round(t_end / dt) + 1`` sample times, ``table``
    the reference and its derivatives at them (``ref_order`` of them known),
    ``noise`` and ``disturbance`` their per-sample values (None: none).
    """

    dt: float
    order: int
    t: np.ndarray
    table: np.ndarray
    ref_order: int
    substeps: int
    limits: tuple[float, float] | None
    noise: np.ndarray | None
    disturbance: np.ndarray | None
    x0: np.ndarray
    diverge_at: float | None
    output: Signal
    input: Signal
    controller_repr: str
    controller_config: dict[str, Any] | None

    @property
    def samples(self) -> int:
        """The number of samples, ``t_0 = 0`` and the last included."""
        return len(self.t)


def _check_loop(plant: Any, controller: Any, t_end: Any, record: bool) -> tuple[float, int, int]:
    """``(dt, order, steps)`` of a plant and a controller that fit together."""
    for attr in ("dt", "order", "step"):
        if not hasattr(controller, attr):
            raise ValueError(f"controller must have an attribute {attr!r}")
    dt = controller.dt
    if not is_real(dt) or not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"controller.dt must be a finite number > 0, got {dt!r}")
    dt = float(dt)
    n = getattr(plant, "order", None)
    moves = callable(getattr(plant, "rhs", None)) or callable(getattr(plant, "advance", None))
    if not isinstance(n, (int, np.integer)) or n < 1 or not moves:
        raise ValueError(
            "plant must have an integer order >= 1 and an rhs(t, x, u) method (or, for a "
            "plant that advances itself, advance(t, x, u, dt))"
        )
    n = int(n)
    if controller.order != n:
        raise ValueError(f"controller.order ({controller.order}) must equal the plant order ({n})")
    if record and not hasattr(controller, "diagnostics"):
        raise ValueError("controller has no attribute 'diagnostics'; pass record=False")
    if not is_real(t_end) or not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0, got {t_end!r}")
    steps = round(t_end / dt)
    if steps < 1:
        raise ValueError(f"t_end ({t_end}) must be at least half a sample period dt ({dt})")
    return dt, n, steps


def _check_start(plant: Any, n: int, table: np.ndarray, diverge_at: Any) -> np.ndarray:
    """The plant's initial state, checked against ``diverge_at``."""
    if diverge_at is not None and not (
        is_real(diverge_at) and math.isfinite(diverge_at) and diverge_at > 0
    ):
        raise ValueError(f"diverge_at must be None or a finite number > 0, got {diverge_at!r}")
    x0 = np.array(plant.x0, dtype=np.float64).reshape(-1)
    if diverge_at is not None:
        e0 = abs(float(x0[0]) - float(table[0, 0]))
        if not e0 <= diverge_at:
            raise ValueError(
                f"diverge_at ({diverge_at}) must be at least the initial error |z1(0)| ({e0:.6g})"
            )
    return x0


def check_run(
    plant: Any,
    controller: Any,
    t_end: Any,
    reference: Any,
    u_limits: Any,
    substeps: Any,
    record: bool,
    output: Any,
    input: Any,
    noise: float | Callable[[float], float] | None,
    seed: int | np.random.Generator | None,
    disturbance: float | Callable[[float], float] | None,
    diverge_at: Any,
) -> Setup:
    """Every argument of :func:`famcc.simulate` checked (ValueError naming the bad one)."""
    dt, n, steps = _check_loop(plant, controller, t_end, record)
    substeps = check_substeps(substeps)
    limits = check_limits(u_limits)
    t = np.arange(steps + 1) * dt
    table, ref_order = reference_table(reference, n, t)
    noise_fn = source("noise", noise, seed)
    dist_fn = source("disturbance", disturbance, None)
    x0 = _check_start(plant, n, table, diverge_at)
    out_signal = Signal.of(output if output is not None else getattr(plant, "output", None), "y")
    in_signal = Signal.of(input if input is not None else getattr(plant, "input", None), "u")
    ctrl_repr, ctrl_config = describe_controller_of(controller)
    if x0.size < 1 or not np.all(np.isfinite(x0)):
        # at least the output; a plant may hold more states than its order
        raise ValueError(f"plant.x0 must be finite numbers (at least 1), got {x0.tolist()}")
    return Setup(
        dt=dt,
        order=n,
        t=t,
        table=table,
        ref_order=ref_order,
        substeps=substeps,
        limits=limits,
        noise=sampled(noise_fn, t),
        disturbance=sampled(dist_fn, t),
        x0=x0,
        diverge_at=None if diverge_at is None else float(diverge_at),
        output=out_signal,
        input=in_signal,
        controller_repr=ctrl_repr,
        controller_config=ctrl_config,
    )
