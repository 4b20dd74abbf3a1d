"""The figures of a run and of a scenario: panels chosen, checked, laid out and noted."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, cast

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from famcc.plot.axes import _DPI
from famcc.plot.panels import (
    _panel_accuracy,
    _panel_constraint,
    _panel_error,
    _panel_input,
    _panel_xi,
)
from famcc.plot.phase import _panel_phase, _panel_stage
from famcc.plot.view import _scenario_view, _View, _view

#: The panels of :func:`figure`, in their default order.
PANELS = ("error", "accuracy", "constraint", "input", "xi")
#: The paper's extra panels (:func:`scenario_figure`).
EXTRA_PANELS = ("constraint-zoom", "phase", "stage")
#: The paper's terms in plain words, for the note under each figure (docs/glossary.md).
_TERMS = {
    "z_hat": r"$\hat z$: the controller's estimate",
    "lateral": "LaMC: lateral constraint, bounds the sideways offset from the manifold",
    "longitudinal": "LoMC: longitudinal constraint, bounds the manifold value $s$",
    "oblique": "OMC: oblique constraint, bounds a slanted offset from the manifold",
    "xi": r"$\xi$: place between the bounds ($\pm$1: on one), $\tilde\xi$: with flexible bounds",
    "negfg": "$-F/G$: input holding $z_{n}$ still",
    "sat": "shaded: saturated",
    "h_m": "$h_m$: manifold curve",
}
_DRAW: dict[str, Callable[[Any, _View], str]] = {
    "error": _panel_error,
    "accuracy": _panel_accuracy,
    "constraint": _panel_constraint,
    "constraint-zoom": lambda ax, v: _panel_constraint(ax, v, zoom=True),
    "input": _panel_input,
    "xi": _panel_xi,
    "phase": _panel_phase,
    "stage": _panel_stage,
}
#: A few words per panel, for the legends of reports.
_LEGEND = {
    "error": "z and its estimate",
    "accuracy": "z1 with the accuracy band and the settling time",
    "constraint": "the constrained value with nominal (dashed black) and flexible (solid red) "
    "bounds",
    "constraint-zoom": "the same after T_s",
    "input": "u with the limits and -F/G (where known)",
    "xi": "nominal xi and xi~",
    "phase": "phase portrait (z1, z2)",
    "stage": "constrained stage (s2, ds2)",
}


def _check_panels(v: _View, panels: Sequence[str] | None) -> list[str]:
    r = v.r
    recorded = r.xi is not None and r.bounds is not None and r.nominal_bounds is not None
    if panels is None:
        chosen = [p for p in PANELS if recorded or p not in ("constraint", "xi")]
        return chosen
    if isinstance(panels, str):
        panels = [panels]
    chosen = list(panels)
    known = PANELS + EXTRA_PANELS
    for p in chosen:
        if p not in known:
            raise ValueError(f"unknown panel {p!r}; choose from {', '.join(known)}")
        needs_diag = p in ("constraint", "constraint-zoom", "xi", "stage")
        if needs_diag and not recorded:
            raise ValueError(
                f"panel {p!r} needs the controller's diagnostics; simulate with record=True"
            )
        if p == "phase" and (v.order < 2 or not np.any(np.isfinite(r.z[:, 1]))):
            raise ValueError("panel 'phase' needs order >= 2 and the true z2")
        if p == "stage" and v.order < 3:
            raise ValueError("panel 'stage' is for order >= 3 (at order 2 see 'phase')")
    if not chosen:
        raise ValueError("panels must name at least one panel")
    return chosen


def panels_of(result: Any, panels: Sequence[str] | None = None) -> list[str]:
    """The panels :func:`figure` draws for ``result`` (checked; default: all it has data for).

    >>> import famcc
    >>> from types import SimpleNamespace
    >>> p_only = SimpleNamespace(dt=0.01, order=2, step=lambda e, applied=None: -20.0 * e)
    >>> res = famcc.simulate(famcc.plants.second_order(), p_only, 1.0,
    ...                      reference=famcc.Constant(0.0), record=False)
    >>> panels_of(res)
    ['error', 'accuracy', 'input']
    """
    return _check_panels(_view(result), panels)


def legend(panels: Sequence[str]) -> str:
    """The panels' one-line legend for a report: ``"(a) z and its estimate, ..."``.

    >>> legend(["error", "input"])
    '(a) z and its estimate, (b) u with the limits and -F/G (where known)'
    """
    return ", ".join(f"({chr(97 + i)}) {_LEGEND[p]}" for i, p in enumerate(panels))


def _terms_note(v: _View, panels: Sequence[str]) -> str:
    terms = []
    if v.r.z_hat is not None and "error" not in panels and "accuracy" in panels:
        terms.append(_TERMS["z_hat"])
    if any(p.startswith("constraint") for p in panels) and v.constraint in _TERMS:
        terms.append(_TERMS[v.constraint])
    if "xi" in panels:
        terms.append(_TERMS["xi"])
    if "input" in panels and v.r.neg_f_over_g is not None:
        terms.append(_TERMS["negfg"].replace("{n}", str(v.order)))
    if "phase" in panels or "stage" in panels:
        terms.append(_TERMS["h_m"])
    if v.r.u_limits is not None and v.episodes():
        terms.append(_TERMS["sat"])
    return "  ·  ".join(terms + ["docs/glossary.md"])


def _draw(v: _View, panels: Sequence[str], title: str) -> Figure:
    count = len(panels)
    rows = math.ceil(count / 2)
    fig = Figure(figsize=(12, 3.3 * rows + 0.4), dpi=_DPI, layout="constrained")
    canvas = FigureCanvasAgg(fig)
    grid = fig.add_gridspec(rows, 2)
    for i, name in enumerate(panels):
        wide = count % 2 == 1 and i == count - 1
        ax = fig.add_subplot(grid[i // 2, :] if wide else grid[i // 2, i % 2])
        text = _DRAW[name](ax, v)
        ax.set_title(f"({chr(97 + i)}) {text}")
        ax.grid(True, color="0.9", lw=0.6)
        ax.set_axisbelow(True)
    fig.suptitle(title, fontsize=12)
    note = fig.supxlabel(_terms_note(v, panels), fontsize=8.5, color="0.3")
    # one line: shrink the note (not below 6 pt) until it fits the width
    width = note.get_window_extent(renderer=cast(Any, canvas).get_renderer()).width
    room = 0.98 * fig.bbox.width
    if width > room:
        note.set_fontsize(max(6.0, 8.5 * room / width))
    return fig


def figure(
    result: Any,
    panels: Sequence[str] | None = None,
    *,
    window: tuple[float, float] | None = None,
    eps: float | None = None,
    title: str | None = None,
) -> Figure:
    """The figure of any run: the panels of ``famcc reproduce`` for a user's plant.

    Parameters
    ----------
    result : famcc.SimResult
        Any run of :func:`famcc.simulate`. The constraint, accuracy, ``T_s`` and
        laws come from the controller's configuration that ``simulate`` recorded;
        a run without diagnostics (``record=False`` or a duck-typed controller)
        gets the panels it has data for.
    panels : sequence of str, optional
        Names from :data:`PANELS` (``"error"``, ``"accuracy"``, ``"constraint"``,
        ``"input"``, ``"xi"``) and :data:`EXTRA_PANELS` (``"constraint-zoom"``,
        ``"phase"``, ``"stage"``), drawn in that order, two per row (an odd last
        one spans the row). Default: every panel of :data:`PANELS` the run has
        data for.
    window : (t0, t1), optional
        Time window in seconds for every time axis (and the phase portraits).
        Without it the accuracy panel starts at ``T_s``.
    eps : float, optional
        Accuracy band of the accuracy panel (default: ``result.accuracy``).
    title : str, optional
        Figure title (default: plant output, controller and ``dt``).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        For an unknown panel, or one the run has no data for.

    Examples
    --------
    >>> import famcc
    >>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
    ...                         constraint="lateral", eps=0.1, k_u=5.0)
    >>> res = famcc.simulate(famcc.plants.second_order(), ctrl, 2.0, reference=famcc.Sine(),
    ...                      output=("angle", "rad"), input=("voltage", "V"))
    >>> fig = figure(res, ["accuracy", "input"], window=(0.5, 2.0))
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['$z_{1}$ [rad]', 'voltage $u$ [V]']
    """
    v = _view(result, eps, window)
    chosen = _check_panels(v, panels)
    if title is None:
        out = v.out.name + v.out.bracket()
        title = f"{out} under {result.controller_description}\ndt = {result.dt * 1e3:g} ms" + (
            ""
            if result.u_limits is None
            else f", u in [{result.u_limits[0]:g}, {result.u_limits[1]:g}]" + v.inp.bracket()
        )
    return _draw(v, chosen, title)


def scenario_panels(order: int) -> list[str]:
    """The panels of a scenario figure, in the paper's order.

    >>> scenario_panels(2)
    ['error', 'accuracy', 'constraint', 'constraint-zoom', 'phase', 'input', 'xi']
    """
    extra = ["stage"] if order >= 3 else []
    return ["error", "accuracy", "constraint", "constraint-zoom", "phase", *extra, "input", "xi"]


def scenario_figure(scenario: Any, result: Any, title: str | None = None) -> Figure:
    """The paper-style figure of one scenario run (needs recorded diagnostics).

    The panels of :func:`figure` plus the paper's extras (:func:`scenario_panels`):
    order 2 has seven panels, order 3 eight.

    Parameters
    ----------
    scenario : famcc.scenarios.Scenario
    result : famcc.SimResult
        ``scenario.run(...)``'s result (recorded, so ``z_hat``, ``xi``, ``s`` and the
        bounds are present).
    title : str, optional
        Figure title; by default names the scenario, example, variant and ``dt``.
    """
    if result.xi is None or result.bounds is None:
        raise ValueError("result has no diagnostics; simulate with record=True")
    v = _scenario_view(scenario, result)
    if title is None:
        lo, hi = scenario.u_limits
        title = (
            f'{scenario.name}: example {scenario.example}, variant "{scenario.variant}", '
            f"dt = {result.dt * 1e3:g} ms, u in [{lo:g}, {hi:g}]\n"
            f"{scenario.description}"
        )
    return _draw(v, scenario_panels(v.order), title)


def save(fig: Figure, path: str | Path) -> Path:
    """Writes ``fig`` as PNG to ``path`` and returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, format="png")
    return path
