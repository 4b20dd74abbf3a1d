"""Multi-input plants under one single-output controller per joint: the two-link arm.

:func:`two_link_arm` is the textbook planar arm in a vertical plane (two rigid
links, gravity, coupled inertia). :func:`simulate_joints` closes one loop per
joint with independent single-output controllers (decentralised control: the
coupling through the inertia matrix and gravity acts on each loop as a
disturbance), with the sample-and-hold and RK4 semantics of
:func:`famcc.simulate`, and returns one :class:`famcc.SimResult` per joint.

>>> import famcc
>>> from famcc.joints import simulate_joints, two_link_arm
>>> arm = two_link_arm()
>>> arm.joints, arm.order, [round(g, 2) for g in arm.gain]
(2, 2, [1.71, 13.71])
>>> ctrls = [famcc.Controller(2, 1e-3, famcc.FiniteTime(k=2.0, p=0.5), constraint="lateral",
...                           eps=0.05, k_u=k) for k in (10.0, 3.0)]
>>> shoulder, elbow = simulate_joints(arm, ctrls, 3.0, references=[famcc.Constant(0.5)] * 2,
...                                   u_limits=[(-60.0, 60.0), (-20.0, 20.0)])
>>> shoulder.settling_time(0.05) < 3.0, elbow.output.name
(True, 'elbow angle')
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from famcc._common import Signal
from famcc.simulation import SimResult, _describe_controller, _reference_derivatives, _signal_fn

__all__ = ["TwoLinkArm", "simulate_joints", "two_link_arm"]

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


def simulate_joints(
    plant: Any,
    controllers: Sequence[Any],
    t_end: float,
    references: Sequence[Any],
    u_limits: Sequence[Sequence[float] | None] | None = None,
    substeps: int = 10,
    *,
    noise: float | Callable[[float], float] | None = None,
    seed: int | np.random.Generator | None = None,
    diverge_at: float | None = None,
) -> list[SimResult]:
    """One sampled-and-held loop per joint of a multi-input plant, integrated together.

    At ``t_k = k dt`` controller ``i`` reads its joint's error ``e_i = q_i + n_i -
    y_d,i`` and returns ``v_i``; ``u_i = clip(v_i, u_limits[i])`` is held until
    ``t_k+1`` while the plant is integrated with ``substeps`` RK4 steps, exactly
    as :func:`famcc.simulate` does for one loop.

    Parameters
    ----------
    plant : object
        ``joints``, ``order`` (per joint), ``x0`` (joint ``i``'s output and its
        derivatives at ``x[order i : order (i + 1)]``) and ``rhs(t, x, u)`` with a
        sequence ``u`` of inputs, e.g. :func:`two_link_arm`.
    controllers : sequence
        One per joint, each with ``dt`` (all equal), ``order`` and ``step(e,
        applied=None)``.
    t_end : float
        Horizon, s.
    references : sequence
        One ``reference(t, k)`` per joint (:class:`famcc.Constant`, ...).
    u_limits : sequence of (lo, hi) or None
        Per joint.
    substeps : int
        RK4 steps per sample.
    noise, seed : see :func:`famcc.simulate`
        The same noise level on every joint, independent draws.
    diverge_at : float or None
        Stop when any joint's ``|e_i|`` exceeds it (or a value becomes
        non-finite); every result is then flagged ``diverged``.

    Returns
    -------
    list of SimResult
        One per joint (no controller diagnostics are recorded; ``x`` holds the
        joint's own two states).
    """
    nj, n = int(plant.joints), int(plant.order)
    if len(controllers) != nj or len(references) != nj:
        raise ValueError(f"controllers and references need one entry per joint ({nj})")
    dt = float(controllers[0].dt)
    if any(not math.isclose(float(c.dt), dt) or int(c.order) != n for c in controllers):
        raise ValueError(f"every controller must have dt = {dt} and order = {n}")
    if not (isinstance(t_end, (int, float)) and math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0, got {t_end!r}")
    if not (isinstance(substeps, int) and substeps >= 1):
        raise ValueError(f"substeps must be an integer >= 1, got {substeps!r}")
    limits = list(u_limits) if u_limits is not None else [None] * nj
    if len(limits) != nj:
        raise ValueError(f"u_limits needs one entry (or None) per joint ({nj})")
    refs = [_reference_derivatives(r, n)[0] for r in references]
    rng = np.random.default_rng(seed)
    noise_fns = [_signal_fn("noise", noise, rng) for _ in range(nj)]
    K = round(t_end / dt) + 1
    t_arr = np.arange(K) * dt
    x = [float(v) for v in plant.x0]
    xs, yd, em, vs, us = (np.full((K, nj, w), np.nan) for w in (2 * n, n, 1, 1, 1))
    prev: list[float | None] = [None] * nj
    h, stop = dt / substeps, None
    for k in range(K):
        t = float(t_arr[k])
        xs[k, 0] = x
        u_now = []
        for i in range(nj):
            yd[k, i] = refs[i](t)[:n]
            e = x[n * i] - yd[k, i, 0]
            fn = noise_fns[i]
            meas = e + (float(fn(t)) if fn is not None else 0.0)
            v = float(controllers[i].step(meas, applied=prev[i]))
            lim = limits[i]
            u = v if lim is None else min(max(v, float(lim[0])), float(lim[1]))
            em[k, i, 0], vs[k, i, 0], us[k, i, 0] = meas, v, u
            u_now.append(u)
            if diverge_at is not None and not (abs(e) <= diverge_at and math.isfinite(v)):
                stop = k + 1  # keep this sample
        if stop is not None:
            break
        prev = list(u_now)
        for j in range(substeps if k < K - 1 else 0):
            x = _rk4_step(plant.rhs, t + j * h, x, u_now, h)
        if not all(math.isfinite(v) for v in x):
            if diverge_at is None:
                raise FloatingPointError(f"plant state became non-finite after t = {t:.6g} s")
            stop = k + 1
            break
    keep = K if stop is None else stop
    out = []
    for i in range(nj):
        state = xs[:keep, 0, n * i : n * (i + 1)]
        text, cfg = _describe_controller(controllers[i])
        lim = limits[i]
        out.append(
            SimResult(
                t=t_arr[:keep],
                y=state[:, 0].copy(),
                y_d=yd[:keep, i, 0].copy(),
                x=state.copy(),
                z=state - yd[:keep, i],
                v=vs[:keep, i, 0].copy(),
                u=us[:keep, i, 0].copy(),
                dt=dt,
                u_limits=None if lim is None else (float(lim[0]), float(lim[1])),
                output=plant.outputs[i],
                input=plant.inputs[i],
                controller_repr=text,
                controller_config=cfg,
                reference_repr=repr(references[i]),
                neg_f_over_g_error="unknown for one joint of a coupled plant",
                z1_measured=None if noise_fns[i] is None else em[:keep, i, 0].copy(),
                diverged_at=None if stop is None else float(t_arr[stop - 1]),
            )
        )
    return out


def _rk4_step(
    rhs: Callable[..., Sequence[float]], t: float, x: list[float], u: list[float], h: float
) -> list[float]:
    k1 = rhs(t, x, u)
    k2 = rhs(t + h / 2, [a + h / 2 * b for a, b in zip(x, k1)], u)
    k3 = rhs(t + h / 2, [a + h / 2 * b for a, b in zip(x, k2)], u)
    k4 = rhs(t + h, [a + h * b for a, b in zip(x, k3)], u)
    return [a + h / 6 * (p + 2 * (q + r) + s) for a, p, q, r, s in zip(x, k1, k2, k3, k4)]
