"""What :func:`famcc.tune` measures on the plant before it searches: the input
gain ``G`` (with its sign) and the holding input at the reference.

The gain comes from the plant's ``gain_and_drift`` where it works and from
input pulses (:func:`famcc.tuning.probe.pulse_gain`) where it does not (a
plant with an ``if`` or a table, one in a simulator, a black box). The holding
input is measured at the reference, in steady state: the plant's equilibrium
on a constant set point, else the input over the settled stretch of the
measuring run. A measuring run that diverges, or a gain that changes sign, is a
:class:`famcc.ConfigError` that says what to give instead.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np

from famcc import _core
from famcc._common import DesignWarning
from famcc.plants.stepped import BlackBox
from famcc.signals import Constant
from famcc.tuning import probe
from famcc.tuning.rules import design

__all__ = ["gain_at", "gains_along", "hold_from_run", "measure", "reference_value"]

#: States along the measuring run where the gain is measured by pulses.
PULSE_POINTS = 6
#: The measured gain and hold input are raised by this factor before the search
#: (a bound, not an estimate: the design's rules take ``|G|`` and ``|F/G|`` bounds).
MARGIN = 1.2


def reference_value(reference: Any) -> float | None:
    """The set point of a constant reference, else None."""
    if isinstance(reference, Constant):
        return reference.value
    if isinstance(reference, (int, float)) and not isinstance(reference, bool):
        return float(reference)
    return None


def _exact_gain(plant: Any, t: float, x: np.ndarray) -> float | None:
    """``G`` from ``gain_and_drift``, or None where the plant cannot give it."""
    fn = getattr(plant, "gain_and_drift", None)
    if not callable(fn):
        return None
    try:
        g, _ = fn(float(t), x)
        g = float(g)
    except Exception:  # noqa: BLE001 - a plant's own failure means: measure instead
        return None
    return g if math.isfinite(g) else None


def gain_at(
    plant: Any, dt: float, limits: tuple[float, float], x: np.ndarray | None = None, t: float = 0.0
) -> tuple[float, str]:
    """``G`` at ``x`` (None: the plant's ``x0``) and ``t``: exact where the plant
    gives it, else by a pulse pair; with how it was obtained (or what went wrong)."""
    state = np.asarray(plant.x0 if x is None else x, dtype=float)
    exact = _exact_gain(plant, t, state)
    if exact is not None:
        return exact, "gain_and_drift"
    g, note = probe.pulse_gain(plant, dt, limits, x=x, t0=t)
    return g, note or "pulse"


def gains_along(
    plant: Any, res: Any, dt: float, limits: tuple[float, float], extra: list[float]
) -> float:
    """The signed gain of largest ``|G|`` along the measuring run ``res`` (and
    ``extra`` values measured elsewhere). A gain that changes sign is a
    :class:`famcc.ConfigError`: the controller needs one control direction."""
    gains = [g for g in extra if math.isfinite(g)]
    n = len(res.t)
    if _exact_gain(plant, 0.0, np.asarray(res.x[0], dtype=float)) is not None:
        rows = range(0, n, max(1, n // 400))
        exact = (_exact_gain(plant, float(res.t[k]), res.x[k]) for k in rows)
        gains += [math.nan if g is None else g for g in exact]  # a zero gain is kept
    elif not isinstance(plant, BlackBox):  # a black box's state is hidden: x0 only
        rows = range(n // PULSE_POINTS, n, max(1, n // PULSE_POINTS))
        gains += [gain_at(plant, dt, limits, res.x[k], float(res.t[k]))[0] for k in rows]
    gains = [g for g in gains if math.isfinite(g)]
    if gains and min(gains) < 0.0 < max(gains):
        raise _core.ConfigError(
            f"gain: the plant's input gain G changes sign along tune's measuring run "
            f"(from {min(gains):.4g} to {max(gains):.4g}); famcc needs one control direction "
            "(the sign of G) over the operating range: give gain= with the sign that holds "
            "near the reference, or narrow the range",
            parameter="gain",
            rule="G keeps one sign along the run",
        )
    return max(gains, key=abs) if gains else math.nan


def check_run(res: Any, g0: float) -> None:
    """A :class:`famcc.ConfigError` when the measuring run cannot be trusted (it
    failed or diverged)."""
    if res is None or res.diverged_at is not None:
        when = "" if res is None else f" at t = {res.diverged_at:.4g} s"
        raise _core.ConfigError(
            f"gain: tune's measuring run (the design for G = {g0:.4g}, the gain at x0) "
            f"diverged{when}, so the gain and hold input it would measure are not trusted: "
            "give gain= (with its sign) and hold_input=, or widen u_limits or lengthen "
            "settle_time",
            parameter="gain",
            rule="the measuring run must not diverge",
        )


def hold_from_run(res: Any, eps: float, limits: tuple[float, float]) -> tuple[float, str | None]:
    """The holding input read from the measuring run's settled stretch, and
    None; where the run never settled, the largest input over its second half
    and a warning that says so (the value then bounds the transient, not the
    steady state)."""
    settled = probe.settled_input(res, 2.0 * eps)
    if settled is not None:
        return settled, None
    t = np.asarray(res.t, dtype=float)
    late = t >= 0.5 * float(t[-1])
    negfg = res.neg_f_over_g
    source = negfg if negfg is not None else res.u
    value = float(np.nanmax(np.abs(np.asarray(source, dtype=float)[late])))
    saturated = float(np.mean(np.isin(np.asarray(res.u)[late], limits)))
    return value, (
        f"famcc.tune: hold_input: the measuring run never settled within 2 eps = {2 * eps:g} "
        f"of the reference over its second half ({100 * saturated:.0f} % of it saturated), so "
        f"the holding input ({value:.4g}) is the largest over the transient, not the steady "
        "state: give hold_input= if you know it"
    )


def measure(
    plant: Any,
    g: float | None,
    h: float | None,
    run: Any,
    limits: tuple[float, float],
    dt: float,
    order: int,
    eps: float,
    settle_time: float,
    noise_std: float,
    integral: bool | None,
    max_error: float,
    reference: Any,
    horizon: float,
) -> tuple[float, float, str | None]:
    """``(gain, hold input, warning)`` for :func:`famcc.tune`, the given ``g`` or
    ``h`` kept: the gain at ``x0`` designs a measuring run (``run(design,
    measure=True)``); the gain of largest ``|G|`` along it and the holding input
    at the reference, each :data:`MARGIN` over the measured value, are the
    search's. ``warning`` says when the holding input could not be read in
    steady state."""
    g0, how = gain_at(plant, dt, limits)
    if not (math.isfinite(g0) and g0 != 0.0):
        raise _core.ConfigError(
            f"gain: the plant's input gain at x0 is {g0:g} ({how}), so tune cannot tell the "
            "control direction or the loop's rate: give gain= (with its sign)",
            parameter="gain",
            rule="G(0, x0) finite and nonzero",
        )
    r = reference_value(reference)
    eq = None
    if h is None and r is not None:
        eq = probe.equilibrium_input(plant, r, np.linspace(0.0, horizon, 3), dt)
    guess = h if h is not None else (abs(eq[0]) if eq is not None else 0.0)
    warning = None
    for _ in range(2):  # a second run from the first's hold input, if unsettled
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DesignWarning)
            first = design(
                order,
                dt,
                u_limits=limits,
                eps=eps,
                settle_time=settle_time,
                hold_input=guess,
                gain=g0 * 1.5,
                noise_std=noise_std,
                integral=integral,
                max_error=max_error,
            )
            res = run(first, measure=True)
        check_run(res, g0)
        if h is not None or eq is not None:
            break
        guess, warning = hold_from_run(res, eps, limits)
        if warning is None:
            break
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        extra = [g0]
        if eq is not None:
            extra.append(gain_at(plant, dt, limits, eq[1], horizon)[0])
        gm = gains_along(plant, res, dt, limits, extra)
    if h is None:
        h = MARGIN * (abs(eq[0]) if eq is not None else guess)
    if g is None:
        g = MARGIN * (gm if math.isfinite(gm) else g0 * 1.5)
    return float(g), float(h), warning
