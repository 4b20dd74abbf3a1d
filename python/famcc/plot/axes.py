"""What every panel shares: line styles, axis labels, saturation shading, limits and notes."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from famcc.plot.view import _View

_NOMINAL = {"color": "black", "linestyle": (0, (5, 3)), "linewidth": 1.1}
_FLEXIBLE = {"color": "tab:red", "linestyle": "-", "linewidth": 2.0, "alpha": 0.85}
_SAT = {"color": "tab:orange", "alpha": 0.18, "linewidth": 0}
_ZCOLORS = ("tab:blue", "tab:green", "tab:purple", "tab:brown", "tab:pink")
_DPI = 100
_ABBREVIATION = {"lateral": "LaMC", "longitudinal": "LoMC", "oblique": "OMC"}


def _z(i: int) -> str:
    """``$z_{i+1}$`` (0-based ``i``)."""
    return rf"$z_{{{i + 1}}}$"


def _z_label(v: _View, i: int) -> str:
    return _z(i) + v.out.bracket(i)


def _offset_names(v: _View) -> tuple[str, str, str, int]:
    """``(symbol, what, constraint name, derivative order of its unit)``."""
    n = v.order
    kind = _ABBREVIATION.get(v.constraint or "", "constraint")
    if v.axis == 0:
        sym = r"$s_{fn}$" if n == 2 and v.constraint != "oblique" else rf"$s_{{{n - 1}}}$ offset"
        return sym, "horizontal offset from the manifold", kind, n - 2
    return r"$s$", "manifold value", kind, n - 1


def _bound_names(v: _View) -> tuple[str, str]:
    if v.axis == 0:
        return r"nominal $\pm x_U$", r"flexible $\pm\tilde{x}_U$"
    return r"nominal $\pm y_U$", r"flexible $\pm\tilde{y}_U$"


def _u_label(v: _View) -> str:
    name = v.inp.name
    return (f"{name} $u$" if name != "u" else "$u$") + v.inp.bracket()


def _shade(ax: Any, episodes: Sequence[tuple[float, float]], label: bool = True) -> None:
    first = True
    for a, b in episodes:
        ax.axvspan(a, max(b, a + 1e-3), label="saturated" if (first and label) else None, **_SAT)
        first = False


def _limits(
    values: Sequence[np.ndarray], pad: float = 0.08, floor: float = 1e-9
) -> tuple[float, float]:
    finite = [np.asarray(v, dtype=float)[np.isfinite(v)] for v in values]
    finite = [v for v in finite if v.size]
    if not finite:
        return -1.0, 1.0
    lo = float(min(v.min() for v in finite))
    hi = float(max(v.max() for v in finite))
    span = max(hi - lo, floor, 1e-3 * max(abs(lo), abs(hi)))
    return lo - pad * span, hi + pad * span


def _note(ax: Any, text: str, loc: str = "lower right") -> None:
    x, ha = (0.98, "right") if "right" in loc else (0.02, "left")
    y, va = (0.03, "bottom") if "lower" in loc else (0.97, "top")
    ax.text(
        x,
        y,
        text,
        transform=ax.transAxes,
        ha=ha,
        va=va,
        fontsize=7.5,
        color="0.25",
        bbox={"boxstyle": "round,pad=0.25", "fc": "white", "ec": "0.7", "alpha": 0.9},
    )


def _fmt(v: float) -> str:
    return f"{v:.3g}"


def _short(text: str, n: int = 90) -> str:
    text = " ".join(text.split())
    return text if len(text) <= n else text[: n - 3] + "..."


def _reason(text: str, width: int = 70, lines: int = 2) -> str:
    """A plant's error text for a panel note: without the plant's repr, wrapped, cut."""
    import re
    import textwrap

    text = re.sub(r"^\w+\(.*?\): ", "", " ".join(text.split()))
    wrapped = textwrap.wrap(text, width)
    if len(wrapped) > lines:
        wrapped = [*wrapped[: lines - 1], _short(" ".join(wrapped[lines - 1 :]), width)]
    return "\n".join(wrapped)


def _in_window(v: _View, episodes: Sequence[tuple[float, float]], tt: np.ndarray) -> list[Any]:
    return [(a, b) for a, b in episodes if b >= tt[0] and a <= tt[-1]]
