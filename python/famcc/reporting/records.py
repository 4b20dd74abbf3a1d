"""The report's numbers: a JSON-friendly record per run (any run, a scenario's, a diverged one)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from famcc import verdicts
from famcc.verdicts import STARTUP


def _intervals(t: np.ndarray, mask: np.ndarray) -> list[list[float]]:
    """Runs of True in ``mask`` as ``[start, end]`` sample times."""
    m = np.asarray(mask, dtype=np.int8)
    if not m.any():
        return []
    edges = np.diff(np.concatenate(([0], m, [0])))
    starts = np.flatnonzero(edges == 1)
    stops = np.flatnonzero(edges == -1)
    last = len(t) - 1
    return [[float(t[int(a)]), float(t[min(int(b), last)])] for a, b in zip(starts, stops)]


def _num(v: Any) -> Any:
    """JSON-friendly float (None for None/NaN)."""
    if v is None:
        return None
    v = float(v)
    return v if math.isfinite(v) else None


def _guarantee_text(found: Sequence[verdicts.Verdict]) -> str:
    """One cell: each claim's name and status, failures with their reason."""
    parts = []
    for v in found:
        if v.failed:
            parts.append(f"**{v.name} FAILED**" + (" (known)" if v.known else "") + f": {v.detail}")
        else:
            parts.append(f"{v.name} {v.status}")
    return "; ".join(parts)


def run_record(
    label: str,
    result: Any,
    *,
    eps: float | None = None,
    found: Sequence[verdicts.Verdict] = (),
    runtime_s: float | None = None,
) -> dict[str, Any]:
    """The report's numbers for any run, as a JSON-friendly dict.

    Parameters
    ----------
    label : str
        The run's name in the report.
    result : famcc.SimResult
    eps : float, optional
        Accuracy of the settling time, steady RMS and ripple (default: the
        controller's preset accuracy, :attr:`famcc.SimResult.accuracy`; None
        when there is none).
    found : sequence of famcc.verdicts.Verdict
        The claims judged on this run (none for a user run without requirements).
    runtime_s : float, optional
        Wall time of the simulation.

    Returns
    -------
    dict
        ``label``, ``dt``, ``t_end``, ``eps_z``, ``settling_time``, ``first_entry``,
        ``steady_rms``, ``ripple``, ``max_abs_xi``, ``max_abs_xi_nominal``,
        ``expanded_fraction``, ``expanded_unsaturated_fraction``, ``u_limits``,
        ``u_min``, ``u_max``, ``u_range_after_startup``, ``saturated_fraction``,
        ``saturation_episodes``, ``neg_f_over_g_range``,
        ``neg_f_over_g_outside_limits``, ``neg_f_over_g_error``,
        ``derivatives_error``, ``largest_expansion``, ``nominal_return_time``,
        ``output``, ``input``, ``controller``, ``reference``, ``verdicts``,
        ``verdict_counts``, ``violations`` and ``guarantees`` (one table cell), ...
    """
    e = result.accuracy if eps is None else float(eps)
    horizon = float(result.t[-1])
    limits = result.u_limits
    negfg = result.neg_f_over_g
    negfg_out: list[list[float]] = []
    negfg_range = None
    if negfg is not None:
        finite = np.isfinite(negfg)
        if finite.any():
            negfg_range = [float(np.min(negfg[finite])), float(np.max(negfg[finite]))]
            if limits is not None:
                lo, hi = limits
                negfg_out = _intervals(result.t, finite & ((negfg < lo) | (negfg > hi)))
    late = result.t >= STARTUP
    u_late = result.u[late] if late.any() else result.u
    return {
        "label": label,
        "dt": float(result.dt),
        "t_end": horizon,
        "eps_z": _num(e),
        "settling_time": None if e is None else _num(result.settling_time(e)),
        "first_entry": None if e is None else _num(result.first_entry(e)),
        "steady_rms": None if e is None else _num(result.steady_rms(e)),
        "ripple": None if e is None else _num(result.ripple(e)),
        "last_saturation_end_T_e": _num(result.last_saturation_end),
        "max_abs_xi": _num(result.max_abs_xi),
        "max_abs_xi_nominal": _num(result.max_abs_xi_nominal),
        "expanded_fraction": _num(result.expanded_fraction),
        "expanded_unsaturated_fraction": _num(result.expanded_unsaturated_fraction),
        "clamp_count": int(result.clamp_count),
        "u_limits": None if limits is None else [float(limits[0]), float(limits[1])],
        "u_min": float(result.u_min),
        "u_max": float(result.u_max),
        "u_range_after_startup": [float(np.min(u_late)), float(np.max(u_late))],
        "u_peak_time": float(result.t[int(np.argmax(np.abs(result.u)))]),
        "u_initial": float(result.u[0]),
        "saturated_fraction": float(result.saturated_fraction),
        "saturation_episodes": [[a, b] for a, b in result.saturation_episodes()],
        "neg_f_over_g_range": negfg_range,
        "neg_f_over_g_outside_limits": negfg_out,
        "neg_f_over_g_error": result.neg_f_over_g_error,
        "derivatives_error": result.derivatives_error,
        "largest_expansion": _num(result.largest_expansion),
        "nominal_return_time": _num(result.nominal_return_time),
        "max_abs_z1_last_second": float(np.max(np.abs(result.z1[result.t >= horizon - 1.0]))),
        "output": [result.output.name, result.output.unit],
        "input": [result.input.name, result.input.unit],
        "controller": result.controller_description,
        "reference": result.reference_repr,
        "verdicts": [v.record() for v in found],
        "verdict_counts": verdicts.count(found),
        "violations": [v.text() for v in found if v.failed],
        "guarantees": _guarantee_text(found),
        "runtime_s": _num(runtime_s),
    }


def measure(scenario: Any, result: Any, runtime_s: float | None = None) -> dict[str, Any]:
    """The report's numbers for one scenario run: :func:`run_record` and the paper's.

    Adds ``scenario``, ``example``, ``variant``, ``description``,
    ``saturated_scenario``, ``paper_settling_time``, ``settle_time_T_s``, ``t_prime``,
    ``bound`` (``T_s + T'`` for a run that never saturated, else
    ``max(T_e, T_s) + T'``) with ``bound_kind`` and ``bound_within_horizon``, and
    ``regains_accuracy_claimed``; the verdicts are every claim of
    ``scenario.verdicts`` (held, failed or untested), ``violations`` the failed
    ones (those of ``scenario.check``), all measured to ``scenario.eps_z``.
    """
    found = scenario.verdicts(result)
    rec = run_record(scenario.name, result, eps=scenario.eps_z, found=found, runtime_s=runtime_s)
    bound = scenario.recovery_bound(result)
    rec.update(
        scenario=scenario.name,
        example=scenario.example,
        variant=scenario.variant,
        description=scenario.description,
        saturated_scenario=bool(scenario.saturated),
        paper_settling_time=_num(scenario.paper_settling_time),
        settle_time_T_s=float(scenario.settle_time),
        t_prime=float(scenario.t_prime),
        bound=float(bound),
        bound_kind="max(T_e, T_s) + T'" if result.saturation_episodes() else "T_s + T'",
        bound_within_horizon=bool(bound <= float(result.t[-1])),
        regains_accuracy_claimed=bool(scenario.regains_accuracy),
    )
    return rec


def diverged(scenario: Any, exc: BaseException, runtime_s: float | None = None) -> dict[str, Any]:
    """The record of a run that blew up: every claim failed, no metrics."""
    found = [
        verdicts.Verdict(name, name, verdicts.Status.FAILED, f"the closed loop diverged: {exc}")
        for name in scenario.claims
    ]
    keys = (
        "settling_time",
        "first_entry",
        "max_abs_xi",
        "max_abs_xi_nominal",
        "expanded_fraction",
        "expanded_unsaturated_fraction",
        "steady_rms",
        "ripple",
        "u_min",
        "u_max",
        "saturated_fraction",
        "largest_expansion",
        "nominal_return_time",
        "last_saturation_end_T_e",
        "max_abs_z1_last_second",
    )
    lo, hi = scenario.u_limits
    return {
        "label": scenario.name,
        "scenario": scenario.name,
        "example": scenario.example,
        "variant": scenario.variant,
        "description": scenario.description,
        "saturated_scenario": bool(scenario.saturated),
        "dt": None,
        "t_end": None,
        "eps_z": float(scenario.eps_z),
        "paper_settling_time": _num(scenario.paper_settling_time),
        "settle_time_T_s": float(scenario.settle_time),
        "t_prime": float(scenario.t_prime),
        **dict.fromkeys(keys),
        "bound": None,
        "bound_kind": None,
        "bound_within_horizon": None,
        "regains_accuracy_claimed": bool(scenario.regains_accuracy),
        "clamp_count": None,
        "u_limits": [float(lo), float(hi)],
        "u_range_after_startup": None,
        "u_peak_time": None,
        "u_initial": None,
        "saturation_episodes": [],
        "neg_f_over_g_range": None,
        "neg_f_over_g_outside_limits": [],
        "neg_f_over_g_error": None,
        "derivatives_error": None,
        "output": None,
        "input": None,
        "controller": None,
        "reference": None,
        "verdicts": [v.record() for v in found],
        "verdict_counts": verdicts.count(found),
        "violations": [v.text() for v in found],
        "guarantees": _guarantee_text(found),
        "error": f"{type(exc).__name__}: {exc}",
        "runtime_s": _num(runtime_s),
        "figure": None,
    }
