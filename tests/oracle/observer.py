"""The extended observer in pure Python: the oracle of ``famcc.Controller(..., observer=)``.

Written from docs/observer.md, independently of the core: the extended
high-gain observer of order ``n + 1`` of ``y^(n) = L + b0 u``,

    Zhat' = A Zhat + H (e - Zhat_1) + B b0 u,   H_i = a_i / mu^i  (i = 1..n+1),

``A`` the chain of integrators of order ``n + 1``, ``B`` the unit vector of state
``n``, ``a`` by default those of ``(s + 2)^(n + 1)`` (every pole at ``-2 / mu``). Sampled at ``dt``
with the input held and the measurement held (``"exact"``) or on the straight
line through the samples (``"foh"``), in 60-digit decimal arithmetic from the
exponential of one augmented matrix, without the core's balanced coordinates,
and rounded once. The law runs on ``(Zhat_1..Zhat_n)``; the output is the law's
``v`` minus ``clip(Lhat / b0, -delta, delta)``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from decimal import Decimal, localcontext
from typing import Any

from .reference import ESTIMATE_RANGE, ReferenceController, _expm


def binomial(m: int) -> tuple[float, ...]:
    """``(C(m, i) 2^i)``, ``i = 1..m``: the coefficients of ``(s + 2)^m``, every pole of the
    observer of order ``m`` at ``-2 / mu`` (docs/observer.md)."""
    return tuple(float(math.comb(m, i) * 2**i) for i in range(1, m + 1))


def discretize_extended(mu: float, a: Sequence[float], b0: float, dt: float, method: str):
    """``(Phi, Gamma_e, Gamma_u, D)`` of the observer (order ``m = len(a)``) sampled at ``dt``.

    ``Zhat_(k+1) = Phi Zhat_k + Gamma_e e_k + Gamma_u u_k + D (e_(k+1) - e_k)``; ``D``
    is zero with ``"exact"``. From ``exp(X dt)`` of ``X = [[M, H, B b0, 0], [0, 0, 0, 1],
    [0, 0, 0, 0], [0, 0, 0, 0]]`` (``M = A - H C``; the measurement ``e`` and the
    input held, the measurement's ramp in the last state): the top blocks are
    ``Phi``, ``Gamma_e``, ``Gamma_u`` and ``integral_0^dt exp(M (dt - s)) s ds H``
    ``= dt D``.
    """
    if method not in ("exact", "foh"):
        raise ValueError(f"method must be 'exact' or 'foh', got {method!r}")
    with localcontext() as ctx:
        ctx.prec = 60
        m = len(a)
        mu_d, dt_d, b0_d = Decimal(float(mu)), Decimal(float(dt)), Decimal(float(b0))
        h = [Decimal(float(a[i])) / mu_d ** (i + 1) for i in range(m)]
        zero = Decimal(0)
        size = m + 3
        x = [[zero] * size for _ in range(size)]
        for i in range(m):
            x[i][0] -= h[i]  # - H C
            if i + 1 < m:
                x[i][i + 1] += Decimal(1)  # the chain
            x[i][m] = h[i]  # the measurement
        x[m - 2][m + 1] = b0_d  # the input drives state n = m - 1 (1-based)
        x[m][m + 2] = Decimal(1)  # the measurement's ramp
        big = _expm([[v * dt_d for v in row] for row in x])
        phi = tuple(tuple(float(big[i][j]) for j in range(m)) for i in range(m))
        g_e = tuple(float(big[i][m]) for i in range(m))
        g_u = tuple(float(big[i][m + 1]) for i in range(m))
        feed = tuple(float(big[i][m + 2] / dt_d) if method == "foh" else 0.0 for i in range(m))
    return phi, g_e, g_u, feed


class ObservedReference(ReferenceController):
    """:class:`ReferenceController` with the observer in the differentiator's place.

    The keyword arguments of ``famcc.Controller`` with ``observer`` (a
    ``famcc.Observer``) and ``cancellation_limit`` (``delta``, required: the
    reference has no output limits).
    """

    def __init__(
        self,
        order: int,
        dt: float,
        feedback: Any = None,
        *,
        observer: Any,
        cancellation_limit: float,
        differentiator: Any = None,
        **kwargs: Any,
    ) -> None:
        if differentiator is not None:
            raise ValueError("the observer takes the differentiator's place")
        super().__init__(order, dt, feedback, differentiator=None, **kwargs)
        a = binomial(order + 1) if observer.a is None else tuple(float(v) for v in observer.a)
        self.b0 = float(observer.b0)
        self.delta = float(cancellation_limit)
        self.obs = discretize_extended(observer.mu, a, self.b0, dt, observer.discretization)
        self._lhat = 0.0

    @classmethod
    def from_controller(cls, ctrl: Any) -> ObservedReference:
        kw = dict(ctrl.config())
        kw.pop("differentiator", None)
        for name in ("output_limits", "rate_limit", "integral", "initial_output"):
            if kw.pop(name, None) not in (None, False):
                raise ValueError(f"the reference has no {name}")
        return cls(kw.pop("order"), kw.pop("dt"), **kw)

    def reset(self) -> None:
        super().reset()
        self._lhat = 0.0

    @property
    def lumped(self) -> float:
        return self._lhat

    def _observe(self, e: float, applied: float | None) -> tuple[list, float]:
        """``(Zhat_k, Lhat_k)``: restarted from ``(e, d_2..d_n)`` and 0 at the first step
        and when out of range, else advanced with ``e_(k-1)`` and the input."""
        restart = ([e, *self.initial_derivatives], 0.0)
        if not self._started:
            return restart
        phi, g_e, g_u, feed = self.obs
        u = self._last_v if applied is None else applied
        x = [*self._zhat, self._lhat]
        de = e - self._filtered
        nxt = []
        for row, ge, gu, d in zip(phi, g_e, g_u, feed):
            acc = ge * self._filtered + gu * u
            for p, v in zip(row, x):
                acc += p * v
            nxt.append(acc + d * de)
        if not all(abs(v) <= ESTIMATE_RANGE for v in nxt):
            return restart
        return nxt[:-1], nxt[-1]

    def step(self, e: float, applied: float | None = None) -> float:
        """One step: the law on the estimate, minus the bounded cancellation."""
        e = float(e)
        if not math.isfinite(e):
            raise ValueError(f"e must be finite (got {e})")
        z, lhat = self._observe(e, None if applied is None else float(applied))
        try:
            v = self._finish(z, z, applied, [e, *self.initial_derivatives], e, e)
        except ValueError:
            self._lhat = 0.0
            raise
        c = lhat / self.b0
        c = self.delta if c > self.delta else max(c, -self.delta)
        self._lhat = lhat
        self._last_v = v - c
        return self._last_v
