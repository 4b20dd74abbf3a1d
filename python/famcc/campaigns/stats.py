"""Success rates with exact (Clopper-Pearson) confidence intervals."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from famcc.verdicts import Status


def _betacf(a: float, b: float, x: float) -> float:
    """Continued fraction of the incomplete beta function (modified Lentz)."""
    tiny, eps = 1e-300, 1e-16
    qab, qap, qam = a + b, a + 1.0, a - 1.0
    c, d = 1.0, 1.0 - qab * x / qap
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 10000):
        m2 = 2 * m
        aa = m * (b - m) * x / ((qam + m2) * (a + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        h *= d * c
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        delta = d * c
        h *= delta
        if abs(delta - 1.0) < eps:
            break
    return h


def beta_cdf(x: float, a: float, b: float) -> float:
    """The regularized incomplete beta function ``I_x(a, b)``, ``a, b > 0``.

    >>> round(beta_cdf(0.5, 2.0, 2.0), 12), round(beta_cdf(0.3, 1.0, 1.0), 12)
    (0.5, 0.3)
    """
    if not (a > 0 and b > 0):
        raise ValueError(f"a and b must be > 0, got {a!r}, {b!r}")
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    front = math.exp(
        math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log1p(-x)
    )
    if x < (a + 1.0) / (a + b + 2.0):
        return front * _betacf(a, b, x) / a
    return 1.0 - front * _betacf(b, a, 1.0 - x) / b


def beta_ppf(q: float, a: float, b: float) -> float:
    """The quantile of the Beta(a, b) distribution: ``x`` with ``I_x(a, b) = q``.

    Bisection on :func:`beta_cdf` (monotone), to about 1e-15 in ``x``.

    >>> round(beta_ppf(0.5, 2.0, 2.0), 12), round(beta_ppf(0.975, 1.0, 10.0), 6)
    (0.5, 0.308497)
    """
    if not 0.0 <= q <= 1.0:
        raise ValueError(f"q must lie in [0, 1], got {q!r}")
    if q == 0.0:
        return 0.0
    if q == 1.0:
        return 1.0
    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if beta_cdf(mid, a, b) < q:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-15:
            break
    return 0.5 * (lo + hi)


def clopper_pearson(k: int, n: int, confidence: float = 0.95) -> tuple[float, float]:
    """The exact (Clopper-Pearson) interval of a binomial proportion ``k / n``.

    ``lo = B(alpha/2; k, n - k + 1)`` (0 when ``k = 0``), ``hi = B(1 - alpha/2;
    k + 1, n - k)`` (1 when ``k = n``), ``B`` the beta quantile; it covers the
    true rate with probability at least ``confidence``.

    >>> [round(v, 4) for v in clopper_pearson(5, 10)]
    [0.1871, 0.8129]
    >>> [round(v, 5) for v in clopper_pearson(0, 100)]       # 1 - 0.025**(1/100)
    [0.0, 0.03622]
    """
    if not (isinstance(n, (int, np.integer)) and isinstance(k, (int, np.integer))):
        raise ValueError(f"k and n must be integers, got {k!r}, {n!r}")  # noqa: TRY004
    if n < 1 or not 0 <= k <= n:
        raise ValueError(f"need n >= 1 and 0 <= k <= n, got k = {k}, n = {n}")
    if not 0 < confidence < 1:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence!r}")
    alpha = 1.0 - confidence
    lo = 0.0 if k == 0 else beta_ppf(alpha / 2, k, n - k + 1)
    hi = 1.0 if k == n else beta_ppf(1 - alpha / 2, k + 1, n - k)
    return lo, hi


@dataclass(frozen=True)
class Rate:
    """How many cases held a criterion, with a Clopper-Pearson interval.

    Attributes
    ----------
    name : str
        The criterion.
    held, failed, untested : int
        Case counts; untested cases (the claim could not be decided, e.g. its
        deadline lies beyond the horizon) count neither way.
    lo, hi : float
        The interval of the success rate ``held / (held + failed)`` (NaN when no
        case was tested).
    confidence : float
    """

    name: str
    held: int
    failed: int
    untested: int
    lo: float
    hi: float
    confidence: float = 0.95

    @property
    def tested(self) -> int:
        """``held + failed``."""
        return self.held + self.failed

    @property
    def rate(self) -> float:
        """``held / tested`` (NaN when nothing was tested)."""
        return self.held / self.tested if self.tested else math.nan

    def text(self) -> str:
        """One line: ``"settled: 9,812 of 10,000 (98.12 %, 95 % CI 97.85-98.37 %)"``."""
        if not self.tested:
            return f"{self.name}: untested ({self.untested:,} cases could not decide it)"
        tail = f"; {self.untested:,} untested" if self.untested else ""
        return (
            f"{self.name}: {self.held:,} of {self.tested:,} ({_pct(self.rate)}, "
            f"{100 * self.confidence:g} % CI {_pct(self.lo, False)}-{_pct(self.hi)}){tail}"
        )


def _fmt(v: Any, none: str = "-") -> str:
    """A number to 4 significant digits; ``none`` for None and non-finite values."""
    return none if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.4g}"


def _pct(v: float, unit: bool = True) -> str:
    """``0.98123 -> "98.12 %"``; tiny non-zero values keep two significant digits."""
    if not math.isfinite(v):
        return "-"
    p = 100 * v
    text = f"{p:.2f}" if p == 0 or abs(p) >= 0.01 else f"{p:.2g}"
    return text + (" %" if unit else "")


def _rate(name: str, status: np.ndarray, confidence: float) -> Rate:
    held = int(np.sum(status == Status.HELD.code))
    failed = int(np.sum(status == Status.FAILED.code))
    untested = int(np.sum(status == Status.UNTESTED.code))
    if held + failed:
        lo, hi = clopper_pearson(held, held + failed, confidence)
    else:
        lo = hi = math.nan
    return Rate(name, held, failed, untested, lo, hi, confidence)
