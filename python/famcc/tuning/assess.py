"""Whether a closed-loop run meets a requirement: the one check :func:`tune` and the
worked examples use.

A run meets ``(eps, settle_time, u_limits)`` when

1. it settles: ``|e| < eps`` from some time ``t_s <= settle_time`` to the end;
2. the steady error, the largest ``|e|`` over the last fifth of the run, stays
   below ``eps`` (a run that settled meets it by the definition of ``t_s``; it
   is reported so that a run that did not says how far off it ended, and
   :func:`tune` asks for margin on it);
3. the flexible bounds never expand after ``t_s`` while the actuator has
   headroom (``v`` inside the limits): the preset accuracy was not given up;
4. the input's ripple, its steady oscillation, is at most ``ripple_limit`` of
   the input range (5 % by default): the peak-to-peak of ``u`` about its
   straight-line trend over the steady stretch, the samples after both
   ``t_s`` and the start of the run's last fifth. A smooth convergence of
   ``u`` after settling, or its answer to a load step before the last fifth, is
   not ripple; chatter and a limit cycle are.

>>> import famcc
>>> plant = famcc.plants.dc_motor(load=0.0)
>>> d = famcc.design(2, 1e-3, u_limits=(-12, 12), eps=0.02, settle_time=2.0,
...                  hold_input=0.5, gain=25.0, integral=False)
>>> res = famcc.simulate(plant, d.controller(), 3.0, reference=famcc.Constant(1.0),
...                      u_limits=(-12.0, 12.0))
>>> a = famcc.tuning.assess(res, eps=0.02, settle_time=2.0, u_limits=(-12.0, 12.0))
>>> a.ok, round(a.settling_time, 2), a.ripple < 0.05
(True, 0.81, True)
>>> famcc.tuning.assess(res, eps=0.02, settle_time=0.5, u_limits=(-12.0, 12.0)).failures
['settled at 0.808 s > 0.5 s']
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from famcc.verdicts import Status, Verdict, combine

#: The largest ripple of ``u`` after settling, as a fraction of the input range.
RIPPLE_LIMIT = 0.05


@dataclass(frozen=True)
class Assessment:
    """A run judged against a requirement.

    Attributes
    ----------
    settling_time : float or None
        First time after which ``|e| < eps`` holds to the end, s (None: never).
    steady_error : float
        Largest ``|e|`` over the last fifth of the run, output units.
    expanded_unsaturated : float
        Fraction of the samples after settling with the bounds expanded while
        ``v`` lay inside the limits.
    ripple : float
        Peak-to-peak of ``u`` about its least-squares straight line over the
        steady stretch (after settling and in the last fifth of the run; the
        last 10 % when it never settled), as a fraction of the input range.
    effort : float
        Total variation of ``u`` per second over the run, input units/s.
    saturated : float
        Fraction of samples with ``v`` beyond the limits.
    failures : list of str
        The requirements that failed, in words (empty when all hold): the
        details of the failed :attr:`verdicts`.
    verdicts : tuple of famcc.verdicts.Verdict
        One verdict per requirement (``settling``, ``steady``, ``nominal``,
        ``ripple``; ``bounded`` for a diverged run): held, failed or
        untested (``nominal`` without recorded diagnostics). Given only
        ``failures``, one failed ``requirement`` verdict per text.
    """

    settling_time: float | None
    steady_error: float
    expanded_unsaturated: float
    ripple: float
    effort: float
    saturated: float
    failures: list[str] = field(default_factory=list)
    verdicts: tuple[Verdict, ...] = ()

    def __post_init__(self) -> None:
        if not self.verdicts and self.failures:
            failed = tuple(Verdict("requirement", f, Status.FAILED, f) for f in self.failures)
            object.__setattr__(self, "verdicts", failed)
        elif self.verdicts and not self.failures:
            texts = [v.detail for v in self.verdicts if v.failed]
            object.__setattr__(self, "failures", texts)

    @property
    def ok(self) -> bool:
        """True when no requirement failed."""
        return not self.failures

    @property
    def status(self) -> Status:
        """The requirements together (:func:`famcc.verdicts.combine`)."""
        return combine(v.status for v in self.verdicts)

    def metrics(self) -> dict[str, Any]:
        """The measured numbers as a dict."""
        return {
            "settling_time": self.settling_time,
            "steady_error": self.steady_error,
            "expanded_unsaturated": self.expanded_unsaturated,
            "ripple": self.ripple,
            "effort": self.effort,
            "saturated": self.saturated,
        }

    def __str__(self) -> str:
        ts = "never" if self.settling_time is None else f"{self.settling_time:.3f} s"
        head = "requirement met" if self.ok else "requirement NOT met: " + "; ".join(self.failures)
        return (
            f"settling time {ts}, steady max |e| {self.steady_error:.3g}, expanded with "
            f"headroom {100 * self.expanded_unsaturated:.3g} %, u ripple "
            f"{100 * self.ripple:.3g} % of the range, saturated {100 * self.saturated:.3g} %: "
            + head
        )


def assess(
    result: Any,
    *,
    eps: float,
    settle_time: float,
    u_limits: Sequence[float],
    ripple_limit: float = RIPPLE_LIMIT,
) -> Assessment:
    """Judge a :class:`famcc.SimResult` against ``(eps, settle_time, u_limits)``.

    Parameters
    ----------
    result : famcc.SimResult
        A run with diagnostics recorded (``expanded``); None counts as diverged.
    eps : float
        Required accuracy, output units (> 0).
    settle_time : float
        Required settling time, s.
    u_limits : (lo, hi)
        The actuator's limits, input units.
    ripple_limit : float
        Largest ripple of ``u`` after settling, fraction of ``hi - lo``.
    """
    lo, hi = (float(v) for v in u_limits)
    if not (eps > 0 and math.isfinite(eps)):
        raise ValueError(f"eps must be a finite number > 0, got {eps!r}")
    if not hi > lo:
        raise ValueError(f"u_limits must be (lo, hi) with lo < hi, got {tuple(u_limits)!r}")
    if result is None:
        gone = Verdict("bounded", "the run stays bounded", Status.FAILED, "diverged")
        return Assessment(None, math.inf, 0.0, math.inf, math.inf, 0.0, verdicts=(gone,))
    t = np.asarray(result.t)
    z1 = np.asarray(result.z1)
    u = np.asarray(result.u)
    ts = result.settling_time(eps)
    after = t >= (ts if ts is not None else 0.9 * float(t[-1]))
    expanded = result.expanded
    exp_unsat = (
        float(np.mean((np.asarray(expanded, dtype=bool) & ~result.saturated)[after]))
        if expanded is not None and np.any(after)
        else 0.0
    )
    tail = t >= 0.8 * float(t[-1])
    steady = float(np.max(np.abs(z1[tail])))
    ripple = _ripple(t, u, ts) / (hi - lo)
    effort = float(np.sum(np.abs(np.diff(u))) / max(float(t[-1]), 1e-300))
    held, failed, untested = Status.HELD, Status.FAILED, Status.UNTESTED
    claim = f"|e| < {eps:g} for good by {settle_time:g} s"
    if ts is None:
        settling = Verdict("settling", claim, failed, "never settled")
    elif ts > settle_time:
        settling = Verdict("settling", claim, failed, f"settled at {ts:.3g} s > {settle_time:g} s")
    else:
        settling = Verdict("settling", claim, held, f"settled at {ts:.3g} s")
    claim = f"max |e| over the last fifth < {eps:g}"
    ok = steady < eps
    detail = f"steady |e| {steady:.3g} {'<' if ok else '>='} eps {eps:g}"
    steady_v = Verdict("steady", claim, held if ok else failed, detail)
    claim = "no expansion of the bounds after settling while v has headroom"
    if expanded is None:
        nominal = Verdict("nominal", claim, untested, "diagnostics were not recorded")
    elif exp_unsat > 0:
        why = f"bounds expanded with headroom {100 * exp_unsat:.2g} % of the time"
        nominal = Verdict("nominal", claim, failed, why)
    else:
        nominal = Verdict("nominal", claim, held, "never expanded with headroom")
    claim = f"u ripple (steady oscillation) <= {100 * ripple_limit:g} % of the range"
    ok = not ripple > ripple_limit
    sign = "<=" if ok else ">"
    detail = f"u ripple {100 * ripple:.3g} % {sign} {100 * ripple_limit:g} % of the range"
    ripple_v = Verdict("ripple", claim, held if ok else failed, detail)
    return Assessment(
        ts,
        steady,
        exp_unsat,
        ripple,
        effort,
        float(result.saturated_fraction),
        verdicts=(settling, steady_v, nominal, ripple_v),
    )


def _ripple(t: np.ndarray, u: np.ndarray, ts: float | None) -> float:
    """Peak-to-peak of ``u`` about its least-squares line over the steady stretch:
    the samples at or after both ``ts`` and ``0.8 t[-1]`` (``t >= 0.9 t[-1]``
    when ``ts`` is None)."""
    start = 0.9 * float(t[-1]) if ts is None else max(float(ts), 0.8 * float(t[-1]))
    m = t >= start
    if not np.any(m):
        return math.inf
    tw, uw = t[m], u[m]
    if tw.size >= 2 and float(np.ptp(tw)) > 0.0:
        slope, offset = np.polyfit(tw - tw[0], uw, 1)
        uw = uw - (offset + slope * (tw - tw[0]))
    return float(np.ptp(uw))
