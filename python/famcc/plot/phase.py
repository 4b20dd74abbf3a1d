"""The phase-plane panels: the portrait ``(z1, z2)`` and the constrained stage, with ``h_m``."""

from __future__ import annotations

from typing import Any

import numpy as np

from famcc.plot.axes import _NOMINAL, _ZCOLORS, _limits, _z_label
from famcc.plot.view import _offset, _View


def _manifold_curve(
    ax: Any, law: Any, xs: np.ndarray, shift: float, horizontal: bool, label: str
) -> None:
    try:
        ys = np.asarray([law(float(x)) for x in xs], dtype=float)
    except (TypeError, ValueError, ArithmeticError):
        return
    ax.plot(xs, ys, color="0.35", lw=1.1, label=label)
    if shift > 0:
        style = {k: val for k, val in _NOMINAL.items() if k != "linewidth"}
        for j, sign in enumerate((-1.0, 1.0)):
            xx, yy = (xs + sign * shift, ys) if horizontal else (xs, ys + sign * shift)
            ax.plot(
                xx, yy, lw=0.9, label=rf"shifted by $\pm${shift:g}" if j == 0 else None, **style
            )


def _phase(
    ax: Any,
    x: np.ndarray,
    y: np.ndarray,
    law: Any,
    shift: float,
    horizontal: bool,
    curve_label: str,
    color: str,
) -> None:
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    xlo, xhi = _limits([x], pad=0.12)
    ylo, yhi = _limits([y], pad=0.12)
    if law is not None:
        xs = np.linspace(xlo - shift, xhi + shift, 400)
        _manifold_curve(ax, law, xs, shift, horizontal, curve_label)
    ax.plot(x, y, color=color, lw=1.2, label="trajectory")
    if x.size:
        ax.plot(x[:1], y[:1], "o", color=color, ms=5, label="start")
        ax.plot(x[-1:], y[-1:], "s", color="black", ms=4, label="end")
    ax.set_xlim(xlo, xhi)
    ax.set_ylim(ylo, yhi)
    ax.axhline(0, color="0.8", lw=0.6, zorder=0)
    ax.axvline(0, color="0.8", lw=0.6, zorder=0)


def _panel_phase(ax: Any, v: _View) -> str:
    r = v.r
    m = v.mask()
    order = v.order
    _, _, nom = _offset(v)
    # order 2: the constrained plane itself, with the final nominal bound;
    # order 3: stage 1's manifold z2 = h_m1(z1) (the constraint acts on stage 2)
    shift = float(nom[m][-1]) if order == 2 else 0.0
    law = v.laws[0] if v.laws else None
    _phase(ax, r.z[m, 0], r.z[m, 1], law, shift, v.axis == 0, r"$z_2 = h_{m1}(z_1)$", _ZCOLORS[0])
    ax.set_xlabel(_z_label(v, 0))
    ax.set_ylabel(_z_label(v, 1))
    ax.legend(fontsize=8, loc="best")
    title = r"phase portrait $(z_1, z_2)$"
    return title + (r" = $(s_1, \dot s_1)$" if order == 3 else "")


def _panel_stage(ax: Any, v: _View) -> str:
    r = v.r
    m = v.mask()
    _, _, nom = _offset(v)
    n = v.order
    law = v.laws[n - 2] if len(v.laws) >= n - 1 else None
    _phase(
        ax,
        np.asarray(r.s_prev)[m],
        np.asarray(r.ds_prev)[m],
        law,
        float(nom[m][-1]),
        False,
        rf"$\dot s_{n - 1} = h_{{m{n - 1}}}(s_{n - 1})$",
        "tab:purple",
    )
    ax.set_xlabel(rf"$s_{n - 1}$" + v.out.bracket(n - 2))
    ax.set_ylabel(rf"$\dot s_{n - 1}$" + v.out.bracket(n - 1))
    ax.legend(fontsize=8, loc="best")
    return rf"constrained stage $(s_{n - 1}, \dot s_{n - 1})$ (from $\hat z$)"
