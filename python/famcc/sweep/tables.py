"""The sweep's tables: the lowest passing rates and the text of one run's cell."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from famcc.sweep.run import (
    TARGET_HZ,
    _config,
)


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
