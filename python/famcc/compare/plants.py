"""The compared plants: each :class:`Case` (plant, task, limits, band) and its plant."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

from famcc import _core, plants
from famcc.joints import two_link_arm


@dataclass(frozen=True)
class Case:
    """One plant of the comparison with its task.

    Attributes
    ----------
    name : str
        Key (``"example-1"``, ``"dc-motor"``, ...).
    title : str
        What it is, for the report.
    order, joints : int
        Relative degree per joint; number of joints (1 for a single-output plant).
    reference : tuple of float or None
        Constant set points per joint; None for the paper's ``y_d = sin t``.
    t_end : float
        Horizon, s.
    band : float
        Accuracy band of the settling time, steady RMS and ripple (output unit).
    limits, saturated : tuple of (lo, hi)
        Nominal and tighter input limits per joint.
    gain, hold : tuple of float
        Nominal input gain ``G`` and holding input ``H`` per joint (the scales of
        every controller's parameter ranges).
    family : str
        famcc's design family: ``"finite-time"`` (the paper's example 1),
        ``"variable-exponent"`` (example 2) or ``"rfc"`` (example 3, any order >= 3).
    params : dict
        The plant's nominal parameters (dispersed by +-30 %).
    output_unit, input_unit : str
        For the report.
    factory : callable, optional
        ``factory(**params) -> plant`` (anything :func:`famcc.simulate` takes,
        e.g. a :class:`famcc.plants.Plant`): the plant of a case of your own,
        given to :func:`famcc.compare.compare` as ``own_cases``. With worker
        processes it must pickle (a module-level function or a
        ``functools.partial`` of one). None for the built-in cases.

    Examples
    --------
    >>> import numpy as np, famcc
    >>> from famcc.compare import Case
    >>> class Cart(famcc.plants.Plant):
    ...     def __init__(self, m=2.0, c=0.5):
    ...         super().__init__(2, [0.0, 0.0], name="cart")
    ...         self.m, self.c = m, c
    ...     def rhs(self, t, x, u):
    ...         load = 1.0 if t >= 2.0 else 0.0
    ...         return np.array([x[1], (u - self.c * np.tanh(5 * x[1]) - load) / self.m])
    >>> cart = Case("cart", "a cart with tanh friction", 2, 1, (0.5,), 4.0, 0.01,
    ...             ((-5.0, 5.0),), ((-1.5, 1.5),), (0.5,), (1.5,), "finite-time",
    ...             {"m": 2.0, "c": 0.5}, factory=Cart)
    >>> cart.factory(**cart.params).m
    2.0
    """

    name: str
    title: str
    order: int
    joints: int
    reference: tuple[float, ...] | None
    t_end: float
    band: float
    limits: tuple[tuple[float, float], ...]
    saturated: tuple[tuple[float, float], ...]
    gain: tuple[float, ...]
    hold: tuple[float, ...]
    family: str
    params: dict[str, float] = field(default_factory=dict)
    output_unit: str = ""
    input_unit: str = ""
    factory: Callable[..., Any] | None = None

    @property
    def reversed(self) -> bool:
        """A single-joint plant with a negative input gain ``G < 0``."""
        return self.joints == 1 and self.gain[0] < 0

    def as_positive(self) -> Case:
        """The case as every controller sees it: with a negative gain the input is
        reversed (``G -> |G|``, the limits mirrored, ``u -> -u`` at the plant, see
        :class:`_Bare`), for all alike: simple-pid takes no negative gains and
        famcc's law assumes a positive control direction (issue 33)."""
        if not self.reversed:
            return self

        def mirror(lims: tuple[tuple[float, float], ...]) -> tuple[tuple[float, float], ...]:
            return tuple((-hi, -lo) for lo, hi in lims)

        return replace(
            self,
            gain=(-self.gain[0],),
            limits=mirror(self.limits),
            saturated=mirror(self.saturated),
        )


def _suite_cases() -> list[Case]:
    motor, pend, quad, flex, arm = (
        plants.dc_motor(),
        plants.pendulum(),
        plants.quadrotor_altitude(),
        plants.flexible_joint(),
        two_link_arm(),
    )
    return [
        Case(
            "dc-motor",
            "DC motor, shaft angle to 1 rad, 1 N m load step at 2 s, |u| <= 12 V",
            2,
            1,
            (1.0,),
            5.0,
            0.02,
            ((-12.0, 12.0),),
            ((-6.0, 6.0),),
            (motor.gain,),
            (motor.hold_input(),),
            "finite-time",
            {"J": 0.01, "b": 0.01, "K": 0.25, "R": 1.0, "load": 1.0},
            "rad",
            "V",
        ),
        Case(
            "pendulum",
            "pendulum, from hanging to 1 rad, |u| <= 5 N m",
            2,
            1,
            (1.0,),
            5.0,
            0.02,
            ((-5.0, 5.0),),
            ((-3.0, 3.0),),
            (pend.gain,),
            (pend.hold_input(),),
            "finite-time",
            {"m": 0.5, "l": 0.5, "b": 0.05},
            "rad",
            "N m",
        ),
        Case(
            "quadrotor-altitude",
            "quadrotor altitude to 1 m, thrust in [0, 30] N",
            2,
            1,
            (1.0,),
            6.0,
            0.02,
            ((0.0, 30.0),),
            ((0.0, 16.0),),
            (quad.gain,),
            (quad.hold_input(),),
            "finite-time",
            {"mass": 1.2, "drag": 0.3, "tilt": 0.2},
            "m",
            "N",
        ),
        Case(
            "flexible-joint",
            "flexible joint (order 4), link angle to 0.5 rad, |u| <= 5 N m",
            4,
            1,
            (0.5,),
            6.0,
            0.01,
            ((-5.0, 5.0),),
            ((-1.5, 1.5),),
            (flex.gain,),
            (flex.hold_input(),),
            "rfc",
            {"J_link": 0.05, "J_motor": 0.02, "k": 20.0, "mgl": 0.5, "b_motor": 0.05},
            "rad",
            "N m",
        ),
        Case(
            "two-link-arm",
            "two-link arm, both joints to 0.5 rad, one controller per joint",
            2,
            2,
            (0.5, 0.5),
            5.0,
            0.02,
            ((-60.0, 60.0), (-20.0, 20.0)),
            ((-25.0, 25.0), (-6.0, 6.0)),
            tuple(arm.gain),
            tuple(arm.hold_input()),
            "finite-time",
            {"m1": 1.0, "m2": 1.0, "b": 0.1},
            "rad",
            "N m",
        ),
    ]


def _paper_cases() -> list[Case]:
    # G: the paper's plants have g1 g2 (g3) = 2 nominally; H: the peak |-F/G| of
    # `famcc reproduce` (3.5 for examples 1-2, 10 for example 3).
    return [
        Case(
            "example-1",
            "the paper's example 1 plant (order 2), y_d = sin t",
            2,
            1,
            None,
            10.0,
            0.1,
            ((-100.0, 100.0),),
            ((-2.5, 3.0),),
            (_core.paper_nominal_gain(1),),
            (3.5,),
            "finite-time",
            {"gain": 1.0, "amp": 3.0},
        ),
        Case(
            "example-2",
            "the paper's example 2 (the example 1 plant, famcc's "
            "variable-exponent design), y_d = sin t",
            2,
            1,
            None,
            10.0,
            0.1,
            ((-100.0, 100.0),),
            ((-2.0, 3.0),),
            (_core.paper_nominal_gain(2),),
            (3.5,),
            "variable-exponent",
            {"gain": 1.0, "amp": 3.0},
        ),
        Case(
            "example-3",
            "the paper's example 3 plant (order 3), y_d = sin t",
            3,
            1,
            None,
            10.0,
            0.1,
            ((-100.0, 100.0),),
            ((-7.0, 9.0),),
            (_core.paper_nominal_gain(3),),
            (10.0,),
            "rfc",
            {"gain": 1.0, "amp": 10.0},
        ),
    ]


def cases(quick: bool = False) -> list[Case]:
    """The compared plants: the paper's three examples, the suite and the arm.

    ``quick``: example 1 and the DC motor only.
    """
    every = _paper_cases() + _suite_cases()
    if quick:
        return [c for c in every if c.name in ("example-1", "dc-motor")]
    return every


#: The cases of the user's own that :func:`famcc.compare.compare` runs (by name).
_OWN: dict[str, Case] = {}


def _case(name: str) -> Case:
    if name in _OWN:
        return _OWN[name]
    for c in _paper_cases() + _suite_cases():
        if c.name == name:
            return c
    raise ValueError(f"unknown case {name!r}")


def make_plant(case: Case, factors: dict[str, float] | None = None) -> Any:
    """The case's plant, its parameters multiplied by ``factors`` (dispersion)."""
    p = {k: v * (factors or {}).get(k, 1.0) for k, v in case.params.items()}
    if case.factory is not None:
        return case.factory(**p)
    if case.name in ("example-1", "example-2"):
        return plants.second_order("code", gain=p["gain"], amp=p["amp"])
    if case.name == "example-3":
        return plants.third_order("code", gain=p["gain"], amp=p["amp"])
    if case.name == "two-link-arm":
        return two_link_arm(m=(p["m1"], p["m2"]), b=p["b"])
    build: Callable[..., Any] = getattr(plants, case.name.replace("-", "_"))
    return build(**p)


class _Bare:
    """A plant seen only through ``rhs``: the true ``z1`` is all the metrics need."""

    def __init__(self, plant: Any, reverse: bool = False) -> None:
        self.order, self.x0, self.rhs = plant.order, plant.x0, plant.rhs
        self.output, self.input = plant.output, plant.input
        fast = getattr(plant, "rhs_fast", None)
        if reverse:  # the input reversed (Case.as_positive)
            rhs = plant.rhs
            self.rhs = lambda t, x, u: rhs(t, x, -u)
            if fast is not None:
                self.rhs_fast = lambda t, x, u: fast(t, x, -u)
        elif fast is not None:
            self.rhs_fast = fast
