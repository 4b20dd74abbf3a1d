"""The sweep's runs: one closed loop per scenario, rate, discretization and limits."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any

import numpy as np

from famcc import _core, scenarios
from famcc.scenarios import substeps_for
from famcc.signals import Sine
from famcc.verdicts import STARTUP, Status

#: Sample rates of the sweep, Hz.
RATES_HZ = (50, 100, 200, 300, 500, 1000, 2000, 5000, 10000)
#: The differentiator discretizations compared.
DISCRETIZATIONS = ("exact", "euler", "tustin", "foh")
#: Estimate limits are this many times the initial |z_i| (at least 1).
LIMIT_FACTOR = 4.0
#: The rate the sweep asks about, Hz.
TARGET_HZ = 200
#: The three verdicts, weakest first, with their names in the report.
CRITERIA = (
    ("ok", "guarantees"),
    ("nominal_ok", "+ nominal constraint"),
    ("performance_ok", "+ performance as at the fastest rate"),
)


def initial_error(scenario: Any) -> np.ndarray:
    """The scenario's true initial error vector ``z(0)`` (reference ``y_d = sin t``)."""
    ref = Sine()
    plant = scenario.plant
    y = np.asarray(plant.output_derivatives(0.0, np.asarray(plant.x0, dtype=float)), dtype=float)
    return np.asarray(y - np.array([ref(0.0, k) for k in range(len(y))]), dtype=float)


def estimate_limits(scenario: Any, factor: float = LIMIT_FACTOR) -> list[float]:
    """``factor * max(|z_i(0)|, 1)`` per component: bounds on the estimates fed to the law.

    A user knows the initial state (or its range) and the reference, so these
    need no simulation. They cut the differentiator's start-up peaking and
    any sampling-induced ringing of the estimates without touching the true
    trajectory's range in these examples.
    """
    z0 = initial_error(scenario)
    return [float(factor * max(abs(v), 1.0)) for v in z0]


def _differentiator(
    scenario: Any, discretization: str, limited: bool, factor: float = LIMIT_FACTOR
) -> Any:
    base = scenario.controller_kwargs["differentiator"]
    limits = estimate_limits(scenario, factor) if limited else None
    kind: Any = discretization
    return _core.HighGain(base.mu, list(base.a), discretization=kind, limits=limits)


def run_one(
    name: str,
    variant: str,
    rate_hz: float,
    discretization: str,
    limited: bool,
    t_end: float | None = None,
    limit_factor: float = LIMIT_FACTOR,
) -> dict[str, Any]:
    """One sweep point; returns a JSON-friendly record (never raises for a diverging loop)."""
    sc = scenarios.paper(name, variant)
    dt = 1.0 / rate_hz
    rec: dict[str, Any] = {
        "scenario": name,
        "variant": variant,
        "rate_hz": rate_hz,
        "dt": dt,
        "discretization": discretization,
        "limited": bool(limited),
        "limits": estimate_limits(sc, limit_factor) if limited else None,
        "substeps": substeps_for(dt),
        "settling_time": None,
        "first_entry": None,
        "max_abs_xi": None,
        "clamp_count": None,
        "u_min": None,
        "u_max": None,
        "saturated_fraction": None,
        "largest_expansion": None,
        "saturated_after_startup": None,
        "expanded_after_startup": None,
        "expanded_without_saturation": None,
        "bound_beyond_horizon": None,
        "nominal_ok": False,
        "performance_ok": False,
        "bound": sc.bound,
        "bound_kind": "T_s + T'",
        "settled_within_bound": False,
        "violations": [],
        "error": None,
        "ok": False,
        "runtime_s": None,
    }
    t0 = time.perf_counter()
    try:
        res = sc.run(
            dt=dt,
            t_end=t_end,
            substeps=substeps_for(dt),
            differentiator=_differentiator(sc, discretization, limited, limit_factor),
        )
        if res.diverged:  # stopped there by Scenario.run
            raise FloatingPointError(f"the run diverged at t = {res.diverged_at:.4g} s")
    except (FloatingPointError, ValueError, OverflowError, ArithmeticError) as exc:
        rec["error"] = f"{type(exc).__name__}: {exc}"
        # famcc.ConfigError: rejected at construction (e.g. an unstable
        # discretized differentiator); anything else: the run diverged.
        what = "rejected" if type(exc).__name__ == "ConfigError" else "diverged"
        rec["violations"] = [f"{what}: " + str(exc).split(":")[0]]
        rec["runtime_s"] = time.perf_counter() - t0
        return rec
    rec["runtime_s"] = time.perf_counter() - t0
    horizon = float(res.t[-1])
    ts = res.settling_time(sc.eps_z)
    bound = sc.recovery_bound(res)
    kind = "max(T_e, T_s) + T'" if res.saturation_episodes() else "T_s + T'"
    found = sc.verdicts(res)
    violations = [v.text() for v in found if v.failed]
    untested = [v.text() for v in found if v.status is Status.UNTESTED]
    xi = res.max_abs_xi
    expansion = res.largest_expansion
    late = res.t >= STARTUP
    sat = res.saturated
    exp = np.zeros(sat.shape, dtype=bool) if res.expanded is None else np.asarray(res.expanded)
    sat_late = bool(np.any(sat[late]))
    exp_late = bool(np.any(exp[late]))
    # The accuracy given up with headroom left: expanded while v was inside the limits.
    expanded_unsat = bool(np.any((exp & ~sat)[late]))
    rec.update(
        {
            "settling_time": ts,
            "first_entry": res.first_entry(sc.eps_z),
            "max_abs_xi": None if xi is None or not math.isfinite(xi) else xi,
            "max_abs_xi_nominal": res.max_abs_xi_nominal,
            "clamp_count": int(res.clamp_count),
            "u_min": res.u_min,
            "u_max": res.u_max,
            "saturated_fraction": res.saturated_fraction,
            "expanded_unsaturated_fraction": res.expanded_unsaturated_fraction,
            "t_end": horizon,
            "bound": bound,
            "bound_kind": kind,
            "settled_within_bound": bool(ts is not None and ts <= bound),
            "bound_beyond_horizon": bool(bound > horizon),
            "largest_expansion": expansion,
            "saturated_after_startup": sat_late,
            "expanded_after_startup": exp_late,
            "expanded_without_saturation": expanded_unsat,
            "verdicts": [{k: v.record()[k] for k in ("name", "status", "detail")} for v in found],
            "violations": violations,
            "untested": untested,
            "ok": not violations,
            "nominal_ok": not violations and not expanded_unsat,
        }
    )
    return rec


def _config(rec: dict[str, Any]) -> str:
    return str(rec["discretization"]) + (" + limits" if rec["limited"] else "")


def add_performance(records: Sequence[dict[str, Any]]) -> None:
    """Sets each record's ``performance_ok`` against the fastest rate of its configuration."""
    ref: dict[tuple[str, str], dict[str, Any]] = {}
    for r in records:
        key = (r["scenario"], _config(r))
        if key not in ref or r["rate_hz"] > ref[key]["rate_hz"]:
            ref[key] = r
    for r in records:
        b = ref[(r["scenario"], _config(r))]
        ok = bool(r["nominal_ok"])
        if ok and b["settling_time"] is not None:
            ts = r["settling_time"]
            ok = ts is not None and ts <= 1.1 * b["settling_time"] + 0.25
        if ok and b["saturated_fraction"] is not None:
            ok = r["saturated_fraction"] <= b["saturated_fraction"] + 0.05
        r["performance_ok"] = ok


def _task_cost(rate_hz: float) -> float:
    dt = 1.0 / rate_hz
    return rate_hz * (1.0 + 0.1 * substeps_for(dt))


def sweep(
    names: Sequence[str] | None = None,
    variant: str = "code",
    rates: Sequence[float] = RATES_HZ,
    discretizations: Sequence[str] = DISCRETIZATIONS,
    limited: Sequence[bool] = (False, True),
    t_end: float | None = None,
    jobs: int | None = None,
    progress: Any = None,
    limit_factor: float = LIMIT_FACTOR,
) -> list[dict[str, Any]]:
    """Runs every combination; returns the records sorted by scenario, configuration and rate.

    ``jobs`` worker processes (default: the CPU count; 1 runs in-process);
    ``progress`` is a :class:`famcc.reporting.Progress` or None.
    """
    import os

    names = list(names or scenarios.names())
    tasks = [
        (n, variant, float(r), d, bool(lim), t_end, limit_factor)
        for n in names
        for d in discretizations
        for lim in limited
        for r in rates
    ]
    tasks.sort(key=lambda a: -_task_cost(a[2]))  # longest first: better packing
    jobs = max(1, int(jobs or os.cpu_count() or 1))
    records = []

    def label(rec: dict[str, Any]) -> str:
        tag = "OK" if rec["ok"] else "fail"
        lim = "+limits" if rec["limited"] else ""
        return f"{rec['scenario']} {rec['rate_hz']:g} Hz {rec['discretization']}{lim} ({tag})"

    if jobs == 1:
        for args in tasks:
            rec = run_one(*args)
            records.append(rec)
            if progress is not None:
                progress.step(label(rec), rec["runtime_s"])
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            futures = [pool.submit(run_one, *args) for args in tasks]
            for fut in as_completed(futures):
                rec = fut.result()
                records.append(rec)
                if progress is not None:
                    progress.step(label(rec), rec["runtime_s"])
    order = {n: i for i, n in enumerate(names)}
    dorder = {d: i for i, d in enumerate(discretizations)}
    records.sort(
        key=lambda r: (
            order[r["scenario"]],
            dorder[r["discretization"]],
            r["limited"],
            r["rate_hz"],
        )
    )
    add_performance(records)
    return records
