"""The signals a closed loop is driven by: references, measurement noise and
input disturbances, as functions of time and as tables over a run's samples.

:class:`Sine` and :class:`Constant` are references ``ref(t, k)`` (the ``k``-th
derivative at ``t``); :func:`reference_table` evaluates any reference on a
sample grid at once, :func:`source` turns a ``noise=`` / ``disturbance=``
argument into a function of time and :func:`sampled` into its samples.

>>> import numpy as np
>>> table, m = reference_table(Sine(), 2, np.array([0.0, np.pi / 2]))
>>> m, np.round(table, 12).tolist()
(2, [[0.0, 1.0, -0.0], [1.0, 0.0, -1.0]])
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from famcc.plants.base import is_real

__all__ = ["Constant", "Sine", "describe_reference", "reference_table", "sampled", "source"]


class Sine:
    """Sinusoidal reference ``y_d(t) = amplitude * sin(omega t + phase)``.

    Called as ``ref(t, k)`` it returns the ``k``-th time derivative.

    Parameters
    ----------
    amplitude, omega, phase : float

    Examples
    --------
    >>> ref = Sine()
    >>> ref(0.0, 0), ref(0.0, 1), ref(0.0, 2)
    (0.0, 1.0, -0.0)
    """

    def __init__(self, amplitude: float = 1.0, omega: float = 1.0, phase: float = 0.0) -> None:
        for label, value in (("amplitude", amplitude), ("omega", omega), ("phase", phase)):
            if not isinstance(value, (int, float, np.integer, np.floating)) or not math.isfinite(
                value
            ):
                raise ValueError(f"{label} must be a finite number, got {value!r}")
        self.amplitude = float(amplitude)
        self.omega = float(omega)
        self.phase = float(phase)

    def __call__(self, t: float, k: int = 0) -> float:
        if k < 0:
            raise ValueError(f"derivative order k must be >= 0, got {k}")
        arg = self.omega * t + self.phase
        # d^k/dt^k sin(w t + p) = w^k sin(w t + p + k pi/2), exact phase shifts
        sc = (math.sin(arg), math.cos(arg), -math.sin(arg), -math.cos(arg))[k % 4]
        return self.amplitude * self.omega**k * sc

    def table(self, t: np.ndarray, m: int) -> np.ndarray:
        """``(y_d, ..., y_d^(m))`` at every time of ``t``: shape ``(len(t), m + 1)``,
        the same numbers as calling the reference."""
        arg = self.omega * np.asarray(t, dtype=np.float64) + self.phase
        s, c = np.sin(arg), np.cos(arg)
        cols = [self.amplitude * self.omega**k * (s, c, -s, -c)[k % 4] for k in range(m + 1)]
        return np.stack(cols, axis=1)

    def __repr__(self) -> str:
        return f"Sine(amplitude={self.amplitude!r}, omega={self.omega!r}, phase={self.phase!r})"


class Constant:
    """Constant reference ``y_d(t) = value`` (a regulator's set point).

    Called as ``ref(t, k)`` it returns the ``k``-th time derivative: ``value``
    for ``k = 0``, 0 otherwise.

    Parameters
    ----------
    value : float

    Examples
    --------
    >>> ref = Constant(0.5)
    >>> ref(3.0, 0), ref(3.0, 1)
    (0.5, 0.0)
    """

    def __init__(self, value: float = 0.0) -> None:
        if not is_real(value) or not math.isfinite(value):
            raise ValueError(f"value must be a finite number, got {value!r}")
        self.value = float(value)

    def __call__(self, t: float, k: int = 0) -> float:
        if k < 0:
            raise ValueError(f"derivative order k must be >= 0, got {k}")
        return self.value if k == 0 else 0.0

    def table(self, t: np.ndarray, m: int) -> np.ndarray:
        """As :meth:`Sine.table`."""
        out = np.zeros((len(t), m + 1))
        out[:, 0] = self.value
        return out

    def __repr__(self) -> str:
        return f"Constant({self.value!r})"


_BAD_REFERENCE = (
    "reference must be a callable reference(t, k) such as famcc.Sine() or "
    "famcc.Constant(c), a sequence of callables (y_d, y_d', ...) or None (the paper's "
    "sin t, with a warning)"
)


def _derivatives(reference: Any, order: int) -> tuple[Callable[[float], np.ndarray], int]:
    """``(fn, m)``: ``fn(t)`` gives ``(y_d, ..., y_d^(m))``, ``m`` is n or n - 1."""
    if isinstance(reference, (tuple, list)):
        fns = list(reference)
        if len(fns) < order or not all(callable(fn) for fn in fns):
            raise ValueError(
                f"reference as a sequence must hold at least {order} callables "
                f"(y_d and its derivatives up to order {order - 1}), got {len(fns)}"
            )
        fns = fns[: order + 1]

        def from_seq(t: float) -> np.ndarray:
            return np.array([float(fn(t)) for fn in fns])

        return from_seq, len(fns) - 1
    if callable(reference):

        def from_call(t: float) -> np.ndarray:
            return np.array([float(reference(t, k)) for k in range(order + 1)])

        return from_call, order
    raise ValueError(_BAD_REFERENCE)


def reference_table(reference: Any, order: int, t: np.ndarray) -> tuple[np.ndarray, int]:
    """``(table, m)``: the reference and its derivatives up to ``m`` (n, or n - 1
    for a sequence of n callables) at every time of ``t``, shape ``(len(t), m + 1)``.

    ``None`` is the paper's ``sin t``. The reference is evaluated at ``t[0]``
    first; an error or a non-finite value there raises ValueError naming it.
    """
    if reference is None:
        reference = Sine()
    fn, m = _derivatives(reference, order)
    t = np.asarray(t, dtype=np.float64)
    try:
        probe = fn(float(t[0]))
    except Exception as exc:
        raise ValueError(f"reference could not be evaluated at t = {float(t[0]):g}: {exc}") from exc
    if not np.all(np.isfinite(probe)):
        raise ValueError(f"reference returned a non-finite value at t = {float(t[0]):g}")
    if isinstance(reference, (Sine, Constant)):
        return reference.table(t, m), m
    rows = [probe] + [fn(float(v)) for v in t[1:]]
    return np.array(rows, dtype=np.float64).reshape(len(t), m + 1), m


def source(label: str, value: Any, seed: Any) -> Callable[[float], float] | None:
    """``noise=`` / ``disturbance=`` as a function of t (None when absent).

    A callable is checked at ``t = 0``; a float is a constant disturbance, or
    the standard deviation of white Gaussian noise drawn from
    ``numpy.random.default_rng(seed)`` (one draw per call).
    """
    if value is None:
        return None
    if callable(value):
        fn = value
        try:
            probe = float(fn(0.0))
        except Exception as exc:
            raise ValueError(f"{label} could not be evaluated at t = 0: {exc}") from exc
        if not math.isfinite(probe):
            raise ValueError(f"{label}(0.0) must be finite, got {probe!r}")
        return fn  # type: ignore[no-any-return]
    if not is_real(value) or not math.isfinite(value):
        raise ValueError(f"{label} must be None, a finite number or a callable of t, got {value!r}")
    level = float(value)
    if label == "disturbance":
        return None if level == 0 else (lambda t: level)
    if level < 0:
        raise ValueError(f"noise (a standard deviation) must be >= 0, got {value!r}")
    if level == 0:
        return None
    try:
        rng = np.random.default_rng(seed)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"seed must be None, an int or a numpy Generator, got {seed!r}") from exc
    return lambda t: level * float(rng.standard_normal())


def sampled(fn: Callable[[float], float] | None, t: np.ndarray) -> np.ndarray | None:
    """``fn`` at every time of ``t``, in order (None for None)."""
    if fn is None:
        return None
    return np.array([float(fn(float(v))) for v in t], dtype=np.float64)


def describe_reference(reference: Any) -> str:
    """What a reference is, in a few words."""
    if reference is None:
        return "Sine() (the paper's sin t, by default)"
    if isinstance(reference, (tuple, list)):
        return f"{len(reference)} callables (y_d and {len(reference) - 1} derivatives)"
    if isinstance(reference, (Sine, Constant)):
        return repr(reference)
    return f"callable {getattr(reference, '__name__', type(reference).__name__)}(t, k)"
