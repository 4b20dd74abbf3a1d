"""A suite of physical plants, with units, beside the paper's: motors, pendulums, joints.

Every plant is a :class:`famcc.plants.StrictFeedback` with NumPy-ufunc callables,
so ``output_derivatives`` and ``gain_and_drift`` (hence ``-F/G``) are exact, plus
a float fast path for the simulator. Each carries its parameters, the names and
units of its output and input, its nominal input gain ``G`` (``y^(n) = G u +
F``) and a :meth:`hold_input` estimate: what a user knows from a datasheet.

===================  =====  ==============================  ===================
plant                order  output                          input
===================  =====  ==============================  ===================
:func:`dc_motor`     2      shaft angle [rad]               voltage [V]
:func:`pendulum`     2      angle from hanging [rad]        torque [N m]
:func:`quadrotor_altitude`  2  altitude [m]                 thrust [N]
:func:`flexible_joint`  4   link angle [rad]                motor torque [N m]
===================  =====  ==============================  ===================

The two-link planar arm (two inputs, one controller per joint) is
:func:`famcc.joints.two_link_arm`, simulated by :func:`famcc.joints.simulate_joints`;
``famcc.plants.two_link_arm`` is the same function.

Loads are smooth steps (``0.5 (1 + tanh((t - t0) / width))``), so that every
callable stays differentiable and ``-F/G`` can be computed.

>>> from famcc.plants import dc_motor
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
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from famcc.plants import StrictFeedback

__all__ = [
    "PhysicalPlant",
    "dc_motor",
    "flexible_joint",
    "pendulum",
    "quadrotor_altitude",
    "smooth_step",
]

G0 = 9.81  # m/s^2


def smooth_step(t: Any, t0: float, width: float) -> Any:
    """``0.5 (1 + tanh((t - t0) / width))``: 0 well before ``t0``, 1 well after.

    Works on floats, arrays and jets (no comparison), so plants stay
    differentiable.

    >>> round(float(smooth_step(0.0, 1.0, 0.01)), 6), round(float(smooth_step(2.0, 1.0, 0.01)), 6)
    (0.0, 1.0)
    """
    if width <= 0:
        raise ValueError(f"width must be > 0, got {width!r}")
    return 0.5 * (1.0 + np.tanh((t - t0) / width))


class PhysicalPlant(StrictFeedback):
    """A :class:`StrictFeedback` plant with physical parameters and units.

    Attributes
    ----------
    params : dict
        The physical parameters.
    output, input : famcc.Signal
        Name and unit of the output ``y = x[0]`` and of the input ``u``.
    gain : float
        The nominal input gain ``G`` of ``y^(n) = G u + F`` (units of
        ``y/s^n`` per input unit); the largest value over the operating range.
    """

    def __init__(
        self,
        g: Sequence[Any],
        f: Sequence[Any],
        x0: Sequence[float],
        *,
        name: str,
        params: dict[str, float],
        output: tuple[str, str],
        input: tuple[str, str],
        gain: float,
        hold: float,
        fast: Callable[[float, Sequence[float], float], tuple[float, ...]] | None = None,
    ) -> None:
        super().__init__(g, f, x0, name=name, output=output, input=input)
        self.params = dict(params)
        self.gain = float(gain)
        self._hold = float(hold)
        self._fast = fast

    def hold_input(self) -> float:
        """A bound on ``|F/G|`` at rest: the input that holds the largest static load."""
        return self._hold

    def rhs_fast(self, t: float, x: Sequence[float], u: float) -> tuple[float, ...]:
        """:meth:`rhs` on plain floats (used by :func:`famcc.simulate`).

        The plant's own float formula when it has one (``fast=``), else the
        callables ``g`` and ``f`` on an array.
        """
        if self._fast is not None:
            return self._fast(t, x, u)
        xa = np.asarray(x, dtype=float)
        n = self.order
        return tuple(
            float(self.g[i](xa, t)) * (x[i + 1] if i + 1 < n else u) + float(self.f[i](xa, t))
            for i in range(n)
        )

    def __repr__(self) -> str:
        p = ", ".join(f"{k}={v:g}" for k, v in self.params.items())
        return f"{self.name}({p})"


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
    for label, v in (("J", J), ("K", K), ("R", R)):
        if not v > 0:
            raise ValueError(f"{label} must be > 0, got {v!r}")
    gain = K / (J * R)
    damp = b / J + K * K / (J * R)

    def f2(x: Any, t: Any) -> Any:
        torque = load * smooth_step(t, t_load, 0.005)
        if load_step:
            torque = torque + load_step * smooth_step(t, t_step, 0.005)
        return -damp * x[1] - torque / J

    def fast(t: float, x: Sequence[float], u: float) -> tuple[float, ...]:
        # f2 on floats, operation for operation (families compare bit for bit)
        torque = load * float(0.5 * (1.0 + np.tanh((t - t_load) / 0.005)))
        if load_step:
            torque = torque + load_step * float(0.5 * (1.0 + np.tanh((t - t_step) / 0.005)))
        return (1.0 * x[1] + 0.0 * x[0], gain * u + (-damp * x[1] - torque / J))

    return PhysicalPlant(
        g=[lambda x, t: 1.0, lambda x, t: gain],
        f=[lambda x, t: 0.0 * x[0], f2],
        x0=x0,
        name="dc-motor",
        params={
            "J": J,
            "b": b,
            "K": K,
            "R": R,
            "load": load,
            "t_load": t_load,
            "load_step": load_step,
            "t_step": t_step,
        },
        output=("angle", "rad"),
        input=("voltage", "V"),
        gain=gain,
        hold=max(abs(load), abs(load + load_step)) * R / K,
        fast=fast,
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
    for label, v in (("m", m), ("l", l)):
        if not v > 0:
            raise ValueError(f"{label} must be > 0, got {v!r}")
    inertia = m * l * l
    gain = 1.0 / inertia

    def f2(x: Any, t: Any) -> Any:
        return -(m * G0 * l * np.sin(x[0]) + b * x[1]) / inertia

    def fast(t: float, x: Sequence[float], u: float) -> tuple[float, ...]:
        f2 = -(m * G0 * l * float(np.sin(x[0])) + b * x[1]) / inertia
        return (1.0 * x[1] + 0.0 * x[0], gain * u + f2)

    return PhysicalPlant(
        g=[lambda x, t: 1.0, lambda x, t: gain],
        f=[lambda x, t: 0.0 * x[0], f2],
        x0=x0,
        name="pendulum",
        params={"m": m, "l": l, "b": b},
        output=("angle", "rad"),
        input=("torque", "N m"),
        gain=gain,
        hold=m * G0 * l,
        fast=fast,
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
    if not mass > 0:
        raise ValueError(f"mass must be > 0, got {mass!r}")

    def g2(x: Any, t: Any) -> Any:
        return np.cos(tilt * np.sin(0.5 * t)) / mass + 0.0 * x[0]

    def f2(x: Any, t: Any) -> Any:
        return -G0 - drag * x[1] / mass

    def fast(t: float, x: Sequence[float], u: float) -> tuple[float, ...]:
        g = float(np.cos(tilt * np.sin(0.5 * t))) / mass + 0.0 * x[0]
        return (1.0 * x[1] + 0.0 * x[0], g * u + (-G0 - drag * x[1] / mass))

    return PhysicalPlant(
        g=[lambda x, t: 1.0, g2],
        f=[lambda x, t: 0.0 * x[0], f2],
        x0=x0,
        name="quadrotor-altitude",
        params={"mass": mass, "drag": drag, "tilt": tilt},
        output=("altitude", "m"),
        input=("thrust", "N"),
        gain=1.0 / mass,
        hold=mass * G0 / math.cos(tilt),
        fast=fast,
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
    for label, v in (("J_link", J_link), ("J_motor", J_motor), ("k", k)):
        if not v > 0:
            raise ValueError(f"{label} must be > 0, got {v!r}")

    def f2(x: Any, t: Any) -> Any:
        return -(k * x[0] + mgl * np.sin(x[0])) / J_link

    def f4(x: Any, t: Any) -> Any:
        return (k * (x[0] - x[2]) - b_motor * x[3]) / J_motor

    def fast(t: float, x: Sequence[float], u: float) -> tuple[float, ...]:
        return (
            1.0 * x[1] + 0.0 * x[0],
            k / J_link * x[2] + -(k * x[0] + mgl * float(np.sin(x[0]))) / J_link,
            1.0 * x[3] + 0.0 * x[0],
            1.0 / J_motor * u + (k * (x[0] - x[2]) - b_motor * x[3]) / J_motor,
        )

    return PhysicalPlant(
        g=[lambda x, t: 1.0, lambda x, t: k / J_link, lambda x, t: 1.0, lambda x, t: 1.0 / J_motor],
        f=[lambda x, t: 0.0 * x[0], f2, lambda x, t: 0.0 * x[0], f4],
        x0=x0,
        name="flexible-joint",
        params={"J_link": J_link, "J_motor": J_motor, "k": k, "mgl": mgl, "b_motor": b_motor},
        output=("link angle", "rad"),
        input=("motor torque", "N m"),
        gain=k / (J_link * J_motor),
        hold=abs(mgl),
        fast=fast,
    )
