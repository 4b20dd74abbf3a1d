"""``famcc.report``: a report with figures for any runs, a user's own plants and controllers."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from famcc import _core, verdicts
from famcc.reporting.notes import _accuracy_text, _missing_notes, _saturation_note
from famcc.reporting.records import run_record
from famcc.reporting.tables import _label
from famcc.reporting.writer import _save_figure, _write
from famcc.sim import SimResult


def _labelled(results: Any) -> list[tuple[str, Any]]:
    """``[(label, SimResult), ...]`` from a result, a list, labelled pairs or a dict."""
    if isinstance(results, SimResult):
        results = [results]
    items = list(results.items()) if isinstance(results, dict) else list(results)
    out: list[tuple[str, Any]] = []
    for i, item in enumerate(items):
        if isinstance(item, SimResult):
            out.append((f"run {i + 1}", item))
        elif isinstance(item, (tuple, list)) and len(item) == 2 and isinstance(item[1], SimResult):
            out.append((str(item[0]), item[1]))
        else:
            raise ValueError(
                "results must be SimResults, (label, SimResult) pairs or a dict "
                f"{{label: SimResult}}; item {i} is {type(item).__name__}"
            )
    if not out:
        raise ValueError("results is empty: give at least one SimResult")
    labels = [label for label, _ in out]
    if len(set(labels)) != len(labels):
        raise ValueError(f"labels must be unique, got {labels}")
    return out


def _stem(label: str, taken: set[str]) -> str:
    stem = "".join(c if c.isalnum() else "-" for c in label.lower()).strip("-") or "run"
    stem = "-".join(part for part in stem.split("-") if part)
    base, k = stem, 2
    while stem in taken:
        stem, k = f"{base}-{k}", k + 1
    taken.add(stem)
    return stem


def report(
    results: Any,
    out: str | Path,
    *,
    eps: float | None = None,
    settle_time: float | None = None,
    title: str = "famcc report",
    figures: bool = True,
    panels: Sequence[str] | None = None,
) -> Path:
    """A markdown report with figures for any runs, in the format of ``famcc reproduce``.

    Writes ``out/report.md`` (header, headline, a results table, the claims,
    notes, one figure per run), ``out/summary.json`` (the same numbers) and
    ``out/<label>.png``.

    Parameters
    ----------
    results : SimResult, list of SimResult, list of (label, SimResult) or dict
        The runs; unlabelled ones are called "run 1", "run 2", ...
    out : path
        Output directory (created).
    eps : float, optional
        Your accuracy requirement on ``|z1|``. It is also the accuracy of the
        settling time, steady RMS and ripple; without it each run uses its
        controller's preset accuracy (:attr:`famcc.SimResult.accuracy`), if any.
    settle_time : float, optional
        Your requirement on time: ``|z1| < eps`` for good from ``settle_time``
        seconds on (:func:`famcc.verdicts.settled_by`). Needs ``eps``.
    title : str
        The report's title.
    figures : bool
        Draw each run's figure (:meth:`famcc.SimResult.plot`).
    panels : sequence of str, optional
        The figures' panels (default: all the runs have data for).

    Returns
    -------
    pathlib.Path
        The path of ``report.md``.

    Notes
    -----
    A user's run carries no paper claims. Claims are judged only against the
    requirements given here (:func:`famcc.verdicts.requirements`): with ``eps``
    alone, "settled by the end of the run"; with ``eps`` and ``settle_time``,
    "settled by ``settle_time``", untested when that lies beyond the horizon.
    Each is held, failed or untested, never held for something untested.

    Examples
    --------
    >>> import tempfile, famcc
    >>> def run(k_u):
    ...     ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
    ...                             constraint="lateral", eps=0.1, k_u=k_u)
    ...     return famcc.simulate(famcc.plants.second_order(), ctrl, 3.0,
    ...                           reference=famcc.Sine(), u_limits=(-2.5, 3.0))
    >>> with tempfile.TemporaryDirectory() as d:
    ...     md = report([("k_u = 5", run(5.0)), ("k_u = 2", run(2.0))], d, eps=0.1,
    ...                 settle_time=2.0, figures=False)
    ...     text = md.read_text()
    >>> "| k_u = 5 |" in text and "## Claims" in text
    True
    """
    runs = _labelled(results)
    if settle_time is not None and eps is None:
        raise ValueError("settle_time is a requirement on |z1| < eps: give eps too")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    records = []
    taken: set[str] = set()
    for label, res in runs:
        found = verdicts.requirements(res, eps=eps, settle_time=settle_time)
        rec = run_record(label, res, eps=eps, found=found)
        rec["figure"] = None
        if figures:
            from famcc import plot  # deferred: famcc.plot loads matplotlib

            chosen = plot.panels_of(res, panels)
            fig = plot.figure(res, chosen, eps=eps, title=f"{label}: {res.controller_description}")
            _save_figure(rec, fig, out, _stem(label, taken), plot.legend(chosen))
        records.append(rec)
    if eps is None:
        wanted = "none (no claims judged)"
    elif settle_time is None:
        wanted = f"|z1| < {eps:g} by the end of each run"
    else:
        wanted = f"|z1| < {eps:g} for good from {settle_time:g} s on"
    intro = (
        f"{len(records)} run(s); requirements: {wanted}; famcc {_core.__version__}"
        ". The same numbers are in [`summary.json`](summary.json); the figures are explained "
        "in `docs/figures.md`, the terms in `docs/glossary.md`."
    )
    md, _ = _write(
        records,
        out,
        title=title,
        intro=intro,
        notes=_run_notes(records),
        summary_meta={"eps": eps, "settle_time": settle_time},
        key="runs",
    )
    return md


def _run_notes(records: Sequence[dict[str, Any]]) -> list[str]:
    """Notes on user runs: controller, accuracy, saturation, what was not computed."""
    notes = []
    for r in records:
        line = f"- **{_label(r)}.** {r['controller']}; reference {r['reference']}."
        if r["eps_z"] is None:
            line += (
                " No accuracy eps: the controller presets none for z1 and none was given, so "
                "no settling time, steady RMS or ripple."
            )
        else:
            line += _accuracy_text(r)
        notes.append(line)
        if r["u_limits"] is not None and r["saturation_episodes"]:
            notes.append(_saturation_note(r))
        notes += _missing_notes(r)
    return notes
