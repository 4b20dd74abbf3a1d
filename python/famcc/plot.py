"""Figures of the paper's simulations (and of the sample-rate sweep).

Every function draws on a fresh :class:`matplotlib.figure.Figure` attached to
an Agg canvas, never through ``pyplot``: nothing here touches the global
backend or needs a display, and a figure is freed as soon as it is dropped.

One figure per scenario mirrors the paper's panels:

- order 2 (3 x 2): (a) ``z`` and ``z_hat`` against time, (b) ``z1`` after
  ``T_s`` with the accuracy band, (c) the constrained offset (``s_fn`` for
  LaMC, ``s`` for LoMC) with the nominal and flexible bounds, (d) the same
  after ``T_s``, (e) the phase portrait ``(z1, z2) = (s1, ds1)``, (f) ``u``
  with ``-F/G`` and the actuator limits;
- order 3 (4 x 2): the same, plus (f) the constrained stage's phase portrait
  ``(s2, ds2)`` and (h) the constraint variable ``xi~``.

Saturation episodes (commanded ``v`` outside the limits) are shaded.

>>> import famcc
>>> from famcc import plot
>>> sc = famcc.scenarios.paper("finite-time")
>>> fig = plot.scenario_figure(sc, sc.run(t_end=1.5))
>>> len(fig.axes)
6
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

# The differentiator's start-up (peaking) window: the u and z panels zoom past it.
from famcc.verdicts import STARTUP

__all__ = ["constrained_offset", "save", "scenario_figure", "sweep_figure"]


_NOMINAL = {"color": "black", "linestyle": (0, (5, 3)), "linewidth": 1.1}
_FLEXIBLE = {"color": "tab:red", "linestyle": "-", "linewidth": 2.0, "alpha": 0.85}
_SAT = {"color": "tab:orange", "alpha": 0.18, "linewidth": 0}
_ZCOLORS = ("tab:blue", "tab:green", "tab:purple")
_DPI = 100


# ---------------------------------------------------------------------------
# quantities
# ---------------------------------------------------------------------------


def _active_axis(scenario: Any) -> int:
    """0 for the lateral constraint (x direction), 1 otherwise (y direction)."""
    return 0 if scenario.controller_kwargs.get("constraint") == "lateral" else 1


def constrained_offset(scenario: Any, result: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(offset, flexible bound, nominal bound)`` in the constraint's direction.

    The offset is what the constraint bounds: the horizontal offset ``s_fn``
    from the zero manifold for LaMC, the manifold value ``s`` for LoMC. It is
    recovered as ``xi~ * x~_U`` (or ``xi~ * y~_U``), which equals the
    controller's offset exactly unless ``xi~`` was clamped; the bounds are the
    upper ones (the lower ones are their negatives).
    """
    ax = _active_axis(scenario)
    flex = np.asarray(result.bounds, dtype=float)[:, ax]
    nom = np.asarray(result.nominal_bounds, dtype=float)[:, ax]
    if ax == 1:
        offset = np.asarray(result.s, dtype=float)
    else:
        offset = np.asarray(result.xi, dtype=float) * flex
    return offset, flex, nom


def _offset_label(scenario: Any) -> str:
    return r"$s_{fn}$ (horizontal offset)" if _active_axis(scenario) == 0 else r"$s$"


def _bound_names(scenario: Any) -> tuple[str, str]:
    if _active_axis(scenario) == 0:
        return r"nominal $\pm x_U$", r"flexible $\pm\tilde{x}_U$"
    return r"nominal $\pm y_U$", r"flexible $\pm\tilde{y}_U$"


def _z_unit(i: int) -> str:
    return ("[y]", "[y/s]", "[y/s$^2$]", "[y/s$^3$]")[min(i, 3)]


def _law(scenario: Any, stage: int) -> Any:
    """The callable ``h_m`` of a stage (0-based), or None."""
    import famcc

    kw = scenario.controller_kwargs
    fb, sk = kw.get("feedback"), kw.get("skew")
    fb = fb[stage] if isinstance(fb, (list, tuple)) else fb
    sk = sk[stage] if isinstance(sk, (list, tuple)) else sk
    try:
        return famcc.skewed(fb, sk)
    except (TypeError, ValueError):  # a law the binding does not know: draw no curve
        return None


# ---------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------


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


def _after(t: np.ndarray, t0: float) -> np.ndarray:
    mask = t >= t0
    if mask.sum() < 2:
        mask = np.ones_like(t, dtype=bool)
    return mask


# ---------------------------------------------------------------------------
# panels
# ---------------------------------------------------------------------------


def _panel_z(ax: Any, sc: Any, r: Any) -> None:
    t = r.t
    n = r.z.shape[1]
    keep = _after(t, STARTUP)
    shown = []
    for i in range(n):
        c = _ZCOLORS[i % len(_ZCOLORS)]
        ax.plot(t, r.z[:, i], color=c, lw=1.4, label=rf"$z_{i + 1}$")
        if r.z_hat is not None:
            ax.plot(
                t, r.z_hat[:, i], color=c, lw=1.0, ls="--", alpha=0.9, label=rf"$\hat z_{i + 1}$"
            )
            shown.append(r.z_hat[keep, i])
        shown.append(r.z[:, i])
    lo, hi = _limits(shown)
    ax.set_ylim(lo, hi)
    clipped = []
    if r.z_hat is not None:
        for i in range(n):
            zh = r.z_hat[:, i]
            k = int(np.nanargmax(np.abs(zh)))
            if not lo <= zh[k] <= hi:
                clipped.append(rf"$\hat z_{i + 1}$ peaks at {_fmt(zh[k])} (t = {t[k]:.3f} s)")
    legend_low = r.z[0, 0] > 0
    if clipped:  # make room for the note on the side free of the legend
        room = 0.14 * (hi - lo)
        if legend_low:
            ax.set_ylim(lo, hi + room)
        else:
            ax.set_ylim(lo - room, hi)
        _note(
            ax, "off scale: " + "; ".join(clipped), "upper right" if legend_low else "lower right"
        )
    ax.set_title(r"(a) error $z$ (solid) and its estimate $\hat z$ (dashed)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel(" ".join(rf"$z_{i + 1}$ {_z_unit(i)}" for i in range(n)))
    ax.legend(ncol=n, fontsize=8, loc="lower right" if legend_low else "upper right")


def _panel_z_zoom(ax: Any, sc: Any, r: Any, episodes: list[Any]) -> None:
    t = r.t
    eps = sc.eps_z
    mask = _after(t, sc.settle_time)
    tt = t[mask]
    _shade(ax, [(a, b) for a, b in episodes if b >= tt[0]])
    ax.axhspan(-eps, eps, color="tab:green", alpha=0.08, lw=0)
    ax.axhline(eps, color="tab:green", ls=":", lw=1.2, label=rf"$\pm\epsilon_z$ = $\pm${eps:g}")
    ax.axhline(-eps, color="tab:green", ls=":", lw=1.2)
    ax.plot(tt, r.z[mask, 0], color=_ZCOLORS[0], lw=1.4, label=r"$z_1$")
    if r.z_hat is not None:
        ax.plot(tt, r.z_hat[mask, 0], color=_ZCOLORS[0], lw=1.0, ls="--", label=r"$\hat z_1$")
    ts = r.settling_time(eps)
    if ts is not None and ts >= tt[0]:
        ax.axvline(ts, color="0.3", lw=1.0, ls="-.", label=f"settled {ts:.3g} s")
    elif ts is not None:
        _note(ax, f"settled at {ts:.3g} s (before $T_s$)", "upper left")
    else:
        _note(ax, f"not settled to |z1| < {eps:g} by the end", "upper left")
    # scale to what happens once z1 first reached the band (later excursions
    # included), so the approach from the initial error does not flatten it
    entry = r.first_entry(eps)
    ref = tt[0] if entry is None else max(entry, tt[0])
    late = np.abs(r.z[t >= ref, 0])
    peak = max(float(np.nanmax(late)) if late.size else eps, eps)
    half = max(1.35 * peak, 2.5 * eps)
    ax.set_ylim(-half, half)
    early = np.abs(r.z[mask, 0]) > half
    if early.any():
        _note(
            ax,
            f"|z1| > {half:.2g} off scale until t = {tt[np.flatnonzero(early)[-1]]:.2f} s",
            "lower right",
        )
    ax.set_xlim(tt[0], tt[-1])
    ax.set_title(rf"(b) $z_1$ after $T_s$ = {sc.settle_time:g} s")
    ax.set_xlabel("time [s]")
    ax.set_ylabel(r"$z_1$ [y]")
    ax.legend(fontsize=8, ncol=2, loc="upper right")


def _panel_offset(ax: Any, sc: Any, r: Any, episodes: list[Any], zoom: bool) -> None:
    t = r.t
    off, flex, nom = constrained_offset(sc, r)
    mask = _after(t, sc.settle_time) if zoom else np.ones_like(t, dtype=bool)
    tt = t[mask]
    nom_label, flex_label = _bound_names(sc)
    _shade(ax, [(a, b) for a, b in episodes if b >= tt[0]])
    ax.plot(tt, flex[mask], label=flex_label, **_FLEXIBLE)
    ax.plot(tt, -flex[mask], **_FLEXIBLE)
    ax.plot(tt, nom[mask], label=nom_label, **_NOMINAL)
    ax.plot(tt, -nom[mask], **_NOMINAL)
    ax.plot(tt, off[mask], color="tab:blue", lw=1.2, label=_offset_label(sc))
    ax.set_xlim(tt[0], tt[-1])
    if zoom:
        peak = float(np.nanmax(np.abs(np.concatenate([off[mask], flex[mask]]))))
        ax.set_ylim(-1.25 * peak, 1.25 * peak)
        ax.set_title(rf"(d) the same after $T_s$ = {sc.settle_time:g} s")
    else:
        peak = float(np.nanmax(np.abs(np.concatenate([off, flex]))))
        ax.set_ylim(-1.12 * peak, 1.12 * peak)
        what = (
            r"horizontal offset $s_{fn}$ (LaMC)"
            if _active_axis(sc) == 0
            else r"manifold value $s$ (LoMC)"
        )
        ax.set_title(f"(c) {what} and its bounds")
    ax.set_xlabel("time [s]")
    unit = "[y]" if _active_axis(sc) == 0 else _z_unit(r.z.shape[1] - 1)
    ax.set_ylabel(("$s_{fn}$ " if _active_axis(sc) == 0 else "$s$ ") + unit)
    ax.legend(fontsize=8, ncol=2, loc="upper right")


def _manifold_curve(
    ax: Any, law: Any, xs: np.ndarray, shift: float, horizontal: bool, label: str
) -> None:
    try:
        ys = np.asarray([law(float(x)) for x in xs], dtype=float)
    except (TypeError, ValueError, ArithmeticError):
        return
    ax.plot(xs, ys, color="0.35", lw=1.1, label=label)
    if shift > 0:
        if horizontal:  # LaMC bounds: the curve shifted left/right by x_U
            ax.plot(
                xs - shift,
                ys,
                lw=0.9,
                label=rf"shifted by $\pm${shift:g}",
                **{k: v for k, v in _NOMINAL.items() if k != "linewidth"},
            )
            ax.plot(
                xs + shift, ys, lw=0.9, **{k: v for k, v in _NOMINAL.items() if k != "linewidth"}
            )
        else:  # LoMC bounds: shifted up/down by y_U
            ax.plot(
                xs,
                ys + shift,
                lw=0.9,
                label=rf"shifted by $\pm${shift:g}",
                **{k: v for k, v in _NOMINAL.items() if k != "linewidth"},
            )
            ax.plot(
                xs, ys - shift, lw=0.9, **{k: v for k, v in _NOMINAL.items() if k != "linewidth"}
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
    ax.plot(x[:1], y[:1], "o", color=color, ms=5, label="start")
    ax.plot(x[-1:], y[-1:], "s", color="black", ms=4, label="end")
    ax.set_xlim(xlo, xhi)
    ax.set_ylim(ylo, yhi)
    ax.axhline(0, color="0.8", lw=0.6, zorder=0)
    ax.axvline(0, color="0.8", lw=0.6, zorder=0)


def _panel_phase_z(ax: Any, sc: Any, r: Any) -> None:
    lateral = _active_axis(sc) == 0
    order = r.z.shape[1]
    _, _, nom = constrained_offset(sc, r)
    # order 2: the constrained plane itself, with the final nominal bound;
    # order 3: stage 1's manifold z2 = h_m1(z1) (the constraint acts on stage 2)
    shift = float(nom[-1]) if order == 2 else 0.0
    _phase(
        ax, r.z[:, 0], r.z[:, 1], _law(sc, 0), shift, lateral, r"$z_2 = h_{m1}(z_1)$", _ZCOLORS[0]
    )
    title = r"(e) phase portrait $(z_1, z_2)$"
    if order == 3:
        title += r" = $(s_1, \dot s_1)$"
    ax.set_title(title)
    ax.set_xlabel(r"$z_1$ [y]")
    ax.set_ylabel(r"$z_2$ [y/s]")
    ax.legend(fontsize=8, loc="best")


def _panel_phase_stage(ax: Any, sc: Any, r: Any) -> None:
    _, _, nom = constrained_offset(sc, r)
    n = r.z.shape[1]
    _phase(
        ax,
        np.asarray(r.s_prev),
        np.asarray(r.ds_prev),
        _law(sc, n - 2),
        float(nom[-1]),
        False,
        rf"$\dot s_{n - 1} = h_{{m{n - 1}}}(s_{n - 1})$",
        "tab:purple",
    )
    ax.set_title(rf"(f) constrained stage $(s_{n - 1}, \dot s_{n - 1})$ (from $\hat z$)")
    ax.set_xlabel(rf"$s_{n - 1}$ {_z_unit(n - 2)}")
    ax.set_ylabel(rf"$\dot s_{n - 1}$ {_z_unit(n - 1)}")
    ax.legend(fontsize=8, loc="best")


def _panel_u(ax: Any, sc: Any, r: Any, episodes: list[Any], label: str) -> None:
    t = r.t
    lo_lim, hi_lim = sc.u_limits
    _shade(ax, episodes)
    ax.plot(t, r.u, color="tab:blue", lw=1.1, label="$u$ (applied)")
    shown = [r.u[_after(t, STARTUP)]]
    if r.neg_f_over_g is not None:
        ax.plot(t, r.neg_f_over_g, color="tab:red", lw=1.2, ls="--", label="$-F/G$")
        shown.append(r.neg_f_over_g)
    lo, hi = _limits(shown, pad=0.1)
    if sc.saturated:
        pad = 0.1 * (hi_lim - lo_lim)
        lo, hi = min(lo, lo_lim - pad), max(hi, hi_lim + pad)
    in_view = [v for v in (lo_lim, hi_lim) if lo <= v <= hi]
    for j, v in enumerate(in_view):
        ax.axhline(v, color="black", ls="-.", lw=1.0, label="limits" if j == 0 else None)
    notes = []
    if len(in_view) < 2:
        notes.append(f"limits [{lo_lim:g}, {hi_lim:g}] outside the view")
    if r.u_min < lo or r.u_max > hi:
        k = int(np.argmax(np.abs(r.u)))
        notes.append(
            f"off scale before {STARTUP:g} s: u in [{_fmt(r.u_min)}, {_fmt(r.u_max)}] "
            f"(largest |u| at t = {t[k]:.3f} s)"
        )
    if notes:  # room below the data for the note
        lo -= (0.06 + 0.08 * len(notes)) * (hi - lo)
        _note(ax, "\n".join(notes), "lower right")
    ax.set_ylim(lo, hi)
    ax.set_title(label)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("$u$ [input units]")
    ax.legend(fontsize=8, ncol=2, loc="upper right")


def _panel_xi(ax: Any, sc: Any, r: Any, episodes: list[Any]) -> None:
    _shade(ax, episodes)
    ax.plot(r.t, r.xi, color="tab:blue", lw=1.0, label=r"$\tilde\xi$")
    ax.axhline(1.0, color="black", ls="-.", lw=1.0, label=r"$\pm 1$")
    ax.axhline(-1.0, color="black", ls="-.", lw=1.0)
    ax.set_ylim(-1.15, 1.15)
    ax.set_title(rf"(h) constraint variable $\tilde\xi$ (max $|\tilde\xi|$ = {r.max_abs_xi:.4f})")
    ax.set_xlabel("time [s]")
    ax.set_ylabel(r"$\tilde\xi$ [-]")
    ax.legend(fontsize=8, ncol=3, loc="lower right")


# ---------------------------------------------------------------------------
# figures
# ---------------------------------------------------------------------------


def scenario_figure(scenario: Any, result: Any, title: str | None = None) -> Figure:
    """The paper-style figure of one scenario run (needs recorded diagnostics).

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
    order = result.z.shape[1]
    rows = 3 if order == 2 else 4
    fig = Figure(figsize=(12, 3.3 * rows), dpi=_DPI, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(rows, 2)
    episodes = result.saturation_episodes()
    _panel_z(axes[0, 0], scenario, result)
    _panel_z_zoom(axes[0, 1], scenario, result, episodes)
    _panel_offset(axes[1, 0], scenario, result, episodes, zoom=False)
    _panel_offset(axes[1, 1], scenario, result, episodes, zoom=True)
    _panel_phase_z(axes[2, 0], scenario, result)
    if order == 2:
        _panel_u(axes[2, 1], scenario, result, episodes, "(f) input $u$ and $-F/G$")
    else:
        _panel_phase_stage(axes[2, 1], scenario, result)
        _panel_u(axes[3, 0], scenario, result, episodes, "(g) input $u$ and $-F/G$")
        _panel_xi(axes[3, 1], scenario, result, episodes)
    for ax in fig.axes:
        ax.grid(True, color="0.9", lw=0.6)
        ax.set_axisbelow(True)
    if title is None:
        lo, hi = scenario.u_limits
        title = (
            f'{scenario.name}: example {scenario.example}, variant "{scenario.variant}", '
            f"dt = {result.dt * 1e3:g} ms, u in [{lo:g}, {hi:g}]\n"
            f"{scenario.description}"
        )
    fig.suptitle(title, fontsize=12)
    return fig


def save(fig: Figure, path: str | Path) -> Path:
    """Writes ``fig`` as PNG to ``path`` and returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, format="png")
    return path


def sweep_figure(rows: Sequence[dict[str, Any]], title: str = "") -> Figure:
    """Settling time and the margin ``1 - max |xi~|`` against the sample rate.

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

    from famcc import scenarios

    names = list(dict.fromkeys(r["scenario"] for r in rows))
    discs = list(dict.fromkeys(r["discretization"] for r in rows))
    handles: list[Any] = []
    labels: list[Any] = []
    ncol = min(3, len(names))
    nblock = math.ceil(len(names) / ncol)
    fig = Figure(figsize=(max(5.0 * ncol, 9.0), 5.2 * nblock + 0.6), dpi=_DPI, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(2 * nblock, ncol, squeeze=False)
    styles = {"exact": "-", "euler": ":", "tustin": "--"}
    markers = {"exact": "o", "euler": "^", "tustin": "s"}
    colors = {"exact": "tab:blue", "euler": "tab:red", "tustin": "tab:green"}
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
        sc = scenarios.paper(name, rows[0].get("variant", "code"))
        if not sc.saturated:
            ax_t.axhline(
                sc.bound, color="black", ls="-.", lw=1.0, label=f"bound $T_s+T'$ = {sc.bound:.3g} s"
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
