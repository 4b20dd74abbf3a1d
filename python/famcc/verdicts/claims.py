"""The claims a run can fail (Theorems 1-3, Corollaries 1-3) and a user's requirements."""

from __future__ import annotations

from typing import Any

import numpy as np

from famcc.verdicts.status import Status
from famcc.verdicts.verdict import (
    STARTUP,
    Verdict,
    _diverged,
    _expanded,
    _is_due,
    _last_bound,
    _t,
    recovery_windows,
)


def settling(result: Any, eps: float, settle_time: float, t_prime: float) -> Verdict:
    """``|z1| < eps`` for good from ``max(T_e, T_s) + T'`` on (Corollaries 1-3)."""
    t_e, bound = _last_bound(result, settle_time, t_prime)
    horizon = float(result.t[-1])
    ts = result.settling_time(eps)
    where = f"max(T_e, T_s) + T' = max({t_e:.3g}, {settle_time:g}) + {t_prime:.3g}"
    claim = f"|z1| < {eps:g} for good from {where} = {bound:.3g} s on"
    if (diverged := _diverged(result, "settling", claim)) is not None:
        return diverged
    if bound > horizon:
        return Verdict(
            "settling",
            claim,
            Status.UNTESTED,
            f"the bound {bound:.3g} s lies beyond the horizon {horizon:g} s (settled at {_t(ts)})",
        )
    if ts is not None and ts <= bound:
        return Verdict("settling", claim, Status.HELD, f"settled at {ts:.3f} s")
    return Verdict(
        "settling",
        claim,
        Status.FAILED,
        "never settled" if ts is None else f"settled only at {ts:.3f} s",
    )


def unsaturated(result: Any, startup: float = STARTUP) -> Verdict:
    """The commanded ``v`` stays inside the limits after the start-up window."""
    claim = f"v inside the limits after the start-up ({startup:g} s)"
    if result.u_limits is None:
        return Verdict("unsaturated", claim, Status.UNTESTED, "the run had no limits")
    late = np.asarray(result.t) >= startup
    sat = np.asarray(result.saturated)[late]
    if not sat.any():
        return Verdict("unsaturated", claim, Status.HELD, "never outside after the start-up")
    first = float(np.asarray(result.t)[late][int(np.argmax(sat))])
    return Verdict(
        "unsaturated",
        claim,
        Status.FAILED,
        f"outside the limits at {100 * float(np.mean(sat)):.1f} % of the samples "
        f"after the start-up, first at {first:.3f} s",
    )


def nominal(result: Any, startup: float = STARTUP) -> Verdict:
    """The bounds stay nominal (no flexible expansion) after the start-up window."""
    claim = f"bounds nominal (state inside the nominal constraint) after {startup:g} s"
    exp = _expanded(result)
    if exp is None:
        return Verdict("nominal", claim, Status.UNTESTED, "diagnostics were not recorded")
    late = np.asarray(result.t) >= startup
    bad = exp[late]
    if not bad.any():
        xi_nom = result.xi_nominal
        tail = (
            ""
            if xi_nom is None
            else f" (max nominal |xi| {float(np.max(np.abs(xi_nom[late]))):.3f})"
        )
        return Verdict("nominal", claim, Status.HELD, "never expanded after the start-up" + tail)
    first = float(np.asarray(result.t)[late][int(np.argmax(bad))])
    return Verdict(
        "nominal",
        claim,
        Status.FAILED,
        f"expanded at {100 * float(np.mean(bad)):.1f} % of the samples after the "
        f"start-up, first at {first:.3f} s, up to {result.largest_expansion:.3g}x",
    )


# ---------------------------------------------------------------------------
# claims of a run with saturation
# ---------------------------------------------------------------------------


def settles(result: Any, eps: float, within: float, known_failure: bool = False) -> Verdict:
    """The run is settled by ``within`` seconds (the paper's horizon).

    ``|z1| < eps`` from some time on until ``within`` (or the end of the run,
    when it is shorter): what the paper's saturated figures show within their
    10 s. A run that is still saturated, or still outside the band, at that
    time fails. Recurring saturation may take the error out of the band again
    later; :func:`recovery` judges what follows each episode.
    """
    horizon = min(float(result.t[-1]), within)
    claim = f"settled by {horizon:g} s: |z1| < {eps:g} from some time on until {horizon:g} s"
    if (diverged := _diverged(result, "settles", claim)) is not None:
        return diverged
    t = np.asarray(result.t)
    upto = t <= horizon + 1e-9 * max(1.0, horizon)
    z1 = np.abs(np.asarray(result.z1, dtype=float))[upto]
    outside = np.flatnonzero(~(z1 < eps))
    if outside.size == 0:
        return Verdict("settles", claim, Status.HELD, "inside the band from the first sample")
    last = int(outside[-1])
    if last + 1 < z1.size:
        return Verdict("settles", claim, Status.HELD, f"settled at {float(t[last + 1]):.3f} s")
    sat = 100 * float(np.mean(np.asarray(result.saturated)[upto]))
    return Verdict(
        "settles",
        claim,
        Status.FAILED,
        f"|z1| = {float(z1[-1]):.3g} at {horizon:g} s (saturated {sat:.0f} % of the "
        "time until then)",
        known=known_failure,
    )


def _windows_verdict(
    name: str, claim: str, result: Any, settle_time: float, t_prime: float, bad_in_window: Any
) -> Verdict:
    horizon = float(result.t[-1])
    windows = recovery_windows(result, settle_time, t_prime)
    if not windows:
        return Verdict(name, claim, Status.UNTESTED, "the actuator never saturated")
    due = [w for w in windows if _is_due(w, horizon)]
    if not due:
        gaps = [w[2] - w[0] for w in windows]
        return Verdict(
            name,
            claim,
            Status.UNTESTED,
            f"no claim fell due: after each of the {len(windows)} episodes "
            f"saturation returned (or the run ended) within {max(gaps):.3g} s, "
            f"sooner than T' = {t_prime:.3g} s",
        )
    t = np.asarray(result.t)
    failures = []
    for t_e, d, until in due:
        mask = (t >= d) & ((t < until) | (until >= horizon))
        why = bad_in_window(mask)
        if why:
            failures.append(
                f"after the episode ending at {t_e:.3f} s: {why} in [{d:.3f}, {until:.3f}] s"
            )
    n = len(due)
    if failures:
        return Verdict(
            name,
            claim,
            Status.FAILED,
            f"{len(failures)} of {n} due windows fail; " + "; ".join(failures[:2]),
        )
    return Verdict(
        name, claim, Status.HELD, f"all {n} due windows hold; {len(windows) - n} not due"
    )


def recovery(result: Any, eps: float, settle_time: float, t_prime: float) -> Verdict:
    """``|z1| < eps`` from each episode's ``max(T_e, T_s) + T'`` until the next episode."""
    claim = (
        f"|z1| < {eps:g} regained by max(T_e, T_s) + T' after every saturation "
        "episode, until the next"
    )
    z1 = np.abs(np.asarray(result.z1, dtype=float))

    def bad(mask: np.ndarray) -> str:
        worst = float(np.max(z1[mask])) if mask.any() else 0.0
        return "" if not mask.any() or worst < eps else f"max |z1| = {worst:.3g}"

    return _windows_verdict("recovery", claim, result, settle_time, t_prime, bad)


def nominal_again(result: Any, settle_time: float, t_prime: float) -> Verdict:
    """The bounds are nominal again in every due recovery window."""
    claim = "bounds nominal again by max(T_e, T_s) + T' after every saturation episode"
    exp = _expanded(result)
    if exp is None:
        return Verdict("nominal-again", claim, Status.UNTESTED, "diagnostics were not recorded")

    def bad(mask: np.ndarray) -> str:
        n = int(np.count_nonzero(exp[mask]))
        return f"expanded at {n} samples" if n else ""

    return _windows_verdict("nominal-again", claim, result, settle_time, t_prime, bad)


# ---------------------------------------------------------------------------
# a user's requirements
# ---------------------------------------------------------------------------


def settled_by(result: Any, eps: float, by: float) -> Verdict:
    """``|z1| < eps`` for good from ``by`` seconds on: a requirement a user states.

    Unlike :func:`settling`, the time is not moved by saturation: the user asked
    for accuracy by ``by``. "For good" means until the end of the run, all a run
    can show. Untested when ``by`` lies beyond the horizon.

    >>> import numpy as np, famcc
    >>> t = np.arange(0, 3.001, 0.01)
    >>> z1 = np.where(t < 1.5, 1.0, 0.01)
    >>> r = famcc.SimResult(t=t, y=z1, y_d=0 * t, x=z1[:, None], z=z1[:, None],
    ...                     v=0 * t, u=0 * t, dt=0.01)
    >>> [settled_by(r, 0.1, by).status for by in (2.0, 1.0, 5.0)]
    [<Status.HELD: 'held'>, <Status.FAILED: 'failed'>, <Status.UNTESTED: 'untested'>]
    """
    horizon = float(result.t[-1])
    ts = result.settling_time(eps)
    claim = f"|z1| < {eps:g} for good from {by:g} s on (required)"
    if (diverged := _diverged(result, "settled-by", claim)) is not None:
        return diverged
    if by > horizon:
        return Verdict(
            "settled-by",
            claim,
            Status.UNTESTED,
            f"{by:g} s lies beyond the horizon {horizon:g} s (settled at {_t(ts)})",
        )
    if ts is not None and ts <= by:
        return Verdict("settled-by", claim, Status.HELD, f"settled at {ts:.3f} s")
    why = "outside the band at the end of the run" if ts is None else f"settled only at {ts:.3f} s"
    return Verdict("settled-by", claim, Status.FAILED, why)


def requirements(
    result: Any, eps: float | None = None, settle_time: float | None = None
) -> list[Verdict]:
    """The claims a user's requirements make about a run (none without requirements).

    Parameters
    ----------
    result : famcc.SimResult
    eps : float, optional
        Required accuracy of ``|z1|``. Without it there is nothing to judge.
    settle_time : float, optional
        ``|z1| < eps`` is required for good from this time on (:func:`settled_by`);
        without it, only "settled by the end of the run" (:func:`settles` at the
        horizon). Needs ``eps``.

    Raises
    ------
    ValueError
        ``settle_time`` without ``eps``, or a bad value.

    >>> import numpy as np, famcc
    >>> t = np.arange(0, 3.001, 0.01)
    >>> r = famcc.SimResult(t=t, y=t, y_d=0 * t, x=t[:, None], z=np.exp(-t)[:, None],
    ...                     v=0 * t, u=0 * t, dt=0.01)
    >>> requirements(r)
    []
    >>> [(v.name, v.status) for v in requirements(r, eps=0.1, settle_time=2.5)]
    [('settled-by', <Status.HELD: 'held'>)]
    """
    if eps is None:
        if settle_time is not None:
            raise ValueError("settle_time is a requirement on |z1| < eps: give eps too")
        return []
    if not (isinstance(eps, (int, float)) and np.isfinite(eps) and eps > 0):
        raise ValueError(f"eps must be a finite number > 0, got {eps!r}")
    if settle_time is None:
        return [settles(result, eps, within=float(result.t[-1]))]
    if not (
        isinstance(settle_time, (int, float)) and np.isfinite(settle_time) and settle_time >= 0
    ):
        raise ValueError(f"settle_time must be a finite number >= 0, got {settle_time!r}")
    return [settled_by(result, eps, float(settle_time))]
