"""A suite of physical plants, with units, beside the paper's: motors, pendulums, joints.

Each plant is a :class:`famcc.plants.model.Model` written once (its rows with
NumPy ufuncs), so its output derivatives and ``-F/G`` are exact, its family
(:func:`famcc.plants.family`) computes exactly what its members compute, and
the simulator's fast path runs the same arithmetic on floats. Each member
carries its parameters, the names and units of its output and input, its
nominal input gain ``G`` (``y^(n) = G u + F``) and a :meth:`hold_input`
estimate: what a user knows from a datasheet.

===========================  =====  ==========================  ===================
plant                        order  output                      input
===========================  =====  ==========================  ===================
:func:`dc_motor`             2      shaft angle [rad]           voltage [V]
:func:`pendulum`             2      angle from hanging [rad]    torque [N m]
:func:`quadrotor_altitude`   2      altitude [m]                thrust [N]
:func:`flexible_joint`       4      link angle [rad]            motor torque [N m]
===========================  =====  ==========================  ===================

The two-link planar arm (two inputs, one controller per joint) is
:func:`famcc.plants.two_link_arm`, simulated by :func:`famcc.joints.simulate_joints`.

Loads are smooth steps (``0.5 (1 + tanh((t - t0) / width))``), so that every
row stays differentiable and ``-F/G`` can be computed.

>>> m = dc_motor()
>>> m.order, m.output.name, m.output.unit, m.input.unit
(2, 'angle', 'rad', 'V')
>>> round(m.gain, 3)                    # K / (J R), rad/s^2 per V
25.0
>>> round(m.hold_input(), 3)            # holds the 1 N m load: R T / K
4.0
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from famcc.plants.model import Model, PhysicalPlant

__all__ = [
    "DC_MOTOR",
    "FLEXIBLE_JOINT",
    "G0",
    "MODELS",
    "PENDULUM",
    "QUADROTOR_ALTITUDE",
    "PhysicalPlant",
    "dc_motor",
    "flexible_joint",
    "pendulum",
    "quadrotor_altitude",
    "smooth_step",
]

G0 = 9.81  # m/s^2
#: The width of the loads' smooth steps, s.
STEP_WIDTH = 0.005

Rows = list[tuple[Any, Any]]


def smooth_step(t: Any, t0: Any, width: float) -> Any:
    """``0.5 (1 + tanh((t - t0) / width))``: 0 well before ``t0``, 1 well after.

    Works on floats, arrays and jets (no comparison), so plants stay
    differentiable.

    >>> round(float(smooth_step(0.0, 1.0, 0.01)), 6), round(float(smooth_step(2.0, 1.0, 0.01)), 6)
    (0.0, 1.0)
    """
    if width <= 0:
        raise ValueError(f"width must be > 0, got {width!r}")
    return 0.5 * (1.0 + np.tanh((t - t0) / width))


# -- DC motor ---------------------------------------------------------------------


def _dc_motor_derive(p: Mapping[str, Any]) -> dict[str, Any]:
    J, K, R = p["J"], p["K"], p["R"]
    return {
        "gain": K / (J * R),
        "damp": p["b"] / J + K * K / (J * R),
        "J": J,
        "load": p["load"],
        "t_load": p["t_load"],
        "load_step": p["load_step"],
        "t_step": p["t_step"],
    }


def _dc_motor_terms(t: Any, x: Any, c: Mapping[str, Any]) -> Rows:
    torque = c["load"] * smooth_step(t, c["t_load"], STEP_WIDTH) + c["load_step"] * smooth_step(
        t, c["t_step"], STEP_WIDTH
    )
    return [(1.0, 0.0 * x[0]), (c["gain"], -c["damp"] * x[1] - torque / c["J"])]


DC_MOTOR = Model(
    name="dc-motor",
    order=2,
    params={
        "J": 0.01,
        "b": 0.01,
        "K": 0.25,
        "R": 1.0,
        "load": 1.0,
        "t_load": 2.0,
        "load_step": 0.0,
        "t_step": 3.0,
    },
    x0=(0.0, 0.0),
    derive=_dc_motor_derive,
    terms=_dc_motor_terms,
    output=("angle", "rad"),
    input=("voltage", "V"),
    gain=lambda p: p["K"] / (p["J"] * p["R"]),
    hold=lambda p: max(abs(p["load"]), abs(p["load"] + p["load_step"])) * p["R"] / p["K"],
    positive=("J", "K", "R"),
    description="Position of a DC motor driven by its armature voltage (inductance neglected).",
)


def dc_motor(
    J: float = 0.01,
    b: float = 0.01,
    K: float = 0.25,
    R: float = 1.0,
    load: float = 1.0,
    t_load: float = 2.0,
    x0: Sequence[float] = (0.0, 0.0),
    load_step: float = 0.0,
    t_step: float = 3.0,
) -> PhysicalPlant:
    """Position of a DC motor driven by its armature voltage (inductance neglected).

    ``J theta'' = K i - b theta' - T_load(t)``, ``R i = V - K theta'``, so
    ``theta'' = (K / (J R)) V - (b / J + K^2 / (J R)) theta' - T_load / J``.

    Parameters
    ----------
    J : float
        Rotor and load inertia, kg m^2.
    b : float
        Viscous friction, N m s/rad.
    K : float
        Torque and back-EMF constant, N m/A = V s/rad.
    R : float
        Armature resistance, ohm.
    load : float
        Load torque after ``t_load``, N m (a smooth 5 ms step).
    t_load : float
        Time of the load step, s.
    load_step : float
        A further load torque from ``t_step`` on, N m (a second smooth step).
    t_step : float
        Time of the further step, s.
    x0 : (float, float)
        Initial angle (rad) and speed (rad/s).
    """
    params = {"J": J, "b": b, "K": K, "R": R, "load": load, "t_load": t_load}
    return PhysicalPlant(DC_MOTOR, x0, **params, load_step=load_step, t_step=t_step)


# -- pendulum ---------------------------------------------------------------------


def _pendulum_derive(p: Mapping[str, Any]) -> dict[str, Any]:
    m, l = p["m"], p["l"]
    inertia = m * l * l
    return {"inertia": inertia, "gain": 1.0 / inertia, "m": m, "l": l, "b": p["b"]}


def _pendulum_terms(t: Any, x: Any, c: Mapping[str, Any]) -> Rows:
    f2 = -(c["m"] * G0 * c["l"] * np.sin(x[0]) + c["b"] * x[1]) / c["inertia"]
    return [(1.0, 0.0 * x[0]), (c["gain"], f2)]


PENDULUM = Model(
    name="pendulum",
    order=2,
    params={"m": 0.5, "l": 0.5, "b": 0.05},
    x0=(0.0, 0.0),
    derive=_pendulum_derive,
    terms=_pendulum_terms,
    output=("angle", "rad"),
    input=("torque", "N m"),
    gain=lambda p: 1.0 / (p["m"] * p["l"] * p["l"]),
    hold=lambda p: p["m"] * G0 * p["l"],
    positive=("m", "l"),
    description="A pendulum driven by a torque at its pivot, angle measured from hanging.",
)


def pendulum(
    m: float = 0.5, l: float = 0.5, b: float = 0.05, x0: Sequence[float] = (0.0, 0.0)
) -> PhysicalPlant:
    """A pendulum driven by a torque at its pivot, angle measured from hanging.

    ``m l^2 theta'' = u - m g l sin(theta) - b theta'``.

    Parameters
    ----------
    m : float
        Bob mass, kg.
    l : float
        Length, m.
    b : float
        Viscous friction, N m s/rad.
    x0 : (float, float)
        Initial angle (rad) and speed (rad/s).
    """
    return PhysicalPlant(PENDULUM, x0, m=m, l=l, b=b)


# -- quadrotor altitude -------------------------------------------------------------


def _quadrotor_derive(p: Mapping[str, Any]) -> dict[str, Any]:
    return {"mass": p["mass"], "drag": p["drag"], "tilt": p["tilt"]}


def _quadrotor_terms(t: Any, x: Any, c: Mapping[str, Any]) -> Rows:
    mass = c["mass"]
    g2 = np.cos(c["tilt"] * np.sin(0.5 * t)) / mass + 0.0 * x[0]
    return [(1.0, 0.0 * x[0]), (g2, -G0 - c["drag"] * x[1] / mass)]


QUADROTOR_ALTITUDE = Model(
    name="quadrotor-altitude",
    order=2,
    params={"mass": 1.2, "drag": 0.3, "tilt": 0.2},
    x0=(0.0, 0.0),
    derive=_quadrotor_derive,
    terms=_quadrotor_terms,
    output=("altitude", "m"),
    input=("thrust", "N"),
    gain=lambda p: 1.0 / p["mass"],
    hold=lambda p: p["mass"] * G0 / math.cos(p["tilt"]),
    positive=("mass",),
    description="Altitude of a quadrotor from its total thrust; a slow attitude wobble tilts it.",
)


def quadrotor_altitude(
    mass: float = 1.2, drag: float = 0.3, tilt: float = 0.2, x0: Sequence[float] = (0.0, 0.0)
) -> PhysicalPlant:
    """Altitude of a quadrotor from its total thrust; a slow attitude wobble tilts it.

    ``m z'' = T cos(phi(t)) - m g - c z'`` with ``phi(t) = tilt sin(0.5 t)``; the
    thrust ``T`` must stay in ``[0, T_max]`` (use asymmetric ``u_limits``).

    Parameters
    ----------
    mass : float
        kg.
    drag : float
        Vertical drag, N s/m.
    tilt : float
        Amplitude of the attitude wobble, rad (the thrust's vertical share
        varies between ``cos(tilt)`` and 1).
    x0 : (float, float)
        Initial altitude (m) and climb rate (m/s).
    """
    return PhysicalPlant(QUADROTOR_ALTITUDE, x0, mass=mass, drag=drag, tilt=tilt)


# -- flexible joint ---------------------------------------------------------------


def _flexible_joint_derive(p: Mapping[str, Any]) -> dict[str, Any]:
    return dict(p)


def _flexible_joint_terms(t: Any, x: Any, c: Mapping[str, Any]) -> Rows:
    J_link, J_motor, k = c["J_link"], c["J_motor"], c["k"]
    f2 = -(k * x[0] + c["mgl"] * np.sin(x[0])) / J_link
    f4 = (k * (x[0] - x[2]) - c["b_motor"] * x[3]) / J_motor
    return [(1.0, 0.0 * x[0]), (k / J_link, f2), (1.0, 0.0 * x[0]), (1.0 / J_motor, f4)]


FLEXIBLE_JOINT = Model(
    name="flexible-joint",
    order=4,
    params={"J_link": 0.05, "J_motor": 0.02, "k": 20.0, "mgl": 0.5, "b_motor": 0.05},
    x0=(0.0, 0.0, 0.0, 0.0),
    derive=_flexible_joint_derive,
    terms=_flexible_joint_terms,
    output=("link angle", "rad"),
    input=("motor torque", "N m"),
    gain=lambda p: p["k"] / (p["J_link"] * p["J_motor"]),
    hold=lambda p: abs(p["mgl"]),
    positive=("J_link", "J_motor", "k"),
    description="A single-link arm driven through an elastic joint; output: the link angle.",
)


def flexible_joint(
    J_link: float = 0.05,
    J_motor: float = 0.02,
    k: float = 20.0,
    mgl: float = 0.5,
    b_motor: float = 0.05,
    x0: Sequence[float] = (0.0, 0.0, 0.0, 0.0),
) -> PhysicalPlant:
    """A single-link arm driven through an elastic joint; output: the link angle.

    ``J_l q_l'' = -k (q_l - q_m) - mgl sin(q_l)``,
    ``J_m q_m'' = k (q_l - q_m) + u - b_m q_m'``; state ``(q_l, q_l', q_m, q_m')``,
    relative degree 4, ``G = k / (J_l J_m)``.

    Parameters
    ----------
    J_link, J_motor : float
        Link and motor inertia, kg m^2.
    k : float
        Joint stiffness, N m/rad.
    mgl : float
        Gravity torque at horizontal, N m.
    b_motor : float
        Motor friction, N m s/rad.
    x0 : sequence of 4 float
    """
    return PhysicalPlant(
        FLEXIBLE_JOINT, x0, J_link=J_link, J_motor=J_motor, k=k, mgl=mgl, b_motor=b_motor
    )


#: The suite's models by name.
MODELS = {m.name: m for m in (DC_MOTOR, PENDULUM, QUADROTOR_ALTITUDE, FLEXIBLE_JOINT)}
