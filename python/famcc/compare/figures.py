"""The report's figures: a radar chart per plant and the time series of its telling case."""

from __future__ import annotations

from typing import Any

import numpy as np

from famcc.compare.findings import RADAR
from famcc.compare.plants import Case

_LABEL = {"famcc": "famcc", "lmcc": "LMCC", "pid": "PID", "adrc": "ADRC"}
_COLOR = {"famcc": "C3", "lmcc": "C1", "pid": "C0", "adrc": "C2"}


def _radar_figure(scores: dict[str, dict[str, float]], title: str) -> Any:
    import matplotlib.pyplot as plt

    axes = [a for a, _, _ in RADAR if all(a in s for s in scores.values())]
    ang = np.linspace(0, 2 * np.pi, len(axes), endpoint=False).tolist()
    fig = plt.figure(figsize=(5.6, 4.2), dpi=80)
    ax = fig.add_axes((0.14, 0.1, 0.6, 0.76), projection="polar")
    for kind, s in scores.items():
        vals = [0.05 + 0.95 * s[a] for a in axes]
        ax.plot(ang + ang[:1], vals + vals[:1], color=_COLOR[kind], label=_LABEL[kind], lw=1.6)
        ax.fill(ang + ang[:1], vals + vals[:1], color=_COLOR[kind], alpha=0.08)
    ax.set_xticks(ang)
    ax.set_xticklabels(axes, fontsize=7)
    ax.set_yticks([0.05, 0.525, 1.0])
    ax.set_yticklabels(["worst", "", "best"], fontsize=6)
    ax.set_ylim(0, 1.05)
    ax.set_title(title, fontsize=9)
    ax.legend(loc="upper left", bbox_to_anchor=(1.12, 1.05), fontsize=7)
    return fig


def _series_figure(case: Case, results: dict[str, Any], condition: str) -> Any:
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.0, 4.4), dpi=80, sharex=True)
    for kind, res in results.items():
        r = res[0]
        a1.plot(r.t, r.z1, color=_COLOR[kind], lw=0.8, label=_LABEL[kind])
        a2.plot(r.t, r.u, color=_COLOR[kind], lw=0.6)
    a1.axhline(case.band, color="k", ls=":", lw=0.7)
    a1.axhline(-case.band, color="k", ls=":", lw=0.7)
    lim = 5 * case.band
    a1.set_ylim(-lim, lim)
    a1.set_ylabel(f"z1 [{case.output_unit}]" if case.output_unit else "z1")
    a2.set_ylabel(f"u [{case.input_unit}]" if case.input_unit else "u (joint 1)")
    a2.set_xlabel("t [s]")
    a1.legend(fontsize=7, ncol=4, loc="upper right")
    a1.set_title(f"{case.name}, {condition}: error (band dotted, zoomed) and input", fontsize=9)
    fig.tight_layout()
    return fig


def _telling(result: dict[str, Any], name: str, found: list[dict[str, Any]]) -> str:
    """The condition to draw for a plant: famcc's largest loss, else the mid noise level."""
    mine = [x for x in found if x["case"] == name]
    conds = result["meta"]["conditions"]
    if mine:
        worst = max(mine, key=lambda x: x.get("ratio", 1e9))
        if worst["condition"] != "dispersion":
            return str(worst["condition"])
    return "noise 1e-3" if "noise 1e-3" in conds else "nominal"
