"""The one writer of ``report.md`` and ``summary.json`` (``famcc reproduce``, ``famcc.report``)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from famcc import _core
from famcc.reporting.tables import _COLUMNS, _label, _table, _verdict_lines, headline


def _save_figure(rec: dict[str, Any], fig: Any, out: Path, stem: str, legend: str) -> None:
    """Writes ``fig`` as ``out/stem.png`` and notes the file and its legend in ``rec``."""
    from famcc import plot  # deferred: famcc.plot loads matplotlib

    fname = f"{stem}.png"
    plot.save(fig, out / fname)
    rec["figure"] = fname
    rec["figure_legend"] = legend


def _write(
    records: Sequence[dict[str, Any]],
    out: Path,
    *,
    title: str,
    intro: str,
    notes: Sequence[str],
    summary_meta: dict[str, Any],
    key: str,
    regenerate: str | None = None,
    columns_extra: str = "",
) -> tuple[Path, Path]:
    """The one writer of ``report.md`` and ``summary.json`` (reproduce and report)."""
    out.mkdir(parents=True, exist_ok=True)
    failed = sum(r["verdict_counts"]["failed"] for r in records)
    untested = sum(r["verdict_counts"]["untested"] for r in records)
    total = sum(r["verdict_counts"]["total"] for r in records)
    summary = {
        "famcc_version": _core.__version__,
        **summary_meta,
        "guarantees": {
            k: sum(r["verdict_counts"][k] for r in records)
            for k in ("held", "failed", "untested", "tested", "total")
        },
        "no_guarantee_failed": failed == 0,
        "all_guarantees_hold": failed == 0 and untested == 0 and total > 0,
        key: list(records),
    }
    json_path = out / "summary.json"
    json_path.write_text(json.dumps(summary, indent=2) + "\n")
    claims = _verdict_lines(records) if total else ["No claims: no requirements were given."]
    lines = [
        f"# {title}",
        "",
        intro,
        "",
        headline(records),
        "",
        "## Results",
        "",
        *_table(records),
        "",
        _COLUMNS + columns_extra,
        "",
        "## Claims",
        "",
        *claims,
        "",
        "## Notes",
        "",
        *notes,
        "",
    ]
    figs = [r for r in records if r.get("figure")]
    if figs:
        lines += ["## Figures", ""]
        for r in figs:
            what = r.get("description") or r.get("controller") or ""
            head = _label(r) + (f" (example {r['example']})" if "example" in r else "")
            lines += [
                f"### {head}",
                "",
                (f"{what}. " if what else "")
                + f"Panels: {r['figure_legend']}. Shaded: v outside the limits.",
                "",
                f"![{_label(r)}]({r['figure']})",
                "",
            ]
    if regenerate:
        lines += ["## Regenerate", "", "```sh", regenerate, "```", ""]
    md_path = out / "report.md"
    md_path.write_text("\n".join(lines))
    return md_path, json_path
