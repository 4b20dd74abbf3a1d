"""The time panels: error, accuracy, constraint, input and ``xi``.

Each draws on an axis and returns its title (without the letter).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from famcc.plot.axes import (
    _FLEXIBLE,
    _NOMINAL,
    _ZCOLORS,
    _bound_names,
    _fmt,
    _in_window,
    _limits,
    _note,
    _offset_names,
    _reason,
    _shade,
    _u_label,
    _z,
    _z_label,
)
from famcc.plot.view import _offset, _View

# The differentiator's start-up (peaking) window: the u and z panels zoom past it.
from famcc.verdicts import STARTUP


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
