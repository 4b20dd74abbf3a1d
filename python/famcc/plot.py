"""Figures of closed-loop runs: any run's, the paper's scenarios', the sweep's.

Every function draws on a fresh :class:`matplotlib.figure.Figure` attached to
an Agg canvas, never through ``pyplot``: nothing here touches the global
backend or needs a display, and a figure is freed as soon as it is dropped.

The panels have one home, this module, and two figures use them:

- :func:`figure` (also :meth:`famcc.SimResult.plot`): any run, a user's own
  plant and controller. Panels, chosen by name: ``"error"`` (``z`` and its
  estimate ``z_hat``), ``"accuracy"`` (``z1`` with the eps band and the
  settling time), ``"constraint"`` (the constrained value with its nominal and
  flexible bounds), ``"input"`` (``u``, the limits, saturation and ``-F/G``)
  and ``"xi"`` (the nominal ``xi`` and ``xi~``);
- :func:`scenario_figure` (``famcc reproduce``): the same panels plus the
  paper's extras, in the paper's order: the constrained value zoomed after
  ``T_s``, the phase portrait ``(z1, z2)`` and, at order 3, the constrained
  stage ``(s2, ds2)``.

Axes carry the names and units of the plant's output and input
(:class:`famcc.Signal`), one quantity per line; saturation episodes (commanded
``v`` outside the limits) are shaded; a one-line note at the bottom says the
paper's terms in plain words (docs/glossary.md).

>>> import famcc
>>> from famcc import plot
>>> sc = famcc.scenarios.paper("finite-time")
>>> fig = plot.scenario_figure(sc, sc.run(t_end=1.5))
>>> len(fig.axes), fig.axes[0].get_title()[:9]
(7, '(a) error')
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, cast

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from famcc._common import Signal

# The differentiator's start-up (peaking) window: the u and z panels zoom past it.
from famcc.verdicts import STARTUP

__all__ = [
    "EXTRA_PANELS",
    "PANELS",
    "constrained_offset",
    "figure",
    "legend",
    "panels_of",
    "save",
    "scenario_figure",
    "scenario_panels",
    "sweep_figure",
]

#: The panels of :func:`figure`, in their default order.
PANELS = ("error", "accuracy", "constraint", "input", "xi")
#: The paper's extra panels (:func:`scenario_figure`).
EXTRA_PANELS = ("constraint-zoom", "phase", "stage")

_NOMINAL = {"color": "black", "linestyle": (0, (5, 3)), "linewidth": 1.1}
_FLEXIBLE = {"color": "tab:red", "linestyle": "-", "linewidth": 2.0, "alpha": 0.85}
_SAT = {"color": "tab:orange", "alpha": 0.18, "linewidth": 0}
_ZCOLORS = ("tab:blue", "tab:green", "tab:purple", "tab:brown", "tab:pink")
_DPI = 100
_ABBREVIATION = {"lateral": "LaMC", "longitudinal": "LoMC", "oblique": "OMC"}

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


# ---------------------------------------------------------------------------
# what a figure needs to know about a run
# ---------------------------------------------------------------------------


@dataclass
class _View:
    """A run and what its panels need: accuracy, ``T_s``, constraint, laws, window."""

    r: Any
    eps: float | None
    settle_time: float | None
    constraint: str | None
    laws: list[Any] = field(default_factory=list)
    show_limits: bool = False
    window: tuple[float, float] | None = None

    @property
    def t(self) -> np.ndarray:
        return np.asarray(self.r.t, dtype=float)

    @property
    def order(self) -> int:
        return int(self.r.z.shape[1])

    @property
    def out(self) -> Signal:
        return getattr(self.r, "output", None) or Signal("y")

    @property
    def inp(self) -> Signal:
        return getattr(self.r, "input", None) or Signal("u")

    @property
    def axis(self) -> int:
        """0 when the constraint acts in the x direction (LaMC, OMC), 1 for LoMC."""
        if self.constraint in ("lateral", "oblique"):
            return 0
        if self.constraint == "longitudinal" or self.r.nominal_bounds is None:
            return 1
        # a controller without a configuration: the direction whose bound is used
        nb = np.abs(np.nan_to_num(np.asarray(self.r.nominal_bounds, dtype=float)))
        return 0 if nb[:, 0].max() > 0 and nb[:, 1].max() == 0 else 1

    def mask(self, after: float | None = None) -> np.ndarray:
        """Samples inside the window; without a window, those from ``after`` on."""
        t = self.t
        if self.window is not None:
            m = (t >= self.window[0]) & (t <= self.window[1])
        elif after is not None:
            m = t >= after
        else:
            return np.ones_like(t, dtype=bool)
        return m if m.sum() >= 2 else np.ones_like(t, dtype=bool)

    def zoom_start(self) -> float | None:
        """``T_s`` when the accuracy panels start there (no window, ``T_s`` in the run)."""
        ts = self.settle_time
        if self.window is None and ts is not None and ts < float(self.t[-1]):
            return ts
        return None

    def episodes(self) -> list[tuple[float, float]]:
        return list(self.r.saturation_episodes())


def _laws_from(feedback: Any, skew: Any, order: int) -> list[Any]:
    """The callables ``h_m`` of the stages (None where the binding cannot build one)."""
    import famcc

    n = max(order - 1, 0)
    fbs = list(feedback) if isinstance(feedback, (list, tuple)) else [feedback] * n
    sks = list(skew) if isinstance(skew, (list, tuple)) else [skew] * n
    laws: list[Any] = []
    for fb, sk in zip(fbs, sks):
        try:
            laws.append(famcc.skewed(fb, sk))
        except (TypeError, ValueError):  # a law the binding does not know: draw no curve
            laws.append(None)
    return laws


def _view(
    result: Any, eps: float | None = None, window: tuple[float, float] | None = None
) -> _View:
    """What the general figure knows of a run: from its recorded controller configuration."""
    cfg = getattr(result, "controller_config", None) or {}
    accuracy = eps if eps is not None else getattr(result, "accuracy", None)
    laws = _laws_from(cfg.get("feedback"), cfg.get("skew"), result.z.shape[1]) if cfg else []
    show = False
    if result.u_limits is not None:  # limits in view when saturated or near the input
        late = np.asarray(result.t) >= STARTUP
        late = late if late.sum() >= 2 else np.ones_like(late)
        u_late = float(np.max(np.abs(np.asarray(result.u)[late])))
        near = max(abs(x) for x in result.u_limits) <= 3.0 * u_late
        show = near or bool(np.any(np.asarray(result.saturated)[late]))
    if window is not None:
        t0, t1 = (float(w) for w in window)
        if not (math.isfinite(t0) and math.isfinite(t1) and t0 < t1):
            raise ValueError(f"window must be (t0, t1) with t0 < t1, got {window!r}")
        window = (t0, t1)
    return _View(
        result,
        accuracy,
        getattr(result, "settle_time", None),
        getattr(result, "constraint", None),
        laws,
        show,
        window,
    )


def _scenario_view(scenario: Any, result: Any) -> _View:
    kw = scenario.controller_kwargs
    return _View(
        result,
        float(scenario.eps_z),
        float(scenario.settle_time),
        kw.get("constraint", "longitudinal"),
        _laws_from(kw.get("feedback"), kw.get("skew"), result.z.shape[1]),
        bool(scenario.saturated),
    )


def constrained_offset(
    result: Any, constraint: str | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(offset, flexible bound, nominal bound)`` in the constraint's direction.

    The offset is what the constraint bounds: the horizontal offset (``s_fn`` at
    order 2) from the zero manifold for LaMC and OMC, the manifold value ``s`` for
    LoMC. The LaMC/OMC offset is recovered as ``xi~ * x~_U``, which equals the
    controller's offset exactly unless ``xi~`` was clamped; the bounds are the
    upper ones (the lower ones are their negatives).

    Parameters
    ----------
    result : famcc.SimResult
        A recorded run (``record=True``).
    constraint : str, optional
        ``"lateral"``, ``"longitudinal"`` or ``"oblique"``; default: the
        controller's, as recorded in ``result``.
    """
    if result.bounds is None or result.nominal_bounds is None:
        raise ValueError("result has no diagnostics; simulate with record=True")
    view = _view(result)
    if constraint is not None:
        view.constraint = constraint
    return _offset(view)


def _offset(v: _View) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    ax = v.axis
    flex = np.asarray(v.r.bounds, dtype=float)[:, ax]
    nom = np.asarray(v.r.nominal_bounds, dtype=float)[:, ax]
    if ax == 1:
        offset = np.asarray(v.r.s, dtype=float)
    else:
        offset = np.asarray(v.r.xi, dtype=float) * flex
    return offset, flex, nom


# ---------------------------------------------------------------------------
# labels
# ---------------------------------------------------------------------------


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


# ---------------------------------------------------------------------------
# panels: each draws on an axis and returns its title (without the letter)
# ---------------------------------------------------------------------------


def _panel_error(ax: Any, v: _View) -> str:
    r = v.r
    m = v.mask()
    t = v.t[m]
    n = v.order
    keep = m & (v.t >= STARTUP)
    if keep.sum() < 2:
        keep = m
    shown = []
    known = [i for i in range(n) if np.any(np.isfinite(r.z[m, i]))]
    for i in range(n):
        c = _ZCOLORS[i % len(_ZCOLORS)]
        if i in known:
            ax.plot(t, r.z[m, i], color=c, lw=1.4, label=_z(i))
            shown.append(r.z[m, i])
        if r.z_hat is not None:
            ax.plot(
                t, r.z_hat[m, i], color=c, lw=1.0, ls="--", alpha=0.9, label=rf"$\hat z_{i + 1}$"
            )
            shown.append(r.z_hat[keep, i])
    lo, hi = _limits(shown)
    ax.set_ylim(lo, hi)
    notes = []
    if r.z_hat is not None:
        for i in range(n):
            zh = r.z_hat[m, i]
            if not np.any(np.isfinite(zh)):
                continue
            k = int(np.nanargmax(np.abs(zh)))
            if not lo <= zh[k] <= hi:
                notes.append(rf"$\hat z_{i + 1}$ peaks at {_fmt(zh[k])} (t = {t[k]:.3f} s)")
    if len(known) < n:
        why = getattr(r, "derivatives_error", None)
        notes.append(
            ("true $z_2$" if n == 2 else f"true $z_2..z_{n}$")
            + " unknown"
            + (f":\n{_reason(why)}" if why else "")
            if n > 1
            else ""
        )
    legend_low = bool(np.isfinite(r.z[m, 0][0]) and r.z[m, 0][0] > 0)
    notes = [s for s in notes if s]
    if notes:  # make room for the note on the side free of the legend
        room = (0.08 + 0.07 * sum(n.count("\n") + 1 for n in notes)) * (hi - lo)
        if legend_low:
            ax.set_ylim(lo, hi + room)
        else:
            ax.set_ylim(lo - room, hi)
        _note(
            ax,
            ("off scale: " if "peaks" in notes[0] else "") + "\n".join(notes),
            "upper right" if legend_low else "lower right",
        )
    ax.set_xlim(t[0], t[-1])
    ax.set_xlabel("time [s]")
    ax.set_ylabel("\n".join(_z_label(v, i) for i in range(n)))
    ax.legend(ncol=min(n, 3), fontsize=8, loc="lower right" if legend_low else "upper right")
    what = "" if v.out.name == "y" else f" of the {v.out.name}"
    hat = r" and its estimate $\hat z$ (dashed)" if r.z_hat is not None else ""
    return rf"error $z${what} (solid){hat}"


def _panel_accuracy(ax: Any, v: _View) -> str:
    r = v.r
    t = v.t
    eps = v.eps
    start = v.zoom_start()
    mask = v.mask(after=start)
    tt = t[mask]
    _shade(ax, _in_window(v, v.episodes(), tt))
    ax.plot(tt, r.z[mask, 0], color=_ZCOLORS[0], lw=1.4, label=_z(0))
    if r.z_hat is not None:
        ax.plot(tt, r.z_hat[mask, 0], color=_ZCOLORS[0], lw=1.0, ls="--", label=r"$\hat z_1$")
    if eps is None:
        _note(ax, "no accuracy eps known: pass eps= to draw the band", "upper left")
        lo, hi = _limits([r.z[mask, 0]])
        ax.set_ylim(lo, hi)
    else:
        unit = v.out.bracket()[2:-1] if v.out.unit else ""
        ax.axhspan(-eps, eps, color="tab:green", alpha=0.08, lw=0)
        ax.axhline(
            eps,
            color="tab:green",
            ls=":",
            lw=1.2,
            label=rf"$\pm\epsilon_z$ = $\pm${eps:g}" + (f" {unit}" if unit else ""),
        )
        ax.axhline(-eps, color="tab:green", ls=":", lw=1.2)
        ts = r.settling_time(eps)
        if ts is not None and tt[0] <= ts <= tt[-1]:
            ax.axvline(ts, color="0.3", lw=1.0, ls="-.", label=f"settled {ts:.3g} s")
        elif ts is not None and ts < tt[0]:
            _note(ax, f"settled at {ts:.3g} s (before the view)", "upper left")
        elif ts is not None:
            _note(ax, f"settled at {ts:.3g} s (after the view)", "upper left")
        else:
            _note(ax, f"not settled to |z1| < {eps:g} by the end", "upper left")
        # scale to what happens once z1 first reached the band (later excursions
        # included), so the approach from the initial error does not flatten it
        entry = r.first_entry(eps)
        ref = tt[0] if entry is None else max(entry, tt[0])
        late = np.abs(r.z[mask & (t >= ref), 0])
        late = late[np.isfinite(late)]
        peak = max(float(np.max(late)) if late.size else eps, eps)
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
    ax.set_xlabel("time [s]")
    ax.set_ylabel(_z_label(v, 0))
    ax.legend(fontsize=8, ncol=2, loc="upper right")
    if start is not None:
        return rf"$z_1$ after $T_s$ = {start:g} s, with the accuracy band"
    return r"$z_1$ with the accuracy band"


def _panel_constraint(ax: Any, v: _View, zoom: bool = False) -> str:
    t = v.t
    off, flex, nom = _offset(v)
    start = v.zoom_start() if zoom else None
    mask = v.mask(after=start)
    tt = t[mask]
    nom_label, flex_label = _bound_names(v)
    sym, what, kind, k = _offset_names(v)
    _shade(ax, _in_window(v, v.episodes(), tt))
    ax.plot(tt, flex[mask], label=flex_label, **_FLEXIBLE)
    ax.plot(tt, -flex[mask], **_FLEXIBLE)
    ax.plot(tt, nom[mask], label=nom_label, **_NOMINAL)
    ax.plot(tt, -nom[mask], **_NOMINAL)
    ax.plot(tt, off[mask], color="tab:blue", lw=1.2, label=sym)
    ax.set_xlim(tt[0], tt[-1])
    both = np.concatenate([off[mask], flex[mask]])
    both = both[np.isfinite(both)]
    peak = float(np.max(np.abs(both))) if both.size else 1.0
    peak = peak if peak > 0 else 1.0
    ax.set_ylim(-(1.25 if zoom else 1.12) * peak, (1.25 if zoom else 1.12) * peak)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(sym + v.out.bracket(k))
    ax.legend(fontsize=8, ncol=2, loc="upper right")
    if zoom:
        return rf"the same after $T_s$ = {start:g} s" if start is not None else "the same, zoomed"
    return f"{what} {sym} ({kind}) and its bounds"


def _panel_input(ax: Any, v: _View) -> str:
    r = v.r
    m = v.mask()
    t = v.t[m]
    u = np.asarray(r.u, dtype=float)[m]
    limits = r.u_limits
    _shade(ax, _in_window(v, v.episodes(), t))
    ax.plot(t, u, color="tab:blue", lw=1.1, label="$u$ (applied)")
    keep = v.t[m] >= STARTUP
    shown = [u[keep] if keep.sum() >= 2 else u]
    negfg = r.neg_f_over_g
    if negfg is not None:
        ax.plot(t, negfg[m], color="tab:red", lw=1.2, ls="--", label="$-F/G$")
        shown.append(negfg[m])
    lo, hi = _limits(shown, pad=0.1)
    if limits is not None and v.show_limits:
        pad = 0.1 * (limits[1] - limits[0])
        lo, hi = min(lo, limits[0] - pad), max(hi, limits[1] + pad)
    in_view = [] if limits is None else [x for x in limits if lo <= x <= hi]
    for j, x in enumerate(in_view):
        ax.axhline(x, color="black", ls="-.", lw=1.0, label="limits" if j == 0 else None)
    notes = []
    if limits is not None and len(in_view) < 2:
        notes.append(f"limits [{limits[0]:g}, {limits[1]:g}] outside the view")
    if limits is None:
        notes.append("no actuator limits")
    if u.size and (float(np.min(u)) < lo or float(np.max(u)) > hi):
        k = int(np.argmax(np.abs(u)))
        notes.append(
            f"off scale before {STARTUP:g} s: u in [{_fmt(float(np.min(u)))}, "
            f"{_fmt(float(np.max(u)))}] (largest |u| at t = {t[k]:.3f} s)"
        )
    if negfg is None:
        why = getattr(r, "neg_f_over_g_error", None)
        notes.append("$-F/G$ unknown" + (f":\n{_reason(why)}" if why else ""))
    if notes:  # room below the data for the note
        lo -= (0.06 + 0.08 * sum(n.count("\n") + 1 for n in notes)) * (hi - lo)
        _note(ax, "\n".join(notes), "lower right")
    ax.set_ylim(lo, hi)
    ax.set_xlim(t[0], t[-1])
    ax.set_xlabel("time [s]")
    ax.set_ylabel(_u_label(v))
    ax.legend(fontsize=8, ncol=2, loc="upper right")
    what = "" if v.inp.name == "u" else f" ({v.inp.name})"
    return f"input $u${what}" + (" and $-F/G$" if negfg is not None else "")


def _panel_xi(ax: Any, v: _View) -> str:
    r = v.r
    m = v.mask()
    t = v.t[m]
    _shade(ax, _in_window(v, v.episodes(), t))
    xi_nom = None if r.xi_nominal is None else np.asarray(r.xi_nominal, dtype=float)[m]
    if xi_nom is not None:
        ax.plot(t, xi_nom, color="0.35", lw=1.0, ls="--", label=r"nominal $\xi$")
    ax.plot(t, np.asarray(r.xi, dtype=float)[m], color="tab:blue", lw=1.0, label=r"$\tilde\xi$")
    ax.axhline(1.0, color="black", ls="-.", lw=1.0, label=r"$\pm 1$ (on a bound)")
    ax.axhline(-1.0, color="black", ls="-.", lw=1.0)
    top = 1.15
    if xi_nom is not None and np.any(np.isfinite(xi_nom)):
        peak = float(np.nanmax(np.abs(xi_nom)))
        top = min(max(top, 1.1 * peak), 3.0)
        if peak > top:
            k = int(np.nanargmax(np.abs(xi_nom)))
            _note(
                ax,
                rf"nominal $|\xi|$ peaks at {peak:.3g} (t = {t[k]:.2f} s), off scale",
                "upper left",
            )
    ax.set_ylim(-top, top)
    ax.set_xlim(t[0], t[-1])
    ax.set_xlabel("time [s]")
    ax.set_ylabel(
        "\n".join(
            ([r"nominal $\xi$ [-]"] if xi_nom is not None else []) + [r"flexible $\tilde\xi$ [-]"]
        )
    )
    ax.legend(fontsize=8, ncol=4, loc="lower right")
    mx = r.max_abs_xi
    return r"nominal $\xi$ and flexible $\tilde\xi$" + (
        rf" (max $|\tilde\xi|$ = {mx:.4f})" if mx is not None else ""
    )


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


# ---------------------------------------------------------------------------
# figures
# ---------------------------------------------------------------------------


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
