"""famcc's peers for :mod:`famcc.compare`: PID, linear ADRC and LMCC, one interface each.

Every controller here has the duck-typed interface :func:`famcc.simulate` uses:
``dt`` (s), ``order`` and ``step(e, applied=None) -> float``, where ``e = y -
y_d`` is famcc's error (PID's error is ``setpoint - y``: the adapters give
simple-pid the set point 0 and the measurement ``e``, so its error is ``-e``).
``applied`` is the input the actuator really applied at the previous sample.

* :class:`PIDPeer` -- `simple-pid <https://pypi.org/project/simple-pid/>`_ with
  its output limits (its anti-windup: the integral is clamped to them) and a
  first-order low-pass filter on the measurement (PIDF; simple-pid's
  derivative acts on the raw measurement).
* :class:`ADRCPeer` -- linear ADRC with an extended state observer,
  bandwidth-parameterised (closed-loop bandwidth ``w_cl``, observer at
  ``k_eso w_cl``), ``b0`` the plant's nominal input gain: `pyadrc
  <https://pypi.org/project/pyadrc/>`_'s ``StateSpace`` at orders 1 and 2; at
  higher orders (which pyadrc does not implement) :class:`LinearADRC`, the same
  discretisation generalised and checked against pyadrc at order 2.
* :func:`lmcc` -- famcc with the ``Linear`` law and no flexible boundary
  (``rho_e=None``): linear manifold constraint control, the low-complexity PPC
  special case the paper names (its §4, "LMCC ... special cases of FAMCC").

Both peers are optional dependencies: ``pip install 'famcc[compare]'``.

>>> pid = PIDPeer(1e-3, 2, kp=20.0, ki=5.0, kd=4.0, tf=2e-3, u_limits=(-5.0, 5.0))
>>> round(pid.step(0.1), 3)          # e = y - y_d = 0.1: push down, clamped to -5
-2.001
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from famcc import _core

__all__ = ["ADRCPeer", "LinearADRC", "PIDPeer", "lmcc"]


def _need(module: str) -> Any:
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise ImportError(
            f"famcc.peers needs {module!r}, an optional dependency: pip install 'famcc[compare]'"
        ) from exc


def _positive(label: str, value: float) -> float:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise ValueError(f"{label} must be a finite number > 0, got {value!r}")
    return float(value)


def _limits(u_limits: Sequence[float] | None) -> tuple[float | None, float | None]:
    if u_limits is None:
        return (None, None)
    lo, hi = (float(v) for v in u_limits)
    if not lo < hi:
        raise ValueError(f"u_limits must satisfy lo < hi, got {u_limits!r}")
    return (lo, hi)


class PIDPeer:
    """simple-pid on famcc's error, with a low-pass filter on the measurement.

    ``u = -(kp e_f + ki int e_f dt + kd de_f/dt)`` with ``e_f`` the error
    through ``1 / (tf s + 1)`` (discretised exactly); simple-pid clamps the
    output and the integral to ``u_limits`` (anti-windup) and differentiates
    the measurement, not the error (no derivative kick).

    Parameters
    ----------
    dt : float
        Sample period, s.
    order : int
        The plant's order (only reported: PID needs none).
    kp, ki, kd : float
        Gains in input units per output unit, per output unit s, per output
        unit / s.
    tf : float
        Time constant of the measurement filter, s (0: no filter).
    u_limits : (lo, hi) or None
        The actuator limits (simple-pid's ``output_limits``).
    """

    def __init__(
        self,
        dt: float,
        order: int,
        *,
        kp: float,
        ki: float,
        kd: float,
        tf: float,
        u_limits: Sequence[float] | None = None,
    ) -> None:
        pid_mod = _need("simple_pid")
        self.dt = _positive("dt", dt)
        self.order = int(order)
        for label, v in (("kp", kp), ("ki", ki), ("kd", kd), ("tf", tf)):
            if not (math.isfinite(v) and v >= 0):
                raise ValueError(f"{label} must be a finite number >= 0, got {v!r}")
        self.gains = (float(kp), float(ki), float(kd))
        self.tf = float(tf)
        self._a = 1.0 if tf == 0 else 1.0 - math.exp(-self.dt / tf)
        # sample_time=None: simple-pid would otherwise hold its output for 10 ms (its default).
        self._pid = pid_mod.PID(
            kp, ki, kd, setpoint=0.0, sample_time=None, output_limits=_limits(u_limits)
        )
        self._ef: float | None = None

    def step(self, e: float, applied: float | None = None) -> float:
        """The input for the measured error ``e = y - y_d`` (``applied`` is unused)."""
        self._ef = e if self._ef is None else self._ef + self._a * (e - self._ef)
        return float(self._pid(self._ef, dt=self.dt))

    def __repr__(self) -> str:
        kp, ki, kd = self.gains
        return f"PIDPeer(kp={kp:.4g}, ki={ki:.4g}, kd={kd:.4g}, tf={self.tf:.3g})"


def _binomial(n: int) -> list[float]:
    """Coefficients of ``(s + 1)^n`` from ``s^0`` up to ``s^(n-1)``."""
    return [float(math.comb(n, i)) for i in range(n)]


class LinearADRC:
    """Linear ADRC of any order ``n``: an ``(n + 1)``-state ESO and state feedback.

    The model is ``y^(n) = b0 u + f``, ``f`` the total disturbance (an
    extended state). The ESO is pyadrc's current-estimator discretisation
    ``x^_k = (A - L C A) x^_k-1 + (B - L C B) u_k-1 + L y_k`` of the exact
    discrete chain of integrators, with all ``n + 1`` observer poles at ``z =
    exp(-k_eso w_cl dt)`` (Ackermann's formula); the law
    ``u = -(sum k_i x^_i + x^_n+1) / b0`` puts the ``n`` closed-loop poles at
    ``-w_cl`` (``k_i`` from ``(s + w_cl)^n``). At ``n = 2`` this is pyadrc's
    ``StateSpace`` (the tests check it sample for sample).

    Parameters
    ----------
    order : int
        ``n >= 1``.
    dt, b0, w_cl, k_eso : float
        Sample period (s), input gain (output units / s^n per input unit),
        closed-loop bandwidth (rad/s), observer / closed-loop bandwidth ratio.
    u_limits : (lo, hi) or None
        Output clamp.
    """

    def __init__(
        self,
        order: int,
        dt: float,
        b0: float,
        w_cl: float,
        k_eso: float,
        u_limits: Sequence[float] | None = None,
    ) -> None:
        n = int(order)
        if n < 1:
            raise ValueError(f"order must be >= 1, got {order!r}")
        dt, w_cl, k_eso = _positive("dt", dt), _positive("w_cl", w_cl), _positive("k_eso", k_eso)
        if not (math.isfinite(b0) and b0 != 0):
            raise ValueError(f"b0 must be a finite nonzero number, got {b0!r}")
        m = n + 1
        A = np.zeros((m, m))
        for i in range(m):
            for j in range(i, m):
                A[i, j] = dt ** (j - i) / math.factorial(j - i)
        B = np.array([b0 * dt ** (n - i) / math.factorial(n - i) for i in range(n)] + [0.0])
        C = np.zeros(m)
        C[0] = 1.0
        z = math.exp(-k_eso * w_cl * dt)
        # Ackermann on the dual pair (A^T, A^T C^T): poles of A - L C A at z.
        At = A.T
        b = At @ C
        ctrb = np.column_stack([np.linalg.matrix_power(At, i) @ b for i in range(m)])
        poly = np.poly(np.full(m, z))  # (x - z)^m, highest power first
        phi = sum(c * np.linalg.matrix_power(At, m - i) for i, c in enumerate(poly))
        e_last = np.zeros(m)
        e_last[-1] = 1.0
        self.L = (e_last @ np.linalg.solve(ctrb, phi)).reshape(-1)
        self.k = np.array([c * w_cl ** (n - i) for i, c in enumerate(_binomial(n))])
        self._oA = A - np.outer(self.L, C @ A)
        self._oB = B - self.L * (C @ B)
        self.b0, self.order, self.dt = float(b0), n, dt
        self.xhat = np.zeros(m)
        self.u_limits = _limits(u_limits)

    def __call__(self, y: float, u_prev: float) -> float:
        """One step: measurement ``y_k`` and the previous input ``u_k-1``."""
        self.xhat = self._oA @ self.xhat + self._oB * u_prev + self.L * y
        u = -(float(self.k @ self.xhat[:-1]) + float(self.xhat[-1])) / self.b0
        lo, hi = self.u_limits
        if lo is not None and u < lo:
            return lo
        if hi is not None and u > hi:
            return hi
        return u


class ADRCPeer:
    """Linear ADRC on famcc's error: pyadrc at orders 1-2, :class:`LinearADRC` above.

    The ESO measures ``e = y - y_d`` and the reference is 0 (error-based ADRC:
    the reference's derivatives become part of the total disturbance, as
    famcc, which also sees only ``e``). The observer starts at ``(e_0, 0,
    ...)``, as famcc's differentiator does, so neither peaks from a wrong
    initial output.

    Parameters
    ----------
    dt : float
        Sample period, s.
    order : int
        The plant's order ``n`` (the ADRC's).
    b0 : float
        The plant's nominal input gain ``G`` (``y^(n) = G u + F``).
    w_cl, k_eso : float
        Closed-loop bandwidth (rad/s) and observer bandwidth ratio.
    u_limits : (lo, hi) or None
        The actuator limits (pyadrc's magnitude limiter).
    """

    def __init__(
        self,
        dt: float,
        order: int,
        *,
        b0: float,
        w_cl: float,
        k_eso: float,
        u_limits: Sequence[float] | None = None,
    ) -> None:
        self.dt = _positive("dt", dt)
        self.order = int(order)
        self.params = (float(b0), float(w_cl), float(k_eso))
        if self.order <= 2:
            adrc = _need("pyadrc")
            self._ss: Any = adrc.StateSpace(
                self.order, self.dt, float(b0), float(w_cl), float(k_eso), m_lim=_limits(u_limits)
            )
            self._own: LinearADRC | None = None
        else:
            self._ss = None
            self._own = LinearADRC(self.order, self.dt, b0, w_cl, k_eso, u_limits)
        self._started = False

    def step(self, e: float, applied: float | None = None) -> float:
        """The input for the measured error ``e`` given the previous applied input."""
        u_prev = 0.0 if applied is None else float(applied)
        if self._ss is not None:
            if not self._started:
                self._ss.reset([e] + [0.0] * self.order)
                self._started = True
            return float(self._ss(e, u_prev, 0.0))
        assert self._own is not None
        if not self._started:
            self._own.xhat[:] = 0.0
            self._own.xhat[0] = e
            self._started = True
        return self._own(e, u_prev)

    def __repr__(self) -> str:
        b0, w, k = self.params
        impl = "pyadrc" if self._ss is not None else "LinearADRC"
        return f"ADRCPeer({impl}, b0={b0:.4g}, w_cl={w:.4g}, k_eso={k:.3g})"


def lmcc(
    order: int,
    dt: float,
    *,
    k: float,
    eps: float,
    settle_time: float,
    k_u: float,
    mu: float,
) -> Any:
    """famcc with ``Linear(k)`` in every stage and no flexible boundary (LMCC).

    The manifold is linear (``s = z_n + ... `` with all roots at ``-k``), the
    constraint longitudinal on ``s`` with final half-width ``eps``, and
    ``rho_e=None`` switches the error-driven flexible bounds off: the
    low-complexity PPC / LMCC of the paper's references, its special case.
    ``mu`` is the high-gain differentiator's time constant (s), discretized as
    famcc picks for ``dt`` (:meth:`famcc.HighGain.discretization_for`).
    """
    stages = [_core.Linear(k) for _ in range(order - 1)] if order > 1 else [_core.Linear(k)]
    return _core.Controller(
        order,
        dt,
        stages if len(stages) > 1 else stages[0],
        constraint="longitudinal",
        eps=eps,
        settle_time=settle_time,
        k_u=k_u,
        rho_e=None,
        differentiator=_core.HighGain.default(
            order, mu=mu, discretization=_core.HighGain.discretization_for(order, dt, mu)
        ),
    )
