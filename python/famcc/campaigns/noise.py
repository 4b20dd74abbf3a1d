"""Sensor noise for campaigns: counter-based normal draws, reproducible per case."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

_MASK = (1 << 64) - 1
_GOLDEN = 0x9E3779B97F4A7C15


def _mix(z: np.ndarray) -> np.ndarray:
    """SplitMix64's finaliser on uint64 arrays (wrapping arithmetic)."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    out: np.ndarray = z ^ (z >> np.uint64(31))
    return out


def noise_keys(seed: int, cases: np.ndarray) -> np.ndarray:
    """One 64-bit noise key per case index, from the campaign's seed."""
    base = np.uint64((seed * _GOLDEN + 0x632BE59BD9B4E019) & _MASK)
    with np.errstate(over="ignore"):
        return _mix(np.asarray(cases, dtype=np.uint64) * np.uint64(_GOLDEN) + base)


def standard_normal(keys: np.ndarray, k: int) -> np.ndarray:
    """Standard normal draws for sample ``k``, one per key (Box-Muller on hashes).

    A pure function of the key and ``k``: a case's noise does not depend on
    the chunk it runs in, the executor or the other cases.

    >>> import numpy as np
    >>> z = standard_normal(noise_keys(1, np.arange(20000)), 7)
    >>> round(float(z.mean()), 1), round(float(z.std()), 1)
    (0.0, 1.0)
    """
    c1 = np.uint64(((2 * k + 1) * _GOLDEN) & _MASK)
    c2 = np.uint64(((2 * k + 2) * _GOLDEN) & _MASK)
    h1 = _mix(keys ^ c1)
    h2 = _mix(keys ^ c2)
    u1 = ((h1 >> np.uint64(11)).astype(np.float64) + 1.0) * 2.0**-53
    u2 = (h2 >> np.uint64(11)).astype(np.float64) * 2.0**-53
    return np.sqrt(-2.0 * np.log(u1)) * np.cos(2.0 * math.pi * u2)


class NoisySensor:
    """A controller that reads ``e + sigma n_k``: a case's sensor noise, for :func:`simulate`.

    ``n_k`` are the campaign's draws for the case (:func:`standard_normal` of its
    key and the sample index), so :func:`famcc.simulate` with this wrapper
    feeds the controller exactly what the campaign fed it. Diagnostics and
    configuration are the wrapped controller's.
    """

    def __init__(self, controller: Any, sigma: float, key: int) -> None:
        self.controller = controller
        self.sigma = float(sigma)
        self.key = int(key)
        self._keys = np.array([self.key], dtype=np.uint64)
        self._k = 0

    @property
    def dt(self) -> float:
        """The controller's sample period."""
        return float(self.controller.dt)

    @property
    def order(self) -> int:
        """The controller's order."""
        return int(self.controller.order)

    @property
    def diagnostics(self) -> Any:
        """The controller's diagnostics."""
        return self.controller.diagnostics

    def config(self) -> dict[str, Any]:
        """The controller's configuration."""
        return dict(self.controller.config())

    def step(self, e: float, applied: float | None = None) -> float:
        """Steps the controller with the noisy measurement."""
        n = float(self.sigma * standard_normal(self._keys, self._k)[0])
        self._k += 1
        return float(self.controller.step(e + n, applied=applied))

    def __repr__(self) -> str:
        return f"NoisySensor(sigma={self.sigma:g}, key={self.key}) -> {self.controller!r}"
