"""Held-out plants for ``benches/heldout.py``: written the way an engineer writes them.

None of these is in the package: an ``if`` in a load, ``np.tanh`` friction, a
negative input gain, a square root that needs clipping, a MuJoCo model. Each
case gives the plant, the sample period, the actuator's limits, the accuracy
``eps``, the settling time and the constant set point.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from famcc.plants import Plant


class VanDerPol(Plant):
    """``x'' = 1.5 (1 - x^2) x' - x + u``: an unstable limit cycle to regulate."""

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        return np.array([x[1], 1.5 * (1 - x[0] ** 2) * x[1] - x[0] + u])


class Tank(Plant):
    """A gravity-drained tank, ``A h' = u - c sqrt(h)``, pump input in [0, 2]."""

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        h = max(x[0], 0.0)
        return np.array([(u - 0.6 * np.sqrt(h)) / 1.5])


class Motor3(Plant):
    """A DC motor with its armature inductance (order 3) and a step load at 2 s."""

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        _theta, w, i = x
        load = 0.3 if t >= 2.0 else 0.0
        return np.array([w, (0.5 * i - 0.1 * w - load) / 0.01, (u - 1.0 * i - 0.5 * w) / 0.05])


class Maglev(Plant):
    """Magnetic levitation: more current lifts the ball, so ``y`` falls (negative gain)."""

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        return np.array([x[1], 9.81 - 0.05 * u / x[0] - 0.5 * np.tanh(50 * x[1])])


class Roll(Plant):
    """A quadrotor's roll axis with a gust on [1, 1.2) s."""

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        gust = 0.5 if 1.0 <= t < 1.2 else 0.0
        return np.array([x[1], (u - 0.02 * x[1]) / 0.01 + gust])


#: A damped double pendulum in MuJoCo, its shoulder driven by a torque motor.
PENDULUM = """
<mujoco>
  <option timestep="0.001"/>
  <worldbody>
    <body pos="0 0 1">
      <joint name="hinge" type="hinge" axis="0 1 0" damping="0.05"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.02" mass="0.5"/>
      <body pos="0 0 -0.3">
        <joint name="elbow" type="hinge" axis="0 1 0" damping="0.2"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.2" size="0.015" mass="0.1"/>
      </body>
    </body>
  </worldbody>
  <actuator><motor name="torque" joint="hinge" ctrlrange="-3 3"/></actuator>
</mujoco>
"""


def _mujoco_pendulum() -> Any:
    from famcc.plants import MuJoCo

    return MuJoCo(PENDULUM, actuator="torque", joint="hinge", x0=[0.0, 0.0])


def cases() -> dict[str, dict[str, Any]]:
    """The held-out cases by name (built afresh: a MuJoCo model per call)."""
    out: dict[str, dict[str, Any]] = {
        "van-der-pol": {
            "plant": VanDerPol(2, [2.0, 0.0]),
            "dt": 1e-3,
            "u_limits": (-3.0, 3.0),
            "eps": 0.05,
            "settle_time": 5.0,
            "r": 0.0,
        },
        "tank": {
            "plant": Tank(1, [0.5]),
            "dt": 0.01,
            "u_limits": (0.0, 2.0),
            "eps": 0.02,
            "settle_time": 15.0,
            "r": 1.0,
        },
        "motor3-load": {
            "plant": Motor3(3, [0.0, 0.0, 0.0]),
            "dt": 1e-3,
            "u_limits": (-12.0, 12.0),
            "eps": 0.02,
            "settle_time": 1.5,
            "r": 1.0,
        },
        "maglev": {
            "plant": Maglev(2, [0.025, 0.0]),
            "dt": 1e-3,
            "u_limits": (0.0, 10.0),
            "eps": 0.001,
            "settle_time": 1.0,
            "r": 0.02,
        },
        "roll-gust": {
            "plant": Roll(2, [0.3, 0.0]),
            "dt": 1e-3,
            "u_limits": (-0.5, 0.5),
            "eps": 0.01,
            "settle_time": 0.5,
            "r": 0.0,
        },
    }
    try:
        out["mujoco-pendulum"] = {
            "plant": _mujoco_pendulum(),
            "dt": 2e-3,
            "u_limits": (-3.0, 3.0),
            "eps": 0.01,
            "settle_time": 1.5,
            "r": 1.0,
        }
    except ImportError:  # famcc[mujoco] not installed: the other cases still run
        pass
    return out
