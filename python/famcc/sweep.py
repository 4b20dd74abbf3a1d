"""Sample-rate sweep: how slow may the controller be sampled?

For every scenario, sample rate (50 Hz to 10 kHz), differentiator
discretization (``"exact"``, ``"euler"``, ``"tustin"``, ``"foh"``) and with or without
saturation of the estimates fed to the law (``HighGain(..., limits=...)``), one
closed-loop run of :meth:`famcc.scenarios.Scenario.run` with the scenario's
differentiator replaced. Each run gets three nested verdicts:

``ok`` (keeps its guarantees)
    no claim of ``scenario.verdicts(result)`` fails (see :mod:`famcc.verdicts`):
    settling within the corollary's bound, no saturation and nominal bounds
    after the start-up for the scenarios designed without saturation;
    settling by 10 s and recovery after every saturation episode for the
    saturated ones. Untested claims are listed apart (never counted as held).
    Runs that blow up fail.
``nominal_ok``
    also the accuracy is never given up with headroom left: after the start-up
    (:data:`famcc.verdicts.STARTUP`) the bounds are never expanded while ``v``
    is inside the limits. (The flexible boundary keeps ``|xi~| < 1`` by
    construction, so ``|xi~| < 1`` alone cannot show that sampling left the
    nominal constraint intact.)
``performance_ok``
    also the run performs like the fastest swept rate (same configuration):
    settles no later than ``1.1 t_ref + 0.25 s`` and saturates at most 5
    percentage points more often.

The plant is integrated with RK4 steps of at most :data:`MAX_RK4_STEP` (the
same 10 substeps per sample as ``famcc reproduce`` at 1 kHz), so the plant is
equally accurate at every rate and only the controller's sampling changes.

Estimate limits a user can know without simulating: ``LIMIT_FACTOR`` times the
initial error vector's magnitudes, floored at 1 (:func:`estimate_limits`).

>>> from famcc import sweep
>>> sweep.substeps_for(1e-3), sweep.substeps_for(1 / 50), sweep.substeps_for(1e-4)
(10, 200, 1)
"""

from __future__ import annotations

import json
import math
import time
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any

import numpy as np

from famcc.scenarios import MAX_RK4_STEP, substeps_for
from famcc.verdicts import STARTUP

__all__ = [
    "DISCRETIZATIONS",
    "LIMIT_FACTOR",
    "MAX_RK4_STEP",
    "RATES_HZ",
    "estimate_limits",
    "lowest_rates",
    "run_one",
    "substeps_for",
    "sweep",
    "write_sweep_report",
]

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
    from famcc.simulation import Sine

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
    import famcc

    base = scenario.controller_kwargs["differentiator"]
    limits = estimate_limits(scenario, factor) if limited else None
    kind: Any = discretization
    return famcc.HighGain(base.mu, list(base.a), discretization=kind, limits=limits)


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
    from famcc import scenarios

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
    untested = [v.text() for v in found if v.status == "untested"]
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
            "verdicts": [{"name": v.name, "status": v.status, "detail": v.detail} for v in found],
            "violations": violations,
            "untested": untested,
            "ok": not violations,
            "nominal_ok": not violations and not expanded_unsat,
        }
    )
    return rec


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

    from famcc import scenarios

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


def _config(rec: dict[str, Any]) -> str:
    return str(rec["discretization"]) + (" + limits" if rec["limited"] else "")


def lowest_rates(
    records: Sequence[dict[str, Any]], key: str = "ok"
) -> dict[tuple[str, str], dict[str, Any]]:
    """Per (scenario, configuration): the lowest rate from which every higher swept rate
    passes (``"from"``, None if even the highest fails) and the lowest passing rate at all
    (``"any"``). ``key`` is the verdict: ``"ok"``, ``"nominal_ok"`` or
    ``"performance_ok"`` (see the module's documentation)."""
    groups: dict[tuple[str, str], list[dict[str, Any]]] = {}
    for r in records:
        groups.setdefault((r["scenario"], _config(r)), []).append(r)
    out = {}
    for k, recs in groups.items():
        recs = sorted(recs, key=lambda r: r["rate_hz"])
        frm = None
        for r in reversed(recs):
            if not r[key]:
                break
            frm = r["rate_hz"]
        passing = [r["rate_hz"] for r in recs if r[key]]
        out[k] = {"from": frm, "any": passing[0] if passing else None}
    return out


def _rate(v: Any) -> str:
    return "none" if v is None else f"{v:g} Hz"


def xi_text(x: float | None) -> str:
    """``max |xi~|`` with enough digits never to print a value below 1 as "1.000"."""
    if x is None:
        return "-"
    if x < 0.9995:
        return f"{x:.3f}"
    margin = 1.0 - x
    if margin <= 0.0:
        return "1"
    return f"1-{margin:.0e}"


def _seconds(v: float | None) -> str:
    return "never" if v is None else f"{v:.2f} s"


def _cell(r: dict[str, Any]) -> str:
    if r["error"]:
        return "diverged"
    ts = r["settling_time"]
    body = f"{'never' if ts is None else f'{ts:.2f}'} / {xi_text(r['max_abs_xi'])}"
    if not r["ok"]:
        return f"**x** {body}"
    marks = ""
    if not r["nominal_ok"]:
        marks += " (n)"
    elif not r["performance_ok"]:
        marks += " (p)"
    if r["untested"]:
        marks += " (u)"
    return body + marks


def _lowest_table(
    low: dict[tuple[str, str], Any], names: list[str], configs: list[str]
) -> list[str]:
    lines = ["| scenario | " + " | ".join(configs) + " |", "|---|" + "---|" * len(configs)]
    for n in names:
        cells = []
        for c in configs:
            v = low.get((n, c), {"from": None, "any": None})
            cell = _rate(v["from"])
            if v["any"] is not None and (v["from"] is None or v["any"] < v["from"]):
                cell += f" ({_rate(v['any'])})"
            cells.append(cell)
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    return lines


def _needed(low: dict[tuple[str, str], Any], names: list[str], config: str) -> float | None:
    """The rate every scenario needs with ``config`` (None if some never passes)."""
    per = [low.get((n, config), {}).get("from") for n in names]
    return None if any(v is None for v in per) else max(per)


def question_rate(records: Sequence[dict[str, Any]]) -> float:
    """The rate the report asks about: :data:`TARGET_HZ` when it was swept, else the
    lowest swept rate (the report speaks only of rates it ran)."""
    rates = {r["rate_hz"] for r in records}
    return float(TARGET_HZ) if TARGET_HZ in rates else float(min(rates))


def _answer(
    records: Sequence[dict[str, Any]],
    lows: dict[str, dict[tuple[str, str], Any]],
    names: list[str],
    configs: list[str],
) -> list[str]:
    target = question_rate(records)
    top = max(r["rate_hz"] for r in records)
    ok_low = lows["ok"]
    lines = []
    if "exact" in configs:
        today = {n: ok_low.get((n, "exact"), {}).get("from") for n in names}
        lines += [
            "- **Today** (exact discretization, no estimate limits) the scenarios keep their "
            "guarantees from: "
            + ", ".join(f"{n} {_rate(today[n])}" for n in names)
            + f"; all of them together need {_rate(_needed(ok_low, names, 'exact'))}.",
            "",
        ]
    lines += [
        (
            "Rate every scenario needs (lowest swept rate from which all faster rates pass), "
            "per configuration and criterion:"
        ),
        "",
        "| configuration | " + " | ".join(label for _, label in CRITERIA) + " |",
        "|---|" + "---|" * len(CRITERIA),
    ]
    for c in configs:
        lines.append(
            f"| {c} | " + " | ".join(_rate(_needed(lows[k], names, c)) for k, _ in CRITERIA) + " |"
        )
    lines.append("")
    verdicts = []
    for k, label in CRITERIA:
        good = [c for c in configs if (_needed(lows[k], names, c) or math.inf) <= target]
        verdicts.append((label, good))
    g_ok, g_nom, g_perf = (v[1] for v in verdicts)
    if g_ok:
        lines.append(
            f"- **By the guarantees as checked: yes.** At {target:g} Hz and every faster "
            "swept rate every "
            f"scenario keeps its guarantees with {', '.join(g_ok)}."
        )
    else:
        lines.append(
            f"- **By the guarantees as checked: no** configuration brings every "
            f"scenario down to {target:g} Hz."
        )
    nom_text = "yes, with " + ", ".join(g_nom) if g_nom else "no"
    lines.append(
        f"- **With the nominal constraint kept: {nom_text}.** "
        + (
            ""
            if g_nom
            else f"At {target:g} Hz, with every configuration, some run expands its bounds "
            "after the start-up while v is inside the limits: the sampled state reaches "
            "(within rho_e) or crosses the nominal boundary that Theorems 1-3 keep it "
            "inside, and only the flexible boundary keeps |xi~| < 1. Per "
            "configuration, the rates in the table above."
        )
    )
    lines.append(
        f"- **At {target:g} Hz with the performance of the {top:g} Hz run kept: "
        f"{'yes, with ' + ', '.join(g_perf) if g_perf else 'no'}.**"
    )
    perf = {c: _needed(lows["performance_ok"], names, c) for c in configs}
    reached = {c: v for c, v in perf.items() if v is not None}
    if reached:
        best = min(reached.values())
        lines.append(
            f"- **Lowest rate at which every scenario passes all three: {best:g} Hz**, "
            f"with {', '.join(c for c, v in reached.items() if v == best)}."
        )
    if "exact + limits" in configs and "exact" in configs:
        changed = [
            n
            for n in names
            if any(
                lows[k].get((n, "exact")) != lows[k].get((n, "exact + limits")) for k, _ in CRITERIA
            )
        ]
        lines.append(
            f"- **Estimate limits** change a lowest rate of {len(changed)} of {len(names)} "
            "scenarios with the exact discretization"
            + (f" ({', '.join(changed)})" if changed else "")
            + ". The estimates rarely exceed a few times the initial error, so the clip "
            "is mostly inactive; it trims the start-up peaking and keeps some slow loops from "
            "blowing up, but it cannot remove the phase lag that sampling adds."
        )
    untested = [r for r in records if r["rate_hz"] == target and r["ok"] and r["untested"]]
    if untested:
        examples = ", ".join(f"{r['scenario']} {_config(r)}" for r in untested[:3])
        lines.append(
            f"- Caveat: {len(untested)} passing {target:g} Hz runs have untested claims "
            "(a bound beyond the horizon, or saturation returning sooner than T' after every "
            f"episode; marked (u)), e.g. {examples}."
        )
    return lines


def _compare_table(
    records: Sequence[dict[str, Any]], names: list[str], configs: list[str], rate: float
) -> list[str]:
    """The target rate next to the fastest swept rate, per scenario and configuration."""
    top = max(r["rate_hz"] for r in records)
    by = {(r["scenario"], _config(r), r["rate_hz"]): r for r in records}
    head = (
        f"| scenario | configuration | settling [s] at {rate:g} Hz / {top:g} Hz | "
        f"max \\|xi~\\| | saturated | largest expansion | verdict at {rate:g} Hz |"
    )
    lines = [head, "|---|---|---|---|---|---|---|"]
    for n in names:
        for c in configs:
            a, b = by.get((n, c, rate)), by.get((n, c, top))
            if a is None or b is None:
                continue
            if a["error"]:
                lines.append(
                    f"| {n} | {c} | diverged / {_seconds(b['settling_time'])} | - | - | - | fails |"
                )
                continue

            def pct(v: float | None) -> str:
                return "-" if v is None else f"{100 * v:.1f} %"

            def exp(v: float | None) -> str:
                if v is None or v <= 1.0:
                    return "-"
                return f"{v:.3g}x" if v >= 1.001 else f"1+{v - 1.0:.0e}x"

            if a["performance_ok"]:
                verdict = "all three"
            elif a["nominal_ok"]:
                verdict = "guarantees + nominal; slower / saturates more"
            elif a["ok"]:
                verdict = "guarantees only (nominal bounds not kept)"
            else:
                verdict = "fails: " + "; ".join(a["violations"])[:80]
            lines.append(
                f"| {n} | {c} | {_seconds(a['settling_time'])} / "
                f"{_seconds(b['settling_time'])} | {xi_text(a['max_abs_xi'])} / "
                f"{xi_text(b['max_abs_xi'])} | {pct(a['saturated_fraction'])} / "
                f"{pct(b['saturated_fraction'])} | {exp(a['largest_expansion'])} / "
                f"{exp(b['largest_expansion'])} | {verdict} |"
            )
    return lines


def write_sweep_report(
    records: Sequence[dict[str, Any]], out: str | Path, meta: dict[str, Any], figure: bool = True
) -> Path:
    """Writes ``sweep.md``, ``sweep.json`` and ``sweep.png`` into ``out``; returns sweep.md."""
    from famcc import scenarios

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    names = list(dict.fromkeys(r["scenario"] for r in records))
    configs = list(dict.fromkeys(_config(r) for r in records))
    rates = sorted({r["rate_hz"] for r in records})
    if any("performance_ok" not in r for r in records):
        add_performance(records)
    lows = {k: lowest_rates(records, k) for k, _ in CRITERIA}
    low = lows["ok"]
    (out / "sweep.json").write_text(
        json.dumps(
            {
                "meta": meta,
                "records": list(records),
                "lowest_rates": [
                    {
                        "scenario": k[0],
                        "configuration": k[1],
                        **{f"{crit}_from": lows[crit][k]["from"] for crit, _ in CRITERIA},
                        **{f"{crit}_any": lows[crit][k]["any"] for crit, _ in CRITERIA},
                    }
                    for k in low
                ],
            },
            indent=2,
        )
        + "\n"
    )
    if figure:
        from famcc import plot

        plot.save(plot.sweep_figure(records), out / "sweep.png")

    variant = meta.get("variant", "code")
    factor = meta.get("limit_factor", LIMIT_FACTOR)
    lim_rows = []
    for n in names:
        sc = scenarios.paper(n, variant)
        z0 = initial_error(sc)
        lim_rows.append(
            f"| {n} | ({', '.join(f'{v:.3g}' for v in z0)}) | "
            f"({', '.join(f'{v:.3g}' for v in estimate_limits(sc, factor))}) |"
        )
    wall = (
        f", {meta['runtime_s']:.0f} s wall time on {meta.get('jobs', 1)} process(es)"
        if meta.get("runtime_s")
        else ""
    )
    lines = [
        "# famcc sweep: settling time and max |xi~| against the sample rate",
        "",
        (
            f"Variant `{variant}`, horizon {meta.get('t_end') or 10:g} s (saturated runs are "
            "extended until their recovery claims can fall due), rates "
            f"{', '.join(f'{r:g}' for r in rates)} Hz, {len(records)} runs{wall}."
        ),
        "",
        (
            "Each run replaces the scenario's differentiator by "
            "`famcc.HighGain(mu, a, discretization=..., limits=...)` (same mu and a) and calls "
            "`scenario.run(dt=1/rate, substeps=max(1, ceil(dt / 1e-4)))`, so the plant's RK4 step "
            "is at most 0.1 ms at every rate (10 substeps at 1 kHz, as in `famcc reproduce`). "
            "A run **keeps its guarantees** when none of the claims of `scenario.verdicts` "
            "fails (docs/design.md §8): for the scenarios designed without saturation, settling "
            "within max(T_e, T_s) + T', no saturation and nominal bounds after the first "
            f"{STARTUP:g} s; for the saturated ones, settled by 10 s, and |z1| < 0.1 and nominal "
            "bounds again after every saturation episode whose recovery bound falls due. "
            "Untested claims are marked (u), never counted as held. Loops that blow up fail."
        ),
        "",
        (
            "Two stricter verdicts: **nominal constraint**: also, after the first "
            f"{STARTUP:g} s, the bounds are never expanded while v is inside the limits (the "
            "accuracy given up with headroom left). The flexible bounds open as soon as the state "
            "comes within rho_e of the nominal boundary and keep |xi~| < 1 by construction, so "
            "|xi~| < 1 alone does not show that sampling left the nominal constraint intact. "
            "**Performance**: settles no later than 1.1 x + 0.25 s the fastest swept rate's "
            "settling time (same configuration) and saturates at most 5 percentage points more "
            "often."
        ),
        "",
        (
            "Estimate limits (`+ limits`): the estimates fed to the law are clipped to "
            f"{factor:g} x max(|z_i(0)|, 1), numbers a user knows from the initial state and "
            "the reference without simulating:"
        ),
        "",
        "| scenario | z(0) | limits |",
        "|---|---|---|",
        *lim_rows,
        "",
        "## Answer",
        "",
        *_answer(records, lows, names, configs),
        "",
        "## Lowest sample rate per scenario",
        "",
        (
            "Lowest rate from which every faster swept rate passes; in brackets the lowest "
            "passing rate at all, when lower (isolated passes)."
        ),
        "",
    ]
    for k, label in CRITERIA:
        lines += [f"**{label}**", "", *_lowest_table(lows[k], names, configs), ""]
    lines += [
        *(
            [
                f"## {question_rate(records):g} Hz next to {max(rates):g} Hz",
                "",
                *_compare_table(records, names, configs, question_rate(records)),
            ]
            if question_rate(records) < max(rates)
            else []
        ),
        "",
        "![sweep](sweep.png)",
        "",
        "## All runs",
        "",
        (
            "Cells: settling time to |z1| < 0.1 [s] / max |xi~| (`1-3e-04` means 1 - 3e-4); "
            "**x**: does not keep its guarantees (reasons in `sweep.json`); (n): keeps them but "
            "does not keep the nominal bounds; (p): keeps both but settles later or saturates more "
            "than at the fastest rate; (u): some claim untested (a bound beyond the horizon, or "
            'saturation returning sooner than T\'); "never": not settled by the end; '
            '"diverged": the loop blew up.'
        ),
        "",
    ]
    for n in names:
        lines += [
            f"### {n}",
            "",
            "| configuration | " + " | ".join(f"{r:g} Hz" for r in rates) + " |",
            "|---|" + "---|" * len(rates),
        ]
        for c in configs:
            row = {r["rate_hz"]: r for r in records if r["scenario"] == n and _config(r) == c}
            lines.append(
                f"| {c} | " + " | ".join(_cell(row[r]) if r in row else "" for r in rates) + " |"
            )
        lines.append("")
    md = out / "sweep.md"
    md.write_text("\n".join(lines))
    return md
