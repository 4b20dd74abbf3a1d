"""Measuring a plant by experiments: the input gain and the holding input that
:func:`famcc.tune` needs, without the plant's derivatives.

None of these experiments asks for ``gain_and_drift`` or jets, so a plant with
an ``if`` in its load, a lookup table, hidden state or a simulator behind it (a
:class:`famcc.plants.Stepped`, a :class:`famcc.plants.BlackBox`) is measured
the same way as a formula:

- **The input gain** ``G`` of ``y^(n) = G u + F``, with its sign, by a pulse
  pair: from one state the plant is run twice for a few samples, holding
  ``u_a`` and then ``u_b``. The two outputs differ by
  ``G (u_b - u_a) t^n / n! (1 + O(t))``, so a least-squares fit of the
  difference on ``t^(n-1) .. t^(n+2)`` gives ``G`` from the ``t^n``
  coefficient (the ``t^(n-1)`` term absorbs a simulator's own first-order
  integration). A response that grows like a lower power of ``t`` than ``n``
  says the order is too high; one without a ``t^n`` term, too low.
- **The holding input at the reference** (the input that keeps ``y`` on a set
  point ``r``, in steady state): the plant's equilibrium with ``x[0] = r``,
  found by Newton's method on its own ``rhs`` (or on ``advance(x) - x`` for a
  plant that advances itself), evaluated at several times of the horizon so a
  load that switches on is seen. Where the state is hidden (a black box) or the
  reference moves, it is read from a closed-loop run instead: the input applied
  over the samples where the error has settled (:func:`settled_input`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from famcc import sim
from famcc.plants.stepped import BlackBox
from famcc.signals import Constant

__all__ = ["equilibrium_input", "pulse_gain", "settled_input"]

#: Samples of each pulse of :func:`pulse_gain`, and the pulse's size as a
#: fraction of the input range.
PULSE_SAMPLES, PULSE_FRACTION = 16, 0.05
#: Newton iterations of :func:`equilibrium_input`, and its residual tolerance
#: relative to the plant's response to a unit input.
NEWTON_STEPS, NEWTON_TOL = 60, 1e-9
_ZERO = Constant(0.0)


class _Hold:
    """A 'controller' that holds one input."""

    def __init__(self, u: float, dt: float, order: int) -> None:
        self.u, self.dt, self.order = float(u), float(dt), int(order)

    def step(self, e: float, applied: float | None = None) -> float:
        return self.u


class _From:
    """A plant seen from state ``x`` (None: its own ``x0``, read afresh) at time
    ``t0``, without its derivatives (a pulse needs only ``y``)."""

    def __init__(self, plant: Any, x: np.ndarray | None, t0: float) -> None:
        self._plant, self._t0 = plant, float(t0)
        self._x = None if x is None else np.array(x, dtype=np.float64)
        self.order = plant.order
        advance = getattr(plant, "advance", None)
        if callable(advance):
            self.advance = lambda t, x, u, dt: advance(self._t0 + t, x, u, dt)
        else:
            self.rhs = lambda t, x, u: plant.rhs(self._t0 + t, x, u)

    @property
    def x0(self) -> np.ndarray:
        return np.array(self._plant.x0, dtype=np.float64) if self._x is None else self._x.copy()


def _outputs(plant: Any, u: float, dt: float, samples: int) -> np.ndarray:
    """``y`` at ``k dt``, ``k = 0..samples``, with ``u`` held (NaN where it stopped)."""
    res = sim.simulate(
        plant, _Hold(u, dt, plant.order), samples * dt, reference=_ZERO, record=False
    )
    y = np.full(samples + 1, math.nan)
    y[: len(res.y)] = res.y[: samples + 1]
    return y


def pulse_gain(
    plant: Any,
    dt: float,
    u_limits: tuple[float, float],
    *,
    x: np.ndarray | None = None,
    t0: float = 0.0,
    u_center: float = 0.0,
) -> tuple[float, str]:
    """The input gain ``G`` (with its sign) at state ``x`` and time ``t0``, and a
    note: empty when the measurement is clean, else what looks wrong.

    ``x=None`` runs the plant from its own ``x0`` (the only start a black box
    has). The pulse pair holds ``u_center -/+ PULSE_FRACTION`` of the input
    range (kept inside ``u_limits``) for :data:`PULSE_SAMPLES` samples of ``dt``.
    A run that fails or is not finite gives ``(nan, why)``.

    Examples
    --------
    >>> from famcc.plants import Plant
    >>> class Motor(Plant):                   # y'' = -3 y' + 2.5 u, loaded at t >= 1
    ...     def rhs(self, t, x, u):
    ...         return np.array([x[1], -3.0 * x[1] + 2.5 * u - (0.3 if t >= 1 else 0.0)])
    >>> g, note = pulse_gain(Motor(2, [0.0, 0.0]), 1e-3, (-5.0, 5.0))
    >>> round(g, 4), note
    (2.5, '')
    """
    n = int(plant.order)
    lo, hi = float(u_limits[0]), float(u_limits[1])
    du = PULSE_FRACTION * (hi - lo)
    center = min(max(float(u_center), lo + du), hi - du)
    view = _From(plant, x, t0)
    try:
        ya = _outputs(view, center - du, dt, PULSE_SAMPLES)
        yb = _outputs(view, center + du, dt, PULSE_SAMPLES)
    except (ArithmeticError, ValueError) as exc:
        return math.nan, f"a pulse run failed ({exc})"
    d = (yb - ya)[1:]
    if not np.all(np.isfinite(d)):
        return math.nan, "a pulse run was not finite"
    horizon = PULSE_SAMPLES * dt
    s = np.arange(1, PULSE_SAMPLES + 1) / PULSE_SAMPLES  # t / horizon
    powers = [p for p in range(n - 1, n + 3) if p >= 1]
    basis = np.stack([s**p for p in powers], axis=1)
    coef = np.linalg.lstsq(basis, d, rcond=None)[0]
    lead = coef[powers.index(n)]
    g = math.factorial(n) * float(lead) / (horizon**n * 2.0 * du)
    size = float(np.max(np.abs(d)))
    if n > 1 and abs(coef[0]) > 0.5 * max(abs(lead), 1e-300):
        return g, (
            f"y responds to the input like t^{n - 1} over {PULSE_SAMPLES} samples: "
            f"is the order lower than {n}?"
        )
    if size == 0.0 or abs(lead) < 0.1 * size:
        return g, (
            f"y does not respond to the input like t^{n} over {PULSE_SAMPLES} samples: "
            f"is the order higher than {n}?"
        )
    return g, ""


def _newton(residual: Callable[[np.ndarray], np.ndarray], w: np.ndarray) -> np.ndarray | None:
    """A root of ``residual`` from ``w`` (damped Newton, finite-difference
    Jacobian), or None when it does not converge."""
    r = residual(w)
    scale = 1.0 + float(np.max(np.abs(r)))
    for _ in range(NEWTON_STEPS):
        norm = float(np.max(np.abs(r)))
        if not math.isfinite(norm):
            return None
        if norm <= NEWTON_TOL * scale:
            return w
        jac = np.empty((r.size, w.size))
        for j in range(w.size):
            h = 1e-6 * (1.0 + abs(w[j]))
            wp, wm = w.copy(), w.copy()
            wp[j] += h
            wm[j] -= h
            jac[:, j] = (residual(wp) - residual(wm)) / (2.0 * h)
        step = np.linalg.lstsq(jac, -r, rcond=None)[0]
        for _ in range(30):  # halve until the residual falls
            trial = w + step
            r_trial = residual(trial)
            if np.all(np.isfinite(r_trial)) and np.max(np.abs(r_trial)) < norm:
                w, r = trial, r_trial
                break
            step = 0.5 * step
        else:
            return None
    return w if float(np.max(np.abs(r))) <= NEWTON_TOL * scale else None


def equilibrium_input(
    plant: Any, r: float, times: Any, dt: float, u_guess: float = 0.0
) -> tuple[float, np.ndarray] | None:
    """The input that holds the plant's output at the set point ``r``, and its
    equilibrium state, as the largest ``|u|`` over ``times``; None when the
    plant's state is hidden (a black box) or an equilibrium is not found.

    Newton's method solves ``rhs(t, x, u) = 0`` (or ``advance(t, x, u, dt) = x``
    for a plant that advances itself) for ``u`` and every state but
    ``x[0] = r``, starting from ``x0`` with ``x[0] = r``.

    Examples
    --------
    >>> from famcc.plants import Plant
    >>> class Tank(Plant):                    # h' = (u - 0.5 sqrt(h)) / 2
    ...     def rhs(self, t, x, u):
    ...         return np.array([(u - 0.5 * np.sqrt(max(x[0], 0.0))) / 2.0])
    >>> u, x = equilibrium_input(Tank(1, [0.2]), 1.44, [0.0], 0.1)
    >>> round(u, 6)
    0.6
    """
    if isinstance(plant, BlackBox):
        return None
    x0 = np.array(plant.x0, dtype=np.float64).reshape(-1)
    advance = getattr(plant, "advance", None)
    best: tuple[float, np.ndarray] | None = None
    for t in times:
        t = float(t)

        def residual(w: np.ndarray, t: float = t) -> np.ndarray:
            x = np.concatenate(([r], w[:-1]))
            with np.errstate(all="ignore"):
                if callable(advance):
                    out = (np.asarray(advance(t, x, float(w[-1]), dt), dtype=float) - x) / dt
                else:
                    out = np.asarray(plant.rhs(t, x, float(w[-1])), dtype=float)
            return out.reshape(-1)

        start = np.concatenate((x0[1:], [float(u_guess)]))
        try:
            w = _newton(residual, start)
        except (ArithmeticError, ValueError, TypeError):
            w = None
        if w is None:
            return None
        u = float(w[-1])
        if best is None or abs(u) > abs(best[0]):
            best = (u, np.concatenate(([r], w[:-1])))
    return best


def settled_input(res: Any, tol: float) -> float | None:
    """The holding input read from a closed-loop run: the largest ``|u|``,
    averaged over a tenth of the stretch, over the second half of the run's
    settled tail (the samples from which the error stays within ``tol`` to the
    end), or ``-F/G`` there when the run has it; None when that tail is shorter
    than a fifth of the run.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> t = np.linspace(0.0, 1.0, 101)
    >>> run = SimpleNamespace(t=t, z=np.c_[np.exp(-20 * t)], u=1.5 + 0.0 * t,
    ...                       neg_f_over_g=None)
    >>> settled_input(run, 0.01)
    1.5
    """
    e = np.abs(np.asarray(res.z, dtype=float)[:, 0])
    outside = np.flatnonzero(~(e <= tol))
    start = int(outside[-1]) + 1 if outside.size else 0
    if len(e) - start < max(1, len(e) // 5):
        return None
    start = (start + len(e)) // 2  # the loop's own transient has passed
    negfg = res.neg_f_over_g
    if negfg is not None and np.all(np.isfinite(np.asarray(negfg)[start:])):
        return float(np.max(np.abs(np.asarray(negfg)[start:])))
    u = np.asarray(res.u, dtype=float)[start:]
    w = max(1, u.size // 10)
    mean = np.convolve(u, np.ones(w) / w, mode="valid")
    return float(np.max(np.abs(mean)))
