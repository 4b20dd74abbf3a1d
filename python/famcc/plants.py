"""Strict-feedback plants for closed-loop simulation.

The plants of the paper are strict-feedback systems (paper eq. SFS)::

    x_i' = g_i(x, t) x_{i+1} + f_i(x, t),   i = 1, ..., n-1
    x_n' = g_n(x, t) u + f_n(x, t)
    y    = x_1

where ``g_i`` and ``f_i`` depend on ``x_1..x_i`` and ``t`` only. With the fully
actuated coordinates ``y, y', ..., y^(n-1)`` the plant reads (paper eq. FAS)
``y^(n) = G_a(x, t) u + F_a(x, t)`` with ``G_a = g_1 g_2 ... g_n``. A controller's
error vector is ``Z = (z_1, ..., z_n)`` with ``z_i = y^(i-1) - y_d^(i-1)`` and
``dz_n/dt = G u + F``, ``G = G_a``, ``F = F_a - y_d^(n)`` (paper eq. FASe);
``-F/G`` is the input that would hold ``dz_n/dt = 0``.

Every plant here reports ``y, ..., y^(n-1)`` and ``(G_a, F_a)`` exactly from the
state. The paper's plants use hand-derived closed forms; the generic
:class:`StrictFeedback` plant uses truncated Taylor arithmetic ("jets", exact
forward-mode differentiation in time) when its callables accept jets.

Examples
--------
>>> import numpy as np
>>> from famcc.plants import second_order
>>> plant = second_order("paper")
>>> plant.order, plant.variant
(2, 'paper')
>>> x = plant.x0
>>> plant.output_derivatives(0.0, x)          # (y, y') at t = 0
array([-1.        ,  1.52701512])
>>> g_a, f_a = plant.gain_and_drift(0.0, x)   # y'' = g_a u + f_a
>>> round(g_a, 6)
2.112398
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from famcc import _core
from famcc._common import Signal
from famcc._jet import Jet, as_scalar, cos, sin

__all__ = [
    "VARIANTS",
    "Family",
    "FamilyPlant",
    "PhysicalPlant",
    "Plant",
    "StrictFeedback",
    "TwoLinkArm",
    "dc_motor",
    "family",
    "flexible_joint",
    "pendulum",
    "quadrotor_altitude",
    "second_order",
    "smooth_step",
    "third_order",
    "two_link_arm",
]

#: The variants every paper plant supports (see docs/design.md §6.3).
VARIANTS = ("paper", "code")

ScalarFn = Callable[[Any, Any], Any]


# ---------------------------------------------------------------------------
# Plants
# ---------------------------------------------------------------------------


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


class StrictFeedback(Plant):
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

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        n = self.order
        out = np.empty(n)
        for i in range(n):
            nxt = x[i + 1] if i + 1 < n else u
            out[i] = as_scalar(self.g[i](x, t)) * nxt + as_scalar(self.f[i](x, t))
        return out

    # -- exact derivatives via the Taylor method --------------------------------
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
                for i in range(n):
                    nxt = xs[i + 1] if i + 1 < n else u
                    gi = as_scalar(self.g[i](xs, tj))
                    fi = as_scalar(self.f[i](xs, tj))
                    rate = gi * nxt + fi
                    ck = rate.c[k] if isinstance(rate, Jet) else (float(rate) if k == 0 else 0.0)
                    coeffs[i].append(ck / (k + 1))
            except TypeError as exc:
                raise NotImplementedError(
                    f"{self!r}: exact derivatives need g and f callables that accept jets "
                    "(write them with operators and NumPy ufuncs such as np.sin, not math.*); "
                    f"calling them with jets failed: {exc}"
                ) from exc
        return coeffs

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        n = self.order
        x = np.asarray(x, dtype=np.float64)
        if n == 1:
            return np.array([x[0]])
        if n == 2:
            return np.array(
                [
                    x[0],
                    as_scalar(self.g[0](x, t)) * x[1] + as_scalar(self.f[0](x, t)),
                ]
            )
        c1 = self._taylor(t, x, 0.0, n - 1)[0]
        return np.array([c1[k] * math.factorial(k) for k in range(n)])

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        n = self.order
        x = np.asarray(x, dtype=np.float64)
        gain = 1.0
        for gi in self.g:
            gain *= as_scalar(gi(x, t))
        if n == 1:
            return float(gain), float(as_scalar(self.f[0](x, t)))
        # y^(n) is affine in u; with u = 0 it is F_a.
        c1 = self._taylor(t, x, 0.0, n)[0]
        return float(gain), float(c1[n] * math.factorial(n))


def _check_variant(variant: str) -> str:
    if variant not in VARIANTS:
        raise ValueError(f"variant must be one of {VARIANTS!r}, got {variant!r}")
    return variant


class _SecondOrder(StrictFeedback):
    """Paper eq. System_sim; right-hand side, exact output derivatives, ``G_a`` and
    ``F_a`` from the compiled plant (famcc-paper).

    ``gain`` scales the input gain ``g2`` and ``amp`` is the disturbance amplitude;
    with ``gain = 1`` and the variant's ``amp`` the arithmetic is the paper's, bit
    for bit (multiplying by 1.0 is exact).
    """

    def __init__(
        self,
        variant: str,
        gain: float = 1.0,
        amp: float | None = None,
        x0: Sequence[float] | None = None,
    ) -> None:
        self._paper = _core.PaperPlant(
            2,
            variant,
            float(gain),
            None if amp is None else float(amp),
            None if x0 is None else [float(v) for v in x0],
        )
        self._gain = float(gain)
        self._amp = (1.0 if variant == "paper" else 3.0) if amp is None else float(amp)
        amp = self._amp
        b = self._gain

        def g1(x: Any, t: Any) -> Any:
            return 1.0 + 0.1 * cos(x[0]) + 0.1 * sin(t)

        def f1(x: Any, t: Any) -> Any:
            return -x[0] + sin(t)

        def g2(x: Any, t: Any) -> Any:
            return b * (2.0 + 0.2 * sin(x[0] * x[1]) + 0.1 * cos(t))

        def f2(x: Any, t: Any) -> Any:
            return -(x[0] * x[0] - 1.0) * x[1] + amp * sin(t) + amp * cos(2.0 * t)

        super().__init__([g1, g2], [f1, f2], self._paper.x0, name="second-order", variant=variant)
        self.params = {"gain": self._gain, "amp": self._amp}

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        return np.array(self._paper.rhs(t, x, u))

    def rhs_fast(self, t: float, x: Sequence[float], u: float) -> tuple[float, ...]:
        """:meth:`rhs` on plain floats (used by :func:`famcc.simulate`)."""
        return self._paper.rhs(t, x, u)

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        return np.array(self._paper.output_derivatives(t, x))

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        return self._paper.gain_and_drift(t, x)


class _ThirdOrder(StrictFeedback):
    """Paper eq. System_sim3 (with the factor ``x2`` restored in ``x1'``); right-hand
    side, exact output derivatives, ``G_a`` and ``F_a`` from the compiled plant
    (famcc-paper).

    ``gain`` scales the input gain ``g3`` and ``amp`` is the disturbance amplitude
    (10 in both variants); the defaults give the paper's arithmetic bit for bit.
    """

    def __init__(
        self, variant: str, gain: float = 1.0, amp: float = 10.0, x0: Sequence[float] | None = None
    ) -> None:
        self._paper = _core.PaperPlant(
            3, variant, float(gain), float(amp), None if x0 is None else [float(v) for v in x0]
        )
        self._gain, self._amp = float(gain), float(amp)
        b, amp = self._gain, self._amp

        def g1(x: Any, t: Any) -> Any:
            return 1.0 + 0.1 * sin(x[0]) + 0.1 * cos(t)

        def f1(x: Any, t: Any) -> Any:
            return -x[0] + cos(t)

        def g2(x: Any, t: Any) -> Any:
            return 1.0 + 0.1 * cos(x[0] * x[1]) + 0.1 * sin(t)

        def f2(x: Any, t: Any) -> Any:
            return -(x[0] * x[0] - 1.0) * x[1] + sin(t)

        def g3(x: Any, t: Any) -> Any:
            return b * (2.0 + 0.2 * sin(x[0] * x[1] * x[2]) + 0.1 * cos(t))

        def f3(x: Any, t: Any) -> Any:
            return -(x[0] * x[0] + x[1]) * x[2] + amp * sin(t) + amp * cos(2.0 * t)

        super().__init__(
            [g1, g2, g3], [f1, f2, f3], self._paper.x0, name="third-order", variant=variant
        )
        self.params = {"gain": self._gain, "amp": self._amp}

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        return np.array(self._paper.rhs(t, x, u))

    def rhs_fast(self, t: float, x: Sequence[float], u: float) -> tuple[float, ...]:
        """:meth:`rhs` on plain floats (used by :func:`famcc.simulate`)."""
        return self._paper.rhs(t, x, u)

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        return np.array(self._paper.output_derivatives(t, x))

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        return self._paper.gain_and_drift(t, x)


def second_order(
    variant: str = "code",
    *,
    gain: float = 1.0,
    amp: float | None = None,
    x0: Sequence[float] | None = None,
) -> Plant:
    """The paper's second-order plant (eq. System_sim), ``x(0) = (-1, 0.5)``.

    ``x1' = (1 + 0.1 cos x1 + 0.1 sin t) x2 - x1 + sin t`` and
    ``x2' = b (2 + 0.2 sin(x1 x2) + 0.1 cos t) u + f2`` with
    ``f2 = -(x1^2 - 1) x2 + a (sin t + cos 2t)``, ``a = 1`` in variant ``"paper"``
    (as printed) and ``a = 3`` in variant ``"code"`` (the authors' MATLAB code),
    ``b = 1``. The keywords change the plant for robustness studies
    (:func:`famcc.campaigns.campaign`); without them it is the paper's.

    Parameters
    ----------
    variant : {"code", "paper"}
    gain : float
        ``b``, a factor on the input gain (1: the paper's).
    amp : float, optional
        ``a``, the disturbance amplitude (default: the variant's).
    x0 : (float, float), optional
        Initial state (default ``(-1, 0.5)``).

    Examples
    --------
    >>> p = second_order()
    >>> p.name, p.variant, p.x0.tolist()
    ('second-order', 'code', [-1.0, 0.5])
    >>> second_order("paper", gain=0.8, x0=(0.0, 0.0)).params
    {'gain': 0.8, 'amp': 1.0}
    """
    return _SecondOrder(_check_variant(variant), gain, amp, x0)


def third_order(
    variant: str = "code",
    *,
    gain: float = 1.0,
    amp: float = 10.0,
    x0: Sequence[float] | None = None,
) -> Plant:
    """The paper's third-order plant (eq. System_sim3).

    ``x1' = (1 + 0.1 sin x1 + 0.1 cos t) x2 - x1 + cos t`` (the printed equation
    omits the factor ``x2``, which makes the plant uncontrollable; both variants
    restore it), ``x2' = (1 + 0.1 cos(x1 x2) + 0.1 sin t) x3 - (x1^2 - 1) x2 + sin t``,
    ``x3' = (2 + 0.2 sin(x1 x2 x3) + 0.1 cos t) u - (x1^2 + x2) x3 + 10 sin t
    + 10 cos 2t``. ``x(0) = (1, -0.2, 0.4)`` in variant ``"paper"``, ``(1, 0.5, 4)``
    in variant ``"code"``.

    ``gain`` (a factor on ``g3``, 1 by default) and ``amp`` (the disturbance
    amplitude, 10 by default) change the plant for robustness studies.

    Parameters
    ----------
    variant : {"code", "paper"}
    gain, amp : float
    x0 : (float, float, float), optional
        Initial state (default: the variant's).

    Examples
    --------
    >>> third_order("paper").x0.tolist()
    [1.0, -0.2, 0.4]
    >>> third_order(amp=5.0).params
    {'gain': 1.0, 'amp': 5.0}
    """
    return _ThirdOrder(_check_variant(variant), gain, amp, x0)


# The physical plant suite lives in its own module; re-exported here.
# Vectorised families of these plants (famcc.campaigns); their home is famcc.families.
from famcc.families import Family, FamilyPlant, family
from famcc.joints import TwoLinkArm, two_link_arm
from famcc.plant_suite import (
    PhysicalPlant,
    dc_motor,
    flexible_joint,
    pendulum,
    quadrotor_altitude,
    smooth_step,
)
