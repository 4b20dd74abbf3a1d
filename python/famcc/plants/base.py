"""The plant protocol of :func:`famcc.simulate`: the base class :class:`Plant`.

A plant is anything with ``order``, ``x0`` and ``rhs(t, x, u)``; for the true
error vector and ``-F/G`` it also offers ``output_derivatives(t, x)`` and
``gain_and_drift(t, x)`` (either may raise :class:`NotImplementedError`), and
for speed ``rhs_fast(t, x, u)`` on plain floats. The paper's plants, the
physical suite and the families' members all derive from :class:`Plant`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from famcc._common import Signal

__all__ = ["Plant", "is_real"]


def is_real(value: Any) -> bool:
    """True for a real number that is not a bool."""
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)


class Plant:
    """Base class of single-input single-output plants with output ``y = x[0]``.

    Subclasses implement :meth:`rhs`; :meth:`output_derivatives` and
    :meth:`gain_and_drift` raise :class:`NotImplementedError` unless overridden.
    A plant may also offer ``rhs_fast(t, x, u)``, the same vector field on plain
    sequences of floats returning a tuple; :func:`famcc.simulate` then
    integrates without NumPy's per-call overhead on tiny arrays (about 3x faster).

    Parameters
    ----------
    order : int
        Relative degree ``n`` (number of states for strict-feedback plants).
    x0 : array_like
        Initial state.
    name, variant : str
        Labels for reports.
    output, input : (name, unit), name, :class:`famcc.Signal` or None
        What the output ``y = x[0]`` and the input ``u`` are, e.g.
        ``output=("angle", "rad")``, ``input=("voltage", "V")``. Figures and
        reports label every axis with them (the error ``z_i`` in the output's
        unit per ``s^(i-1)``). Default: ``"y"`` and ``"u"`` without units.

    Examples
    --------
    >>> class Integrator(Plant):
    ...     def rhs(self, t, x, u):
    ...         return np.array([u])
    >>> p = Integrator(1, [0.5], name="integrator", output=("position", "m"),
    ...                input=("speed", "m/s"))
    >>> p.rhs(0.0, p.x0, 2.0)
    array([2.])
    >>> p.output.unit, p.input
    ('m', Signal(name='speed', unit='m/s'))
    """

    def __init__(
        self,
        order: int,
        x0: Sequence[float],
        name: str = "plant",
        variant: str = "",
        *,
        output: Any = None,
        input: Any = None,
    ) -> None:
        if not isinstance(order, (int, np.integer)) or order < 1:
            raise ValueError(f"order must be an integer >= 1, got {order!r}")
        x0_arr = np.array(x0, dtype=np.float64).reshape(-1)
        if not np.all(np.isfinite(x0_arr)):
            raise ValueError("x0 must be finite")
        self.order = int(order)
        self._x0 = x0_arr
        self.name = name
        self.variant = variant
        self.output = Signal.of(output, "y")
        self.input = Signal.of(input, "u")

    @property
    def x0(self) -> np.ndarray:
        """Initial state (a fresh float64 copy on every access)."""
        return self._x0.copy()

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        """Return ``dx/dt`` at time ``t``, state ``x`` and input ``u``."""
        raise NotImplementedError(f"{type(self).__name__} does not define rhs")

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        """Return ``(y, y', ..., y^(n-1))`` computed exactly from the state."""
        raise NotImplementedError(f"{type(self).__name__} cannot report its output derivatives")

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        """Return ``(G_a, F_a)`` with ``y^(n) = G_a u + F_a`` (paper eq. FAS)."""
        raise NotImplementedError(f"{type(self).__name__} cannot report its total gain and drift")

    def __repr__(self) -> str:
        label = f", variant={self.variant!r}" if self.variant else ""
        return f"{type(self).__name__}(name={self.name!r}, order={self.order}{label})"
