"""The paper's two plants, from the compiled famcc-paper crate (their one home).

:func:`second_order` (examples 1 and 2, eq. System_sim) and :func:`third_order`
(example 3, eq. System_sim3) in the variants ``"paper"`` (as printed) and
``"code"`` (the authors' MATLAB code). Right-hand side, exact output
derivatives and ``(G_a, F_a)`` are famcc-paper's (``famcc._core.PaperPlant``);
the simulator integrates them in Rust (``famcc._core.PaperLanes``).

>>> p = second_order("paper")
>>> p.order, p.variant
(2, 'paper')
>>> p.output_derivatives(0.0, p.x0)          # (y, y') at t = 0
array([-1.        ,  1.52701512])
>>> round(p.gain_and_drift(0.0, p.x0)[0], 6)   # y'' = G_a u + F_a
2.112398
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from famcc import _core
from famcc.plants.base import Plant

__all__ = ["VARIANTS", "PaperPlant", "check_variant", "second_order", "third_order"]

#: The variants every paper plant supports (see docs/design.md §6.3).
VARIANTS = ("paper", "code")

#: The plants' names by order.
_NAMES = {2: "second-order", 3: "third-order"}


def check_variant(variant: Any) -> str:
    """``variant`` when it is one of :data:`VARIANTS`, else ValueError."""
    if variant not in VARIANTS:
        raise ValueError(f"variant must be one of {VARIANTS!r}, got {variant!r}")
    return str(variant)


class PaperPlant(Plant):
    """One of the paper's plants with a gain factor, an amplitude and an initial state.

    ``gain`` scales the input gain (``g2`` or ``g3``) and ``amp`` is the
    disturbance amplitude; with ``gain = 1`` and the variant's ``amp`` the
    arithmetic is the paper's, bit for bit. Build it with :func:`second_order`
    or :func:`third_order`.
    """

    def __init__(
        self,
        order: int,
        variant: str,
        gain: float = 1.0,
        amp: float | None = None,
        x0: Sequence[float] | None = None,
    ) -> None:
        self._paper = _core.PaperPlant(
            order,
            variant,
            float(gain),
            None if amp is None else float(amp),
            None if x0 is None else [float(v) for v in x0],
        )
        super().__init__(order, self._paper.x0, name=_NAMES[order], variant=variant)
        default = (1.0 if variant == "paper" else 3.0) if order == 2 else 10.0
        self.params = {"gain": float(gain), "amp": default if amp is None else float(amp)}

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        return np.array(self._paper.rhs(t, x, u))

    def rhs_fast(self, t: float, x: Sequence[float], u: float) -> tuple[float, ...]:
        """:meth:`rhs` on plain floats."""
        return self._paper.rhs(t, x, u)

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        return np.array(self._paper.output_derivatives(t, x))

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        return self._paper.gain_and_drift(t, x)

    def derivatives_table(
        self, t: np.ndarray, x: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`output_derivatives` and :meth:`gain_and_drift` at every sample at once:
        ``(derivatives (K, n), G_a (K,), F_a (K,))``, the same numbers."""
        t = np.ascontiguousarray(t, dtype=np.float64)
        x = np.ascontiguousarray(x, dtype=np.float64)
        return self.compiled().table(t, x)  # type: ignore[no-any-return]

    def compiled(self) -> Any:
        """The plant as the simulator's compiled lanes (one lane)."""
        return _core.PaperLanes(
            self.order,
            self.variant,
            np.array([self.params["gain"]]),
            np.array([self.params["amp"]]),
        )


def second_order(
    variant: str = "code",
    *,
    gain: float = 1.0,
    amp: float | None = None,
    x0: Sequence[float] | None = None,
) -> PaperPlant:
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
    return PaperPlant(2, check_variant(variant), gain, amp, x0)


def third_order(
    variant: str = "code",
    *,
    gain: float = 1.0,
    amp: float = 10.0,
    x0: Sequence[float] | None = None,
) -> PaperPlant:
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
    return PaperPlant(3, check_variant(variant), gain, amp, x0)
