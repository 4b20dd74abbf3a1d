"""Strict-feedback plants (paper eq. SFS) and their exact derivatives.

::

    x_i' = g_i(x, t) x_{i+1} + f_i(x, t),   i = 1, ..., n-1
    x_n' = g_n(x, t) u + f_n(x, t),          y = x_1

where ``g_i`` and ``f_i`` depend on ``x_1..x_i`` and ``t`` only. With the fully
actuated coordinates ``y, ..., y^(n-1)`` the plant reads (paper eq. FAS)
``y^(n) = G_a u + F_a`` with ``G_a = g_1 ... g_n``; ``-F/G`` is the input that
holds ``dz_n/dt = 0``. :class:`StrictForm` computes the right-hand side,
``y, ..., y^(n-1)`` and ``(G_a, F_a)`` from a plant's rows ``(g_i, f_i)``,
the derivatives exactly with truncated Taylor arithmetic (jets, the Taylor
method for ODEs); :class:`StrictFeedback` takes the rows as callables.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from famcc.plants.base import Plant
from famcc.plants.jets import Jet, as_scalar

__all__ = ["StrictFeedback", "StrictForm"]

ScalarFn = Callable[[Any, Any], Any]


class StrictForm(Plant):
    """A strict-feedback plant given by its rows: subclasses implement :meth:`rows`.

    ``rows(t, x)`` returns ``[(g_1, f_1), ..., (g_n, f_n)]`` for a state ``x``
    of floats or of jets and a time ``t`` (a float or a jet); everything else
    follows from it, written once.
    """

    def rows(self, t: Any, x: Any) -> Sequence[tuple[Any, Any]]:
        """``(g_i, f_i)`` of every row at ``t`` and ``x``."""
        raise NotImplementedError(f"{type(self).__name__} does not define rows")

    def _jet_failure(self, exc: Exception) -> NotImplementedError:
        return NotImplementedError(
            f"{self!r}: exact derivatives need g and f callables that accept jets "
            "(write them with operators and NumPy ufuncs such as np.sin, not math.*); "
            f"calling them with jets failed: {exc}"
        )

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        n = self.order
        out = np.empty(n)
        for i, (g, f) in enumerate(self.rows(t, x)):
            nxt = x[i + 1] if i + 1 < n else u
            out[i] = as_scalar(g) * nxt + as_scalar(f)
        return out

    def _taylor(self, t: float, x: np.ndarray, u: float, degree: int) -> list[list[float]]:
        """Normalised Taylor coefficients of every state up to ``degree``.

        Coefficient ``k + 1`` of ``x_i`` is coefficient ``k`` of ``x_i'`` divided by
        ``k + 1``; coefficient ``k`` of the right-hand side needs only the state's
        coefficients up to ``k``, so the series is built one degree at a time.
        """
        n = self.order
        coeffs = [[float(v)] for v in x]
        for k in range(degree):
            tj = Jet([float(t), 1.0] + [0.0] * (k - 1)) if k >= 1 else Jet([float(t)])
            xs = np.empty(n, dtype=object)
            for i in range(n):
                xs[i] = Jet(coeffs[i][: k + 1])
            try:
                rows = self.rows(tj, xs)
                for i, (g, f) in enumerate(rows):
                    nxt = xs[i + 1] if i + 1 < n else u
                    rate = as_scalar(g) * nxt + as_scalar(f)
                    ck = rate.c[k] if isinstance(rate, Jet) else (float(rate) if k == 0 else 0.0)
                    coeffs[i].append(ck / (k + 1))
            except TypeError as exc:
                raise self._jet_failure(exc) from exc
        return coeffs

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        n = self.order
        x = np.asarray(x, dtype=np.float64)
        if n == 1:
            return np.array([x[0]])
        if n == 2:
            g, f = self.rows(t, x)[0]
            return np.array([x[0], as_scalar(g) * x[1] + as_scalar(f)])
        c1 = self._taylor(t, x, 0.0, n - 1)[0]
        return np.array([c1[k] * math.factorial(k) for k in range(n)])

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        n = self.order
        x = np.asarray(x, dtype=np.float64)
        rows = self.rows(t, x)
        gain = 1.0
        for g, _ in rows:
            gain *= as_scalar(g)
        if n == 1:
            return float(gain), float(as_scalar(rows[0][1]))
        # y^(n) is affine in u; with u = 0 it is F_a.
        c1 = self._taylor(t, x, 0.0, n)[0]
        return float(gain), float(c1[n] * math.factorial(n))


class StrictFeedback(StrictForm):
    """Generic strict-feedback plant (paper eq. SFS) from callables.

    Parameters
    ----------
    g, f : sequence of callables
        ``g = [g_1, ..., g_n]`` and ``f = [f_1, ..., f_n]``, each called as
        ``g_i(x, t)`` with the state ``x`` (1-D array) and time ``t`` and returning a
        scalar. ``g_i`` and ``f_i`` must depend on ``x[0..i-1]`` and ``t`` only
        (strict-feedback structure); otherwise the output derivatives would depend
        on the input.
    x0 : array_like
        Initial state of length ``n``.
    name, variant : str
        Labels for reports.
    output, input : (name, unit), name, :class:`famcc.Signal` or None
        Names and units of ``y = x[0]`` and ``u`` (see :class:`Plant`).

    Notes
    -----
    What is supported exactly, for any order ``n``:

    * :meth:`rhs` with plain float callables.
    * :meth:`output_derivatives` for ``n <= 2`` with plain float callables
      (``y' = g_1 x_2 + f_1`` needs no derivative of ``g`` or ``f``).
    * ``G_a = g_1 ... g_n`` with plain float callables; ``F_a`` for ``n = 1``
      (``F_a = f_1``).
    * Everything else (``y''`` and higher, ``F_a`` for ``n >= 2``) needs time
      derivatives of ``g_i`` and ``f_i`` along the trajectory. These are computed
      exactly with truncated Taylor arithmetic (the Taylor method for ODEs): the
      callables are called with a 1-D object array of jets for ``x`` and a jet for
      ``t``. Callables written with operators and NumPy ufuncs (``np.sin``,
      ``np.cos``, ``np.exp``, ``np.log``, ``np.sqrt``, ``np.tanh``, ``np.arctan``,
      ``**``) accept jets; callables using :mod:`math`, ``float()`` or comparisons
      do not, and the methods then raise :class:`NotImplementedError` saying so.

    Examples
    --------
    A damped oscillator ``x1' = x2``, ``x2' = 2 u - x1 - 0.5 x2``:

    >>> plant = StrictFeedback(
    ...     g=[lambda x, t: 1.0, lambda x, t: 2.0],
    ...     f=[lambda x, t: 0.0, lambda x, t: -x[0] - 0.5 * x[1]],
    ...     x0=[1.0, 0.0])
    >>> plant.rhs(0.0, plant.x0, 0.5)
    array([0., 0.])
    >>> plant.gain_and_drift(0.0, plant.x0)
    (2.0, -1.0)
    """

    def __init__(
        self,
        g: Sequence[ScalarFn],
        f: Sequence[ScalarFn],
        x0: Sequence[float],
        name: str = "strict-feedback",
        variant: str = "",
        *,
        output: Any = None,
        input: Any = None,
    ) -> None:
        for label, fns in (("g", g), ("f", f)):
            if callable(fns) or isinstance(fns, (str, bytes)) or not hasattr(fns, "__iter__"):
                raise TypeError(
                    f"{label} must be a sequence of callables, one per state "
                    f"({label}=[{label}_1, ..., {label}_n], each {label}_i(x, t) -> float), "
                    f"got {type(fns).__name__}; e.g. for a second-order plant "
                    f"{label}=[lambda x, t: ..., lambda x, t: ...]"
                )
        g, f = list(g), list(f)
        if len(g) == 0 or len(g) != len(f):
            raise ValueError(
                f"g and f must be non-empty and of equal length, got {len(g)} and {len(f)}"
            )
        if not all(callable(c) for c in g + f):
            raise ValueError("every entry of g and f must be callable as fn(x, t)")
        super().__init__(len(g), x0, name=name, variant=variant, output=output, input=input)
        if self._x0.shape != (self.order,):
            raise ValueError(
                f"x0 must have length {self.order} (the order), got {self._x0.shape[0]}"
            )
        self.g = g
        self.f = f

    def rows(self, t: Any, x: Any) -> list[tuple[Any, Any]]:
        return [(gi(x, t), fi(x, t)) for gi, fi in zip(self.g, self.f)]
