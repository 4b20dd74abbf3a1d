"""Vectorised plant families: the right-hand side of N plants at once, with NumPy.

A :class:`Family` is a plant whose parameters are arrays: ``rhs(t, x, u, p)``
takes the states of N plants as an ``(n, N)`` array, their held inputs as an
``(N,)`` array and a dict of parameters (each a float or an ``(N,)`` array), and
returns ``dx/dt`` as an ``(n, N)`` array. :func:`famcc.campaigns.campaign`
integrates such families in lockstep for robustness campaigns;
:meth:`Family.plant` builds the ordinary (scalar) plant of one member, which
:func:`famcc.simulate` runs.

The ready-made families evaluate exactly the arithmetic of their scalar plants,
operation for operation, so a campaign's case and :func:`famcc.simulate` on that
case's plant compute the same numbers:

=======================  =====  ======================================  ==================
name                     order  scalar plant                            parameters
=======================  =====  ======================================  ==================
``second-order``         2      :func:`famcc.plants.second_order`       gain, amp
``third-order``          3      :func:`famcc.plants.third_order`        gain, amp
``dc-motor``             2      :func:`famcc.plants.dc_motor`           J, b, K, R, load, t_load
``pendulum``             2      :func:`famcc.plants.pendulum`           m, l, b
``quadrotor-altitude``   2      :func:`famcc.plants.quadrotor_altitude` mass, drag, tilt
``flexible-joint``       4      :func:`famcc.plants.flexible_joint`     J_link, J_motor, k, mgl, b_motor
=======================  =====  ======================================  ==================

Examples
--------
>>> import numpy as np
>>> from famcc.plants import family
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

import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from famcc._common import Signal

__all__ = ["FAMILIES", "Family", "FamilyPlant", "family", "names"]

#: ``rhs(t, x, u, p)``: time, states ``(n, N)``, inputs ``(N,)``, parameters.
VectorRHS = Callable[[float, np.ndarray, np.ndarray, Mapping[str, Any]], Any]
#: ``plant(x0, **params)``: the scalar plant of one member.
PlantFactory = Callable[..., Any]


class Family:
    """A plant family evaluated for N members at once.

    Parameters
    ----------
    name : str
        Label for reports.
    order : int
        Number of states (the relative degree for strict-feedback plants).
    rhs : callable
        ``rhs(t, x, u, p)`` with ``t`` a float, ``x`` the states as an ``(n, N)``
        array, ``u`` the held inputs as an ``(N,)`` array and ``p`` a dict of
        parameters (every name of ``params``, each a float or an ``(N,)``
        array); returns ``dx/dt`` as an ``(n, N)`` array or a sequence of ``n``
        arrays. Write it with NumPy ufuncs (``np.sin``), not :mod:`math`.
    params : dict of str to float
        The parameters and their nominal values.
    x0 : sequence of float
        The nominal initial state.
    plant : callable, optional
        ``plant(x0=..., **params)`` returning the scalar plant of one member
        (a :class:`famcc.plants.Plant`). Default: a :class:`FamilyPlant` that
        evaluates ``rhs`` on one member.
    output, input : (name, unit), name, :class:`famcc.Signal` or None
        What ``y = x[0]`` and ``u`` are.
    description : str
        One line for reports.

    Notes
    -----
    Ready-made families (:func:`family`) and their scalar plants compute the
    same operations in the same order, so a campaign's per-case numbers and
    :func:`famcc.simulate` agree sample for sample. A family of your own
    agrees with its default :class:`FamilyPlant` in the same way; with a
    ``plant`` factory of your own, keep the arithmetic identical (floating
    point is not associative). For process pools the family must pickle:
    define ``rhs`` and ``plant`` at module level, not as lambdas.

    Examples
    --------
    A family of damped oscillators ``y'' = b u - c y'`` with dispersed ``b, c``:

    >>> import numpy as np
    >>> def rhs(t, x, u, p):
    ...     return (x[1], p["b"] * u - p["c"] * x[1])
    >>> osc = Family("oscillator", 2, rhs, {"b": 2.0, "c": 0.5}, [1.0, 0.0])
    >>> osc.rhs(0.0, np.array([[1.0, 1.0], [0.0, 2.0]]), np.ones(2), {"c": np.array([0.5, 1.0])})
    array([[0., 2.],
           [2., 0.]])
    >>> osc.plant(b=4.0).rhs(0.0, np.array([1.0, 0.0]), 1.0)
    array([0., 4.])
    """

    def __init__(
        self,
        name: str,
        order: int,
        rhs: VectorRHS,
        params: Mapping[str, float],
        x0: Sequence[float],
        plant: PlantFactory | None = None,
        *,
        output: Any = None,
        input: Any = None,
        description: str = "",
    ) -> None:
        if not isinstance(order, (int, np.integer)) or isinstance(order, bool) or order < 1:
            raise ValueError(f"order must be an integer >= 1, got {order!r}")
        if not callable(rhs):
            raise ValueError("rhs must be callable as rhs(t, x, u, p)")  # noqa: TRY004
        if plant is not None and not callable(plant):
            raise ValueError("plant must be None or callable as plant(x0=..., **params)")
        x0_arr = np.array(x0, dtype=np.float64).reshape(-1)
        if x0_arr.shape != (order,) or not np.all(np.isfinite(x0_arr)):
            raise ValueError(f"x0 must be {order} finite numbers, got {list(x0)!r}")
        nominal: dict[str, float] = {}
        for key, value in dict(params).items():
            if not isinstance(key, str) or not key.isidentifier():
                raise ValueError(f"parameter names must be identifiers, got {key!r}")
            if not _is_real(value) or not math.isfinite(value):
                raise ValueError(f"parameter {key!r} must be a finite number, got {value!r}")
            nominal[key] = float(value)
        self.name = str(name)
        self.order = int(order)
        self._rhs = rhs
        self.params = nominal
        self._x0 = x0_arr
        self._plant = plant
        self.output = Signal.of(output, "y")
        self.input = Signal.of(input, "u")
        self.description = description

    @property
    def x0(self) -> np.ndarray:
        """The nominal initial state (a fresh copy)."""
        return self._x0.copy()

    def full_params(self, p: Mapping[str, Any] | None = None) -> dict[str, Any]:
        """The nominal parameters updated with ``p`` (unknown names raise ValueError)."""
        out: dict[str, Any] = dict(self.params)
        for key, value in (p or {}).items():
            if key not in out:
                raise ValueError(
                    f"{self.name} has no parameter {key!r}; its parameters are "
                    f"{', '.join(self.params) or 'none'}"
                )
            out[key] = value
        return out

    def rhs(
        self, t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any] | None = None
    ) -> np.ndarray:
        """``dx/dt`` of every member, shape ``(n, N)``; missing parameters are nominal."""
        return np.asarray(self._rhs(t, x, u, self.full_params(p)), dtype=np.float64)

    def plant(self, x0: Sequence[float] | None = None, **params: float) -> Any:
        """The scalar plant of one member: the nominal one updated with ``params``.

        Parameters
        ----------
        x0 : sequence of float, optional
            Initial state (default: the family's nominal ``x0``).
        **params : float
            Parameter values (default: nominal).
        """
        full = self.full_params(params)
        start = self.x0 if x0 is None else np.array(x0, dtype=np.float64).reshape(-1)
        if self._plant is not None:
            return self._plant(x0=tuple(float(v) for v in start), **full)
        return FamilyPlant(self, start, full)

    def __repr__(self) -> str:
        p = ", ".join(f"{k}={v:g}" for k, v in self.params.items())
        return f"Family({self.name!r}, order={self.order}, {p})"


class FamilyPlant:
    """One member of a :class:`Family` as an ordinary plant (``rhs(t, x, u)``).

    It evaluates the family's vectorised ``rhs`` on a single member, so it
    computes exactly what a campaign computes for that member. It knows no
    output derivatives or ``-F/G`` (:func:`famcc.simulate` then records only
    ``z1``).

    Examples
    --------
    >>> import numpy as np
    >>> osc = Family("osc", 1, lambda t, x, u, p: (p["a"] * u,), {"a": 2.0}, [0.0])
    >>> FamilyPlant(osc, [0.0], {"a": 3.0}).rhs(0.0, np.zeros(1), 1.0)
    array([3.])
    """

    def __init__(
        self, fam: Family, x0: Sequence[float] | np.ndarray, params: Mapping[str, float]
    ) -> None:
        self.family = fam
        self.order = fam.order
        self._x0 = np.array(x0, dtype=np.float64).reshape(-1)
        if self._x0.shape != (fam.order,):
            raise ValueError(f"x0 must have length {fam.order}, got {self._x0.shape[0]}")
        self.params = {k: float(v) for k, v in fam.full_params(params).items()}
        self._p1 = {k: np.array([v]) for k, v in self.params.items()}
        self.name = fam.name
        self.variant = ""
        self.output = fam.output
        self.input = fam.input

    @property
    def x0(self) -> np.ndarray:
        """Initial state (a fresh copy)."""
        return self._x0.copy()

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        """``dx/dt`` of this member."""
        xs = np.asarray(x, dtype=np.float64).reshape(self.order, 1)
        out = self.family._rhs(t, xs, np.array([float(u)]), self._p1)
        return np.asarray(out, dtype=np.float64).reshape(self.order, -1)[:, 0]

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        """Not known for a generic family member."""
        raise NotImplementedError(
            f"a member of the family {self.family.name!r} reports no output derivatives"
        )

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        """Not known for a generic family member."""
        raise NotImplementedError(
            f"a member of the family {self.family.name!r} reports no gain and drift"
        )

    def __repr__(self) -> str:
        p = ", ".join(f"{k}={v:g}" for k, v in self.params.items())
        return f"{self.name}({p})"


# ---------------------------------------------------------------------------
# The ready-made families. Each right-hand side repeats the operations of its
# scalar plant's rhs_fast in the same order (famcc.plants, famcc.plant_suite).
# ---------------------------------------------------------------------------


def _second_order_rhs(t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any]) -> Any:
    x1, x2 = x[0], x[1]
    st = math.sin(t)
    g1 = 1.0 + 0.1 * np.cos(x1) + 0.1 * st
    g2 = p["gain"] * (2.0 + 0.2 * np.sin(x1 * x2) + 0.1 * math.cos(t))
    f2 = -(x1 * x1 - 1.0) * x2 + p["amp"] * (st + math.cos(2.0 * t))
    return (g1 * x2 - x1 + st, g2 * u + f2)


def _third_order_rhs(t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any]) -> Any:
    x1, x2, x3 = x[0], x[1], x[2]
    st, ct = math.sin(t), math.cos(t)
    amp = p["amp"]
    return (
        (1.0 + 0.1 * np.sin(x1) + 0.1 * ct) * x2 - x1 + ct,
        (1.0 + 0.1 * np.cos(x1 * x2) + 0.1 * st) * x3 - (x1 * x1 - 1.0) * x2 + st,
        p["gain"] * (2.0 + 0.2 * np.sin(x1 * x2 * x3) + 0.1 * ct) * u
        - (x1 * x1 + x2) * x3
        + amp * st
        + amp * math.cos(2.0 * t),
    )


class _PaperPlant:
    """Picklable factory of a paper plant with parameters (a module-level callable)."""

    def __init__(self, which: str, variant: str) -> None:
        self.which, self.variant = which, variant

    def __call__(self, x0: Sequence[float], **params: float) -> Any:
        from famcc import plants

        make = plants.second_order if self.which == "second_order" else plants.third_order
        return make(self.variant, x0=x0, **params)


def _smooth_step(t: Any, t0: Any, width: float) -> Any:
    # famcc.plant_suite.smooth_step, on arrays of t0 too.
    return 0.5 * (1.0 + np.tanh((t - t0) / width))


def _dc_motor_rhs(t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any]) -> Any:
    J, b, K, R = p["J"], p["b"], p["K"], p["R"]
    gain = K / (J * R)
    damp = b / J + K * K / (J * R)
    f2 = -damp * x[1] - p["load"] * _smooth_step(t, p["t_load"], 0.005) / J
    return (1.0 * x[1] + 0.0 * x[0], gain * u + f2)


def _dc_motor_plant(x0: Sequence[float], **p: float) -> Any:
    from famcc.plant_suite import dc_motor

    return dc_motor(x0=x0, **p)


def _pendulum_rhs(t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any]) -> Any:
    m, l, b = p["m"], p["l"], p["b"]
    inertia = m * l * l
    gain = 1.0 / inertia
    f2 = -(m * _G0 * l * np.sin(x[0]) + b * x[1]) / inertia
    return (1.0 * x[1] + 0.0 * x[0], gain * u + f2)


def _pendulum_plant(x0: Sequence[float], **p: float) -> Any:
    from famcc.plant_suite import pendulum

    return pendulum(x0=x0, **p)


def _quadrotor_rhs(t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any]) -> Any:
    mass = p["mass"]
    g2 = np.cos(p["tilt"] * np.sin(0.5 * t)) / mass + 0.0 * x[0]
    f2 = -_G0 - p["drag"] * x[1] / mass
    return (1.0 * x[1] + 0.0 * x[0], g2 * u + f2)


def _quadrotor_plant(x0: Sequence[float], **p: float) -> Any:
    from famcc.plant_suite import quadrotor_altitude

    return quadrotor_altitude(x0=x0, **p)


def _flexible_joint_rhs(t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any]) -> Any:
    J_link, J_motor, k = p["J_link"], p["J_motor"], p["k"]
    f2 = -(k * x[0] + p["mgl"] * np.sin(x[0])) / J_link
    f4 = (k * (x[0] - x[2]) - p["b_motor"] * x[3]) / J_motor
    return (
        1.0 * x[1] + 0.0 * x[0],
        k / J_link * x[2] + f2,
        1.0 * x[3] + 0.0 * x[0],
        1.0 / J_motor * u + f4,
    )


def _flexible_joint_plant(x0: Sequence[float], **p: float) -> Any:
    from famcc.plant_suite import flexible_joint

    return flexible_joint(x0=x0, **p)


_G0 = 9.81  # m/s^2, as famcc.plant_suite.G0


def _make(name: str, variant: str | None) -> Family:
    if name in ("second-order", "third-order"):
        from famcc.plants import VARIANTS

        variant = "code" if variant is None else variant
        if variant not in VARIANTS:
            raise ValueError(f"variant must be one of {VARIANTS!r}, got {variant!r}")
        if name == "second-order":
            amp = 1.0 if variant == "paper" else 3.0
            return Family(
                name,
                2,
                _second_order_rhs,
                {"gain": 1.0, "amp": amp},
                [-1.0, 0.5],
                _PaperPlant("second_order", variant),
                description=f"the paper's second-order plant (variant {variant!r}) with a "
                "factor gain on its input gain and disturbance amplitude amp",
            )
        x0 = [1.0, -0.2, 0.4] if variant == "paper" else [1.0, 0.5, 4.0]
        return Family(
            name,
            3,
            _third_order_rhs,
            {"gain": 1.0, "amp": 10.0},
            x0,
            _PaperPlant("third_order", variant),
            description=f"the paper's third-order plant (variant {variant!r}) with a "
            "factor gain on its input gain and disturbance amplitude amp",
        )
    if variant is not None:
        raise ValueError(f"the family {name!r} has no variants (got variant={variant!r})")
    from famcc import plant_suite

    suite: dict[str, tuple[int, VectorRHS, PlantFactory, Any]] = {
        "dc-motor": (2, _dc_motor_rhs, _dc_motor_plant, plant_suite.dc_motor),
        "pendulum": (2, _pendulum_rhs, _pendulum_plant, plant_suite.pendulum),
        "quadrotor-altitude": (2, _quadrotor_rhs, _quadrotor_plant, plant_suite.quadrotor_altitude),
        "flexible-joint": (
            4,
            _flexible_joint_rhs,
            _flexible_joint_plant,
            plant_suite.flexible_joint,
        ),
    }
    order, rhs, factory, build = suite[name]
    nominal = build()
    doc = (build.__doc__ or "").strip().splitlines()[0]
    return Family(
        name,
        order,
        rhs,
        nominal.params,
        nominal.x0,
        factory,
        output=nominal.output,
        input=nominal.input,
        description=doc,
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
    return _make(name, variant)


def _is_real(value: Any) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)
