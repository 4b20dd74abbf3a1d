"""Metrics of a closed-loop run: functions over a :class:`famcc.SimResult`'s data.

Every metric is a function of the recorded arrays (``t``, ``z``, ``v``, ``u``,
``u_limits`` and, when recorded, the controller's diagnostics); the result
object's methods of the same names call these. Settling means: the first time
after which ``|z1| < eps`` holds to the end of the horizon.

>>> import numpy as np, famcc
>>> t = np.array([0.0, 0.1, 0.2, 0.3, 0.4])
>>> z1 = np.array([1.0, 0.05, 0.2, 0.01, 0.0])
>>> r = famcc.SimResult(t=t, y=z1, y_d=0 * t, x=z1[:, None], z=z1[:, None],
...                     v=0 * t, u=0 * t, dt=0.1)
>>> first_entry(r, 0.1), settling_time(r, 0.1)
(0.1, 0.3)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from famcc import _core
from famcc.plants.base import is_real

__all__ = [
    "as_float",
    "check_eps",
    "expanded_fraction",
    "expanded_unsaturated_fraction",
    "first_entry",
    "iae",
    "largest_expansion",
    "last_outside",
    "last_saturation_end",
    "max_abs_xi",
    "max_abs_xi_nominal",
    "never_settled",
    "nominal_return_time",
    "preset_accuracy",
    "ripple",
    "rms_u",
    "saturated",
    "saturated_fraction",
    "saturation_episodes",
    "settling_time",
    "steady_rms",
    "tail_max",
    "tv_u_per_s",
    "z1",
    "z1_ripple",
]

Run = Any  # a famcc.SimResult, or anything with its attributes


def as_float(value: Any) -> float | None:
    """``float(value)`` for a real number, else None."""
    return float(value) if is_real(value) else None


def check_eps(eps: Any) -> float:
    """``eps`` as a float when it is a finite number > 0, else ValueError."""
    if not (is_real(eps) and eps > 0 and math.isfinite(eps)):
        raise ValueError(f"eps must be a finite number > 0, got {eps!r}")
    return float(eps)


def preset_accuracy(config: Mapping[str, Any] | None) -> float | None:
    """The output accuracy ``eps_z`` a controller configuration presets, or None.

    famcc-core's rule (``Config::output_accuracy``, through
    :meth:`famcc.ControllerSpec.output_accuracy`): the controller's ``eps``
    bounds the constrained offset, which is ``|z1|`` itself only at order 1
    (``s = z1``) and for LaMC at order 2 (``eps_x = eps_z``, Corollary 1);
    otherwise a skewed first stage (SSMD or NSMD) presets its ``eps_z``
    (Corollaries 2 and 3). With integral action, or for a configuration that
    is not a famcc controller's, None.
    """
    if not config or "order" not in config or "dt" not in config:
        return None
    try:
        spec = _core.ControllerSpec.from_config(dict(config))
        return spec.output_accuracy()
    except (_core.ConfigError, TypeError, ValueError):
        return None  # not a configuration famcc-core reads: it presets nothing


def z1(r: Run) -> np.ndarray:
    """The tracking error ``y - y_d``."""
    return np.asarray(r.z)[:, 0]


def last_outside(values: np.ndarray, eps: float) -> int:
    """Index of the last sample with ``|value| >= eps`` (NaN counts as outside); -1 if none."""
    outside = np.flatnonzero(~(np.abs(values) < eps))
    return int(outside[-1]) if outside.size else -1


def settling_time(r: Run, eps: float) -> float | None:
    """First time after which ``|z1| < eps`` holds to the end of the horizon.

    That is the sample time following the last sample with ``|z1| >= eps``;
    0.0 when every sample is inside; None when the last sample is outside.
    """
    eps = check_eps(eps)
    last = last_outside(z1(r), eps)
    if last < 0:
        return 0.0
    if last == len(r.t) - 1:
        return None
    return float(r.t[last + 1])


def first_entry(r: Run, eps: float) -> float | None:
    """First sample time with ``|z1| < eps`` (None if never)."""
    eps = check_eps(eps)
    inside = np.flatnonzero(np.abs(z1(r)) < eps)
    return float(r.t[inside[0]]) if inside.size else None


def _after_settling(r: Run, values: np.ndarray, eps: float) -> np.ndarray | None:
    ts = settling_time(r, eps)
    if ts is None:
        return None
    return values[np.asarray(r.t) >= ts]


def steady_rms(r: Run, eps: float) -> float | None:
    """RMS of ``z1`` from the settling time to ``eps`` on (None if never settled)."""
    tail = _after_settling(r, z1(r), eps)
    return float(np.sqrt(np.mean(np.square(tail)))) if tail is not None and tail.size else None


def ripple(r: Run, eps: float) -> float | None:
    """Peak-to-peak of the applied ``u`` from the settling time to ``eps`` on.

    The chattering a sampled loop keeps once settled (a law with an infinite
    slope at 0 ripples, docs/design.md §7.2). For a moving reference or a
    varying load it includes the input's own swing. None if never settled.
    """
    tail = _after_settling(r, np.asarray(r.u), eps)
    return float(np.max(tail) - np.min(tail)) if tail is not None and tail.size else None


def z1_ripple(r: Run, eps: float) -> float | None:
    """Peak-to-peak of ``z1`` (output unit) from the settling time to ``eps`` on.

    The residual oscillation of the error once settled: chattering of the
    loop, or noise fed through it. None if never settled.
    """
    tail = _after_settling(r, z1(r), eps)
    return float(np.max(tail) - np.min(tail)) if tail is not None and tail.size else None


def max_abs_xi(r: Run) -> float | None:
    """``max |xi|`` over the run (None when diagnostics were not recorded)."""
    if r.xi is None or len(r.xi) == 0:
        return None
    return float(np.max(np.abs(r.xi)))


def max_abs_xi_nominal(r: Run) -> float | None:
    """``max |xi|`` of the nominal constraint variable (None when not recorded).

    Above 1 the state left the nominal constraint set; only the flexible
    boundary then kept ``|xi~| < 1``.
    """
    if r.xi_nominal is None or len(r.xi_nominal) == 0:
        return None
    return float(np.max(np.abs(r.xi_nominal)))


def saturated(r: Run) -> np.ndarray:
    """Per sample: True where the commanded ``v`` lay outside ``u_limits``."""
    v = np.asarray(r.v)
    if r.u_limits is None:
        return np.zeros(v.shape, dtype=bool)
    lo, hi = r.u_limits
    out: np.ndarray = (v < lo) | (v > hi)
    return out


def saturated_fraction(r: Run) -> float:
    """Fraction of samples whose ``v`` lay outside ``u_limits`` (0 without limits)."""
    sat = saturated(r)
    return float(np.mean(sat)) if sat.size else 0.0


def expanded_fraction(r: Run) -> float | None:
    """Fraction of samples with the flexible bounds expanded (None when not recorded)."""
    if r.expanded is None or len(r.expanded) == 0:
        return None
    return float(np.mean(np.asarray(r.expanded, dtype=bool)))


def expanded_unsaturated_fraction(r: Run) -> float | None:
    """Fraction of samples expanded while ``v`` lay inside the limits.

    There the preset accuracy was given up although the actuator had
    headroom: a sign of ``k_u`` too small for the plant, or of a sample rate too
    low for the design. None when not recorded.
    """
    if r.expanded is None or len(r.expanded) == 0:
        return None
    return float(np.mean(np.asarray(r.expanded, dtype=bool) & ~saturated(r)))


def saturation_episodes(r: Run) -> list[tuple[float, float]]:
    """Runs of consecutive saturated samples as ``(start, end)`` times.

    An episode covers the hold intervals ``[t_k, t_k + dt)`` of its samples, so
    ``end`` is the time of the first unsaturated sample after the run (clipped
    to the last sample time when the run reaches the end of the horizon).
    """
    sat = saturated(r).astype(np.int8)
    if not sat.any():
        return []
    edges = np.diff(np.concatenate(([0], sat, [0])))
    starts = np.flatnonzero(edges == 1)
    stops = np.flatnonzero(edges == -1)  # index after the last saturated one
    t = np.asarray(r.t)
    return [
        (float(t[a]), float(t[b]) if b < len(t) else float(t[-1])) for a, b in zip(starts, stops)
    ]


def last_saturation_end(r: Run) -> float | None:
    """End ``T_e`` of the last saturation episode (None if never saturated)."""
    episodes = saturation_episodes(r)
    return episodes[-1][1] if episodes else None


def largest_expansion(r: Run) -> float | None:
    """Largest ratio flexible / nominal bound over samples and directions.

    1.0 when never expanded; directions with a zero nominal bound (unused by the
    constraint) are ignored. None when diagnostics were not recorded.
    """
    if r.expansion is not None and len(r.expansion):
        return float(max(1.0, np.nanmax(np.asarray(r.expansion, dtype=float))))
    if r.bounds is None or r.nominal_bounds is None or r.expanded is None:
        return None
    if not np.any(r.expanded):
        return 1.0
    b = np.asarray(r.bounds, dtype=float)
    nb = np.asarray(r.nominal_bounds, dtype=float)
    ok = np.isfinite(b) & np.isfinite(nb) & (nb > 0)
    if not ok.any():
        return 1.0
    return float(max(1.0, np.max(b[ok] / nb[ok])))


def nominal_return_time(r: Run) -> float | None:
    """First time after the last expanded sample with bounds equal to nominal.

    None when the bounds never expanded or have not returned by the end.
    """
    if r.bounds is None or r.nominal_bounds is None or r.expanded is None:
        return None
    expanded = np.flatnonzero(np.asarray(r.expanded, dtype=bool))
    if expanded.size == 0:
        return None
    b = np.asarray(r.bounds, dtype=float)
    nb = np.asarray(r.nominal_bounds, dtype=float)
    equal = np.all(np.isclose(b, nb, rtol=1e-12, atol=0.0), axis=1)
    after = np.flatnonzero(equal[expanded[-1] + 1 :])
    if after.size == 0:
        return None
    return float(r.t[expanded[-1] + 1 + after[0]])


def iae(r: Run) -> float:
    """Integral of the absolute error, ``int |z1| dt`` (output unit times s).

    The trapezoidal rule over the samples of the whole run (the true error,
    not the measured one). NaN when ``z1`` is (a diverged run ends at its
    last finite sample, so it stays finite).
    """
    a = np.abs(z1(r))
    if a.size < 2:
        return 0.0
    return float(r.dt * (np.sum(a) - 0.5 * (a[0] + a[-1])))


def rms_u(r: Run) -> float:
    """Root mean square of the applied input ``u`` over the run (input unit).

    The control effort; for a plant that needs a holding input (gravity, a
    load) it includes that share.
    """
    u = np.asarray(r.u, dtype=float)
    return float(np.sqrt(np.mean(np.square(u)))) if u.size else 0.0


def tv_u_per_s(r: Run) -> float:
    """Total variation of the applied input per second, ``sum |u_k+1 - u_k| / T``.

    In input units per s, over the run's duration ``T``: how much the
    actuator moves, i.e. chattering and noise in the input. A smooth input
    of amplitude ``A`` and frequency ``f`` scores about ``4 A f``.
    """
    u = np.asarray(r.u, dtype=float)
    duration = float(r.t[-1] - r.t[0]) if len(r.t) > 1 else 0.0
    if duration <= 0:
        return 0.0
    return float(np.sum(np.abs(np.diff(u))) / duration)


def never_settled(r: Run, eps: float) -> bool:
    """True when ``|z1| < eps`` does not hold up to the end (or the run diverged)."""
    return r.diverged_at is not None or settling_time(r, eps) is None


def tail_max(t: np.ndarray, values: np.ndarray, window: float) -> float:
    """``max`` of ``values`` over the last ``window`` seconds."""
    mask = np.asarray(t) >= (t[-1] - window)
    return float(np.max(values[mask]))
