"""The textbook two-link planar arm: two inputs, one controller per joint.

:func:`two_link_arm` builds it; :func:`famcc.joints.simulate_joints` closes
one loop per joint (decentralised control: the coupling through the inertia
matrix and gravity acts on each loop as a disturbance).

>>> arm = two_link_arm()
>>> arm.joints, arm.order, [round(g, 2) for g in arm.gain]
(2, 2, [1.71, 13.71])
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from famcc._common import Signal

__all__ = ["TwoLinkArm", "two_link_arm"]

G0 = 9.81  # m/s^2


class TwoLinkArm:
    """A planar two-link arm in a vertical plane, angles from the horizontal.

    ``M(q) q'' + c(q, q') + g(q) + b q' = tau`` with (Spong, Hutchinson and
    Vidyasagar, "Robot Modeling and Control", §7.4) ``M11 = m1 lc1^2 + m2 (l1^2 +
    lc2^2 + 2 l1 lc2 cos q2) + I1 + I2``, ``M12 = m2 (lc2^2 + l1 lc2 cos q2) +
    I2``, ``M22 = m2 lc2^2 + I2``, ``c = h (-(2 q1' q2' + q2'^2), q1'^2)`` with
    ``h = m2 l1 lc2 sin q2``, ``g1 = (m1 lc1 + m2 l1) g cos q1 + m2 lc2 g cos(q1 +
    q2)``, ``g2 = m2 lc2 g cos(q1 + q2)``. State ``(q1, q1', q2, q2')``: joint ``i``
    is ``x[2 i : 2 i + 2]``, input ``tau`` (N m) per joint.

    Attributes
    ----------
    joints, order : int
        2 joints, each of relative degree 2.
    gain : list of float
        Per joint, the largest ``(M^-1)_ii`` over ``q2`` (rad/s^2 per N m): the
        nominal input gain of each decentralised loop.
    outputs, inputs : list of famcc.Signal
        Names and units per joint.
    params : dict
    """

    joints = 2
    order = 2

    def __init__(
        self, m: Sequence[float], lengths: Sequence[float], b: float, x0: Sequence[float]
    ) -> None:
        (m1, m2), (l1, l2) = (float(v) for v in m), (float(v) for v in lengths)
        for label, v in (("m1", m1), ("m2", m2), ("l1", l1), ("l2", l2)):
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"{label} must be a finite number > 0, got {v!r}")
        self.params = {"m1": m1, "m2": m2, "l1": l1, "l2": l2, "b": float(b)}
        self._m, self._l = (m1, m2), (l1, l2)
        self._lc = (l1 / 2, l2 / 2)  # uniform rods
        self._i = (m1 * l1 * l1 / 12, m2 * l2 * l2 / 12)
        self._b = float(b)
        self._x0 = np.array(x0, dtype=float).reshape(-1)
        if self._x0.shape != (4,) or not np.all(np.isfinite(self._x0)):
            raise ValueError(f"x0 must be 4 finite numbers (q1, q1', q2, q2'), got {x0!r}")
        grid = np.linspace(-math.pi, math.pi, 73)
        inv = [np.linalg.inv(self.inertia(q2)) for q2 in grid]
        self.gain = [float(max(a[i, i] for a in inv)) for i in range(2)]
        self.outputs = [Signal("shoulder angle", "rad"), Signal("elbow angle", "rad")]
        self.inputs = [Signal("shoulder torque", "N m"), Signal("elbow torque", "N m")]
        self.name = "two-link-arm"

    @property
    def x0(self) -> np.ndarray:
        """Initial state (a fresh copy)."""
        return self._x0.copy()

    def inertia(self, q2: float) -> np.ndarray:
        """The inertia matrix ``M(q)`` (kg m^2); it depends on ``q2`` only."""
        (m1, m2), (l1, _), (lc1, lc2), (i1, i2) = self._m, self._l, self._lc, self._i
        c = math.cos(q2)
        m12 = m2 * (lc2 * lc2 + l1 * lc2 * c) + i2
        m11 = m1 * lc1 * lc1 + m2 * (l1 * l1 + lc2 * lc2 + 2 * l1 * lc2 * c) + i1 + i2
        return np.array([[m11, m12], [m12, m2 * lc2 * lc2 + i2]])

    def gravity(self, q1: float, q2: float) -> tuple[float, float]:
        """Gravity torques ``g(q)`` (N m)."""
        (m1, m2), (l1, _), (lc1, lc2) = self._m, self._l, self._lc
        g2 = m2 * lc2 * G0 * math.cos(q1 + q2)
        return (m1 * lc1 + m2 * l1) * G0 * math.cos(q1) + g2, g2

    def hold_input(self) -> list[float]:
        """Per joint, the largest gravity torque (N m): the arm stretched horizontally."""
        return [abs(v) for v in self.gravity(0.0, 0.0)]

    def rhs(self, t: float, x: Sequence[float], u: Sequence[float]) -> list[float]:
        """``dx/dt`` for the state ``(q1, q1', q2, q2')`` and torques ``u`` (floats)."""
        q1, w1, q2, w2 = x
        (m11, m12), (_, m22) = self.inertia(q2)
        h = self._m[1] * self._l[0] * self._lc[1] * math.sin(q2)
        g1, g2 = self.gravity(q1, q2)
        r1 = u[0] + h * (2 * w1 * w2 + w2 * w2) - g1 - self._b * w1
        r2 = u[1] - h * w1 * w1 - g2 - self._b * w2
        det = m11 * m22 - m12 * m12
        return [w1, (m22 * r1 - m12 * r2) / det, w2, (m11 * r2 - m12 * r1) / det]

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        """Per joint, ``(q_i, q_i')``: shape ``(joints, order)``."""
        return np.asarray(x, dtype=float).reshape(self.joints, self.order)

    def __repr__(self) -> str:
        p = ", ".join(f"{k}={v:g}" for k, v in self.params.items())
        return f"two-link-arm({p})"


def two_link_arm(
    m: Sequence[float] = (1.0, 1.0),
    lengths: Sequence[float] = (1.0, 1.0),
    b: float = 0.1,
    x0: Sequence[float] = (0.0, 0.0, 0.0, 0.0),
) -> TwoLinkArm:
    """The textbook two-link arm: 1 kg, 1 m uniform links, joint friction 0.1 N m s/rad.

    Parameters
    ----------
    m : (float, float)
        Link masses, kg.
    lengths : (float, float)
        Link lengths, m (uniform rods: centre of mass at half length, inertia
        ``m l^2 / 12`` about it).
    b : float
        Viscous joint friction, N m s/rad.
    x0 : 4 floats
        ``(q1, q1', q2, q2')`` in rad and rad/s (default: stretched horizontally,
        at rest, where gravity's torque is largest).
    """
    return TwoLinkArm(m, lengths, b, x0)
