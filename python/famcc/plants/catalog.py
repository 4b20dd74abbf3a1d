"""The ready-made plant families: the paper's plants and the physical suite, on arrays.

A :class:`Family` is a plant whose parameters are arrays: ``rhs(t, x, u, p)``
takes the states of N plants as an ``(n, N)`` array, their held inputs as an
``(N,)`` array and a dict of parameters (each a float or an ``(N,)`` array), and
returns ``dx/dt`` as an ``(n, N)`` array. :func:`famcc.campaigns.campaign`
integrates such families in lockstep for robustness campaigns;
:meth:`Family.plant` builds the ordinary (scalar) plant of one member, which
:func:`famcc.simulate` runs.

A ready-made family is not a second definition of its plant: the paper's
families evaluate famcc-paper's plants lane by lane (``famcc._core.PaperLanes``),
the physical ones their :class:`~famcc.plants.model.Model` on arrays, so a
campaign's case and :func:`famcc.simulate` on that case's plant compute the same
numbers:

=======================  =====  ======================================  ==================
name                     order  scalar plant                            parameters
=======================  =====  ======================================  ==================
``second-order``         2      :func:`famcc.plants.second_order`       gain, amp
``third-order``          3      :func:`famcc.plants.third_order`        gain, amp
``dc-motor``             2      :func:`famcc.plants.dc_motor`           J, b, K, R, load, t_load, load_step, t_step
``pendulum``             2      :func:`famcc.plants.pendulum`           m, l, b
``quadrotor-altitude``   2      :func:`famcc.plants.quadrotor_altitude` mass, drag, tilt
``flexible-joint``       4      :func:`famcc.plants.flexible_joint`     J_link, J_motor, k, mgl, b_motor
=======================  =====  ======================================  ==================

Examples
--------
>>> import numpy as np
>>> motors = family("dc-motor")
>>> motors.order, motors.params["J"]
(2, 0.01)
>>> x = np.zeros((2, 3))                        # three motors at rest
>>> p = {"J": np.array([0.01, 0.02, 0.04])}     # three inertias, the rest nominal
>>> motors.rhs(0.0, x, np.ones(3), p)[1]        # acceleration under 1 V, rad/s^2
array([25.  , 12.5 ,  6.25])
>>> motors.plant(J=0.02).rhs(0.0, np.zeros(2), 1.0)[1]
np.float64(12.5)
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from famcc import _core
from famcc.plants.family import Family
from famcc.plants.model import Model, PhysicalPlant
from famcc.plants.paper import PaperPlant, check_variant
from famcc.plants.suite import MODELS

__all__ = ["FAMILIES", "family", "names"]


# ---------------------------------------------------------------------------
# The ready-made families: the plants' own definitions, on arrays.
# ---------------------------------------------------------------------------


class _PaperRhs:
    """The paper's plant on arrays (famcc-paper's, lane by lane); picklable."""

    def __init__(self, order: int, variant: str) -> None:
        self.order, self.variant = order, variant

    def __call__(self, t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any]) -> Any:
        n = np.asarray(x).shape[1]
        return self.lanes(p, n).rhs(t, x, u)

    def lanes(self, p: Mapping[str, Any], n: int) -> Any:
        gain, amp = (
            np.broadcast_to(np.asarray(p[k], dtype=np.float64), (n,)) for k in ("gain", "amp")
        )
        return _core.PaperLanes(
            self.order, self.variant, np.ascontiguousarray(gain), np.ascontiguousarray(amp)
        )


class _PaperFactory:
    """The paper plant of one member; picklable."""

    def __init__(self, order: int, variant: str) -> None:
        self.order, self.variant = order, variant

    def __call__(self, x0: Sequence[float], **params: float) -> PaperPlant:
        return PaperPlant(self.order, self.variant, params["gain"], params["amp"], x0)


class _ModelRhs:
    """A model's right-hand side on arrays; picklable (the model by name)."""

    def __init__(self, name: str) -> None:
        self.name = name

    def __call__(self, t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any]) -> Any:
        return MODELS[self.name].rhs(t, x, u, p)


class _ModelFactory:
    """A model's member; picklable."""

    def __init__(self, name: str) -> None:
        self.name = name

    def __call__(self, x0: Sequence[float], **params: float) -> PhysicalPlant:
        return PhysicalPlant(MODELS[self.name], x0, **params)


def _paper_family(name: str, variant: str) -> Family:
    order = 2 if name == "second-order" else 3
    nominal = PaperPlant(order, variant)
    rhs = _PaperRhs(order, variant)
    return Family(
        name,
        order,
        rhs,
        nominal.params,
        nominal.x0.tolist(),
        _PaperFactory(order, variant),
        description=f"the paper's {name} plant (variant {variant!r}) with a "
        "factor gain on its input gain and disturbance amplitude amp",
        compiled=rhs.lanes,
    )


def _model_family(model: Model) -> Family:
    return Family(
        model.name,
        model.order,
        _ModelRhs(model.name),
        model.params,
        model.x0,
        _ModelFactory(model.name),
        output=model.output,
        input=model.input,
        description=model.description,
    )


#: The ready-made families: name -> whether it has the paper's variants.
FAMILIES = {
    "second-order": True,
    "third-order": True,
    "dc-motor": False,
    "pendulum": False,
    "quadrotor-altitude": False,
    "flexible-joint": False,
}


def names() -> list[str]:
    """The names of the ready-made families.

    >>> names()[:2]
    ['second-order', 'third-order']
    """
    return list(FAMILIES)


def family(name: str, variant: str | None = None) -> Family:
    """A ready-made family by name (see :func:`names`).

    Parameters
    ----------
    name : str
        ``"second-order"``, ``"third-order"`` (the paper's plants), ``"dc-motor"``,
        ``"pendulum"``, ``"quadrotor-altitude"`` or ``"flexible-joint"``.
    variant : {"code", "paper"}, optional
        For the paper's plants (default ``"code"``); the others have none.

    Examples
    --------
    >>> f = family("second-order", "paper")
    >>> f.params, f.x0.tolist()
    ({'gain': 1.0, 'amp': 1.0}, [-1.0, 0.5])
    """
    if name not in FAMILIES:
        raise ValueError(f"family must be one of {', '.join(FAMILIES)}, got {name!r}")
    if FAMILIES[name]:
        return _paper_family(name, check_variant("code" if variant is None else variant))
    if variant is not None:
        raise ValueError(f"the family {name!r} has no variants (got variant={variant!r})")
    return _model_family(MODELS[name])
