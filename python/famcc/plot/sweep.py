"""The figure of ``famcc sweep``: settling time and margin against the sample rate."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from famcc.plot.axes import _DPI


def sweep_figure(
    rows: Sequence[dict[str, Any]], bounds: Mapping[str, float | None], title: str = ""
) -> Figure:
    """Settling time and the margin ``1 - max |xi~|`` against the sample rate.

    ``bounds`` maps each scenario to its settling bound ``T_s + T'`` (s), or None
    where the bound varies per run (the scenarios that saturate).

    ``rows`` are :mod:`famcc.sweep` records (keys ``scenario``, ``rate_hz``,
    ``discretization``, ``limited``, ``settling_time``, ``max_abs_xi``, ``ok``,
    ``error``). Per scenario two stacked panels: settling time (with ``T_s + T'`` for
    scenarios that do not saturate) and the margin on a log axis. Line style and marker
    per discretization; runs with estimate limits thinner with hollow markers. Runs that
    fail are marked with a black cross (at the top of the panel when they never settled or
    blew up).
    """
    from matplotlib.lines import Line2D
    from matplotlib.ticker import NullLocator
    from matplotlib.transforms import blended_transform_factory

    names = list(dict.fromkeys(r["scenario"] for r in rows))
    discs = list(dict.fromkeys(r["discretization"] for r in rows))
    handles: list[Any] = []
    labels: list[Any] = []
    ncol = min(3, len(names))
    nblock = math.ceil(len(names) / ncol)
    fig = Figure(figsize=(max(5.0 * ncol, 9.0), 5.2 * nblock + 0.6), dpi=_DPI, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(2 * nblock, ncol, squeeze=False)
    styles = {"exact": "-", "euler": ":", "tustin": "--", "foh": "-."}
    markers = {"exact": "o", "euler": "^", "tustin": "s", "foh": "D"}
    colors = {"exact": "tab:blue", "euler": "tab:red", "tustin": "tab:green", "foh": "tab:purple"}
    for j, name in enumerate(names):
        ax_t = axes[2 * (j // ncol), j % ncol]
        ax_m = axes[2 * (j // ncol) + 1, j % ncol]
        top = blended_transform_factory(ax_t.transData, ax_t.transAxes)
        fails_at_top = set()
        for d in discs:
            for lim in (False, True):
                sel = sorted(
                    (
                        r
                        for r in rows
                        if r["scenario"] == name
                        and r["discretization"] == d
                        and bool(r["limited"]) == lim
                    ),
                    key=lambda r: r["rate_hz"],
                )
                if not sel:
                    continue
                rates = np.array([r["rate_hz"] for r in sel], dtype=float)
                ts = np.array(
                    [np.nan if r["settling_time"] is None else r["settling_time"] for r in sel],
                    dtype=float,
                )
                xi = np.array(
                    [np.nan if r["max_abs_xi"] is None else r["max_abs_xi"] for r in sel],
                    dtype=float,
                )
                margin = np.maximum(1.0 - xi, 1e-17)
                style = {
                    "ls": styles.get(d, "-"),
                    "marker": markers.get(d, "o"),
                    "color": colors.get(d, "black"),
                    "label": d + (" + limits" if lim else ""),
                }
                if lim:
                    style.update(lw=1.0, ms=7, mfc="none", alpha=0.9)
                else:
                    style.update(lw=1.8, ms=4)
                ax_t.plot(rates, ts, **style)
                ax_m.plot(rates, margin, **style)
                for r, t_s in zip(sel, ts):
                    if r["ok"]:
                        continue
                    if np.isfinite(t_s):
                        ax_t.plot([r["rate_hz"]], [t_s], "x", color="black", ms=8, mew=1.6)
                    else:
                        fails_at_top.add(r["rate_hz"])
        bound = bounds.get(name)
        if bound is not None:
            ax_t.axhline(
                bound, color="black", ls="-.", lw=1.0, label=f"bound $T_s+T'$ = {bound:.3g} s"
            )
            ax_t.set_title(f"{name}", fontsize=10)
        else:
            ax_t.set_title(f"{name} (bound max($T_e$, $T_s$)+$T'$ varies per run)", fontsize=10)
        if fails_at_top:  # headroom, then the crosses in it
            lo, hi = ax_t.get_ylim()
            ax_t.set_ylim(lo, hi + 0.18 * (hi - lo))
        for rate in sorted(fails_at_top):
            ax_t.plot([rate], [0.95], "x", color="black", ms=8, mew=1.6, transform=top)
        swept = sorted({r["rate_hz"] for r in rows})
        for ax in (ax_t, ax_m):
            ax.set_xscale("log")
            ax.set_xticks(swept, [f"{v:g}" for v in swept], fontsize=7)
            ax.xaxis.set_minor_locator(NullLocator())
        ax_t.set_ylabel("settling time [s]")
        ax_t.set_xlabel("sample rate [Hz]")
        ax_m.set_yscale("log")
        ax_m.set_ylabel(r"margin $1 - \max|\tilde\xi|$ [-]")
        ax_m.set_xlabel("sample rate [Hz]")
        for ax in (ax_t, ax_m):
            ax.grid(True, which="both", color="0.9", lw=0.6)
        if j == 0:
            handles, labels = ax_t.get_legend_handles_labels()
    if names:
        handles.append(Line2D([], [], color="black", ls="-.", lw=1.0))
        labels.append("bound $T_s + T'$ (unsaturated scenarios)")
        handles.append(Line2D([], [], color="black", ls="none", marker="x", ms=8, mew=1.6))
        labels.append("guarantees not kept")
        handles_labels = [
            (h, lab) for h, lab in zip(handles, labels) if not lab.startswith("bound $T_s+T'$")
        ]
        fig.legend(
            [h for h, _ in handles_labels],
            [lab for _, lab in handles_labels],
            loc="outside lower center",
            ncol=8 if ncol >= 3 else 4,
            fontsize=8,
        )
    for k in range(len(names), nblock * ncol):  # unused slots
        axes[2 * (k // ncol), k % ncol].set_visible(False)
        axes[2 * (k // ncol) + 1, k % ncol].set_visible(False)
    fig.suptitle(
        title
        or "Sample-rate sweep: settling time to |z1| < 0.1 and the margin "
        "1 - max|xi~|\n(x: guarantees not kept; x at the top: never settled or "
        "diverged; missing points: no value)",
        fontsize=11,
    )
    return fig
