"""One closed-loop run of the comparison and its numbers (the unit of work)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from famcc import signals, sim
from famcc.compare.builders import _design_warnings_silenced, build
from famcc.compare.conditions import RK4_STEP, condition_of
from famcc.compare.plants import Case, _Bare, make_plant
from famcc.joints import simulate_joints

#: The weight of TV(u) / H in the tuning objective, s.
TV_WEIGHT = 0.01


@_design_warnings_silenced()
def run(
    case: Case,
    kind: str,
    params: Sequence[dict[str, Any]],
    condition: str,
    *,
    factors: dict[str, float] | None = None,
    t_end: float | None = None,
    seed: int = 0,
) -> list[Any]:
    """Simulate ``kind`` with ``params`` (one dict per joint) under ``condition``.

    Returns one :class:`famcc.SimResult` per joint. famcc's run-time health warning
    (bounds expanded with headroom) is silenced: the comparison measures that cost
    instead (see :func:`build`).
    """
    cond = condition_of(condition)
    dt = cond["dt"]
    limits = getattr(case.as_positive(), cond["limits"])
    plant = make_plant(case, factors)
    horizon = case.t_end if t_end is None else t_end
    substeps = max(1, math.ceil(dt / RK4_STEP - 1e-9))
    noise = cond["noise"] or None
    refs = (
        [signals.Sine()]
        if case.reference is None
        else [signals.Constant(v) for v in case.reference]
    )
    e0 = max(abs(float(plant.x0[case.order * j]) - refs[j](0.0, 0)) for j in range(case.joints))
    bound = 10.0 * max(e0, 1.0)
    ctrls = [build(kind, params[j], dt, limits[j]) for j in range(case.joints)]
    if case.joints > 1:
        return simulate_joints(
            plant,
            ctrls,
            horizon,
            refs,
            u_limits=limits,
            substeps=substeps,
            noise=noise,
            seed=seed,
            diverge_at=bound,
        )
    res = sim.simulate(
        _Bare(plant, case.reversed),
        ctrls[0],
        horizon,
        reference=refs[0],
        u_limits=limits[0],
        substeps=substeps,
        record=False,
        noise=noise,
        seed=seed,
        diverge_at=bound,
    )
    return [res]


def metrics(case: Case, results: Sequence[Any], t_end: float) -> dict[str, Any]:
    """The compared numbers of one run (summed or worst over the joints) and ``J``.

    ``iae`` (output unit s, summed), ``steady_rms`` (worst, None if a joint
    never settled), ``final_rms`` (RMS of ``z1`` over the run's second half,
    worst), ``settling_time`` (worst), ``rms_u`` (largest), ``tv_u`` (TV(u) per
    s, summed), ``z1_ripple`` and ``u_ripple`` (peak-to-peak after settling,
    worst), ``saturated`` (share of samples with the input at a limit, largest), ``diverged``, ``never_settled``
    and ``objective`` (the tuning objective ``J``).
    """
    b = case.band
    worst: Callable[[list[float | None]], float | None] = lambda vs: (
        None if any(v is None for v in vs) else max(float(v) for v in vs if v is not None)
    )
    diverged = any(r.diverged for r in results)
    m: dict[str, Any] = {
        "iae": float(sum(r.iae for r in results)),
        "steady_rms": worst([r.steady_rms(b) for r in results]),
        "final_rms": worst([_final_rms(r) for r in results]),
        "settling_time": worst([r.settling_time(b) for r in results]),
        "rms_u": max(r.rms_u for r in results),
        "tv_u": float(sum(r.tv_u_per_s for r in results)),
        "z1_ripple": worst([r.z1_ripple(b) for r in results]),
        "u_ripple": worst([r.ripple(b) for r in results]),
        "saturated": max(_at_limit(r) for r in results),
        "diverged": diverged,
        "never_settled": any(r.never_settled(b) for r in results),
    }
    if diverged:
        m.update(final_rms=None, steady_rms=None, settling_time=None, objective=1e6)
        return m
    tv = sum(r.tv_u_per_s / h for r, h in zip(results, case.hold))
    m["objective"] = m["iae"] / (b * t_end) + TV_WEIGHT * tv + 10.0 * m["never_settled"]
    return m


def _at_limit(r: Any) -> float:
    """Share of samples with the input at a limit: ``v`` outside, or ``u`` on it.

    A peer clamps its own output to the limits (simple-pid, pyadrc), so its
    ``v`` never lies outside them; ``u`` on a limit counts for all alike.
    """
    if r.u_limits is None or not len(r.u):
        return 0.0
    lo, hi = r.u_limits
    tol = 1e-9 * max(1.0, abs(lo), abs(hi))
    u = np.asarray(r.u)
    return float(np.mean(np.asarray(r.saturated) | (u <= lo + tol) | (u >= hi - tol)))


def _final_rms(r: Any) -> float | None:
    t = np.asarray(r.t)
    tail = r.z1[t >= 0.5 * float(t[-1])]
    return float(np.sqrt(np.mean(np.square(tail)))) if tail.size else None
