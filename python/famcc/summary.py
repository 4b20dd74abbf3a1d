"""A run's metrics in one dict and a few lines of plain words (:func:`summarize`).

>>> import numpy as np, famcc
>>> t = np.arange(0.0, 2.001, 0.5)
>>> r = famcc.SimResult(t=t, y=t, y_d=0 * t, x=t[:, None],
...                     z=np.array([[1.0], [0.5], [0.05], [0.02], [0.0]]),
...                     v=np.array([4.0, 2.0, 1.0, 0.0, 1.0]),
...                     u=np.array([3.0, 2.0, 1.0, 0.0, 1.0]), dt=0.5, u_limits=(-3, 3))
>>> s = summarize(r, eps=0.1)
>>> s["settling_time"], s["ripple"], s["saturated_fraction"]
(1.0, 1.0, 0.2)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from famcc import metrics as m
from famcc.plants.base import is_real

__all__ = ["CONSTRAINTS", "Summary", "describe_controller", "summarize"]

#: Constraint names of the controller's configuration and the paper's abbreviations.
CONSTRAINTS = {"lateral": "LaMC", "longitudinal": "LoMC", "oblique": "OMC"}


class Summary(dict[str, Any]):
    """:meth:`famcc.SimResult.summary`: the metrics (a ``dict``) and a short text.

    ``str(summary)`` and ``summary.text`` give the text, a few lines in plain
    words; the keys are the metrics.
    """

    def __init__(self, metrics: dict[str, Any], text: str) -> None:
        super().__init__(metrics)
        self.text = text

    def __str__(self) -> str:
        return self.text


def _pct(v: float | None) -> str:
    return "-" if v is None else f"{100 * v:.3g} %"


def describe_controller(config: Mapping[str, Any] | None, text: str | None) -> str:
    """One line: constraint, laws, eps, ``T_s``, ``k_u`` (or the controller's type)."""
    cfg = config
    if not cfg:
        text = text or "unknown controller"
        if text.startswith("<") and " object at " in text:  # object.__repr__
            text = text[1:].split(" object at ")[0].rsplit(".", 1)[-1]
        return (text if len(text) <= 60 else text[:57] + "...") + " (no famcc configuration)"
    kind = str(cfg.get("constraint"))
    parts = [f"{CONSTRAINTS.get(kind, kind)} ({kind} constraint)"]
    laws = cfg.get("feedback") or []
    skews = cfg.get("skew") or [None] * len(laws)
    stages = []
    for law, skew in zip(laws, skews):
        name = {"Smooth": "SSMD", "Nonsingular": "NSMD"}.get(type(skew).__name__)
        stages.append(repr(law) + (f" + {name}" if name else ""))
    if stages:
        parts.append("h_p " + ", ".join(stages))
    eps = cfg.get("eps")
    parts.append(f"eps = {eps:g}" if is_real(eps) else f"eps = {eps}")
    settle = m.as_float(cfg.get("settle_time"))
    if settle is not None:
        parts.append(f"T_s = {settle:g} s")
    if is_real(cfg.get("k_u")):
        parts.append(f"k_u = {cfg['k_u']:g}")
    return ", ".join(parts)


def summarize(r: Any, eps: float | None = None) -> Summary:
    """The run's metrics as a dict, with a short text (``.text``, or ``str()``).

    Parameters
    ----------
    r : famcc.SimResult
    eps : float, optional
        Accuracy for the settling time, steady RMS and ripple. Default: the
        accuracy the controller's configuration presets; when there is none,
        those metrics are None and the text says so.

    Returns
    -------
    Summary
        A ``dict`` with ``eps``, ``settling_time``, ``first_entry``,
        ``steady_rms``, ``ripple`` (peak-to-peak ``u`` after settling),
        ``z1_ripple`` (peak-to-peak ``z1`` after settling), ``iae``,
        ``rms_u``, ``tv_u_per_s``, ``diverged``, ``diverged_at``,
        ``never_settled``,
        ``max_abs_xi_nominal``, ``max_abs_xi``, ``expanded_fraction``,
        ``expanded_unsaturated_fraction``, ``saturated_fraction``, ``u_min``,
        ``u_max``, ``saturation_episodes`` (their number),
        ``last_saturation_end``, ``largest_expansion``, ``nominal_return_time``,
        ``max_abs_z1_final_second``, ``clamp_count``, ``neg_f_over_g_error``
        and ``derivatives_error``.
    """
    e = m.preset_accuracy(r.controller_config) if eps is None else m.check_eps(eps)
    episodes = m.saturation_episodes(r)
    metrics: dict[str, Any] = {
        "eps": e,
        "settling_time": None if e is None else m.settling_time(r, e),
        "first_entry": None if e is None else m.first_entry(r, e),
        "max_abs_z1_final_second": m.tail_max(r.t, np.abs(m.z1(r)), 1.0),
        "max_abs_xi": m.max_abs_xi(r),
        "max_abs_xi_nominal": m.max_abs_xi_nominal(r),
        "expanded_fraction": m.expanded_fraction(r),
        "expanded_unsaturated_fraction": m.expanded_unsaturated_fraction(r),
        "steady_rms": None if e is None else m.steady_rms(r, e),
        "ripple": None if e is None else m.ripple(r, e),
        "z1_ripple": None if e is None else m.z1_ripple(r, e),
        "iae": m.iae(r),
        "rms_u": m.rms_u(r),
        "tv_u_per_s": m.tv_u_per_s(r),
        "diverged": r.diverged_at is not None,
        "diverged_at": r.diverged_at,
        "never_settled": None if e is None else m.never_settled(r, e),
        "u_min": float(np.min(r.u)),
        "u_max": float(np.max(r.u)),
        "saturated_fraction": m.saturated_fraction(r),
        "saturation_episodes": len(episodes),
        "last_saturation_end": m.last_saturation_end(r),
        "largest_expansion": m.largest_expansion(r),
        "nominal_return_time": m.nominal_return_time(r),
        "clamp_count": int(r.clamp_count),
        "neg_f_over_g_error": r.neg_f_over_g_error,
        "derivatives_error": r.derivatives_error,
    }
    return Summary(metrics, "\n".join(_lines(r, metrics)))


def _lines(r: Any, s: dict[str, Any]) -> list[str]:
    ou = "" if r.output.unit is None else f" {r.output.unit}"
    iu = "" if r.input.unit is None else f" {r.input.unit}"
    eps = s["eps"]
    if eps is None:
        first = (
            "no accuracy eps known (the controller presets none): pass eps= for the "
            "settling time, steady RMS and ripple"
        )
    elif s["settling_time"] is not None:
        first = (
            f"settled to |z1| < {eps:g}{ou} at {s['settling_time']:.3g} s (first entry "
            f"{s['first_entry']:.3g} s); steady RMS {s['steady_rms']:.3g}{ou}; "
            f"u ripple after settling {s['ripple']:.3g}{iu} (peak-to-peak)"
        )
    else:
        fe = s["first_entry"]
        first = (
            f"NOT settled to |z1| < {eps:g}{ou} by the end ({float(r.t[-1]):g} s; first "
            f"entry {'never' if fe is None else f'{fe:.3g} s'}, max |z1| in the last second "
            f"{s['max_abs_z1_final_second']:.3g}{ou})"
        )
    sat = (
        "no actuator limits"
        if r.u_limits is None
        else f"saturated {_pct(s['saturated_fraction'])} of the samples"
    )
    if r.xi is None:
        second = f"no controller diagnostics recorded (no xi, no bounds); {sat}"
    else:
        xi_nom = s["max_abs_xi_nominal"]
        nominal = (
            f"max |xi~| {s['max_abs_xi']:.3g}"
            if xi_nom is None
            else f"max nominal |xi| {xi_nom:.3g}"
            + (" (> 1: left the nominal set)" if xi_nom > 1 else "")
        )
        exp = s["expanded_unsaturated_fraction"]
        second = f"{nominal}; expanded while unsaturated {_pct(exp)}; {sat}"
    first += (
        f"; IAE {s['iae']:.3g}{ou} s; RMS u {s['rms_u']:.3g}{iu}; TV(u) {s['tv_u_per_s']:.3g}{iu}/s"
    )
    if s["diverged"]:
        first = f"DIVERGED at {s['diverged_at']:.4g} s (the run was stopped); " + first
    lines = [first, second]
    missing = []
    if r.neg_f_over_g_error:
        missing.append(f"-F/G unknown: {r.neg_f_over_g_error}")
    if r.derivatives_error:
        n = r.z.shape[1]
        which = "z2" if n == 2 else f"z2..z{n}"
        missing.append(f"{which} unknown: {r.derivatives_error}")
    if missing:
        lines.append("; ".join(missing))
    return lines
