"""``famcc compare``: famcc against PID, ADRC and LMCC on every plant under real conditions.

Every controller (``famcc``, its special case ``lmcc``, ``pid`` and ``adrc``, see
:mod:`famcc.peers`) is tuned by the same procedure (:func:`tune_budget`: the same
number of closed-loop runs and the same objective on the nominal plant), then
evaluated unchanged under every condition: nominal; saturated (tighter input
limits); measurement noise at three levels; +-30 % parameter dispersion (N
seeded random plants); 200 Hz (the nominal runs at 1 kHz). :func:`compare`
returns the numbers, :func:`write_report` writes ``report.md`` with one table
and one radar chart per plant, time series of the telling cases and a section
"Where famcc loses" computed from the numbers (:func:`losses`).

The tuning procedure
--------------------
Each controller has documented parameter ranges (:func:`space`), scaled by the
plant's nominal input gain ``G`` and holding input ``H`` and by the accuracy
band. Of a budget of ``B`` closed-loop runs on the nominal plant, the first
``B/2`` are a seeded Latin hypercube over the ranges (log-uniform where the
range spans decades), the other ``B/2`` come in rounds around the best so far
(Gaussian steps in the unit cube, halved each round). The objective is
``J = IAE / (band T) + 0.01 sum TV(u) / H + 10 [never settled]`` (``T`` the
horizon, ``TV(u)`` the input's total variation per second), ``J = 10^6`` for
a diverged run: accuracy and a quiet actuator, on the same scale for every
controller.

>>> from famcc.compare import CONDITIONS, controllers
>>> controllers()
['famcc', 'lmcc', 'pid', 'adrc']
>>> [c for c in CONDITIONS]
['nominal', 'saturated', 'noise 1e-4', 'noise 1e-3', 'noise 1e-2', 'dispersion', '200 Hz']
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "CONDITIONS",
    "Case",
    "Space",
    "cases",
    "compare",
    "controllers",
    "famcc_candidates",
    "losses",
    "radar_scores",
    "space",
    "write_report",
]

#: The conditions, in table order (``"1 kHz"`` is the nominal column: the design rate).
CONDITIONS = (
    "nominal",
    "saturated",
    "noise 1e-4",
    "noise 1e-3",
    "noise 1e-2",
    "dispersion",
    "200 Hz",
)
QUICK_CONDITIONS = ("nominal", "saturated", "noise 1e-3", "dispersion", "200 Hz")
NOISE = {"noise 1e-4": 1e-4, "noise 1e-3": 1e-3, "noise 1e-2": 1e-2}
#: The nominal sample period (1 kHz) and the low rate of the "200 Hz" condition, s.
DT, DT_LOW = 1e-3, 5e-3
#: Largest RK4 step of the plant integration (s): 2 substeps per sample at 1 kHz.
RK4_STEP = 5e-4
#: Parameter dispersion: every physical parameter times U(1 - D, 1 + D).
DISPERSION = 0.3
#: A loss is reported when a peer beats famcc by more than this factor.
LOSS_FACTOR = 1.1
#: The weight of TV(u) / H in the tuning objective, s.
TV_WEIGHT = 0.01

_KINDS = ("famcc", "lmcc", "pid", "adrc")


def controllers() -> list[str]:
    """The compared controllers, famcc first."""
    return list(_KINDS)


# ---------------------------------------------------------------------------
# cases: plant, reference, limits, accuracy band
# ---------------------------------------------------------------------------


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


def _suite_cases() -> list[Case]:
    from famcc import plants
    from famcc.joints import two_link_arm

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
            (2.0,),
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
            (2.0,),
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
            (2.0,),
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


def _case(name: str) -> Case:
    for c in _paper_cases() + _suite_cases():
        if c.name == name:
            return c
    raise ValueError(f"unknown case {name!r}")


def make_plant(case: Case, factors: dict[str, float] | None = None) -> Any:
    """The case's plant, its parameters multiplied by ``factors`` (dispersion)."""
    from famcc import plants
    from famcc.joints import two_link_arm

    p = {k: v * (factors or {}).get(k, 1.0) for k, v in case.params.items()}
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

    def __init__(self, plant: Any) -> None:
        self.order, self.x0, self.rhs = plant.order, plant.x0, plant.rhs
        self.output, self.input = plant.output, plant.input
        fast = getattr(plant, "rhs_fast", None)
        if fast is not None:
            self.rhs_fast = fast


# ---------------------------------------------------------------------------
# parameter spaces
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Space:
    """A controller's documented parameter ranges; ``params(u)`` maps the unit cube.

    ``ranges`` maps each name to ``(lo, hi, log)``; ``fixed`` holds the
    parameters that are not searched (e.g. ADRC's ``b0 = G``); ``default`` is
    the controller's documented default setting (the paper's design for famcc,
    the textbook pole placement for the peers), the first candidate the tuning
    tries.
    """

    kind: str
    ranges: dict[str, tuple[float, float, bool]]
    fixed: dict[str, Any] = field(default_factory=dict)
    default: dict[str, float] = field(default_factory=dict)

    @property
    def dims(self) -> int:
        return len(self.ranges)

    def params(self, u: Sequence[float] | np.ndarray) -> dict[str, Any]:
        """The parameters at the point ``u`` of ``[0, 1]^dims``."""
        out = dict(self.fixed)
        for x, (name, (lo, hi, log)) in zip(u, self.ranges.items()):
            x = min(max(float(x), 0.0), 1.0)
            out[name] = lo * (hi / lo) ** x if log else lo + (hi - lo) * x
        return out

    def unit(self, params: dict[str, float]) -> np.ndarray:
        """The point of the unit cube of ``params`` (clipped to the ranges)."""
        out = []
        for name, (lo, hi, log) in self.ranges.items():
            v = float(params[name])
            x = math.log(v / lo) / math.log(hi / lo) if log else (v - lo) / (hi - lo)
            out.append(min(max(x, 0.0), 1.0))
        return np.array(out)


#: The paper's k_u of examples 1-3 (famcc's default there; 1.5 H elsewhere).
PAPER_K_U = {"example-1": 5.0, "example-2": 2.0, "example-3": 30.0}


def famcc_candidates(
    plant: Any,
    dt: float,
    *,
    order: int,
    family: str,
    band: float,
    gain: float,
    hold: float,
    k_u: float | None = None,
) -> Space:
    """famcc's parameter ranges on a plant: the paper's designs, scaled.

    Around the paper's settings (the default: law gain ``k = 1``, ``T_s = 1`` s,
    ``eps`` = the band, ``mu = 0.01`` s, ``k_u`` the paper's or ``1.5 H``): ``k``
    (1/s) in [0.3, 10], ``T_s`` in [0.1, 2] s, ``eps`` in [0.2, 1] x band (LaMC;
    LoMC designs scale theirs with it), ``k_u`` in [0.3, 30] x ``H``, ``mu`` in
    [1, 30] ms, all log-uniform. ``family`` picks the laws: ``"finite-time"``
    (LaMC, ``FiniteTime(k, 0.5)``, the paper's example 1 at the default),
    ``"variable-exponent"`` (LoMC + SSMD, example 2) or ``"rfc"`` (LoMC,
    ``FixedTime`` stages + NSMD at any order >= 3, example 3). ``plant``, ``dt``
    and ``gain`` are for the design procedure that will replace these ranges
    (``famcc.design``); the ranges need only ``hold`` and ``band``.
    """
    del plant, dt, gain
    if family not in ("finite-time", "variable-exponent", "rfc"):
        raise ValueError(f"family must be finite-time, variable-exponent or rfc, got {family!r}")
    return Space(
        "famcc",
        {
            "k": (0.3, 10.0, True),
            "settle_time": (0.1, 2.0, True),
            "eps": (0.2 * band, band, True),
            "k_u": (0.3 * hold, 30.0 * hold, True),
            "mu": (1e-3, 3e-2, True),
        },
        {"family": family, "order": order, "band": band},
        {"k": 1.0, "settle_time": 1.0, "eps": band, "k_u": k_u or 1.5 * hold, "mu": 0.01},
    )


def space(kind: str, case: Case, joint: int = 0) -> Space:
    """The parameter ranges of controller ``kind`` on ``case`` (joint ``joint``).

    All log-uniform; the default (the first candidate) in brackets.

    * ``famcc``: :func:`famcc_candidates`.
    * ``lmcc``: ``Linear(k)`` stages, ``k`` in [0.3, 30] 1/s (2); ``eps`` of the
      LoMC on ``s`` = ``eps_factor`` x band x ``k^(n-1)``, ``eps_factor`` in
      [0.1, 1] (0.5); ``T_s``, ``k_u``, ``mu`` as famcc's.
    * ``pid``: with a bandwidth ``w`` in [1, 200] rad/s (10), ``kp = cp w^n / G``,
      ``kd = cd w^(n-1) / G``, ``ki = ci w^(n+1) / G``; ``cp, cd`` in [0.5, 20]
      (3), ``ci`` in [0.03, 3] (1): the default places the poles of a double
      integrator at ``-w``; measurement filter ``tf = ctf / w``, ``ctf`` in
      [1e-3, 0.3] (0.01).
    * ``adrc``: ``w_cl`` in [1, 200] rad/s (10), ``k_eso`` in [2, 10] (5), ``b0 = G``.
    """
    g, h, n = case.gain[joint], case.hold[joint], case.order
    if kind == "famcc":
        return famcc_candidates(
            None,
            DT,
            order=n,
            family=case.family,
            band=case.band,
            gain=g,
            hold=h,
            k_u=PAPER_K_U.get(case.name),
        )
    if kind == "lmcc":
        return Space(
            "lmcc",
            {
                "k": (0.3, 30.0, True),
                "eps_factor": (0.1, 1.0, True),
                "settle_time": (0.1, 2.0, True),
                "k_u": (0.3 * h, 30.0 * h, True),
                "mu": (1e-3, 3e-2, True),
            },
            {"order": n, "band": case.band},
            {"k": 2.0, "eps_factor": 0.5, "settle_time": 1.0, "k_u": 1.5 * h, "mu": 0.01},
        )
    if kind == "pid":
        return Space(
            "pid",
            {
                "w": (1.0, 200.0, True),
                "cp": (0.5, 20.0, True),
                "cd": (0.5, 20.0, True),
                "ci": (0.03, 3.0, True),
                "ctf": (1e-3, 0.3, True),
            },
            {"order": n, "gain": g},
            {"w": 10.0, "cp": 3.0, "cd": 3.0, "ci": 1.0, "ctf": 0.01},
        )
    if kind == "adrc":
        return Space(
            "adrc",
            {"w_cl": (1.0, 200.0, True), "k_eso": (2.0, 10.0, True)},
            {"order": n, "b0": g},
            {"w_cl": 10.0, "k_eso": 5.0},
        )
    raise ValueError(f"kind must be one of {', '.join(_KINDS)}, got {kind!r}")


def build(kind: str, p: dict[str, Any], dt: float, u_limits: tuple[float, float]) -> Any:
    """The controller of ``kind`` with parameters ``p`` at sample period ``dt``.

    famcc's construction-time findings (:class:`famcc.DesignWarning`, e.g. a
    differentiator too fast for a 200 Hz loop) are silenced here: the comparison
    evaluates every candidate as tuned, and the measured runs show the cost.
    """
    import warnings

    from famcc._common import DesignWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        return _build(kind, p, dt, u_limits)


def _build(kind: str, p: dict[str, Any], dt: float, u_limits: tuple[float, float]) -> Any:
    import famcc
    from famcc.peers import ADRCPeer, PIDPeer, lmcc

    n = int(p["order"])
    if kind == "pid":
        w, g = p["w"], p["gain"]
        return PIDPeer(
            dt,
            n,
            kp=p["cp"] * w**n / g,
            ki=p["ci"] * w ** (n + 1) / g,
            kd=p["cd"] * w ** (n - 1) / g,
            tf=p["ctf"] / w,
            u_limits=u_limits,
        )
    if kind == "adrc":
        return ADRCPeer(dt, n, b0=p["b0"], w_cl=p["w_cl"], k_eso=p["k_eso"], u_limits=u_limits)
    if kind == "lmcc":
        eps = p["eps_factor"] * p["band"] * p["k"] ** (n - 1)
        return lmcc(
            n, dt, k=p["k"], eps=eps, settle_time=p["settle_time"], k_u=p["k_u"], mu=p["mu"]
        )
    if kind != "famcc":
        raise ValueError(f"kind must be one of {', '.join(_KINDS)}, got {kind!r}")
    hg = famcc.HighGain.default(n, mu=p["mu"])
    # the envelope latch of the authors' code, as `famcc reproduce` (variant "code") uses
    common = {
        "settle_time": p["settle_time"],
        "k_u": p["k_u"],
        "differentiator": hg,
        "latch": "authors",
    }
    k, eps = p["k"], p["eps"]
    if p["family"] == "finite-time":
        return famcc.Controller(
            n, dt, famcc.FiniteTime(k=k, p=0.5), constraint="lateral", eps=eps, **common
        )
    if p["family"] == "variable-exponent":  # example 2, scaled: eps_z = eps, LoMC 1.5 eps
        return famcc.Controller(
            n,
            dt,
            famcc.VariableExponent(1.5 * k, 0.5, 2.0, 3.0),
            skew=famcc.Smooth(2.25 * eps, eps),
            constraint="longitudinal",
            eps=1.5 * eps,
            **common,
        )
    # rfc (example 3, scaled by k): stage i has FixedTime(2^i k, 0.5, 2^(i-1) k, 2) + NSMD
    laws, skews = [], []
    for i in range(n - 1):
        laws.append(famcc.FixedTime(2.0**i * k, 0.5, 2.0 ** (i - 1) * k, 2.0))
        skews.append(famcc.Nonsingular(eps * 30.0**i, eps * 2.0**i, 0.1 * 10.0**i))
    return famcc.Controller(
        n,
        dt,
        laws,
        skew=skews,
        constraint="longitudinal",
        eps=30.0 * eps * 3.0 ** (n - 3),
        **common,
    )


# ---------------------------------------------------------------------------
# one closed-loop run (the unit of work, in worker processes)
# ---------------------------------------------------------------------------


def condition_of(name: str) -> dict[str, Any]:
    """``dt``, which limits and the noise level of a condition (dispersion is per plant)."""
    if name not in CONDITIONS:
        raise ValueError(f"condition must be one of {', '.join(CONDITIONS)}, got {name!r}")
    return {
        "dt": DT_LOW if name == "200 Hz" else DT,
        "limits": "saturated" if name == "saturated" else "limits",
        "noise": NOISE.get(name, 0.0),
    }


def run(
    case: Case,
    kind: str,
    params: Sequence[dict[str, Any]],
    condition: str,
    *,
    factors: dict[str, float] | None = None,
    t_end: float | None = None,
    seed: int = 0,
) -> list[Any]:
    """Simulate ``kind`` with ``params`` (one dict per joint) under ``condition``.

    famcc's run-time health warning (bounds expanded with headroom) is silenced:
    the comparison measures that cost instead (see :func:`build`).
    """
    import warnings

    from famcc._common import DesignWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        return _run(case, kind, params, condition, factors=factors, t_end=t_end, seed=seed)


def _run(
    case: Case,
    kind: str,
    params: Sequence[dict[str, Any]],
    condition: str,
    *,
    factors: dict[str, float] | None = None,
    t_end: float | None = None,
    seed: int = 0,
) -> list[Any]:
    """Simulate ``kind`` with ``params`` (one dict per joint) under ``condition``.

    Returns one :class:`famcc.SimResult` per joint.
    """
    import famcc
    from famcc.joints import simulate_joints

    cond = condition_of(condition)
    dt = cond["dt"]
    limits = getattr(case, cond["limits"])
    plant = make_plant(case, factors)
    horizon = case.t_end if t_end is None else t_end
    substeps = max(1, math.ceil(dt / RK4_STEP - 1e-9))
    noise = cond["noise"] or None
    refs = [famcc.Sine()] if case.reference is None else [famcc.Constant(v) for v in case.reference]
    e0 = max(abs(float(plant.x0[case.order * j]) - refs[j](0.0, 0)) for j in range(case.joints))
    bound = 10.0 * max(e0, 1.0)
    ctrls = [build(kind, params[j], dt, limits[j]) for j in range(case.joints)]
    if case.joints > 1:
        return simulate_joints(
            plant,
            ctrls,
            horizon,
            refs,
            u_limits=limits,
            substeps=substeps,
            noise=noise,
            seed=seed,
            diverge_at=bound,
        )
    res = famcc.simulate(
        _Bare(plant),
        ctrls[0],
        horizon,
        reference=refs[0],
        u_limits=limits[0],
        substeps=substeps,
        record=False,
        noise=noise,
        seed=seed,
        diverge_at=bound,
    )
    return [res]


def metrics(case: Case, results: Sequence[Any], t_end: float) -> dict[str, Any]:
    """The compared numbers of one run (summed or worst over the joints) and ``J``.

    ``iae`` (output unit s, summed), ``steady_rms`` (worst, None if a joint
    never settled), ``final_rms`` (RMS of ``z1`` over the run's second half,
    worst), ``settling_time`` (worst), ``rms_u`` (largest), ``tv_u`` (TV(u) per
    s, summed), ``z1_ripple`` and ``u_ripple`` (peak-to-peak after settling,
    worst), ``saturated`` (share of samples with the input at a limit, largest), ``diverged``, ``never_settled``
    and ``objective`` (the tuning objective ``J``).
    """
    b = case.band
    worst: Callable[[list[float | None]], float | None] = lambda vs: (
        None if any(v is None for v in vs) else max(float(v) for v in vs if v is not None)
    )
    diverged = any(r.diverged for r in results)
    m: dict[str, Any] = {
        "iae": float(sum(r.iae for r in results)),
        "steady_rms": worst([r.steady_rms(b) for r in results]),
        "final_rms": worst([_final_rms(r) for r in results]),
        "settling_time": worst([r.settling_time(b) for r in results]),
        "rms_u": max(r.rms_u for r in results),
        "tv_u": float(sum(r.tv_u_per_s for r in results)),
        "z1_ripple": worst([r.z1_ripple(b) for r in results]),
        "u_ripple": worst([r.ripple(b) for r in results]),
        "saturated": max(_at_limit(r) for r in results),
        "diverged": diverged,
        "never_settled": any(r.never_settled(b) for r in results),
    }
    if diverged:
        m.update(final_rms=None, steady_rms=None, settling_time=None, objective=1e6)
        return m
    tv = sum(r.tv_u_per_s / h for r, h in zip(results, case.hold))
    m["objective"] = m["iae"] / (b * t_end) + TV_WEIGHT * tv + 10.0 * m["never_settled"]
    return m


def _at_limit(r: Any) -> float:
    """Share of samples with the input at a limit: ``v`` outside, or ``u`` on it.

    A peer clamps its own output to the limits (simple-pid, pyadrc), so its
    ``v`` never lies outside them; ``u`` on a limit counts for all alike.
    """
    if r.u_limits is None or not len(r.u):
        return 0.0
    lo, hi = r.u_limits
    tol = 1e-9 * max(1.0, abs(lo), abs(hi))
    u = np.asarray(r.u)
    return float(np.mean(np.asarray(r.saturated) | (u <= lo + tol) | (u >= hi - tol)))


def _final_rms(r: Any) -> float | None:
    t = np.asarray(r.t)
    tail = r.z1[t >= 0.5 * float(t[-1])]
    return float(np.sqrt(np.mean(np.square(tail)))) if tail.size else None


def _work(task: dict[str, Any]) -> dict[str, Any]:
    """The worker: one run of a task, its metrics (never raises for a failed loop)."""
    t0 = time.perf_counter()
    case = _case(task["case"])
    horizon = task.get("t_end") or case.t_end
    try:
        res = run(
            case,
            task["kind"],
            task["params"],
            task["condition"],
            factors=task.get("factors"),
            t_end=horizon,
            seed=task.get("seed", 0),
        )
        m = metrics(case, res, horizon)
    except (ValueError, FloatingPointError, ArithmeticError) as exc:
        m = {"diverged": True, "never_settled": True, "objective": 1e6, "error": str(exc)}
    m["runtime_s"] = time.perf_counter() - t0
    return {**task, "metrics": m}


# ---------------------------------------------------------------------------
# tuning and evaluation
# ---------------------------------------------------------------------------


def _lhs(rng: np.random.Generator, n: int, d: int) -> np.ndarray:
    """``n`` Latin-hypercube points in ``[0, 1]^d``."""
    out = np.empty((n, d))
    for j in range(d):
        out[:, j] = (rng.permutation(n) + rng.random(n)) / n
    return out


class _Pool:
    """Runs task lists in parallel (or in-process for ``jobs == 1``) with a progress bar."""

    def __init__(self, jobs: int, progress: Any) -> None:
        self.jobs, self.progress = jobs, progress
        self.ex = ProcessPoolExecutor(max_workers=jobs) if jobs > 1 else None

    def map(self, tasks: list[dict[str, Any]]) -> list[dict[str, Any]]:
        out: list[dict[str, Any]] = [{} for _ in tasks]
        if self.ex is None:
            for i, t in enumerate(tasks):
                out[i] = _work(t)
                self._tick(out[i])
            return out
        futures = {self.ex.submit(_work, t): i for i, t in enumerate(tasks)}
        for fut in as_completed(futures):
            out[futures[fut]] = fut.result()
            self._tick(out[futures[fut]])
        return out

    def _tick(self, r: dict[str, Any]) -> None:
        if self.progress is not None:
            tag = "diverged" if r["metrics"].get("diverged") else "ok"
            label = f"{r['stage']} {r['case']} {r['kind']} {r['condition']} ({tag})"
            self.progress.step(label, r["metrics"]["runtime_s"])

    def close(self) -> None:
        if self.ex is not None:
            self.ex.shutdown()


def tune_budget(quick: bool) -> tuple[int, int]:
    """``(B, rounds)``: closed-loop runs per controller and plant, refinement rounds."""
    return (8, 2) if quick else (24, 3)


def compare(
    *,
    quick: bool = False,
    jobs: int | None = None,
    progress: Any = None,
    seed: int = 2026,
    dispersion_plants: int | None = None,
    case_names: Sequence[str] | None = None,
) -> dict[str, Any]:
    """Tune every controller on every plant, then run every condition.

    Parameters
    ----------
    quick : bool
        Two plants, five conditions, budget 8, 2 dispersed plants, 4 s horizons.
    jobs : int, optional
        Worker processes (default: the CPU count).
    progress : object with ``step(label, seconds)``, optional
        E.g. :class:`famcc.reporting.Progress`; :func:`total_runs` gives its total.
    seed : int
        Seeds the tuning, the noise and the dispersion.
    dispersion_plants : int, optional
        Dispersed plants per case (default 6, quick 2).
    case_names : sequence of str, optional
        A subset of :func:`cases`.

    Returns
    -------
    dict
        ``meta``, ``tuned`` (per case and controller: parameters, objective,
        the search history) and ``runs`` (per case, controller and condition:
        the metrics; ``dispersion`` holds the worst over the dispersed plants).
    """
    t0 = time.perf_counter()
    chosen = [c for c in cases(quick) if case_names is None or c.name in case_names]
    if not chosen:
        raise ValueError(f"case_names matched no case: {case_names!r}")
    jobs = max(1, int(jobs or os.cpu_count() or 1))
    budget, rounds = tune_budget(quick)
    n_disp = dispersion_plants if dispersion_plants is not None else (2 if quick else 6)

    def horizon(c: Case) -> float:
        return min(c.t_end, 4.0) if quick else c.t_end

    pool = _Pool(jobs, progress)
    try:
        tuned = _tune(pool, chosen, budget, rounds, seed, horizon)
        runs = _evaluate(pool, chosen, tuned, quick, n_disp, seed, horizon)
    finally:
        pool.close()
    return {
        "meta": {
            "quick": quick,
            "budget": budget,
            "rounds": rounds,
            "dispersion_plants": n_disp,
            "seed": seed,
            "jobs": jobs,
            "conditions": list(QUICK_CONDITIONS if quick else CONDITIONS),
            "controllers": controllers(),
            "cases": [c.name for c in chosen],
            "runtime_s": time.perf_counter() - t0,
        },
        "cases": {c.name: _case_meta(c, horizon(c)) for c in chosen},
        "tuned": tuned,
        "runs": runs,
    }


def total_runs(
    quick: bool = False, dispersion_plants: int | None = None, n_cases: int | None = None
) -> int:
    """The number of closed-loop runs :func:`compare` makes (for a progress bar)."""
    budget, _ = tune_budget(quick)
    conds = QUICK_CONDITIONS if quick else CONDITIONS
    n_disp = dispersion_plants if dispersion_plants is not None else (2 if quick else 6)
    per = budget + len(conds) - 2 + n_disp  # nominal is the tuning's best; dispersion: n_disp
    return per * len(_KINDS) * (n_cases if n_cases is not None else len(cases(quick)))


def _case_meta(c: Case, horizon: float) -> dict[str, Any]:
    return {
        "title": c.title,
        "order": c.order,
        "joints": c.joints,
        "band": c.band,
        "t_end": horizon,
        "limits": c.limits,
        "saturated": c.saturated,
        "gain": c.gain,
        "hold": c.hold,
        "output_unit": c.output_unit,
        "input_unit": c.input_unit,
        "family": c.family,
    }


def _tune(
    pool: _Pool,
    chosen: list[Case],
    budget: int,
    rounds: int,
    seed: int,
    horizon: Callable[[Case], float],
) -> dict[str, Any]:
    spaces = {
        (c.name, k): [space(k, c, j) for j in range(c.joints)] for c in chosen for k in _KINDS
    }
    rngs = {
        key: np.random.default_rng([seed, ci, ki])
        for ci, c in enumerate(chosen)
        for ki, k in enumerate(_KINDS)
        for key in [(c.name, k)]
    }
    hist: dict[tuple[str, str], list[tuple[np.ndarray, float, dict[str, Any]]]] = {
        key: [] for key in spaces
    }
    case_of = {c.name: c for c in chosen}

    def tasks_for(points: dict[tuple[str, str], np.ndarray]) -> list[dict[str, Any]]:
        out = []
        for key, us in points.items():
            for u in us:
                params = [s.params(u) for s in spaces[key]]
                out.append(
                    {
                        "stage": "tune",
                        "case": key[0],
                        "kind": key[1],
                        "params": params,
                        "condition": "nominal",
                        "u": u.tolist(),
                        "t_end": horizon(case_of[key[0]]),
                    }
                )
        return out

    def record(results: list[dict[str, Any]]) -> None:
        for r in results:
            hist[(r["case"], r["kind"])].append(
                (np.array(r["u"]), float(r["metrics"]["objective"]), r["metrics"])
            )

    first = budget - budget // 2
    starts = {}
    for key, sp in spaces.items():  # the default first, then a Latin hypercube
        starts[key] = np.vstack([sp[0].unit(sp[0].default), _lhs(rngs[key], first - 1, sp[0].dims)])
    record(pool.map(tasks_for(starts)))
    left = budget - first
    for r in range(rounds):
        m = left // (rounds - r)
        left -= m
        if m == 0:
            continue
        sigma = 0.2 * 0.5**r
        points = {}
        for key in spaces:
            best = min(hist[key], key=lambda h: h[1])[0]
            step = rngs[key].normal(0.0, sigma, size=(m, best.size))
            points[key] = np.clip(best + step, 0.0, 1.0)
        record(pool.map(tasks_for(points)))
    out: dict[str, Any] = {}
    for (name, kind), h in hist.items():
        best_u, best_j, best_m = min(h, key=lambda e: e[1])
        out.setdefault(name, {})[kind] = {
            "params": [s.params(best_u) for s in spaces[(name, kind)]],
            "u": best_u.tolist(),
            "objective": best_j,
            "nominal": best_m,
            "history": [e[1] for e in h],
            "diverged_candidates": sum(1 for e in h if e[2].get("diverged")),
        }
    return out


def _evaluate(
    pool: _Pool,
    chosen: list[Case],
    tuned: dict[str, Any],
    quick: bool,
    n_disp: int,
    seed: int,
    horizon: Callable[[Case], float],
) -> dict[str, Any]:
    conds = QUICK_CONDITIONS if quick else CONDITIONS
    tasks = []
    for ci, c in enumerate(chosen):
        rng = np.random.default_rng([seed, 99, ci])
        draws = [
            {k: float(rng.uniform(1 - DISPERSION, 1 + DISPERSION)) for k in c.params}
            for _ in range(n_disp)
        ]
        for kind in _KINDS:
            params = tuned[c.name][kind]["params"]
            for cond in conds:
                if cond == "nominal":
                    continue  # the tuning's best run is the nominal one
                if cond == "dispersion":
                    for i, f in enumerate(draws):
                        tasks.append(
                            {
                                "stage": "eval",
                                "case": c.name,
                                "kind": kind,
                                "params": params,
                                "condition": "nominal",
                                "factors": f,
                                "seed": seed + i,
                                "dispersion": i,
                                "t_end": horizon(c),
                            }
                        )
                    continue
                tasks.append(
                    {
                        "stage": "eval",
                        "case": c.name,
                        "kind": kind,
                        "params": params,
                        "condition": cond,
                        "seed": seed,
                        "t_end": horizon(c),
                    }
                )
    done = pool.map(tasks)
    runs: dict[str, Any] = {
        c.name: {k: {"nominal": tuned[c.name][k]["nominal"]} for k in _KINDS} for c in chosen
    }
    disp: dict[tuple[str, str], list[dict[str, Any]]] = {}
    for r in done:
        if "dispersion" in r:
            disp.setdefault((r["case"], r["kind"]), []).append(r["metrics"])
        else:
            runs[r["case"]][r["kind"]][r["condition"]] = r["metrics"]
    for (name, kind), ms in disp.items():
        runs[name][kind]["dispersion"] = _worst_of(ms)
    return runs


def _worst_of(ms: list[dict[str, Any]]) -> dict[str, Any]:
    """The worst over dispersed plants: largest numbers, any flag; counts of failures."""
    out: dict[str, Any] = {"plants": len(ms)}
    for key in (
        "iae",
        "steady_rms",
        "final_rms",
        "settling_time",
        "rms_u",
        "tv_u",
        "z1_ripple",
        "u_ripple",
        "saturated",
        "objective",
    ):
        vals = [m.get(key) for m in ms]
        nums = [float(v) for v in vals if v is not None]
        out[key] = None if len(nums) < len(vals) else max(nums)
    out["diverged"] = any(m.get("diverged") for m in ms)
    out["never_settled"] = any(m.get("never_settled") for m in ms)
    out["diverged_count"] = sum(1 for m in ms if m.get("diverged"))
    out["never_settled_count"] = sum(1 for m in ms if m.get("never_settled"))
    return out


# ---------------------------------------------------------------------------
# what the numbers say
# ---------------------------------------------------------------------------

#: The radar's axes: (name, condition, metric), lower metric is better.
RADAR = (
    ("accuracy", "nominal", "final_rms"),
    ("speed", "nominal", "settling_time"),
    ("effort", "nominal", "rms_u"),
    ("smoothness", "nominal", "tv_u"),
    ("noise robustness", "noise 1e-3", "final_rms"),
    ("saturation robustness", "saturated", "iae"),
)

#: The metrics "Where famcc loses" compares (lower is better).
LOSS_METRICS = (("iae", "IAE"), ("final_rms", "RMS z1 (2nd half)"), ("tv_u", "TV(u)/s"))


def _value(m: dict[str, Any] | None, metric: str, t_end: float) -> float | None:
    """A metric for ranking: None when diverged; a never-settled run takes the horizon."""
    if m is None or m.get("diverged"):
        return None
    v = m.get(metric)
    if v is None and metric == "settling_time":
        return t_end
    return None if v is None else float(v)


def radar_scores(result: dict[str, Any], name: str) -> dict[str, dict[str, float]]:
    """Per controller and radar axis, a score in [0, 1] (1 the best of the four).

    ``score = log(worst / v) / log(worst / best)`` of the axis' metric ``v``
    (lower is better; a log scale because the metrics span decades); all 1 when
    the four are within 5 %; 0 for a diverged run. A never-settled run's
    settling time is the horizon. Axes whose condition was not run are left out.
    """
    runs, t_end = result["runs"][name], result["cases"][name]["t_end"]
    out: dict[str, dict[str, float]] = {k: {} for k in runs}
    for axis, cond, metric in RADAR:
        if any(cond not in runs[k] for k in runs):
            continue
        vals = {k: _value(runs[k][cond], metric, t_end) for k in runs}
        ok = [v for v in vals.values() if v is not None]
        floor = 1e-12
        for k, v in vals.items():
            if v is None:
                out[k][axis] = 0.0
            elif len(ok) < 2 or max(ok) <= 1.05 * max(min(ok), floor):
                out[k][axis] = 1.0
            else:
                lo, hi = max(min(ok), floor), max(ok)
                out[k][axis] = float(math.log(hi / max(v, floor)) / math.log(hi / lo))
    return out


def losses(result: dict[str, Any]) -> list[dict[str, Any]]:
    """Every (plant, condition, metric) where a peer beats famcc, from the numbers.

    A loss: famcc diverged (or never settled) where a peer did not, or a peer's
    metric from :data:`LOSS_METRICS` is more than :data:`LOSS_FACTOR` times
    better than famcc's. Each entry names the best such peer with both values.
    """
    out = []
    for name, runs in result["runs"].items():
        for cond in result["meta"]["conditions"]:
            fm = runs["famcc"].get(cond)
            if fm is None:
                continue
            peers = [k for k in runs if k != "famcc" and cond in runs[k]]
            for flag in ("diverged", "never_settled"):
                if fm.get(flag):
                    fine = [k for k in peers if not runs[k][cond].get(flag)]
                    if fine:
                        out.append(
                            {
                                "case": name,
                                "condition": cond,
                                "metric": flag,
                                "winners": fine,
                                "famcc": True,
                                "peer": False,
                            }
                        )
            if fm.get("diverged"):
                continue
            for metric, _label in LOSS_METRICS:
                fv = fm.get(metric)
                if fv is None:
                    continue
                best = None
                for k in peers:
                    pm = runs[k][cond]
                    pv = None if pm.get("diverged") else pm.get(metric)
                    if pv is not None and pv * LOSS_FACTOR < fv and (best is None or pv < best[1]):
                        best = (k, float(pv))
                if best is not None:
                    out.append(
                        {
                            "case": name,
                            "condition": cond,
                            "metric": metric,
                            "winners": [best[0]],
                            "famcc": float(fv),
                            "peer": best[1],
                            "ratio": float(fv) / max(best[1], 1e-300),
                        }
                    )
    return out


def loss_text(loss: dict[str, Any]) -> str:
    """One line of "Where famcc loses"."""
    where = f"{loss['case']}, {loss['condition']}"
    if loss["metric"] in ("diverged", "never_settled"):
        what = "diverged" if loss["metric"] == "diverged" else "never settled to the band"
        return f"{where}: famcc {what}; {', '.join(loss['winners'])} did not."
    label = dict(LOSS_METRICS)[loss["metric"]]
    return (
        f"{where}: {label} {loss['winners'][0]} {_g(loss['peer'])} vs famcc "
        f"{_g(loss['famcc'])} ({loss['ratio']:.1f}x)"
    )


def _g(v: Any, digits: int = 3) -> str:
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    return f"{float(v):.{digits}g}"


# ---------------------------------------------------------------------------
# the report
# ---------------------------------------------------------------------------

_LABEL = {"famcc": "famcc", "lmcc": "LMCC", "pid": "PID", "adrc": "ADRC"}
_COLOR = {"famcc": "C3", "lmcc": "C1", "pid": "C0", "adrc": "C2"}


def _radar_figure(scores: dict[str, dict[str, float]], title: str) -> Any:
    import matplotlib.pyplot as plt

    axes = [a for a, _, _ in RADAR if all(a in s for s in scores.values())]
    ang = np.linspace(0, 2 * np.pi, len(axes), endpoint=False).tolist()
    fig = plt.figure(figsize=(5.6, 4.2), dpi=80)
    ax = fig.add_axes((0.14, 0.1, 0.6, 0.76), projection="polar")
    for kind, s in scores.items():
        vals = [0.05 + 0.95 * s[a] for a in axes]
        ax.plot(ang + ang[:1], vals + vals[:1], color=_COLOR[kind], label=_LABEL[kind], lw=1.6)
        ax.fill(ang + ang[:1], vals + vals[:1], color=_COLOR[kind], alpha=0.08)
    ax.set_xticks(ang)
    ax.set_xticklabels(axes, fontsize=7)
    ax.set_yticks([0.05, 0.525, 1.0])
    ax.set_yticklabels(["worst", "", "best"], fontsize=6)
    ax.set_ylim(0, 1.05)
    ax.set_title(title, fontsize=9)
    ax.legend(loc="upper left", bbox_to_anchor=(1.12, 1.05), fontsize=7)
    return fig


def _series_figure(case: Case, results: dict[str, Any], condition: str) -> Any:
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.0, 4.4), dpi=80, sharex=True)
    for kind, res in results.items():
        r = res[0]
        a1.plot(r.t, r.z1, color=_COLOR[kind], lw=0.8, label=_LABEL[kind])
        a2.plot(r.t, r.u, color=_COLOR[kind], lw=0.6)
    a1.axhline(case.band, color="k", ls=":", lw=0.7)
    a1.axhline(-case.band, color="k", ls=":", lw=0.7)
    lim = 5 * case.band
    a1.set_ylim(-lim, lim)
    a1.set_ylabel(f"z1 [{case.output_unit}]" if case.output_unit else "z1")
    a2.set_ylabel(f"u [{case.input_unit}]" if case.input_unit else "u (joint 1)")
    a2.set_xlabel("t [s]")
    a1.legend(fontsize=7, ncol=4, loc="upper right")
    a1.set_title(f"{case.name}, {condition}: error (band dotted, zoomed) and input", fontsize=9)
    fig.tight_layout()
    return fig


def _telling(result: dict[str, Any], name: str, found: list[dict[str, Any]]) -> str:
    """The condition to draw for a plant: famcc's largest loss, else the mid noise level."""
    mine = [x for x in found if x["case"] == name]
    conds = result["meta"]["conditions"]
    if mine:
        worst = max(mine, key=lambda x: x.get("ratio", 1e9))
        if worst["condition"] != "dispersion":
            return str(worst["condition"])
    return "noise 1e-3" if "noise 1e-3" in conds else "nominal"


def write_report(result: dict[str, Any], out: str | Path, *, figures: bool = True) -> Path:
    """Writes ``report.md``, ``results.json`` and the figures into ``out``; returns the report."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(out)
    (out / "figures").mkdir(parents=True, exist_ok=True)
    found = losses(result)
    meta = result["meta"]
    lines = _intro(result) + _overview(result)
    for name in meta["cases"]:
        case, info = _case(name), result["cases"][name]
        lines += [
            f"## {name}",
            "",
            (
                f"{info['title']}; band {_g(case.band)} {case.output_unit}, "
                f"horizon {_g(info['t_end'])} s, limits {_lims(case.limits)}, saturated "
                f"{_lims(case.saturated)}."
            ),
            "",
        ]
        lines += _tuned_table(result, name) + [""] + _table(result, name) + [""]
        if figures:
            scores = radar_scores(result, name)
            fig = _radar_figure(scores, f"{name}: characteristics (1 kHz)")
            fig.savefig(out / "figures" / f"{name}-radar.png")
            plt.close(fig)
            cond = _telling(result, name, found)
            series = {
                k: run(
                    case,
                    k,
                    result["tuned"][name][k]["params"],
                    cond,
                    t_end=info["t_end"],
                    seed=meta["seed"],
                )
                for k in _KINDS
            }
            fig = _series_figure(case, series, cond)
            fig.savefig(out / "figures" / f"{name}-series.png")
            plt.close(fig)
            # famcc's own run of that case, in the figure of `famcc reproduce`
            fig = series["famcc"][0].plot(
                ["accuracy", "input"], eps=case.band, title=f"famcc on {name}, {cond}"
            )
            fig.savefig(out / "figures" / f"{name}-famcc.png", dpi=55)
            plt.close(fig)
            lines += [
                f"![{name} radar](figures/{name}-radar.png)",
                f"![{name} time series, {cond}](figures/{name}-series.png)",
                "",
                "famcc's run in that case (`SimResult.plot`; the first joint for the arm):",
                "",
                f"![famcc on {name}, {cond}](figures/{name}-famcc.png)",
                "",
            ]
    lines += ["## Where famcc loses", ""]
    if not found:
        lines += [
            (
                "Nowhere in these runs: no peer beat famcc by more than "
                f"{LOSS_FACTOR:g}x on {', '.join(lb for _, lb in LOSS_METRICS)}."
            ),
            "",
        ]
    else:
        lines += [
            (
                f"Generated from the tables: every plant and condition where a peer beats "
                f"famcc by more than {LOSS_FACTOR:g}x on {', '.join(lb for _, lb in LOSS_METRICS)}"
                ", or where famcc diverged or never settled and a peer did not "
                f"({len(found)} cases)."
            ),
            "",
        ]
        for name in meta["cases"]:
            mine = [x for x in found if x["case"] == name]
            if mine:
                lines += [f"- {loss_text(x)}" for x in mine]
        lines += [""]
        lines += _loss_summary(found, meta)
    (out / "report.md").write_text("\n".join(lines) + "\n")
    payload = {**result, "losses": found}
    (out / "results.json").write_text(json.dumps(payload, indent=1, default=_json))
    return out / "report.md"


def _json(v: Any) -> Any:
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    raise TypeError(type(v).__name__)


def _lims(limits: Sequence[Sequence[float]]) -> str:
    return ", ".join(f"[{_g(lo)}, {_g(hi)}]" for lo, hi in limits)


def _intro(result: dict[str, Any]) -> list[str]:
    meta = result["meta"]
    b, rounds = meta["budget"], meta["rounds"]
    mode = "quick (`--quick`)" if meta["quick"] else "full"
    return [
        "# famcc compare: famcc against PID, ADRC and LMCC",
        "",
        (
            f"Run: {mode}, {len(meta['cases'])} plants x {len(meta['controllers'])} controllers x "
            f"{len(meta['conditions'])} conditions, {meta['jobs']} worker processes, "
            f"**{meta['runtime_s']:.0f} s** wall time (seed {meta['seed']}). Written by "
            "`famcc compare` (`famcc.compare`); the numbers are in `results.json`."
        ),
        "",
        (
            "**Controllers.** famcc: the paper's design family of each plant "
            "(finite-time LaMC, variable-exponent LoMC + SSMD, or recursive fixed-time "
            "LoMC + NSMD) with its flexible boundary; LMCC: famcc with `Linear` stages and "
            "no flexible boundary (`rho_e=None`), the low-complexity PPC special case the "
            "paper names; PID: simple-pid with its output limits (anti-windup) and a "
            "first-order measurement filter; ADRC: linear ADRC with an ESO, bandwidth-"
            "parameterised, `b0` = the plant's nominal gain (pyadrc at order 2, the same "
            "discretisation generalised at orders 3 and 4). Each joint of the arm has its "
            "own controller (decentralised)."
        ),
        "",
        (
            f"**Tuning (the same for all four).** Budget {b} closed-loop runs per controller "
            f"and plant on the nominal plant at 1 kHz: the controller's documented default "
            "(famcc: the paper's design of the example, scaled by the plant's holding input "
            "H elsewhere; PID and ADRC: pole placement at 10 rad/s), "
            f"{b - b // 2 - 1} Latin-hypercube points over its documented ranges "
            "(`famcc.compare.space`, every range log-uniform and scaled by the plant's gain "
            "G, H and the band), then "
            f"{b // 2} in {rounds} rounds of Gaussian steps around the best so far. "
            "Objective `J = IAE / (band T) + 0.01 TV(u) / H + 10 [never settled]`, "
            "`J = 1e6` when diverged (`H` the plant's holding input). The best candidate is "
            "then run unchanged under every condition."
        ),
        "",
        (
            "**Conditions.** nominal (1 kHz); saturated (the tighter limits given per plant); "
            "measurement noise, white Gaussian with std 1e-4, 1e-3, 1e-2 output units; "
            f"dispersion: {meta['dispersion_plants']} plants with every physical parameter "
            f"times U(0.7, 1.3), the worst of them shown; 200 Hz (the same parameters). "
            "A run diverges when |z1| exceeds 10 max(|z1(0)|, 1) or a value becomes non-finite."
        ),
        "",
        (
            "**Metrics.** IAE (int |z1| dt, output unit s, summed over joints); RMS z1 over "
            "the second half of the run; steady RMS and settling time to the band (- when "
            "never settled); RMS u; TV(u)/s (total variation of u per second); peak-to-peak "
            "ripple of z1 and u after settling; saturated: share of samples with the input "
            "at a limit (the peers clamp their own output); flags. "
            "`famcc.SimResult` has them all (`iae`, `steady_rms`, `rms_u`, `tv_u_per_s`, "
            "`z1_ripple`, `ripple`, `diverged`, `never_settled`)."
        ),
        "",
        (
            "**Radar charts** (the paper's empty figure 'Comparison of characteristics of "
            "different controllers'): accuracy = nominal RMS z1 (2nd half), speed = nominal "
            "settling time (horizon if never), effort = nominal RMS u, smoothness = nominal "
            "TV(u)/s, noise robustness = RMS z1 (2nd half) at noise 1e-3, saturation "
            "robustness = IAE with the tighter limits. Each axis scores "
            "`log(worst / v) / log(worst / best)`: 1 the best of the four, 0 the worst or "
            "diverged; all 1 within 5 %."
        ),
        "",
    ]


def _rank(runs: dict[str, Any], cond: str, metric: str) -> list[str]:
    """The controllers that did not diverge, best first by ``metric`` (None last)."""
    live = [k for k in _KINDS if cond in runs[k] and not runs[k][cond].get("diverged")]
    return sorted(
        live, key=lambda k: (runs[k][cond].get(metric) is None, runs[k][cond].get(metric) or 0.0)
    )


def _overview(result: dict[str, Any]) -> list[str]:
    """Per plant and condition: the best IAE, and famcc's place among the four."""
    conds = result["meta"]["conditions"]
    rows = [
        "## Overview",
        "",
        (
            "Best IAE per plant and condition, and famcc's place by IAE among the four "
            "(`div.`: famcc diverged). The tables below have every metric."
        ),
        "",
        "| plant | " + " | ".join(conds) + " |",
        "|---|" + "---|" * len(conds),
    ]
    for name, runs in result["runs"].items():
        cells = []
        for cond in conds:
            order = _rank(runs, cond, "iae")
            place = f"famcc {order.index('famcc') + 1}." if "famcc" in order else "famcc div."
            cells.append(f"{_LABEL[order[0]]} ({place})" if order else "all diverged")
        rows.append(f"| {name} | " + " | ".join(cells) + " |")
    return [*rows, ""]


def _tuned_table(result: dict[str, Any], name: str) -> list[str]:
    rows = [
        "| controller | tuned parameters (joint 1) | J nominal | diverged candidates |",
        "|---|---|---|---|",
    ]
    for k in _KINDS:
        t = result["tuned"][name][k]
        p = t["params"][0]
        shown = ", ".join(
            f"{key} {_g(v)}"
            for key, v in p.items()
            if isinstance(v, float) and key not in ("band", "gain", "b0")
        )
        rows.append(
            f"| {_LABEL[k]} | {shown} | {_g(t['objective'])} | "
            f"{t['diverged_candidates']}/{len(t['history'])} |"
        )
    return rows


def _table(result: dict[str, Any], name: str) -> list[str]:
    runs = result["runs"][name]
    rows = [
        (
            "| condition | controller | IAE | RMS z1 (2nd half) | steady RMS | settling [s] | "
            "RMS u | TV(u)/s | ripple z1 | ripple u | saturated | flags |"
        ),
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for cond in result["meta"]["conditions"]:
        vals = {k: _value(runs[k].get(cond), "iae", 0.0) for k in _KINDS}
        ok = [v for v in vals.values() if v is not None]
        best = min(ok) if ok else None
        for k in _KINDS:
            m = runs[k].get(cond)
            if m is None:
                continue
            flags = []
            if m.get("diverged"):
                n = m.get("diverged_count")
                flags.append("diverged" + (f" {n}/{m['plants']}" if n is not None else ""))
            if m.get("never_settled") and not m.get("diverged"):
                n = m.get("never_settled_count")
                flags.append("never settled" + (f" {n}/{m['plants']}" if n is not None else ""))
            iae = _g(m.get("iae"))
            if best is not None and vals[k] == best:
                iae = f"**{iae}**"
            rows.append(
                f"| {cond} | {_LABEL[k]} | {iae} | {_g(m.get('final_rms'))} | "
                f"{_g(m.get('steady_rms'))} | {_g(m.get('settling_time'))} | "
                f"{_g(m.get('rms_u'))} | {_g(m.get('tv_u'))} | {_g(m.get('z1_ripple'))} | "
                f"{_g(m.get('u_ripple'))} | {_pct(m.get('saturated'))} | {', '.join(flags)} |"
            )
    return rows


def _pct(v: Any) -> str:
    return "-" if v is None else f"{100 * float(v):.3g} %"


def _loss_summary(found: list[dict[str, Any]], meta: dict[str, Any]) -> list[str]:
    """Counts per peer and per condition (from the same list)."""
    by_peer: dict[str, int] = {}
    by_cond: dict[str, int] = {}
    for x in found:
        for w in x["winners"]:
            by_peer[w] = by_peer.get(w, 0) + 1
        by_cond[x["condition"]] = by_cond.get(x["condition"], 0) + 1
    peer_text = ", ".join(f"{_LABEL[k]} {by_peer[k]}" for k in _KINDS if k in by_peer)
    cond_text = ", ".join(f"{c} {by_cond[c]}" for c in meta["conditions"] if c in by_cond)
    return [f"Losses by winning peer: {peer_text}. By condition: {cond_text}.", ""]
