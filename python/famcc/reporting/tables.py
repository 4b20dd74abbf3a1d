"""The cells and tables of ``report.md``: the results, the claims and the headline."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from famcc.verdicts import Status


def _f(v: Any, digits: int = 3) -> str:
    if v is None:
        return "-"
    if isinstance(v, float) and not math.isfinite(v):
        return "-"
    return f"{v:.{digits}g}"


def _t(v: Any) -> str:
    """A time in seconds with ms resolution, trailing zeros dropped."""
    if v is None:
        return "-"
    text = f"{v:.3f}".rstrip("0").rstrip(".")
    return text or "0"


def _bound_cell(r: dict[str, Any]) -> str:
    if r["bound_kind"] == "T_s + T'":
        return f"{r['bound']:.3g} (T_s + T')"
    te = r["last_saturation_end_T_e"]
    return f"{r['bound']:.3g} (T_e = {_t(te)})"


def _pct(v: float | None) -> str:
    return "-" if v is None else f"{100 * v:.1f} %"


def _label(r: dict[str, Any]) -> str:
    return str(r.get("label") or r.get("scenario"))


def _unit(r: dict[str, Any], key: str) -> str:
    sig = r.get(key)
    return f" {sig[1]}" if sig and sig[1] else ""


def _table(records: Sequence[dict[str, Any]]) -> list[str]:
    """One row per run; scenario records add the paper's columns (paper, bound)."""
    paper = any("paper_settling_time" in r for r in records)
    head = [
        "run" if not paper else "scenario",
        "horizon [s]",
        "settling time [s]",
        "first entry [s]",
        *(["paper [s]", "bound [s]"] if paper else []),
        "steady RMS of z1",
        "u ripple (p-p)",
        "max nominal \\|xi\\|",
        "max \\|xi~\\|",
        "expanded while unsaturated",
        "u range",
        "saturated",
        "largest expansion",
        "claims",
    ]
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] * len(head)) + "|"]
    for r in records:
        if r.get("error"):
            cells = [
                _label(r),
                "-",
                "diverged",
                *["-"] * (len(head) - 4),
                r["guarantees"].replace("|", "\\|"),
            ]
            lines.append("| " + " | ".join(cells) + " |")
            continue
        ts = r["settling_time"]
        limits = r["u_limits"]
        u_range = f"[{r['u_min']:.3g}, {r['u_max']:.3g}]" + (
            "" if limits is None else f" in [{limits[0]:g}, {limits[1]:g}]"
        )
        if r["eps_z"] is None:
            settled = "- (no eps)"
        else:
            settled = "never (not within horizon)" if ts is None else _t(ts)
        rms, ripple = r.get("steady_rms"), r.get("ripple")
        cells = [
            _label(r),
            _t(r["t_end"]),
            settled,
            _t(r["first_entry"]),
            *([_t(r["paper_settling_time"]), _bound_cell(r)] if paper else []),
            "-" if rms is None else f"{rms:.3g}{_unit(r, 'output')}",
            "-" if ripple is None else f"{ripple:.3g}{_unit(r, 'input')}",
            _f(r["max_abs_xi_nominal"], 4),
            "-" if r["max_abs_xi"] is None else f"{r['max_abs_xi']:.4f}",
            _pct(r["expanded_unsaturated_fraction"]),
            u_range,
            "-" if limits is None else _pct(r["saturated_fraction"]),
            "-" if r["largest_expansion"] in (None, 1.0) else f"{r['largest_expansion']:.3g}x",
            r["guarantees"].replace("|", "\\|") or "none given",
        ]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


_COLUMNS = (
    "Horizon: length of the run; settling time: first time after which |z1| < eps holds to "
    "the end of the run (`SimResult.settling_time(eps)`); first entry: first sample with "
    "|z1| < eps; steady RMS: RMS of z1 from the settling time on; u ripple: peak-to-peak of "
    "the applied input from the settling time on; max nominal |xi|: the constraint variable "
    "before the flexible expansion (above 1 the state left the nominal constraint set); max "
    "|xi~|: the flexible one the law used (below 1 by construction); expanded while "
    "unsaturated: share of samples with the bounds expanded although v lay inside the limits "
    "(the accuracy given up with headroom left); u range: applied input against the limits; "
    "saturated: share of samples whose commanded v lay outside the limits; largest expansion: "
    "flexible over nominal bound; claims: each claim's status (docs/design.md §8). The terms "
    "are explained in docs/glossary.md."
)


def _verdict_lines(records: Sequence[dict[str, Any]]) -> list[str]:
    """Every claim of every run: one table row each."""
    first = "scenario" if any("paper_settling_time" in r for r in records) else "run"
    lines = [f"| {first} | claim | status | what the run showed |", "|---|---|---|---|"]
    for r in records:
        for v in r["verdicts"]:
            status = Status(v["status"]).shown
            if v["known"] and v["status"] == Status.FAILED:
                status += " (known, docs/errata.md)"
            lines.append(
                f"| {_label(r)} | {v['claim'].replace('|', chr(92) + '|')} | "
                f"{status} | {v['detail'].replace('|', chr(92) + '|')} |"
            )
    return lines


def headline(records: Sequence[dict[str, Any]]) -> str:
    """The report's first finding: the guarantees counted, never summarised.

    >>> headline([{"scenario": "a", "verdict_counts": {"held": 2, "failed": 0, "untested": 1,
    ...                                              "tested": 2, "total": 3},
    ...            "verdicts": [{"name": "settling", "status": "untested"}]}])
    '**2 of 3 guarantees tested: 2 hold, 0 fail; 1 untested** (untested: a settling; why in the table of claims).'
    """
    total = {
        k: sum(r["verdict_counts"][k] for r in records)
        for k in ("held", "failed", "untested", "tested", "total")
    }
    if total["total"] == 0:
        return (
            "**No claims tested: no requirements were given** (pass eps= and settle_time= "
            "to famcc.report to judge the runs against them)."
        )
    text = (
        f"**{total['tested']} of {total['total']} guarantees tested: {total['held']} hold, "
        f"{total['failed']} fail; {total['untested']} untested**"
    )
    untested = [
        f"{_label(r)} {v['name']}"
        for r in records
        for v in r["verdicts"]
        if v["status"] == "untested"
    ]
    if untested:
        text += " (untested: " + ", ".join(untested) + "; why in the table of claims)"
    return text + "."
